/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_record.h - the period record: the core's inputs and outputs of every period, for a replay. */
#ifndef SIM_RECORD_H
#define SIM_RECORD_H

#include <stdint.h>
#include <stdio.h>

#include "../../hal/hal_frame.h"

/*
 * `sim --record FILE` writes, for every PWM period of a scenario, what the
 * core was given and what it gave back, so the same periods can be replayed
 * on another build of the core (a dsPIC image on an instruction simulator,
 * docs/performance.md "Method") and its outputs compared bit for bit.
 * Little-endian throughout. A 16-byte header:
 *   "AN1078R1"   magic (8 bytes)
 *   u16 1        format version
 *   u16 20       bytes per period record
 *   u16          MC_SLOW_STEP_PERIODS of the build that recorded it
 *   u16          its PWM_FREQUENCY_HZ / 10
 * then one 20-byte record per period, in order:
 *   u16 requests  bit r set: mc_request(r) was posted before this period's
 *                 step (a request posted twice counts once, as in the core)
 *   i16 ia, ib, vbus, pot   the frame (mc_adc_frame_t = hal_adc_frame_t, the HAL's
 *                 scalings)
 *   u16 duty[3]   the duties mc_step returned (mc_pwm_out_t)
 *   u8  outputs_on
 *   u8  0
 *   u16 state     the core's state after the step (mc_state_t)
 * The core's remote reference and gains are not recorded: the scenarios set
 * the speed through the pot.
 */

#define SIM_RECORD_MAGIC "AN1078R1"
#define SIM_RECORD_BYTES 20U

/* The header, for a core of slow_periods per window at pwm_hz; 0, or -1 when
 * the write failed. */
int sim_record_header(FILE *f, uint16_t slow_periods, uint32_t pwm_hz);

/* One period's record; 0, or -1 when the write failed. */
int sim_record_period(FILE *f, uint16_t requests, const hal_adc_frame_t *in,
                      const hal_pwm_out_t *out, uint16_t state);

#endif /* SIM_RECORD_H */
