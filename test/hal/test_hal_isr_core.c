/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_hal_isr_core.c - the trampoline, motor.c and the real core: registers follow mc_step(). */
#include "test_support.h"

#include <stdio.h>

#include "sfr_standin.h"

#include "hal_dspic33f.h"
#include "motor.h"

/*
 * hal_isr.c + hal_dspic33f.c + firmware/motor.c + the real mc core, on the stand-in: the ADC
 * buffers are set as the converter would leave them (currents at mid-scale,
 * the nominal bus, the pot at mid travel), the vector is called once per
 * period, and after every call the PWM registers must hold exactly what the
 * core reports in mc_status (duties, outputs on/off).
 */

/* 10-bit code of a unipolar input at fraction x of full scale -> ADC1BUFx. */
static uint16_t raw_unipolar(double x)
{
    unsigned code = (unsigned)(x * 1024.0 + 0.5);
    return (uint16_t)((code ^ 0x200u) << 6);
}

static void set_converter(void)
{
    ADC1BUF0 = raw_unipolar(0.5);                                           /* pot */
    ADC1BUF1 = 0x0000u;                                                     /* ia: 0 A */
    ADC1BUF2 = 0x0000u;                                                     /* ib: 0 A */
    ADC1BUF3 = raw_unipolar(BOARD_VBUS_NOMINAL_V / BOARD_VBUS_FULLSCALE_V); /* vbus */
}

/* One period as the interrupt controller runs it: the ADC interrupt, then,
 * if it raised it, the slow step's (lower priority, so after it). */
static void period(void)
{
    IFS0bits.AD1IF = 1;
    _ADC1Interrupt();
    assert_int_equal(IFS0bits.AD1IF, 0);
    if (IFS0bits.T2IF && IEC0bits.T2IE) {
        _T2Interrupt();
    }
}

static void test_trampoline_should_write_what_the_core_reports_every_period(void **state)
{
    (void)state;
    mc_status_t st;
    unsigned n, on_periods = 0, mismatches = 0;

    sfr_standin_reset();
    hal_init();
    motor_start();
    assert_int_equal(IEC0bits.AD1IE, 1);
    set_converter();

    /* Stopped: the first 10 ms precharge the bootstrap capacitors (the three
     * low switches on), then every switch is off. */
    for (n = 0; n < (unsigned)HAL_PRECHARGE_PERIODS + 50u; n++) {
        period();
        assert_int_equal(P1OVDCON, n < (unsigned)HAL_PRECHARGE_PERIODS ? 0x0015 : 0x0000);
    }
    printf("measured: bootstrap precharge for %u periods (%.1f ms) after motor_start()\n",
           (unsigned)HAL_PRECHARGE_PERIODS, 1000.0 * HAL_PRECHARGE_PERIODS / PWM_FREQUENCY_HZ);
    motor_status(&st);
    assert_int_equal(st.state, MC_STATE_STOPPED);
    assert_int_equal(P1OVDCON, 0x0000);

    motor_request(MC_REQUEST_START_STOP);
    for (n = 0; n < 20000u; n++) { /* 1 s: calibrate, lock, open loop */
        period();
        motor_status(&st);
        if (P1DC1 != st.duty[0] || P1DC2 != st.duty[1] || P1DC3 != st.duty[2] ||
            P1OVDCON != (st.outputs_on ? 0x3F00u : 0x0000u)) {
            mismatches++;
        }
        on_periods += st.outputs_on ? 1u : 0u;
        assert_cmp(P1DC1, <=, PWM_DUTY_MAX);
        assert_cmp(P1DC2, <=, PWM_DUTY_MAX);
        assert_cmp(P1DC3, <=, PWM_DUTY_MAX);
    }
    printf("measured: 20000 periods after START: %u with outputs on, %u register/status "
           "mismatches, final state %d\n",
           on_periods, mismatches, (int)st.state);
    assert_int_equal(mismatches, 0);
    assert_cmp(on_periods, >, 0u); /* the core did turn the bridge on through the HAL */

    motor_request(MC_REQUEST_STOP);
    IFS0bits.AD1IF = 1;
    _ADC1Interrupt();
    motor_status(&st);
    assert_false(st.outputs_on);
    assert_int_equal(P1OVDCON, 0x0000);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_trampoline_should_write_what_the_core_reports_every_period),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
