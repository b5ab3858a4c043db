/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* board.h - the power stage the HAL and the core both read: the board profile and its PWM. */
#ifndef BOARD_H
#define BOARD_H

/*
 * The bottom layer (docs/architecture.md): facts of the hardware and the
 * PWM it runs, which the HAL programs into registers and the core uses for
 * its scalings and timing. Both include this header and nothing of each
 * other's. It includes nothing but the board profile and <stdint.h>.
 *
 * The board is chosen at build time: make BOARD=mclv (the default) or
 * BOARD=mchv, which CMake turns into MC_BOARD_<BOARD>. Every setting below
 * may be overridden with -D on the compiler command line; the core
 * (firmware/mc_derived.h) and the HAL (hal/dspic33f/hal_dspic33f.h) each
 * check the ranges they need, naming the parameter.
 */

#include <stdint.h>

#if defined(MC_BOARD_MCHV)
#include "board_mchv.h"
#else /* MC_BOARD_MCLV, the default */
#include "board_mclv.h"
#endif

/* ---- PWM and ADC timing ---------------------------------------------------- */

/* PWM and current-loop rate, Hz: one ADC interrupt and one mc_step() per
 * period. The cycle budget (docs/design.md) is for 20 kHz. */
#ifndef PWM_FREQUENCY_HZ
#define PWM_FREQUENCY_HZ 20000L
#endif

/* ADC start after the PWM period's midpoint, instruction cycles (AN1078:
 * 80, 2 us at 40 MIPS), so the shunt signals have settled. */
#ifndef PWM_ADC_TRIGGER_TCY
#define PWM_ADC_TRIGGER_TCY 80L
#endif

/* Dead time the HAL programs and the core compensates, ns. */
#ifndef PWM_DEADTIME_NS
#define PWM_DEADTIME_NS BOARD_DEADTIME_NS
#endif

/* Duty counts for 100 % (AN1078 LOOPINTCY, PDCx units: 2000 at 40 MIPS,
 * 20 kHz): the full scale of the duties the core hands the HAL. */
#define PWM_DUTY_MAX ((uint16_t)(BOARD_FCY_HZ / PWM_FREQUENCY_HZ))

#endif /* BOARD_H */
