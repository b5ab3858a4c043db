/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* motor.h - the one running motor: the object the ADC interrupt steps, and its mailbox. */
#ifndef MOTOR_H
#define MOTOR_H

/*
 * The dsPIC image has one mc_t. It lives here, in firmware/, and belongs to
 * the ADC interrupt, which steps it through the HAL's hooks (hal.h,
 * hal_hook_control/finish/slow, implemented in motor.c). Everything else,
 * the main loop (app.c) and the X2Cscope target alike, reaches it only through the
 * calls below, each of which runs the core's call with the interrupts that
 * step it masked (hal_critical_enter: CPU priority 7), so a request never
 * lands mid-step and a status is the snapshot of one period. The masked
 * time is one short core call (a copy of mc_status_t at most), far below
 * the slack the interrupt leaves (docs/board.md "Timing"); a conversion
 * that completes meanwhile is serviced on unmasking.
 *
 * firmware/motor.c implements it on the dsPIC. On the PC, where the caller
 * steps its own mc_t in the same thread, tools/sim/sim_mailbox.c
 * implements the mailbox calls (not motor_start, motor_observe) on that
 * motor, so the X2Cscope target and the main loop run there unchanged.
 */

#include <stdbool.h>
#include <stdint.h>

#include "mc.h"

/* mc_init() on the motor, then start the control interrupts
 * (hal_control_start): from here on the core runs every PWM period and the
 * slow step every MC_SLOW_STEP_PERIODS. */
void motor_start(void);

void motor_request(mc_request_t request);
void motor_status(mc_status_t *status);

/* mc_set_reference() on the motor, masked; returns the number of this
 * choice of reference, the caller's claim (mc_reference_held, mc.h). */
uint8_t motor_set_reference(int16_t ref);

/* The live gains (mc.h note 3): mc_get_gain() / mc_set_gain() on the
 * motor, masked. */
int16_t motor_get_gain(mc_gain_t gain);
bool motor_set_gain(mc_gain_t gain, int16_t value);

/* mc_identify_result() on the motor, unmasked: its 64-bit conversions
 * take far longer than the interrupts may wait. Safe as it is: the
 * sequence's state is written by the slow step while the status is
 * RUNNING, and the status turns final (by the ADC interrupt, after the
 * last window) only once that state is complete; the main loop, the only
 * caller, issues the next request itself. */
void motor_identify_result(mc_id_result_t *r);

/* The running motor, to read (never to write): the X2Cscope target
 * resolves the addresses a client names against it. Its fields change
 * under the interrupt: copy them with motor_copy(). */
const mc_t *motor_view(void);

/* n bytes at src (a field of the running motor, or anything else the
 * control interrupts write) into dst, masked, so the copy is of one period.
 * For a few bytes: the interrupt waits for it. */
void motor_copy(void *dst, const volatile void *src, uint8_t n);

/* An observer of the running motor (e.g. the X2Cscope target's scope):
 * called by the ADC interrupt once per period, after the duties are
 * written and the core's step is complete, so it never delays them. It
 * runs in the interrupt: constant time, no waiting, no UART. NULL removes
 * it. */
typedef void (*motor_observer_t)(void *ctx, const mc_t *mc);
void motor_observe(motor_observer_t fn, void *ctx);

#endif /* MOTOR_H */
