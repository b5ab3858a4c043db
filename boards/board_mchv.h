/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* board_mchv.h - dsPICDEM MCHV (DM330023): scalings and limits (ASSUMED, see below). */
#ifndef BOARD_MCHV_H
#define BOARD_MCHV_H

/*
 * ASSUMED VALUES. The MCHV's PIM, shunt, amplifier gain and DC-bus divider
 * were not found (docs/hardware.md 2.3). Every scaling below is a placeholder of
 * the right order for a 230 Vac rectified bus, marked ASSUMED; measure or
 * read the board's user's guide and override them (-D or edit here) before
 * running a real motor. Microchip's later MCHV code also reverses the
 * current sign: the HAL must deliver currents "+ = into the motor".
 */

#define BOARD_NAME "MCHV"

/* Resolution of the ADC conversions the core reads (ADC1 in 10-bit mode,
 * docs/hardware.md 1.7), bits. */
#ifndef BOARD_ADC_BITS
#define BOARD_ADC_BITS 10
#endif

#ifndef BOARD_FCY_HZ
#define BOARD_FCY_HZ 40000000L
#endif

/* ASSUMED: current that reads as Q15 full scale. */
#ifndef BOARD_I_FULLSCALE_A
#define BOARD_I_FULLSCALE_A 8.0
#endif

/* ASSUMED: sign from the current amplifiers' ADC reading to the core's
 * "+ = into the motor" (the HAL applies it): -1, from Microchip's later MCHV
 * code (docs/hardware.md 2.3: the MCHV shunt path reverses the LEM-designed sense). */
#ifndef BOARD_I_SIGN
#define BOARD_I_SIGN (-1)
#endif

/* ASSUMED: DC-bus voltage that reads as 32767 (a 400 V full-scale divider). */
#ifndef BOARD_VBUS_FULLSCALE_V
#define BOARD_VBUS_FULLSCALE_V 400.0
#endif

/* ASSUMED: 230 Vac rectified. */
#ifndef BOARD_VBUS_NOMINAL_V
#define BOARD_VBUS_NOMINAL_V 320.0
#endif

/* ASSUMED: the highest DC bus the power stage is rated for, V (no
 * overvoltage trip above it; board_mclv.h). */
#ifndef BOARD_VBUS_MAX_V
#define BOARD_VBUS_MAX_V 400.0
#endif

/* The DC bus's bulk capacitance, F: what a regenerating motor charges when the
 * supply cannot take current back (the simulator's bus model, sim --bus-model).
 * [ASSUMED CONSERVATIVE: an offline board's bulk capacitance chosen low; the board's documents were
 * not read. Bench check: the capacitors on the bus rails of the board in hand, their sum.] */
#ifndef BOARD_VBUS_CAPACITANCE_F
#define BOARD_VBUS_CAPACITANCE_F 220e-6
#endif

/* The supply's output resistance as the bus sees it, ohm, leads included:
 * the supply only sources current. [ASSUMED: a bench supply and its leads.
 * Bench check: the bus's drop at a known DC current.] */
#ifndef BOARD_SUPPLY_R_OHM
#define BOARD_SUPPLY_R_OHM 0.1
#endif

/* ASSUMED protection window. */
#ifndef BOARD_VBUS_UNDERVOLTAGE_V
#define BOARD_VBUS_UNDERVOLTAGE_V 200.0
#endif
#ifndef BOARD_VBUS_OVERVOLTAGE_V
#define BOARD_VBUS_OVERVOLTAGE_V 385.0
#endif

/* Shunt window as on the MCLV (board_mclv.h): the low-side conduction a
 * measured phase needs before the sample, ns. [CHOSEN: 3 us, the MCHV's
 * amplifier figure not found either.] */
#ifndef BOARD_SHUNT_MIN_ON_NS
#define BOARD_SHUNT_MIN_ON_NS 3000L
#endif

/* The least dead time the power stage needs, ns, as on the MCLV (AN1078's
 * 2 us): the default PWM dead time and its floor (board_mclv.h). */
#ifndef BOARD_DEADTIME_NS
#define BOARD_DEADTIME_NS 2000L
#endif

#endif /* BOARD_MCHV_H */
