/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_mc_sensor.c - the current-sensor check's judgement (mc_sensor.c, mc.c note 5), window by
 * window on made-up window sums: when it trips, and when it holds for the stall check. */
#include "test_support.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "mc_parts.h"

/* A CLOSED_LOOP window: the current vector of magnitude amp (Q15) at angle th (rad), a speed
 * inside the phase balance's band, the back-EMF ratio emf (Q12), and the errors on d and q as a
 * fraction of the window's threshold (half of the reference's larger component plus the floor,
 * per period). */
typedef struct {
    double amp, th;
    q15_t emf;
    double err;   /* error sums over the threshold: > 1 fails */
    bool stuck_b; /* phase B reads 0 (a failed sensor): the balance's case */
} win_t;

static mc_sensor_t sens;
static int windows;

static void sensor_start(void)
{
    memset(&sens, 0, sizeof(sens));
    mc_sensor_reset(&sens);
    windows = 0;
}

/* One window; true when the check asks for the fault. */
static bool sensor_window(const win_t *w)
{
    mc_slow_in_t si;
    mc_slow_out_t so;
    double ia = w->amp * cos(w->th);
    double ib = w->amp * cos(w->th - 2.0 * M_PI / 3.0);
    int32_t thr;
    memset(&si, 0, sizeof(si));
    memset(&so, 0, sizeof(so));
    if (w->stuck_b) {
        ib = 0.0;
    }
    si.state = MC_STATE_CLOSED_LOOP;
    si.i_ab.alpha = (q15_t)lround(ia);
    si.i_ab.beta = (q15_t)lround((ia + 2.0 * ib) / sqrt(3.0));
    si.sens_ref.d = 0;
    si.sens_ref.q = 2000;
    thr = (2000 / 2 + (int32_t)MC_SENSOR_FLOOR_Q15) * (int32_t)MC_SLOW_STEP_PERIODS;
    si.sens_q = (int32_t)lround(w->err * (double)thr);
    si.est_valid = true;
    si.emf_ratio = w->emf;
    /* the middle of the balance's first band: half the first multiple of half the window rate */
    si.speed_est = (q15_t)(MC_SENSOR_BAL_SYNC16 / 2);
    mc_sensor_window(&sens, &si, &so);
    windows++;
    return so.sensor_fault;
}

/* Healthy: a balanced current turning one step a window, errors well inside. */
static win_t healthy(int n)
{
    win_t w = {4000.0, 1.3 * n, 4096, 0.2, false};
    return w;
}

static void settle(void)
{
    for (int n = 0; n < 40; n++) {
        win_t w = healthy(n);
        assert_false(sensor_window(&w));
    }
}

static void test_a_healthy_drive_should_never_trip(void **state)
{
    (void)state;
    sensor_start();
    for (int n = 0; n < 2000; n++) {
        win_t w = healthy(n);
        assert_false(sensor_window(&w));
    }
    assert_int_equal(sens.cnt, 0);
}

/* After settling, failing windows on a turning rotor (the back-EMF at half the stall
 * check's low fraction in windows dip_from .. dip_to, none when 0) until the trip: how many. */
static int windows_to_trip(int dip_from, int dip_to)
{
    int n;
    sensor_start();
    settle();
    for (n = 1; n <= 20; n++) {
        win_t w = healthy(n);
        w.err = 3.0;
        if (n >= dip_from && n <= dip_to) {
            w.emf = (q15_t)(MC_STALL_BEMF_LO_Q12 / 2);
        }
        if (sensor_window(&w)) {
            break;
        }
    }
    return n;
}

/* Failing windows on a turning rotor: the trip after MC_SENSOR_TRIP / 2 of them, the windows of
 * MC_SENSOR_TIME_S. */
static void test_failing_windows_should_trip_after_the_sensor_time(void **state)
{
    int n = windows_to_trip(0, 0);
    (void)state;
    printf("measured: failing windows to the trip: %d (MC_SENSOR_TRIP %u)\n", n,
           (unsigned)MC_SENSOR_TRIP);
    assert_int_equal(n, (MC_SENSOR_TRIP + 1) / 2);
}

/* A failed sensor whose estimate loses its back-EMF for two windows (fewer than the defer): the
 * held windows count once it comes back, so it trips after as many failing windows as without
 * the dip. */
static void test_a_short_back_emf_dip_should_not_forgive_failing_windows(void **state)
{
    (void)state;
    assert_int_equal(windows_to_trip(2, 3), (MC_SENSOR_TRIP + 1) / 2);
}

/* A rotor stopped in CLOSED_LOOP at light load: the step of the current at the stop fills the
 * balance's filters with a transient on one phase (sixteen times the current before, four
 * windows) while the back-EMF is still read for two of them; then the back-EMF is gone and the
 * errors stay large, the currents balanced: the stall check's case, held for as long as it
 * lasts (the stall check trips in about 20 windows). */
static void test_a_sudden_stop_should_be_held_for_the_stall_check(void **state)
{
    (void)state;
    sensor_start();
    for (int n = 0; n < 40; n++) {
        win_t w = healthy(n);
        w.amp = 1000.0;
        assert_false(sensor_window(&w));
    }
    for (int n = 1; n <= 200; n++) {
        win_t w = healthy(n);
        w.err = 3.0;
        w.amp = 8000.0;
        if (n <= 4) {
            w.amp = 16000.0;
            w.th = M_PI / 6.0; /* phase B's zero crossing: all on A (and C) */
        }
        if (n > 2) {
            w.emf = (q15_t)(MC_STALL_BEMF_LO_Q12 / 4);
        }
        assert_false(sensor_window(&w));
    }
    assert_cmp(sens.cnt, <, MC_SENSOR_TRIP);
}

/* A sensor failed at low speed whose estimate also loses its back-EMF: the phases out of
 * balance override the hold once the filters have had MC_SENSOR_BAL_REFILL windows of it. */
static void test_a_failed_phase_with_a_lost_back_emf_should_trip_on_the_balance(void **state)
{
    int n;
    (void)state;
    sensor_start();
    settle();
    for (n = 1; n <= 100; n++) {
        win_t w = healthy(n);
        w.err = 3.0;
        w.stuck_b = true;
        w.emf = (q15_t)(MC_STALL_BEMF_LO_Q12 / 4);
        if (sensor_window(&w)) {
            break;
        }
    }
    printf("measured: stuck phase B, back-EMF lost: tripped after %d windows\n", n);
    assert_cmp(n, >, (int)MC_SENSOR_BAL_REFILL);
    assert_cmp(n, <=, (int)MC_SENSOR_BAL_REFILL + (MC_SENSOR_TRIP + 1) / 2 + 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_healthy_drive_should_never_trip),
        cmocka_unit_test(test_failing_windows_should_trip_after_the_sensor_time),
        cmocka_unit_test(test_a_short_back_emf_dip_should_not_forgive_failing_windows),
        cmocka_unit_test(test_a_sudden_stop_should_be_held_for_the_stall_check),
        cmocka_unit_test(test_a_failed_phase_with_a_lost_back_emf_should_trip_on_the_balance),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
