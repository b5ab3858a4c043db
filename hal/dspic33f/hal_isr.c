/* hal_isr.c - the ADC interrupt trampoline and the mailbox to the one running motor. */
#include <stddef.h>

#include <xc.h>

#include "hal_dspic33f.h"
#include "hal_regs.h"

/*
 * The one mc_t of the running motor. It belongs to the ADC interrupt, which
 * steps it once per PWM period; the main loop reaches it only through the
 * hal_motor_* functions below, each of which runs the core's call with the
 * interrupt masked (hal_critical_enter: CPU priority 7), so a request never
 * lands mid-step and a status is the snapshot of one period. The masked time
 * is one short core call (a copy of mc_status_t at most), far below the
 * ~17 us of slack the ISR has (HAL_AD1_ADCS in hal_dspic33f.h); a conversion
 * that completes meanwhile keeps AD1IF set and is serviced on unmasking.
 */
static mc_t motor;

/* The optional observer (hal_motor_observe), read by the interrupt. */
static hal_motor_observer_t observer;
static void *observer_ctx;

/* mc_step() calls since the last window end (mc.h: the slow step follows
 * every MC_SLOW_STEP_PERIODS-th, counting from mc_init). */
static uint16_t slow_div;

/* Periods of bootstrap precharge still to come (HAL_P1OVDCON_PRECHARGE):
 * set by hal_motor_start(), the first 10 ms after power-up; the low
 * switches are on while the core keeps the outputs off, and the core
 * turning them on ends it at once. */
static uint16_t precharge_left;

/* Vector of the ADC: the four results are ready (SMPI = 0, one interrupt
 * per special-event conversion set). Clearing the flag first means an
 * overrun (a step longer than a period) re-enters at once instead of
 * silently skipping a period. The duties are written as soon as the
 * control part of the step has them, before the period boundary that
 * loads them (mc.h timing contract; docs/board.md "Timing"); the rest of
 * the step and the observer, if any, come after. */
void HAL_ISR_FAST _ADC1Interrupt(void)
{
    mc_adc_frame_t frame;
    mc_pwm_out_t out;

    hal_regs_timing_pin(true);
    IFS0bits.AD1IF = 0;
    hal_regs_adc_read(&frame);
    mc_step_control(&motor, &frame, &out);
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
    bool on = out.outputs_on;
    mc_step_finish(&motor, &out);
    if (on && !out.outputs_on) {
        P1OVDCON = HAL_P1OVDCON_OFF; /* the finishing part faulted (mc.h): off at once */
    }
    if (++slow_div >= MC_SLOW_STEP_PERIODS) {
        slow_div = 0U;
        IFS0bits.T2IF = 1; /* the window's slow step, as soon as this interrupt returns */
    }
    if (observer != NULL) {
        observer(observer_ctx, &motor);
    }
    hal_regs_timing_pin(false);
}

/* The slow step, pre-empted by the ADC interrupt (mc.h note 4). */
void HAL_ISR _T2Interrupt(void)
{
    IFS0bits.T2IF = 0;
    mc_slow_step(&motor);
}

void hal_motor_start(void)
{
    IEC0bits.AD1IE = 0;
    IEC0bits.T2IE = 0;
    mc_init(&motor);
    slow_div = 0U;
    precharge_left = HAL_PRECHARGE_PERIODS;
    IFS0bits.AD1IF = 0; /* a stale conversion is not a period of the new motor */
    IFS0bits.T2IF = 0;
    IEC0bits.T2IE = 1;
    IEC0bits.AD1IE = 1;
}

void hal_motor_request(mc_request_t request)
{
    hal_irq_state_t s = hal_critical_enter();
    mc_request(&motor, request);
    hal_critical_exit(s);
}

void hal_motor_set_reference(int16_t ref)
{
    hal_irq_state_t s = hal_critical_enter();
    mc_set_reference(&motor, ref);
    hal_critical_exit(s);
}

void hal_motor_status(mc_status_t *status)
{
    hal_irq_state_t s = hal_critical_enter();
    mc_status(&motor, status);
    hal_critical_exit(s);
}

/* Both words change together: masked, so the interrupt never sees a new
 * function with the old context. */
void hal_motor_observe(hal_motor_observer_t fn, void *ctx)
{
    hal_irq_state_t s = hal_critical_enter();
    observer = fn;
    observer_ctx = ctx;
    hal_critical_exit(s);
}

mc_t *hal_motor_core(void)
{
    return &motor;
}
