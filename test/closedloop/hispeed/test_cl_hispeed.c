/* test_cl_hispeed.c - the 2-pole-pair high-speed motor on the MCHV bus to 17,000 rpm. */
#include "cl_helpers.h"

/*
 * Core built for MCHV + hispeed (motor_hispeed.h), plant = the same assumed
 * motor (sim_profiles.c "hispeed"), 320 V bus, 2 us dead time, a fan load of
 * 20 mN m at 17,000 rpm. Pot at full travel (SPEED_REF_MAX_RPM = 17,000 rpm).
 * Pass: closed loop, mean true speed within 1 % of 17,000 rpm over 0.5 s.
 */
static void test_high_speed_motor_should_reach_17000_rpm_on_the_mchv_bus(void **state)
{
    static simcore_t s;
    simcore_cfg_t cfg;
    cl_window_t w;
    double t0;
    (void)state;
    simcore_cfg_default(&cfg);
    cl_setup(&s, &cfg, "hispeed", "mchv");
    cl_event(&s, SIM_EV_LOAD_FAN, 0.02, 0.0);
    simcore_set_speed(&s, (double)SPEED_REF_MAX_RPM);
    simcore_request(&s, MC_REQUEST_START);
    t0 = s.rig.t;
    while (s.rig.t < t0 + 30.0 && !(s.now.state == MC_STATE_CLOSED_LOOP &&
                                    s.now.speed_ref_rpm >= 0.999 * (double)SPEED_REF_MAX_RPM)) {
        simcore_step(&s);
        if (s.now.state == MC_STATE_FAULT) {
            break;
        }
    }
    cl_run(&s, 0.5);
    cl_measure(&s, 0.5, &w);
    printf("measured: high-speed motor, pot at max (%.0f rpm) on %.0f V: true %.0f rpm "
           "(min %.0f, max %.0f), est %.0f rpm, speed error %+.3f %%, angle error mean %+.2f deg "
           "rms %.2f deg, iq %.2f A, reached after %.1f s, closed loop throughout: %s, state %s "
           "fault %s\n",
           (double)SPEED_REF_MAX_RPM, s.rig.inv.prm.vbus_v, cl_speed(&w), w.spd_min, w.spd_max,
           w.est_sum / (double)(w.n > 0 ? w.n : 1), cl_speed_err_pct(&w), cl_ang_mean(&w),
           cl_ang_rms(&w), s.now.iq_true_a, s.rig.t - t0, w.left_closed_loop ? "no" : "yes",
           simcore_state_name(s.now.state), simcore_fault_name(s.now.fault));
    assert_false(w.left_closed_loop);
    assert_true(fabs(cl_speed(&w) - 17000.0) <= 170.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_high_speed_motor_should_reach_17000_rpm_on_the_mchv_bus),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
