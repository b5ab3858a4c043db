/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_motor.c - firmware/motor.c over the dsPIC HAL: the hooks and the mailbox, the core mocked
 * (cmocka). */
#include "test_support.h"

#include <string.h>

#include "sfr_standin.h"

#include "hal_dspic33f.h"
#include "motor.h"

/*
 * motor.c and the HAL's trampoline (hal_isr.c, hal_dspic33f.c on the SFR
 * stand-in) are linked here against the mocks below instead of the core,
 * so the test sees exactly what reaches mc_step_control() and what becomes
 * of the answer, in which order relative to the registers, and that the
 * mailbox masks the interrupts around every core call.
 */

static mc_t *seen_mc; /* the instance the first core call received */

static void check_same_motor(mc_t *mc)
{
    if (seen_mc == NULL) {
        seen_mc = mc;
    }
    assert_ptr_equal(mc, seen_mc);
}

void mc_init(mc_t *mc)
{
    function_called();
    check_same_motor(mc);
    assert_int_equal(IEC0bits.AD1IE, 0); /* not stepped while being reset */
}

static mc_pwm_out_t last_out; /* what the control part returned last */

void mc_step_control(mc_t *mc, const mc_adc_frame_t *in, mc_pwm_out_t *out)
{
    int ia = in->ia, ib = in->ib, vbus = in->vbus, pot = in->pot;

    function_called();
    check_same_motor(mc);
    /* The flag is cleared before the step, the duties written after it. */
    assert_int_equal(IFS0bits.AD1IF, 0);
#if HAL_TIMING_PIN_PORT == HAL_PORT_C
    assert_int_equal((LATC >> HAL_TIMING_PIN_BIT) & 1u, 1u); /* high for the whole interrupt */
#endif
    assert_int_equal(P1DC1, 0xAAAA);
    assert_int_equal(P1DC2, 0xAAAA);
    assert_int_equal(P1DC3, 0xAAAA);
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

/* The rest of the step comes after the duties and the pins: they are
 * already in the registers when it runs (mc.h timing contract). */
bool mc_step_finish(mc_t *mc, mc_pwm_out_t *out)
{
    function_called();
    check_same_motor(mc);
    assert_int_equal(out->duty[0], last_out.duty[0]); /* the same out */
    assert_int_equal(out->duty[1], last_out.duty[1]);
    assert_int_equal(out->duty[2], last_out.duty[2]);
    assert_int_equal(out->outputs_on, last_out.outputs_on);
    assert_int_equal(P1DC1, last_out.duty[0]);
    assert_int_equal(P1DC2, last_out.duty[1]);
    assert_int_equal(P1DC3, last_out.duty[2]);
    assert_int_equal(P1OVDCON & 0x3F00u, last_out.outputs_on ? 0x3F00u : 0u);
    assert_int_equal(IFS0bits.T2IF, 0); /* the window's slow step is triggered after it */
    bool off = (bool)mock();
    if (off) { /* this part faulted */
        out->duty[0] = PWM_DUTY_MAX / 2U;
        out->duty[1] = PWM_DUTY_MAX / 2U;
        out->duty[2] = PWM_DUTY_MAX / 2U;
        out->outputs_on = false;
    }
    return off;
}

void mc_slow_step(mc_t *mc)
{
    function_called();
    check_same_motor(mc);
    assert_int_equal(IFS0bits.T2IF, 0); /* cleared first */
}

void mc_request(mc_t *mc, mc_request_t r)
{
    int request = (int)r;
    check_same_motor(mc);
    assert_int_equal(SRbits.IPL, 7);
    check_expected(request);
}

uint8_t mc_set_reference(mc_t *mc, int16_t ref)
{
    int value = ref;
    check_same_motor(mc);
    assert_int_equal(SRbits.IPL, 7);
    check_expected(value);
    return (uint8_t)mock();
}

void mc_status(const mc_t *mc, mc_status_t *st)
{
    check_same_motor((mc_t *)(uintptr_t)mc);
    assert_int_equal(SRbits.IPL, 7);
    memset(st, 0, sizeof *st);
    st->state = (mc_state_t)mock();
    st->fault = (uint16_t)mock();
    st->ref_seq = 42U;
}

/* Unmasked: its 64-bit conversions must not hold the interrupts off (motor.h). */
void mc_identify_result(const mc_t *mc, mc_id_result_t *r)
{
    check_same_motor((mc_t *)(uintptr_t)mc);
    assert_int_equal(SRbits.IPL, 0);
    memset(r, 0, sizeof *r);
    r->status = (mc_id_status_t)mock();
    r->rs_uohm = (uint32_t)mock();
}

int16_t mc_get_gain(const mc_t *mc, mc_gain_t g)
{
    int gain = (int)g;
    check_same_motor((mc_t *)(uintptr_t)mc);
    assert_int_equal(SRbits.IPL, 7);
    check_expected(gain);
    return (int16_t)mock();
}

bool mc_set_gain(mc_t *mc, mc_gain_t g, int16_t v)
{
    int gain = (int)g, value = v;
    check_same_motor(mc);
    assert_int_equal(SRbits.IPL, 7);
    check_expected(gain);
    check_expected(value);
    return (bool)mock();
}

static void expect_step(int ia, int ib, int vbus, int pot, uint16_t d0, uint16_t d1, uint16_t d2,
                        bool on)
{
    expect_function_call(mc_step_control);
    expect_value(mc_step_control, ia, ia);
    expect_value(mc_step_control, ib, ib);
    expect_value(mc_step_control, vbus, vbus);
    expect_value(mc_step_control, pot, pot);
    will_return(mc_step_control, d0);
    will_return(mc_step_control, d1);
    will_return(mc_step_control, d2);
    will_return(mc_step_control, on);
    expect_function_call(mc_step_finish);
    will_return(mc_step_finish, false);
}

/* The motor started (its object handed to the HAL as the hooks' context),
 * one period with the outputs on behind it (so the bootstrap precharge is
 * over), then the registers back to reset. */
static int setup(void **state)
{
    (void)state;
    sfr_standin_reset();
    expect_function_call(mc_init);
    motor_start();
    P1DC1 = 0xAAAAu;
    P1DC2 = 0xAAAAu;
    P1DC3 = 0xAAAAu;
    expect_step(0, 0, 16384, 16384, 1000u, 1000u, 1000u, true);
    _ADC1Interrupt();
    sfr_standin_reset();
    P1DC1 = 0xAAAAu;
    P1DC2 = 0xAAAAu;
    P1DC3 = 0xAAAAu;
    return 0;
}

static void
test_adc_isr_should_clear_the_flag_read_four_buffers_step_the_core_and_write_three_duties(
    void **state)
{
    (void)state;
    /* Buffers: CH0 pot (AN8), CH1 IA (AN0), CH2 IB (AN1), CH3 VBUS (AN2). */
    ADC1BUF0 = 0x4000u; /* 3/4 of AVDD     -> pot 24576 */
    ADC1BUF1 = 0x0040u; /* one code above mid -> ia  +/-64 */
    ADC1BUF2 = 0xFF80u; /* two codes below    -> ib  -/+128 */
    ADC1BUF3 = 0xC000u; /* 1/4 of AVDD     -> vbus 8192 */
    IFS0bits.AD1IF = 1;
    expect_step(64 * HAL_BOARD_I_SIGN, -128 * HAL_BOARD_I_SIGN, 8192, 24576, 11u, 1000u, 1999u,
                true);

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

/* A fault the core's finishing part raises (mc_step_finish turns out off)
 * switches the outputs off in the same interrupt, after the duties. */
static void test_adc_isr_should_switch_off_at_once_when_the_finishing_part_faults(void **state)
{
    (void)state;
    P1OVDCON = 0x0000u;
    expect_function_call(mc_step_control);
    expect_value(mc_step_control, ia, 0);
    expect_value(mc_step_control, ib, 0);
    expect_value(mc_step_control, vbus, 16384);
    expect_value(mc_step_control, pot, 16384);
    will_return(mc_step_control, 900u);
    will_return(mc_step_control, 1000u);
    will_return(mc_step_control, 1100u);
    will_return(mc_step_control, true);
    expect_function_call(mc_step_finish);
    will_return(mc_step_finish, true);
    _ADC1Interrupt();
    assert_int_equal(P1OVDCON, 0x0000);
    assert_int_equal(P1DC1, 900); /* the PWM already had them; the override wins */
}

static void test_motor_start_should_init_the_core_then_enable_the_adc_interrupt(void **state)
{
    (void)state;
    IEC0bits.AD1IE = 1;
    IFS0bits.AD1IF = 1;
    IFS0bits.T2IF = 1;
    expect_function_call(mc_init);
    motor_start();
    assert_int_equal(IFS0bits.AD1IF, 0);
    assert_int_equal(IFS0bits.T2IF, 0);
    assert_int_equal(IEC0bits.AD1IE, 1);
    assert_int_equal(IEC0bits.T2IE, 1);
}

/* The slow interrupt every MC_SLOW_STEP_PERIODS-th period counted from
 * motor_start(), which is when the core ends its windows (mc.h), and its
 * hook runs mc_slow_step on the same motor. */
static void test_adc_isr_should_raise_the_slow_step_interrupt_after_every_window_counted_from_start(
    void **state)
{
    (void)state;
    expect_function_call(mc_init);
    motor_start();
    for (unsigned w = 0; w < 3U; w++) {
        for (unsigned k = 1; k <= MC_SLOW_STEP_PERIODS; k++) {
            P1DC1 = 0xAAAAu; /* the mock's marker: not yet written this period */
            P1DC2 = 0xAAAAu;
            P1DC3 = 0xAAAAu;
            expect_step(0, 0, 16384, 16384, 1000u, 1000u, 1000u, false);
            _ADC1Interrupt();
            /* Raised by the window's last step, not before. */
            assert_int_equal(IFS0bits.T2IF, (k == MC_SLOW_STEP_PERIODS) ? 1 : 0);
        }
        expect_function_call(mc_slow_step);
        _T2Interrupt();
        assert_int_equal(IFS0bits.T2IF, 0);
    }
}

static void test_motor_mailbox_should_call_the_core_with_interrupts_masked(void **state)
{
    (void)state;
    mc_status_t st;

    SRbits.IPL = 0;
    expect_value(mc_request, request, MC_REQUEST_START_STOP);
    motor_request(MC_REQUEST_START_STOP);
    assert_int_equal(SRbits.IPL, 0);

    expect_value(mc_set_reference, value, -1234);
    will_return(mc_set_reference, 42); /* the choice's number, handed back */
    assert_int_equal(motor_set_reference(-1234), 42);
    assert_int_equal(SRbits.IPL, 0);

    expect_value(mc_set_gain, gain, MC_GAIN_SPD_KP);
    expect_value(mc_set_gain, value, 1234);
    will_return(mc_set_gain, true);
    assert_true(motor_set_gain(MC_GAIN_SPD_KP, 1234));
    assert_int_equal(SRbits.IPL, 0);

    expect_value(mc_get_gain, gain, MC_GAIN_SPD_KP);
    will_return(mc_get_gain, 1234);
    assert_int_equal(motor_get_gain(MC_GAIN_SPD_KP), 1234);
    assert_int_equal(SRbits.IPL, 0);

    will_return(mc_status, MC_STATE_FAULT);
    will_return(mc_status, MC_FAULT_HARDWARE);
    motor_status(&st);
    assert_int_equal(st.state, MC_STATE_FAULT);
    assert_int_equal(st.fault, MC_FAULT_HARDWARE);
    assert_int_equal(SRbits.IPL, 0);
}

static void test_motor_identify_result_should_read_the_core_unmasked(void **state)
{
    (void)state;
    mc_id_result_t r;
    SRbits.IPL = 0;
    will_return(mc_identify_result, MC_ID_DONE);
    will_return(mc_identify_result, 2670000);
    motor_identify_result(&r);
    assert_int_equal(r.status, MC_ID_DONE);
    assert_int_equal(r.rs_uohm, 2670000);
    assert_int_equal(SRbits.IPL, 0);
}

static unsigned observed;

static void observer_spy(void *ctx, const mc_t *mc)
{
    assert_ptr_equal(ctx, &observed);
    check_same_motor((mc_t *)(uintptr_t)mc);
    /* After the duties: the registers already hold this period's output. */
    assert_int_equal(P1DC1, 7);
    assert_int_equal(P1DC3, 9);
    observed++;
}

static void test_adc_isr_should_call_the_observer_after_the_duties_until_removed(void **state)
{
    (void)state;
    observed = 0;
    motor_observe(observer_spy, &observed);
    assert_int_equal(SRbits.IPL, 0);
    expect_step(0, 0, 16384, 16384, 7u, 8u, 9u, true);
    _ADC1Interrupt();
    assert_int_equal(observed, 1);
    motor_observe(NULL, NULL);
    setup(NULL);
    expect_step(0, 0, 16384, 16384, 7u, 8u, 9u, true);
    _ADC1Interrupt();
    assert_int_equal(observed, 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(
            test_adc_isr_should_clear_the_flag_read_four_buffers_step_the_core_and_write_three_duties,
            setup),
        cmocka_unit_test_setup(
            test_adc_isr_should_switch_off_at_once_when_the_finishing_part_faults, setup),
        cmocka_unit_test_setup(test_adc_isr_should_call_the_observer_after_the_duties_until_removed,
                               setup),
        cmocka_unit_test_setup(test_motor_start_should_init_the_core_then_enable_the_adc_interrupt,
                               setup),
        cmocka_unit_test_setup(
            test_adc_isr_should_raise_the_slow_step_interrupt_after_every_window_counted_from_start,
            setup),
        cmocka_unit_test_setup(test_motor_mailbox_should_call_the_core_with_interrupts_masked,
                               setup),
        cmocka_unit_test_setup(test_motor_identify_result_should_read_the_core_unmasked, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
