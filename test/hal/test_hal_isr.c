/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_hal_isr.c - the HAL's interrupt trampoline alone, the firmware's hooks mocked (cmocka). */
#include "test_support.h"

#include "sfr_standin.h"

#include "hal_dspic33f.h"

/*
 * hal_isr.c + hal_dspic33f.c on the SFR stand-in, linked against mocks of
 * the three hooks hal.h asks the firmware for: what the trampoline hands
 * up, what it does with the answer, and in which order relative to the
 * registers. No core, no firmware header: the HAL stands alone.
 */

static hal_pwm_out_t last_out; /* what the control hook returned last */
static int the_ctx;            /* the object handed to hal_control_start() */

void hal_hook_control(void *ctx, const hal_adc_frame_t *in, hal_pwm_out_t *out)
{
    int ia = in->ia, ib = in->ib, vbus = in->vbus, pot = in->pot;

    function_called();
    assert_ptr_equal(ctx, &the_ctx);
    assert_int_equal(IFS0bits.AD1IF, 0); /* the flag is cleared before the hook */
#if HAL_TIMING_PIN_PORT == HAL_PORT_C
    assert_int_equal((LATC >> HAL_TIMING_PIN_BIT) & 1u, 1u); /* high for the whole interrupt */
#endif
    assert_int_equal(P1DC1, 0xAAAA); /* the duties are written after it */
    check_expected(ia);
    check_expected(ib);
    check_expected(vbus);
    check_expected(pot);
    out->duty[0] = (uint16_t)mock();
    out->duty[1] = (uint16_t)mock();
    out->duty[2] = (uint16_t)mock();
    out->outputs_on = (bool)mock();
    last_out = *out;
}

/* The finishing hook comes after the duties and the pins; it may switch
 * the outputs off. */
void hal_hook_finish(void *ctx, hal_pwm_out_t *out)
{
    function_called();
    assert_ptr_equal(ctx, &the_ctx);
    assert_memory_equal(out, &last_out, sizeof *out);
    assert_int_equal(P1DC1, last_out.duty[0]);
    assert_int_equal(P1DC2, last_out.duty[1]);
    assert_int_equal(P1DC3, last_out.duty[2]);
    assert_int_equal(P1OVDCON & 0x3F00u, last_out.outputs_on ? 0x3F00u : 0u);
    assert_int_equal(IFS0bits.T2IF, 0); /* the slow interrupt is raised after it */
    if ((bool)mock()) {
        hal_pwm_off();
    }
}

void hal_hook_slow(void *ctx)
{
    function_called();
    assert_ptr_equal(ctx, &the_ctx);
    assert_int_equal(IFS0bits.T2IF, 0); /* cleared first */
}

/* off_in_finish: the finishing hook calls hal_pwm_off(). */
static void expect_period(int ia, int ib, int vbus, int pot, uint16_t d0, uint16_t d1, uint16_t d2,
                          bool on, bool off_in_finish)
{
    expect_function_call(hal_hook_control);
    expect_value(hal_hook_control, ia, ia);
    expect_value(hal_hook_control, ib, ib);
    expect_value(hal_hook_control, vbus, vbus);
    expect_value(hal_hook_control, pot, pot);
    will_return(hal_hook_control, d0);
    will_return(hal_hook_control, d1);
    will_return(hal_hook_control, d2);
    will_return(hal_hook_control, on);
    expect_function_call(hal_hook_finish);
    will_return(hal_hook_finish, off_in_finish);
}

/* Before any period: marks that the mock sees the duties unwritten. */
static void mark_duties(void)
{
    P1DC1 = P1DC2 = P1DC3 = 0xAAAAu;
}

/* Started with the_ctx, one period with the outputs on behind it (so the
 * bootstrap precharge is over), then the registers back to reset. */
static int setup(void **state)
{
    (void)state;
    sfr_standin_reset();
    hal_control_start(&the_ctx, 20U);
    mark_duties();
    expect_period(0, 0, 16384, 16384, 1000u, 1000u, 1000u, true, false);
    _ADC1Interrupt();
    sfr_standin_reset();
    mark_duties();
    return 0;
}

static void
test_adc_isr_should_clear_the_flag_read_four_buffers_and_write_the_hooks_duties(void **state)
{
    (void)state;
    /* Buffers: CH0 pot (AN8), CH1 IA (AN0), CH2 IB (AN1), CH3 VBUS (AN2). */
    ADC1BUF0 = 0x4000u; /* 3/4 of AVDD     -> pot 24576 */
    ADC1BUF1 = 0x0040u; /* one code above mid -> ia  +/-64 */
    ADC1BUF2 = 0xFF80u; /* two codes below    -> ib  -/+128 */
    ADC1BUF3 = 0xC000u; /* 1/4 of AVDD     -> vbus 8192 */
    IFS0bits.AD1IF = 1;
    expect_period(64 * HAL_BOARD_I_SIGN, -128 * HAL_BOARD_I_SIGN, 8192, 24576, 11u, 1000u, 1999u,
                  true, false);

    _ADC1Interrupt();

    assert_int_equal(IFS0bits.AD1IF, 0);
#if HAL_TIMING_PIN_PORT == HAL_PORT_C
    assert_int_equal((LATC >> HAL_TIMING_PIN_BIT) & 1u, 0u);  /* low again after it */
    assert_int_equal(LATC & ~(1u << HAL_TIMING_PIN_BIT), 0u); /* no other bit touched */
#endif
    assert_int_equal(P1DC1, 11);
    assert_int_equal(P1DC2, 1000);
    assert_int_equal(P1DC3, 1999);
    assert_int_equal(P1OVDCON, 0x3F00);
}

static void test_adc_isr_should_override_the_outputs_off_when_the_hook_says_off(void **state)
{
    (void)state;
    P1OVDCON = 0x3F00u;
    /* Buffers at 0 = mid-scale: zero current, half of vbus and pot. */
    expect_period(0, 0, 16384, 16384, 1000u, 1000u, 1000u, false, false);
    _ADC1Interrupt();
    assert_int_equal(P1OVDCON, 0x0000);
    assert_int_equal(P1DC1, 1000);
}

/* hal_pwm_off() from the finishing hook: off in the same interrupt, the
 * duties left as written (the override wins). */
static void test_pwm_off_from_the_finishing_hook_should_switch_off_at_once(void **state)
{
    (void)state;
    expect_period(0, 0, 16384, 16384, 900u, 1000u, 1100u, true, true);
    _ADC1Interrupt();
    assert_int_equal(P1OVDCON, 0x0000);
    assert_int_equal(P1DC1, 900);
    assert_int_equal(P1DC3, 1100);
}

/* The bootstrap precharge after hal_control_start(): the low switches on
 * while the hooks keep the outputs off, for HAL_PRECHARGE_PERIODS; a hook
 * turning the outputs on ends it at once, for good. */
static void
test_adc_isr_should_precharge_after_start_until_the_hook_turns_the_outputs_on(void **state)
{
    (void)state;
    hal_control_start(&the_ctx, 20U);
    expect_period(0, 0, 16384, 16384, 1000u, 1000u, 1000u, false, false);
    _ADC1Interrupt();
    assert_int_equal(P1OVDCON, 0x0015);
    assert_int_equal(P1DC1, 1000);
    mark_duties();
    expect_period(0, 0, 16384, 16384, 900u, 1000u, 1100u, true, false);
    _ADC1Interrupt();
    assert_int_equal(P1OVDCON, 0x3F00);
    mark_duties();
    expect_period(0, 0, 16384, 16384, 1000u, 1000u, 1000u, false, false);
    _ADC1Interrupt();
    assert_int_equal(P1OVDCON, 0x0000); /* not again before the next hal_control_start() */
}

static void test_control_start_should_drop_stale_flags_then_enable_both_interrupts(void **state)
{
    (void)state;
    IEC0bits.AD1IE = 1;
    IFS0bits.AD1IF = 1;
    IFS0bits.T2IF = 1;
    hal_control_start(&the_ctx, 20U);
    assert_int_equal(IFS0bits.AD1IF, 0);
    assert_int_equal(IFS0bits.T2IF, 0);
    assert_int_equal(IEC0bits.AD1IE, 1);
    assert_int_equal(IEC0bits.T2IE, 1);
    hal_control_stop();
    assert_int_equal(IEC0bits.AD1IE, 0);
    assert_int_equal(IEC0bits.T2IE, 0);
}

/* The slow interrupt after every slow_periods-th period counted from
 * hal_control_start(), for a divider of 1, the core's 20 and the largest. */
static void test_adc_isr_should_raise_the_slow_interrupt_every_slow_periods_from_start(void **state)
{
    static const uint16_t dividers[] = {1U, 20U, 65535U};
    (void)state;
    for (unsigned d = 0; d < sizeof dividers / sizeof dividers[0]; d++) {
        uint16_t n = dividers[d];
        hal_control_start(&the_ctx, n);
        for (unsigned w = 0; w < 2U; w++) {
            for (uint32_t k = 1; k <= n; k++) {
                mark_duties();
                expect_period(0, 0, 16384, 16384, 1000u, 1000u, 1000u, false, false);
                _ADC1Interrupt();
                /* Raised by the last period of each run of n, not before. */
                assert_int_equal(IFS0bits.T2IF, (k == n) ? 1 : 0);
            }
            expect_function_call(hal_hook_slow);
            _T2Interrupt();
            assert_int_equal(IFS0bits.T2IF, 0);
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(
            test_adc_isr_should_clear_the_flag_read_four_buffers_and_write_the_hooks_duties, setup),
        cmocka_unit_test_setup(test_adc_isr_should_override_the_outputs_off_when_the_hook_says_off,
                               setup),
        cmocka_unit_test_setup(test_pwm_off_from_the_finishing_hook_should_switch_off_at_once,
                               setup),
        cmocka_unit_test_setup(
            test_adc_isr_should_precharge_after_start_until_the_hook_turns_the_outputs_on, setup),
        cmocka_unit_test_setup(
            test_control_start_should_drop_stale_flags_then_enable_both_interrupts, setup),
        cmocka_unit_test_setup(
            test_adc_isr_should_raise_the_slow_interrupt_every_slow_periods_from_start, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
