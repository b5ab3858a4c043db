/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* variant_mc_torque.c - the core built with TORQUEMODE: the pot sets Iq, the speed loop is off. */
#include "test_support.h"

#include <math.h>
#include <stdlib.h>
#include <stdio.h>

#include "mc_bench.h"
#include "mc_internal.h"

#if !MC_TORQUE_MODE
#error "variant_mc_torque.c must be built against the torque-mode core (mc_torque)"
#endif

static mc_bench_t b;

/* Two windows of steps (each with its slow step): a reference posted at a
 * window end comes back at the next one (mc.h note 4). */
static void run_two_windows(mc_t *mc, const mc_adc_frame_t *f)
{
    mc_pwm_out_t out;
    for (uint16_t k = 0U; k < 2U * MC_SLOW_STEP_PERIODS; k++) {
        mc_step(mc, f, &out);
        mc_slow_step(mc);
    }
}

static void test_torque_mode_should_map_the_pot_onto_the_iq_reference(void **state)
{
    (void)state;
    mc_t mc;
    mc_init(&mc);
    mc_status_t st;
    mc_adc_frame_t f = {0, 0, MC_VBUS_NOMINAL_Q15, 16384};
    run_two_windows(&mc, &f);
    /* The target is the pot's Iq; the speed target does not move. */
    assert_int_equal(mc.torque_target, mc_pot_to_torque(16384));
    mc_status(&mc, &st);
    assert_int_equal(st.speed_target, MC_SPEED_REF_MIN_Q15);
    /* Remote: an Iq reference, clamped to +-MOTOR_CURRENT_MAX_A. */
    mc_set_reference(&mc, 32767);
    run_two_windows(&mc, &f);
    assert_int_equal(mc.torque_target, MC_IQ_MAX_Q15);
    mc_set_reference(&mc, -32768);
    run_two_windows(&mc, &f);
    assert_int_equal(mc.torque_target, -MC_IQ_MAX_Q15);
    mc_request(&mc, MC_REQUEST_REF_POT);
    run_two_windows(&mc, &f);
    assert_int_equal(mc.torque_target, mc_pot_to_torque(16384));
}

static void
test_torque_mode_should_hold_the_pot_current_in_closed_loop_and_let_speed_follow_load(void **state)
{
    (void)state;
    mc_bench_cfg_t c;
    mc_bench_cfg_default(&c);
    c.pot = 0.0125; /* 0.025 A: friction holds it near 1600 rpm */
    mc_bench_init(&b, &c);
    mc_request(&b.mc, MC_REQUEST_START);
    long n = mc_bench_run_until(&b, MC_STATE_CLOSED_LOOP, 4L * PWM_FREQUENCY_HZ);
    assert_cmp(n, >, 0);
    double rpm_light = 0.0;
    for (long k = 0; k < 2L * PWM_FREQUENCY_HZ; k++) {
        mc_bench_step(&b);
        assert_int_equal(b.st.state, MC_STATE_CLOSED_LOOP);
        if (k > 2L * MC_SLOW_STEP_PERIODS) {
            /* Iq is the slow step's torque target, the pot read at a window
             * end: within the pot's ADC noise of the present reading. */
            assert_int_equal(b.st.iq_ref, b.mc.torque_target);
            /* 4 codes of the 10-bit pot reading (64 Q15 counts each). */
            assert_cmp(abs(b.mc.torque_target - mc_pot_to_torque(b.frame.pot)), <=,
                       mc_pot_to_torque(4 * 64));
        }
        rpm_light = b.rpm_sample;
    }
    /* More load at the same current: the speed falls, the current stays. */
    b.rig.plant.load.active_nm = 0.0003;
    double rpm_loaded = 0.0;
    err_stats_t e;
    err_stats_init(&e);
    for (long k = 0; k < 2L * PWM_FREQUENCY_HZ; k++) {
        mc_bench_step(&b);
        rpm_loaded = b.rpm_sample;
        if (k > PWM_FREQUENCY_HZ) {
            err_stats_add(&e, (b.st.iq - b.st.iq_ref) * BOARD_I_FULLSCALE_A / 32768.0, (double)k);
        }
    }
    printf("measured: torque mode, Iq ref %.3f A: %.0f rpm light, %.0f rpm with 0.3 mN m more\n",
           b.st.iq_ref * BOARD_I_FULLSCALE_A / 32768.0, rpm_light, rpm_loaded);
    err_stats_print("torque mode Iq - Iq ref (loaded)", &e, "A");
    assert_cmp(rpm_loaded, <, rpm_light - 50.0);
    assert_cmp(fabs(err_stats_mean(&e)), <, 0.02);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_torque_mode_should_map_the_pot_onto_the_iq_reference),
        cmocka_unit_test(
            test_torque_mode_should_hold_the_pot_current_in_closed_loop_and_let_speed_follow_load),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
