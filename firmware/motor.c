/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* motor.c - the one running motor: the HAL's interrupt hooks and the main loop's mailbox. */
#include <stddef.h>

#include "motor.h"

#include "../hal/hal.h" /* firmware/ may include hal/hal.h (docs/architecture.md) */

static mc_t motor;

/* The optional observer (motor_observe), read by the ADC interrupt. */
static motor_observer_t observer;
static void *observer_ctx;

/* ---- the HAL's hooks (hal.h), in its interrupts ---------------------------- *
 * ctx is &motor (motor_start hands it to hal_control_start, with the
 * window length the core counts too: MC_SLOW_STEP_PERIODS, both from
 * mc_init). Passed through, it is already where the core's functions take
 * their object, so the control and slow hooks are a jump into the core. */

void hal_hook_control(void *ctx, const hal_adc_frame_t *frame, hal_pwm_out_t *out)
{
    mc_step_control((mc_t *)ctx, frame, out);
}

/* A fault of the finishing part switches the outputs off at once, not at
 * the next period; the observer comes last, so it never delays that. */
void hal_hook_finish(void *ctx, hal_pwm_out_t *out)
{
    if (mc_step_finish((mc_t *)ctx, out)) {
        hal_pwm_off();
    }
    if (observer != NULL) {
        observer(observer_ctx, &motor);
    }
}

void hal_hook_slow(void *ctx)
{
    mc_slow_step((mc_t *)ctx);
}

/* ---- the mailbox ------------------------------------------------------------ */

void motor_start(void)
{
    hal_control_stop();
    mc_init(&motor);
    hal_control_start(&motor, (uint16_t)MC_SLOW_STEP_PERIODS);
}

void motor_request(mc_request_t request)
{
    hal_irq_state_t s = hal_critical_enter();
    mc_request(&motor, request);
    hal_critical_exit(s);
}

uint8_t motor_set_reference(int16_t ref)
{
    hal_irq_state_t s = hal_critical_enter();
    uint8_t seq = mc_set_reference(&motor, ref);
    hal_critical_exit(s);
    return seq;
}

void motor_status(mc_status_t *status)
{
    hal_irq_state_t s = hal_critical_enter();
    mc_status(&motor, status);
    hal_critical_exit(s);
}

int16_t motor_get_gain(mc_gain_t gain)
{
    hal_irq_state_t s = hal_critical_enter();
    int16_t v = mc_get_gain(&motor, gain);
    hal_critical_exit(s);
    return v;
}

bool motor_set_gain(mc_gain_t gain, int16_t value)
{
    hal_irq_state_t s = hal_critical_enter();
    bool ok = mc_set_gain(&motor, gain, value);
    hal_critical_exit(s);
    return ok;
}

/* Both words change together: masked, so the interrupt never sees a new
 * function with the old context. */
void motor_observe(motor_observer_t fn, void *ctx)
{
    hal_irq_state_t s = hal_critical_enter();
    observer = fn;
    observer_ctx = ctx;
    hal_critical_exit(s);
}

void motor_identify_result(mc_id_result_t *r)
{
    mc_identify_result(&motor, r);
}

const mc_t *motor_view(void)
{
    return &motor;
}

void motor_copy(void *dst, const volatile void *src, uint8_t n)
{
    uint8_t *d = (uint8_t *)dst;
    const volatile uint8_t *p = (const volatile uint8_t *)src;
    hal_irq_state_t s = hal_critical_enter();
    while (n-- != 0U) {
        *d++ = *p++;
    }
    hal_critical_exit(s);
}
