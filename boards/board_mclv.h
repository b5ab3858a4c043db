/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* board_mclv.h - dsPICDEM MCLV (DM330021) with the dsPIC33FJ32MC204 PIM: scalings and limits. */
#ifndef BOARD_MCLV_H
#define BOARD_MCLV_H

/*
 * Every value here is a fact about the board (docs/hardware.md section 2); the
 * application settings that use them are in UserParms.h. Each macro may be
 * overridden with -D on the command line.
 */

#define BOARD_NAME "MCLV"

/* Instruction clock: 8 MHz crystal, PLL to 40 MIPS (docs/hardware.md 1.2). */
/* Resolution of the ADC conversions the core reads (ADC1 in 10-bit mode,
 * docs/hardware.md 1.7), bits. */
#ifndef BOARD_ADC_BITS
#define BOARD_ADC_BITS 10
#endif

#ifndef BOARD_FCY_HZ
#define BOARD_FCY_HZ 40000000L
#endif

/* Current that reads as Q15 full scale: Rshunt 0.005 ohm, amplifier gain 75,
 * VDD/2 = 1.65 V -> +-4.4 A (AN1078 UserParms, docs/hardware.md 2.1). */
#ifndef BOARD_I_FULLSCALE_A
#define BOARD_I_FULLSCALE_A 4.4
#endif

/* Sign from the current amplifiers' ADC reading to the core's "+ = into the
 * motor" (+1: as read, -1: negated; the HAL applies it, hal/dspic33f).
 * -1 [SRC: docs/board.md, "Bring-up facts": AN1078's current measurement
 * computes Offset - ADC on this board's amplifiers, the raw reading
 * negated]. Still a bench check (docs/board.md): in LOCK
 * with the rotor held, ia must have the sign of the commanded current. */
#ifndef BOARD_I_SIGN
#define BOARD_I_SIGN (-1)
#endif

/* DC-bus voltage that reads as 32767.
 * UNCHECKED ASSUMPTION: the original MCLV's VBUS divider was not found; this
 * is the MCLV-2 figure (3.3 V x 16 = 52.8 V, docs/hardware.md 2.2). Check the
 * board schematic (DS70331) before trusting the bus protections or the
 * ripple compensation. It is the only place this number lives. */
#ifndef BOARD_VBUS_FULLSCALE_V
#define BOARD_VBUS_FULLSCALE_V 52.8
#endif

/* Nominal DC bus: the 24 V supply of the kit. It sets the SVGen voltage
 * full scale (MC_VOLTAGE_FULLSCALE_V = nominal / sqrt(3)) and the target of
 * the ripple compensation. */
#ifndef BOARD_VBUS_NOMINAL_V
#define BOARD_VBUS_NOMINAL_V 24.0
#endif

/* The highest DC bus the power stage is rated for, V: no overvoltage trip
 * may sit above it (mc_derived.h). [UNCHECKED: Microchip describes the
 * MCLV (DM330021) as a board for motors up to 48 V; its user guide (DS70331)
 * and its bulk capacitors' rating were not read. Bench check: the
 * capacitors' and the MOSFETs' voltage ratings on the board in hand.] */
#ifndef BOARD_VBUS_MAX_V
#define BOARD_VBUS_MAX_V 48.0
#endif

/* The DC bus's bulk capacitance, F: what a regenerating motor charges when the
 * supply cannot take current back (the simulator's bus model, sim --bus-model).
 * [ASSUMED CONSERVATIVE: a 24 V kit's bulk capacitance chosen low: a smaller C rises faster; the
 * board's documents were not read. Bench check: the capacitors on the bus rails of the board in
 * hand, their sum.] */
#ifndef BOARD_VBUS_CAPACITANCE_F
#define BOARD_VBUS_CAPACITANCE_F 470e-6
#endif

/* The supply's output resistance as the bus sees it, ohm, leads included:
 * the supply only sources current. [ASSUMED: a bench supply and its leads.
 * Bench check: the bus's drop at a known DC current.] */
#ifndef BOARD_SUPPLY_R_OHM
#define BOARD_SUPPLY_R_OHM 0.1
#endif

/* Default bus protection window for a 24 V kit; override in UserParms.h. */
#ifndef BOARD_VBUS_UNDERVOLTAGE_V
#define BOARD_VBUS_UNDERVOLTAGE_V 15.0
#endif
#ifndef BOARD_VBUS_OVERVOLTAGE_V
#define BOARD_VBUS_OVERVOLTAGE_V 32.0
#endif

/* Shunt window: how long the low-side switch of a measured phase must have
 * conducted before the ADC samples its shunt, ns: the current amplifier's
 * settling from "no current" (the high side was on) to the phase current.
 * The MCLV's amplifier settling time was not found in Microchip's
 * documents. [CHOSEN: 3 us. A first-order amplifier settles to 1 % in 4.6
 * time constants, so this covers a time constant up to 0.65 us, a closed-
 * loop bandwidth down to about 250 kHz.] The core keeps the measured
 * phases' duties at or below MC_DUTY_SAMPLE_MAX (1758 of 2000 here,
 * mc_derived.h). Bench check: docs/board.md, first power-on step 7. */
#ifndef BOARD_SHUNT_MIN_ON_NS
#define BOARD_SHUNT_MIN_ON_NS 3000L
#endif

/* The least dead time the power stage needs, ns: what the PWM programs by
 * default (PWM_DEADTIME_NS), and the floor the core and the HAL hold it to
 * (a shorter one lets a leg's two switches conduct together). AN1078's 2 us
 * (DTCON1 = 0x40 | 40) [SRC]; the MCLV's switches and drivers were not
 * found to need less, so nothing shorter is allowed. */
#ifndef BOARD_DEADTIME_NS
#define BOARD_DEADTIME_NS 2000L
#endif

#endif /* BOARD_MCLV_H */
