/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* hal_isr.c - the ADC interrupt trampoline and the slow interrupt, calling the firmware's hooks. */
#include <xc.h>

#include "hal_dspic33f.h"
#include "hal_regs.h"

/* The firmware's object, handed back to every hook, the periods between
 * slow interrupts (hal_control_start), and the periods counted since the
 * last one. */
static void *hook_ctx;
static uint16_t slow_periods;
static uint16_t slow_div;

/* Periods of bootstrap precharge still to come (HAL_P1OVDCON_PRECHARGE):
 * set by hal_control_start(), the first 10 ms after power-up; the low
 * switches are on while the hooks keep the outputs off, and a hook turning
 * them on ends it at once. */
static uint16_t precharge_left;

/* Vector of the ADC: the four results are ready (SMPI = 0, one interrupt
 * per special-event conversion set). Clearing the flag first means an
 * overrun (a period's work longer than a period) re-enters at once instead
 * of silently skipping a period. The duties are written as soon as the
 * control hook has them, before the period boundary that loads them
 * (docs/design.md timing contract; docs/board.md "Timing"); the finishing
 * hook comes after. */
void HAL_ISR_FAST _ADC1Interrupt(void)
{
    hal_adc_frame_t frame;
    hal_pwm_out_t out;

    hal_regs_timing_pin(true);
    IFS0bits.AD1IF = 0;
    hal_regs_adc_read(&frame);
    hal_hook_control(hook_ctx, &frame, &out);
    hal_regs_duty_write(&out);
    if (out.outputs_on) {
        precharge_left = 0U;
        P1OVDCON = HAL_P1OVDCON_PWM;
    } else if (precharge_left != 0U) {
        precharge_left--;
        P1OVDCON = HAL_P1OVDCON_PRECHARGE;
    } else {
        P1OVDCON = HAL_P1OVDCON_OFF;
    }
    hal_hook_finish(hook_ctx, &out);
    if (++slow_div >= slow_periods) {
        slow_div = 0U;
        IFS0bits.T2IF = 1; /* the slow interrupt, as soon as this one returns */
    }
    hal_regs_timing_pin(false);
}

/* The slow hook, pre-empted by the ADC interrupt. */
void HAL_ISR _T2Interrupt(void)
{
    IFS0bits.T2IF = 0;
    hal_hook_slow(hook_ctx);
}

void hal_control_stop(void)
{
    IEC0bits.AD1IE = 0;
    IEC0bits.T2IE = 0;
}

void hal_control_start(void *ctx, uint16_t periods)
{
    hal_control_stop();
    hook_ctx = ctx;
    slow_periods = periods;
    slow_div = 0U;
    precharge_left = HAL_PRECHARGE_PERIODS;
    IFS0bits.AD1IF = 0; /* a stale conversion is not a period of the new start */
    IFS0bits.T2IF = 0;
    IEC0bits.T2IE = 1;
    IEC0bits.AD1IE = 1;
}
