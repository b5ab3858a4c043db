/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_cl_hispeed.c - the 2-pole-pair high-speed motor on the MCHV bus to 17,000 rpm. */
#include "cl_helpers.h"

/*
 * Core built for MCHV + hispeed (motor_hispeed.h), plant = the same assumed
 * motor (sim_profiles.c "hispeed"), 320 V bus, 2 us dead time, a fan load of
 * 20 mN m at 17,000 rpm. Pot at full travel (SPEED_REF_MAX_RPM = 17,000 rpm).
 * Pass: closed loop, mean true speed within 1 % of 17,000 rpm over 0.5 s,
 * every angle-error sample within 2 deg.
 */
static void test_high_speed_motor_should_reach_17000_rpm_on_the_mchv_bus(void **state)
{
    static simcore_t s;
    simcore_cfg_t cfg;
    sim_window_t w;
    double t0;
    (void)state;
    simcore_cfg_default(&cfg);
    cl_setup(&s, &cfg, "hispeed", "mchv");
    cl_event(&s, SIM_EV_LOAD_FAN, 0.02, 0.0);
    simcore_set_speed(&s, (double)SPEED_REF_MAX_RPM);
    simcore_request(&s, MC_REQUEST_START);
    t0 = s.rig.t;
    cl_run_until_ref(&s, (double)SPEED_REF_MAX_RPM, 30.0);
    cl_run(&s, 0.5);
    cl_measure(&s, 0.5, &w);
    printf("measured: high-speed motor, pot at max (%.0f rpm) on %.0f V: true %.0f rpm "
           "(min %.0f, max %.0f), est %.0f rpm, speed error %+.3f %%, angle error mean %+.2f deg "
           "rms %.2f deg max %.2f deg, iq %.2f A, reached after %.1f s, closed loop throughout: "
           "%s, state %s fault %s\n",
           (double)SPEED_REF_MAX_RPM, s.rig.inv.prm.vbus_v, sim_window_speed(&w), w.spd_min,
           w.spd_max, sim_window_est(&w), sim_window_speed_err_pct(&w), sim_window_ang_mean(&w),
           sim_window_ang_rms(&w), w.ang_max, s.now.iq_true_a, s.rig.t - t0,
           (w.n_skipped > 0) ? "no" : "yes", mc_state_name(s.now.state),
           mc_fault_name(s.now.fault));
    assert_int_equal(w.n_skipped, 0); /* closed loop throughout */
    assert_cmp(fabs(sim_window_speed(&w) - 17000.0), <=, 170.0);
    assert_cmp(w.ang_max, <=, 2.0);
}

/*
 * The lowest claimed speed, no load (the case that used to lose the rotor:
 * at 320 V the 2 us dead time is worth 12.8 V per phase, more than the
 * 11.5 V of back-EMF at 2,000 rpm). Pot at 0 (SPEED_REF_MIN_RPM): closed loop
 * at the speed (2 %, held 0.2 s), 0.5 s to settle, then over 1 s: no fault,
 * speed error <= 1 %, every angle-error sample within 2 deg.
 */
static void test_high_speed_motor_should_hold_its_lowest_speed_without_load(void **state)
{
    static simcore_t s;
    simcore_cfg_t cfg;
    sim_window_t w;
    (void)state;
    simcore_cfg_default(&cfg);
    cl_setup(&s, &cfg, "hispeed", "mchv");
    cl_start_and_reach(&s, (double)SPEED_REF_MIN_RPM, 10.0);
    cl_run(&s, 0.5);
    cl_measure(&s, 1.0, &w);
    printf(
        "measured: high-speed motor at its lowest speed SPEED_REF_MIN_RPM = %.0f rpm (%.1f %% of "
        "%.0f) on %.0f V, no load: speed error %+.3f %% (true %.1f, min %.0f, max %.0f rpm), "
        "angle error mean %+.2f deg rms %.2f deg max %.2f deg, closed loop throughout: %s, "
        "state %s fault %s\n",
        (double)SPEED_REF_MIN_RPM, 100.0 * SPEED_REF_MIN_RPM / SPEED_REF_MAX_RPM,
        (double)SPEED_REF_MAX_RPM, s.rig.inv.prm.vbus_v, sim_window_speed_err_pct(&w),
        sim_window_speed(&w), w.spd_min, w.spd_max, sim_window_ang_mean(&w), sim_window_ang_rms(&w),
        w.ang_max, (w.n_skipped > 0) ? "no" : "yes", mc_state_name(s.now.state),
        mc_fault_name(s.now.fault));
    assert_int_equal(w.n_skipped, 0); /* closed loop throughout */
    assert_int_equal(s.now.state, MC_STATE_CLOSED_LOOP);
    assert_cmp(fabs(sim_window_speed_err_pct(&w)), <=, 1.0);
    assert_cmp(fabs(sim_window_ang_mean(&w)), <=, 2.0);
    assert_cmp(w.ang_max, <=, 2.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_high_speed_motor_should_reach_17000_rpm_on_the_mchv_bus),
        cmocka_unit_test(test_high_speed_motor_should_hold_its_lowest_speed_without_load),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
