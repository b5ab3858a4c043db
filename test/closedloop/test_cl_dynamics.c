/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_cl_dynamics.c - load step, field weakening and parameter mismatch in closed loop. */
#include "cl_helpers.h"

/*
 * Load step: at 2,000 rpm a brake-like load of 50 % rated torque (0.05 N m)
 * is applied at once. Pass: closed loop throughout, and the true speed back
 * within 2 % of the reference (and staying there for 0.2 s) no later than
 * 100 ms after the step. Dip and recovery time are printed.
 */
static void test_core_should_recover_from_a_half_rated_load_step_within_100_ms(void **state)
{
    static simcore_t s;
    simcore_cfg_t cfg;
    double t_step, t_in = -1.0, dip = 0.0, ref;
    bool left = false;
    (void)state;
    simcore_cfg_default(&cfg);
    cl_setup(&s, &cfg, "hurst", "mclv");
    simcore_set_speed(&s, 2000.0);
    simcore_request(&s, MC_REQUEST_START);
    assert_cmp(cl_run_until_at_speed(&s, 2000.0, 1.0, 0.3, 10.0), >, 0.0);
    ref = s.now.speed_ref_rpm;
    cl_event(&s, SIM_EV_LOAD, 0.5 * s.rated_nm, 0.0);
    t_step = s.rig.t;
    while (s.rig.t < t_step + 0.6) {
        simcore_step(&s);
        if (s.now.state != MC_STATE_CLOSED_LOOP) {
            left = true;
        }
        dip = fmax(dip, (ref - s.now.speed_rpm) / ref);
        if (fabs(s.now.speed_rpm - ref) <= 0.02 * ref) {
            if (t_in < 0.0) {
                t_in = s.now.t_s;
            }
        } else {
            t_in = -1.0;
        }
        if (t_in > 0.0 && s.now.t_s - t_in >= 0.2) {
            break;
        }
    }
    printf("measured: 50 %% load step (%.4f N m) at 2000 rpm: dip %.1f %% (%.0f rpm), back "
           "within 2 %% after %.1f ms, closed loop throughout: %s, iq %.2f A\n",
           0.5 * s.rated_nm, 100.0 * dip, dip * ref, (t_in > 0.0) ? 1000.0 * (t_in - t_step) : -1.0,
           left ? "no" : "yes", s.now.iq_true_a);
    assert_false(left);
    assert_cmp(t_in, >, 0.0);
    assert_cmp(t_in - t_step, <=, 0.100);
}

/*
 * Field weakening: pot at full travel (SPEED_REF_MAX_RPM, 5,300 rpm) on the
 * 24 V bus, friction only. Pass: closed loop, mean true speed >= 5,000 rpm
 * over 0.5 s after the reference has arrived.
 */
static void test_hurst_should_reach_5000_rpm_with_field_weakening_on_24_v(void **state)
{
    static simcore_t s;
    simcore_cfg_t cfg;
    sim_window_t w;
    (void)state;
    simcore_cfg_default(&cfg);
    cl_setup(&s, &cfg, "hurst", "mclv");
    simcore_set_speed(&s, (double)SPEED_REF_MAX_RPM);
    simcore_request(&s, MC_REQUEST_START);
    cl_run_until_ref(&s, (double)SPEED_REF_MAX_RPM, 12.0);
    cl_run(&s, 0.5);
    cl_measure(&s, 0.5, &w);
    printf("measured: field weakening, pot at max (%.0f rpm) on %.0f V: true %.0f rpm (min %.0f), "
           "est %.0f rpm, id %.2f A, iq %.2f A, angle error mean %+.2f deg max %.2f deg, closed "
           "loop throughout: %s\n",
           (double)SPEED_REF_MAX_RPM, s.rig.inv.prm.vbus_v, sim_window_speed(&w), w.spd_min,
           sim_window_est(&w), s.now.id_true_a, s.now.iq_true_a, sim_window_ang_mean(&w), w.ang_max,
           (w.n_skipped > 0) ? "no" : "yes");
    assert_int_equal(w.n_skipped, 0); /* closed loop throughout */
    assert_cmp(sim_window_speed(&w), >=, 5000.0);
}

/*
 * Mismatch: the plant's R and L off by +-30 % and its back-EMF constant by
 * +-20 % from UserParms.h (all 8 corners). Pass: starts, reaches 2,000 rpm
 * (2 %), then holds it for 1 s: closed loop, mean speed error <= 1 %.
 */
static void test_core_should_start_and_hold_2000_rpm_with_mismatched_motor_parameters(void **state)
{
    int k, fails = 0;
    (void)state;
    for (k = 0; k < 8; k++) {
        static simcore_t s;
        simcore_cfg_t cfg;
        sim_window_t w;
        double t_at;
        simcore_cfg_default(&cfg);
        cfg.rs_scale = (k & 1) ? 1.3 : 0.7;
        cfg.l_scale = (k & 2) ? 1.3 : 0.7;
        cfg.ke_scale = (k & 4) ? 1.2 : 0.8;
        cfg.theta0_rad = 0.7 * k;
        cfg.seed = 77u + (uint32_t)k;
        cl_setup(&s, &cfg, "hurst", "mclv");
        simcore_set_speed(&s, 2000.0);
        simcore_request(&s, MC_REQUEST_START);
        t_at = cl_run_until_at_speed(&s, 2000.0, 2.0, 0.2, 10.0);
        cl_measure(&s, 1.0, &w);
        printf("measured: R x%.1f L x%.1f Ke x%.1f: at 2000 rpm after %.2f s; speed error "
               "%+.3f %%, angle error mean %+.2f deg rms %.2f deg; closed loop throughout: %s; "
               "state %s fault %s\n",
               cfg.rs_scale, cfg.l_scale, cfg.ke_scale, t_at, sim_window_speed_err_pct(&w),
               sim_window_ang_mean(&w), sim_window_ang_rms(&w), (w.n_skipped > 0) ? "no" : "yes",
               mc_state_name(s.now.state), mc_fault_name(s.now.fault));
        if (t_at < 0.0 || w.n_skipped > 0 || fabs(sim_window_speed_err_pct(&w)) > 1.0) {
            fails++;
        }
    }
    assert_int_equal(fails, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_core_should_recover_from_a_half_rated_load_step_within_100_ms),
        cmocka_unit_test(test_hurst_should_reach_5000_rpm_with_field_weakening_on_24_v),
        cmocka_unit_test(test_core_should_start_and_hold_2000_rpm_with_mismatched_motor_parameters),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
