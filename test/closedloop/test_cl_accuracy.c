/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_cl_accuracy.c - steady-state angle and speed error of the sensorless loop. */
#include "cl_helpers.h"

/*
 * At each speed: start at rest, pot at the speed, wait for closed loop at
 * the speed (2 %, held 0.2 s), let it settle 0.5 s, then measure over 1 s:
 *   speed error  = mean true speed vs mean reference   <= 1 %
 *   angle error  = mean of (estimated - true) electrical angle  <= 0.3 deg
 *                  (the bias the chip's timing leaves: sample at the
 *                  midpoint plus 2 us, duties from the next boundary; with
 *                  the old whole-period timing assumed in the core the
 *                  bias is -1.7 deg at 2000 rpm, -2.3 deg loaded),
 *                  and every sample (the max over 1 s, at least 8
 *                  mechanical turns at 500 rpm) <= 2 deg; at the lowest
 *                  claimed speed <= 2.5 deg: there the max is set by the
 *                  ADC noise, 1.4 to 2.25 deg over eight noise seeds for the
 *                  Hurst at 500 rpm (docs/tuning.md)
 * (rms printed). Default bench: 2 us dead time, ADC noise
 * sigma 1 code, amplifier offsets, friction only (15.3e-6 N m s/rad + 0.5 mN m).
 * The lowest speed is the lowest closed-loop speed the build claims,
 * SPEED_REF_MIN_RPM (its ratio to SPEED_REF_MAX_RPM is printed).
 */
/* One steady-state window at rpm and load, the plant sampling at sample_at
 * of the period (< 0: the chip's, as the core assumes), on the inverter
 * model given (sim_inv_model_t). Another instant than the chip's gets
 * ideal current sensors: low-side shunts read nothing at the period start
 * (sim_rig.h). */
static void measure_speed(double rpm, double load_nm, double sample_at, int inverter,
                          sim_window_t *w)
{
    static simcore_t s;
    simcore_cfg_t cfg;
    simcore_cfg_default(&cfg);
    cfg.theta0_rad = 1.0;
    cfg.sample_at = sample_at;
    if (sample_at >= 0.0) {
        cfg.amp_tau_s = 0.0;
    }
    cl_setup(&s, &cfg, "hurst", "mclv");
    cl_event(&s, SIM_EV_INVERTER, (double)inverter, 0.0);
    cl_start_and_reach(&s, rpm, 10.0);
    if (load_nm > 0.0) {
        cl_event(&s, SIM_EV_LOAD, load_nm, 0.0);
    }
    cl_run(&s, 0.5);
    cl_measure(&s, 1.0, w);
}

static void check_speed(double rpm, double load_nm, double ang_max_deg)
{
    sim_window_t w;
    measure_speed(rpm, load_nm, -1.0, SIM_INV_AVERAGED, &w);
    printf("measured: %5.0f rpm, load %.3f N m: speed error %+.3f %% (true %.2f, ref %.2f, "
           "est %.2f rpm), angle error mean %+.2f deg, rms %.2f deg, max %.2f deg, "
           "closed loop throughout: %s\n",
           rpm, load_nm, sim_window_speed_err_pct(&w), sim_window_speed(&w), sim_window_ref(&w),
           sim_window_est(&w), sim_window_ang_mean(&w), sim_window_ang_rms(&w), w.ang_max,
           (w.n_skipped > 0) ? "no" : "yes");
    assert_int_equal(w.n_skipped, 0); /* closed loop throughout */
    assert_cmp(fabs(sim_window_speed_err_pct(&w)), <=, 1.0);
    assert_cmp(fabs(sim_window_ang_mean(&w)), <=, 0.3);
    assert_cmp(w.ang_max, <=, ang_max_deg);
}

static void test_angle_and_speed_error_should_be_small_at_1000_rpm(void **state)
{
    (void)state;
    check_speed(1000.0, 0.0, 2.0);
}

static void test_angle_and_speed_error_should_be_small_at_2000_rpm(void **state)
{
    (void)state;
    check_speed(2000.0, 0.0, 2.0);
}

static void test_angle_and_speed_error_should_be_small_at_3000_rpm(void **state)
{
    (void)state;
    check_speed(3000.0, 0.0, 2.0);
}

static void test_angle_and_speed_error_should_be_small_at_the_lowest_claimed_speed(void **state)
{
    (void)state;
    printf("measured: lowest claimed closed-loop speed SPEED_REF_MIN_RPM = %.0f rpm = %.1f %% of "
           "SPEED_REF_MAX_RPM (%.0f rpm)\n",
           (double)SPEED_REF_MIN_RPM, 100.0 * (double)SPEED_REF_MIN_RPM / SPEED_REF_MAX_RPM,
           (double)SPEED_REF_MAX_RPM);
    check_speed((double)SPEED_REF_MIN_RPM, 0.0, 2.5);
}

static void
test_angle_and_speed_error_should_be_small_at_2000_rpm_under_half_rated_load(void **state)
{
    (void)state;
    check_speed(2000.0, 0.05, 2.0);
}

static void test_angle_bias_should_be_small_at_the_lowest_claimed_speed_under_load(void **state)
{
    (void)state;
    check_speed((double)SPEED_REF_MIN_RPM, 0.02, 2.5);
}

static void test_angle_bias_should_be_small_at_3000_rpm_under_load(void **state)
{
    (void)state;
    check_speed(3000.0, 0.03, 2.0);
}

static void test_angle_bias_should_be_small_at_the_top_speed(void **state)
{
    (void)state;
    check_speed((double)SPEED_REF_MAX_RPM, 0.0, 2.0);
}

/* 8 mN m, 0.13 A: what the field-weakening table is derived for at the top
 * speed (motor_hurst.h: 0.165 A). The shunt window leaves the Hurst at most
 * about 16 mN m at 5,300 rpm on 24 V (docs/board.md "Shunt window"); 20 mN m
 * held 5,300 rpm before it and now runs at 4,930 rpm. */
static void test_angle_bias_should_be_small_at_the_top_speed_under_load(void **state)
{
    (void)state;
    check_speed((double)SPEED_REF_MAX_RPM, 0.008, 2.0);
}

/* The 0.3 deg bound can fail: a plant whose timing differs from the core's
 * by half a period (a sample at the period start, duties a whole period
 * later: the timing the core used to assume) biases the angle well past it. */
static void test_angle_bias_should_exceed_its_bound_when_the_plant_timing_differs(void **state)
{
    sim_window_t w;
    (void)state;
    measure_speed(2000.0, 0.05, 0.0, SIM_INV_AVERAGED, &w);
    printf("measured: 2000 rpm, load 0.050 N m, plant sampling at the period start (core: %.2f): "
           "angle error mean %+.2f deg\n",
           (double)MC_SAMPLE_AT, sim_window_ang_mean(&w));
    assert_int_equal(w.n_skipped, 0); /* closed loop throughout */
    assert_cmp(fabs(sim_window_ang_mean(&w)), >, 0.3);
}

/* The same core on the switching-level inverter (sim_inverter.h): every
 * edge, the diodes in the dead times, the PWM ripple in the samples. Near
 * no load the angle bias is larger than on the averaged model (+0.70 deg
 * at 1,000 rpm when written, against +0.02): the dead-time error the
 * core compensates is not the averaged band's there. Held to 1 deg here
 * as a regression guard; the 0.3 deg of the averaged model is issue 13's
 * goal for this inverter too. */
static void test_angle_bias_on_the_switching_inverter(void **state)
{
    static const double rpm[3] = {1000.0, 2000.0, 2000.0};
    static const double load[3] = {0.0, 0.0, 0.05};
    (void)state;
    for (int k = 0; k < 3; k++) {
        sim_window_t w;
        measure_speed(rpm[k], load[k], -1.0, SIM_INV_SWITCHING, &w);
        printf("measured: switching inverter, %4.0f rpm, load %.3f N m: speed error %+.3f %%, "
               "angle error mean %+.2f deg, rms %.2f deg, max %.2f deg\n",
               rpm[k], load[k], sim_window_speed_err_pct(&w), sim_window_ang_mean(&w),
               sim_window_ang_rms(&w), w.ang_max);
        assert_int_equal(w.n_skipped, 0); /* closed loop throughout */
        assert_cmp(fabs(sim_window_speed_err_pct(&w)), <=, 1.0);
        assert_cmp(fabs(sim_window_ang_mean(&w)), <=, 1.0);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_angle_and_speed_error_should_be_small_at_1000_rpm),
        cmocka_unit_test(test_angle_and_speed_error_should_be_small_at_2000_rpm),
        cmocka_unit_test(test_angle_and_speed_error_should_be_small_at_3000_rpm),
        cmocka_unit_test(test_angle_and_speed_error_should_be_small_at_the_lowest_claimed_speed),
        cmocka_unit_test(
            test_angle_and_speed_error_should_be_small_at_2000_rpm_under_half_rated_load),
        cmocka_unit_test(test_angle_bias_should_be_small_at_the_lowest_claimed_speed_under_load),
        cmocka_unit_test(test_angle_bias_should_be_small_at_3000_rpm_under_load),
        cmocka_unit_test(test_angle_bias_should_be_small_at_the_top_speed),
        cmocka_unit_test(test_angle_bias_should_be_small_at_the_top_speed_under_load),
        cmocka_unit_test(test_angle_bias_should_exceed_its_bound_when_the_plant_timing_differs),
        cmocka_unit_test(test_angle_bias_on_the_switching_inverter),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
