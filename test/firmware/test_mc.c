/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_mc.c - the mc core with synthetic ADC frames: states, transitions, protections, helpers. */
#include "test_support.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "mc.h"
#include "mc_contract.h"
#include "mc_internal.h"

/* ---- helpers ---------------------------------------------------------------- */

static mc_t mc;
static mc_pwm_out_t out;
static mc_status_t st;

static mc_adc_frame_t frame(int16_t ia, int16_t ib, int16_t vbus, int16_t pot)
{
    mc_adc_frame_t f;
    f.ia = ia;
    f.ib = ib;
    f.vbus = vbus;
    f.pot = pot;
    return f;
}

static mc_adc_frame_t nominal(void)
{
    return frame(0, 0, MC_VBUS_NOMINAL_Q15, 0);
}

static void step_with(mc_adc_frame_t f)
{
    mc_step(&mc, &f, &out);
    mc_slow_step(&mc); /* a no-op except after a window end (mc.h note 4) */
    mc_status(&mc, &st);
}

static void steps(long n, mc_adc_frame_t f)
{
    for (long k = 0; k < n; k++) {
        step_with(f);
    }
}

static void assert_off(void)
{
    assert_false(out.outputs_on);
    assert_int_equal(out.duty[0], PWM_DUTY_MAX / 2U);
    assert_int_equal(out.duty[1], PWM_DUTY_MAX / 2U);
    assert_int_equal(out.duty[2], PWM_DUTY_MAX / 2U);
}

static int setup(void **state)
{
    (void)state;
    mc_init(&mc);
    memset(&out, 0xA5, sizeof(out));
    mc_status(&mc, &st);
    return 0;
}

/* Start and run to the given state with zero currents. */
static void run_to(mc_state_t s)
{
    mc_request(&mc, MC_REQUEST_START);
    for (long k = 0; k < 200000L; k++) {
        step_with(nominal());
        if (st.state == s) {
            return;
        }
    }
    fail_msg("state %d not reached", (int)s);
}

/* ---- init, STOPPED ------------------------------------------------------------ */

static void test_mc_init_should_leave_the_core_stopped_with_no_fault(void **state)
{
    (void)state;
    assert_int_equal(st.state, MC_STATE_STOPPED);
    assert_int_equal(st.fault, MC_FAULT_NONE);
    assert_false(st.outputs_on);
    assert_int_equal(st.start_retries, 0);
}

static void
test_mc_step_in_stopped_should_give_half_duties_and_outputs_off_whatever_the_frame(void **state)
{
    (void)state;
    uint32_t rng = 7U;
    const int16_t ov = MC_VBUS_OV_Q15;
    for (int k = 0; k < 5000; k++) {
        /* Anything but an overvoltage (which is a fault even when stopped). */
        uint32_t r = test_rand_u32(&rng);
        int16_t vb = (int16_t)(r % (uint32_t)(uint16_t)ov);
        step_with(frame(test_rand_i16(&rng), test_rand_i16(&rng), vb, test_rand_i16(&rng)));
        assert_int_equal(st.state, MC_STATE_STOPPED);
        assert_off();
    }
}

/* The core's contracts (mc_contract.h) report to cmocka here, so a test can
 * expect one to break; the library's own handler aborts. */
void mc_contract_fail(const char *what, const char *file, int line)
{
    mock_assert(0, what, file, line);
}

static void test_mc_request_out_of_range_should_break_its_contract_and_change_nothing(void **state)
{
    (void)state;
    uint8_t seq = mc.mbox.req_seq;
    expect_assert_failure(mc_request(&mc, MC_REQUEST_COUNT));
    expect_assert_failure(mc_request(&mc, (mc_request_t)200));
    assert_int_equal(mc.mbox.req_seq, seq);
    steps(10, nominal());
    assert_int_equal(st.state, MC_STATE_STOPPED);
}

/* ---- calibration -------------------------------------------------------------- */

static void
test_start_should_discard_the_first_conversions_calibrate_the_offsets_then_lock(void **state)
{
    (void)state;
    mc_request(&mc, MC_REQUEST_START);
    mc_adc_frame_t f = frame(300, -200, MC_VBUS_NOMINAL_Q15, 0);
    /* The first MC_CALIB_SKIP_PERIODS conversions (ADC power-up, amplifier
     * settling) are discarded: a wild value there must not move the offsets. */
    mc_adc_frame_t wild = frame(12000, -12000, MC_VBUS_NOMINAL_Q15, 0);
    step_with(wild);
    assert_int_equal(st.state, MC_STATE_CALIBRATE);
    long n = 1;
    while (st.state == MC_STATE_CALIBRATE) {
        assert_off();
        step_with((n < (long)MC_CALIB_SKIP_PERIODS) ? wild : f);
        n++;
        assert_cmp(n, <=, (long)MC_CALIB_SKIP_PERIODS + (long)MC_CALIB_PERIODS + 1);
    }
    printf("measured: calibration took %ld periods (%u discarded, MC_CALIB_PERIODS = %u)\n", n,
           (unsigned)MC_CALIB_SKIP_PERIODS, (unsigned)MC_CALIB_PERIODS);
    assert_int_equal(n, (long)MC_CALIB_SKIP_PERIODS + (long)MC_CALIB_PERIODS);
    assert_int_equal(st.state, MC_STATE_LOCK);
    /* The offsets are formed after that period's duties: the outputs turn
     * on with the next, where the same raw reading means zero current. */
    assert_off();
    step_with(f);
    assert_true(out.outputs_on);
    assert_int_equal(st.ia, 0);
    assert_int_equal(st.ib, 0);
}

static void test_calibration_should_fault_when_an_offset_is_beyond_the_limit(void **state)
{
    (void)state;
    int16_t bad = (int16_t)(MC_OFFSET_MAX_Q15 + 1);
    for (int phase = 0; phase < 2; phase++) {
        for (int sign = -1; sign <= 1; sign += 2) {
            mc_init(&mc);
            mc_request(&mc, MC_REQUEST_START);
            int16_t x = (int16_t)(sign * bad);
            steps((long)MC_CALIB_SKIP_PERIODS + (long)MC_CALIB_PERIODS + 2,
                  phase == 0 ? frame(x, 0, MC_VBUS_NOMINAL_Q15, 0)
                             : frame(0, x, MC_VBUS_NOMINAL_Q15, 0));
            assert_int_equal(st.state, MC_STATE_FAULT);
            assert_int_equal(st.fault, MC_FAULT_OFFSET);
            assert_off();
        }
    }
}

static void test_calibration_should_accept_an_offset_at_the_limit(void **state)
{
    (void)state;
    mc_request(&mc, MC_REQUEST_START);
    steps((long)MC_CALIB_SKIP_PERIODS + (long)MC_CALIB_PERIODS + 2,
          frame(MC_OFFSET_MAX_Q15, 0, MC_VBUS_NOMINAL_Q15, 0));
    assert_int_equal(st.state, MC_STATE_LOCK);
}

/* ---- LOCK and OPEN_LOOP --------------------------------------------------------- */

static void
test_lock_should_hold_a_fixed_angle_with_the_lock_current_for_the_lock_time(void **state)
{
    (void)state;
    run_to(MC_STATE_LOCK);
    assert_off(); /* the period that ended CALIBRATE; the lock's first is the next */
    long n = 0;   /* periods that end in LOCK with the outputs on */
    long level2 = 0;
    for (;;) {
        step_with(nominal());
        if (st.state != MC_STATE_LOCK) {
            break;
        }
        assert_int_equal(st.theta_est, 0);
        /* the lock current, then (from at least MC_LOCK_PERIODS + MC_DTM_N
         * windows on) the dead-time measurement's second level, never back */
        if (st.iq_ref != MC_LOCK_CURRENT_Q15) {
            assert_int_equal(st.iq_ref, MC_DTM_CURRENT_Q15);
            assert_cmp(n + 1, >=, (long)MC_LOCK_PERIODS + (long)MC_DTM_N * MC_SLOW_STEP_PERIODS);
            level2++;
        } else {
            assert_int_equal(level2, 0);
        }
        assert_int_equal(st.id_ref, 0);
        assert_true(out.outputs_on);
        n++;
    }
    printf("measured: lock lasted %ld periods (MC_LOCK_PERIODS = %u, the dead-time measurement "
           "%ld of them, at most %ld), %ld at the second level\n",
           n, (unsigned)MC_LOCK_PERIODS, n - (long)MC_LOCK_PERIODS, (long)MC_DTM_MAX_PERIODS,
           level2);
    assert_cmp(n, >=,
               (long)MC_LOCK_PERIODS +
                   (2L * MC_DTM_N + MC_DTM_SETTLE) * (long)MC_SLOW_STEP_PERIODS);
    assert_cmp(n, <=, (long)MC_LOCK_PERIODS + MC_DTM_MAX_PERIODS);
    assert_cmp(level2, >=, (long)(MC_DTM_SETTLE + MC_DTM_N) * MC_SLOW_STEP_PERIODS);
    assert_int_equal(st.state, MC_STATE_OPEN_LOOP);
}

static void test_lock_should_drive_the_current_towards_its_reference(void **state)
{
    (void)state;
    run_to(MC_STATE_LOCK);
    /* No current measured: the q PI must push Vq up, d stays at 0. */
    steps(50, nominal());
    assert_cmp(st.vq, >, 0);
    assert_int_equal(st.vd, 0);
}

/* The circle limit (mc.c note 3) against currents that jump by a quarter of
 * full scale every few periods, so that the vector jumps onto the circle
 * from inside: |V| never leaves it (by more than the limit's rounding), and
 * the jumps are the periods redone (counted in circle_redos). */
static void test_voltage_circle_should_hold_when_vd_jumps_between_periods(void **state)
{
    (void)state;
    run_to(MC_STATE_LOCK);
    double over = -1e9;
    long near = 0;
    for (long k = 0; k < 4000; k++) {
        int16_t a = (int16_t)(((k / 3) % 2 == 0) ? 8192 : -8192);
        int16_t bb = (int16_t)(((k / 7) % 2 == 0) ? 8192 : -8192);
        step_with(frame(a, bb, MC_VBUS_NOMINAL_Q15, 0));
        assert_int_equal(st.state, MC_STATE_LOCK);
        double m = hypot((double)mc.pi_d.out, (double)mc.pi_q.out);
        over = fmax(over, m - MC_VMAX_Q15);
        near += (m > 0.875 * MC_VMAX_Q15);
        assert_cmp(m, <=, MC_VMAX_Q15 + 0.5); /* vlimit.h: lim rounded */
    }
    printf("measured: %ld of 4000 periods with |V| >= 7/8 Vmax, |V| - Vmax at most %.2f LSB, "
           "%u redone at the circle\n",
           near, over, (unsigned)mc.circle_redos);
    assert_cmp(near, >, 500);
    assert_cmp(mc.circle_redos, >, 0U);
}

static void test_open_loop_should_advance_the_angle_at_constant_acceleration(void **state)
{
    (void)state;
    run_to(MC_STATE_OPEN_LOOP);
    /* The first OPEN_LOOP period is still at the lock angle; after n more
     * the 32-bit angle is INC * n (n + 1) / 2. */
    err_stats_t e;
    err_stats_init(&e);
    for (uint32_t n = 0U; n < 15000U; n++) {
        uint32_t ang = MC_RAMP_STEP_INC * (n * (n + 1U) / 2U);
        int16_t expect = (int16_t)(uint16_t)(ang >> 16);
        err_stats_add(&e, (double)angle_sub(st.theta_forced, expect), (double)n);
        assert_int_equal(st.state, MC_STATE_OPEN_LOOP);
        assert_int_equal(st.iq_ref, MC_RAMP_CURRENT_Q15);
        step_with(nominal());
    }
    err_stats_print("open-loop forced angle vs INC n(n+1)/2", &e, "counts");
    assert_cmp(e.max_abs, ==, 0.0);
}

static void test_open_loop_should_retry_a_failed_start_then_fault(void **state)
{
    (void)state;
    /* Zero currents: the estimator never becomes valid. */
    run_to(MC_STATE_OPEN_LOOP);
    int attempts = 1;
    long coast = 0;
    for (long k = 0; k < 2000000L && st.state != MC_STATE_FAULT; k++) {
        mc_state_t before = st.state;
        step_with(nominal());
        if (before == MC_STATE_OPEN_LOOP && st.state == MC_STATE_CALIBRATE) {
            attempts++;
            assert_int_equal(st.start_retries, attempts - 1);
            assert_off();
            coast = 0;
        }
        if (st.state == MC_STATE_CALIBRATE) {
            coast++;
        }
        if (before == MC_STATE_CALIBRATE && st.state == MC_STATE_LOCK) {
            printf("measured: retry %d after %ld periods with outputs off\n", attempts - 1, coast);
            assert_int_equal(coast, (long)MC_COAST_PERIODS + (long)MC_CALIB_PERIODS - 1);
        }
    }
    assert_int_equal(st.state, MC_STATE_FAULT);
    assert_int_equal(st.fault, MC_FAULT_START_FAILED);
    assert_int_equal(attempts, MC_START_RETRIES + 1);
    assert_int_equal(st.start_retries, MC_START_RETRIES);
    assert_off();
}

/* ---- STOP, START_STOP --------------------------------------------------------------- */

static void stop_from(mc_state_t s, mc_request_t r)
{
    mc_init(&mc);
    run_to(s);
    mc_request(&mc, r);
    step_with(nominal());
    assert_int_equal(st.state, MC_STATE_STOPPED);
    assert_int_equal(st.fault, MC_FAULT_NONE);
    assert_off();
}

static void test_stop_should_reach_stopped_with_outputs_off_from_every_running_state(void **state)
{
    (void)state;
    const mc_state_t states[] = {MC_STATE_CALIBRATE, MC_STATE_LOCK, MC_STATE_OPEN_LOOP};
    for (unsigned k = 0; k < 3U; k++) {
        stop_from(states[k], MC_REQUEST_STOP);
        stop_from(states[k], MC_REQUEST_START_STOP);
    }
}

static void test_start_stop_should_toggle_and_start_should_not_restart_a_running_core(void **state)
{
    (void)state;
    mc_request(&mc, MC_REQUEST_START_STOP);
    step_with(nominal());
    assert_int_equal(st.state, MC_STATE_CALIBRATE);
    steps(5, nominal());
    mc_request(&mc, MC_REQUEST_START); /* already running: no effect */
    step_with(nominal());
    assert_int_equal(st.state, MC_STATE_CALIBRATE);
    mc_request(&mc, MC_REQUEST_STOP);
    step_with(nominal());
    assert_int_equal(st.state, MC_STATE_STOPPED);
    mc_request(&mc, MC_REQUEST_STOP); /* already stopped: no effect */
    step_with(nominal());
    assert_int_equal(st.state, MC_STATE_STOPPED);
}

static void test_set_gain_should_apply_to_d_and_q_together_at_the_next_step_only(void **state)
{
    (void)state;
    q15_t kp0 = mc.pi_d.p.kp;
    q15_t kp = (q15_t)(kp0 / 2 + 1);
    q15_t ki = (q15_t)(mc.pi_d.p.ki / 2 + 1);
    assert_true(mc_set_gain(&mc, MC_GAIN_CUR_KP, kp));
    assert_true(mc_set_gain(&mc, MC_GAIN_CUR_KI, ki));
    assert_int_equal(mc_get_gain(&mc, MC_GAIN_CUR_KP), kp);
    /* posted, not yet applied: the loops keep their gains until mc_step */
    assert_int_equal(mc.pi_d.p.kp, kp0);
    assert_int_equal(mc.pi_q.p.kp, kp0);
    step_with(nominal());
    assert_int_equal(mc.pi_d.p.kp, kp);
    assert_int_equal(mc.pi_q.p.kp, kp);
    assert_int_equal(mc.pi_d.p.ki, ki);
    assert_int_equal(mc.pi_q.p.ki, ki);
    assert_int_equal(mc.pi_d.p.kc, ki); /* Kc = Ki, as AN1078 tunes it */
    assert_int_equal(mc.pi_q.p.kc, ki);
    /* mc_init restores the built-in gains */
    mc_init(&mc);
    assert_int_equal(mc_get_gain(&mc, MC_GAIN_CUR_KP), kp0);
    assert_int_equal(mc.pi_q.p.kp, kp0);
}

static void test_set_gain_should_refuse_unknown_gains_and_negative_values(void **state)
{
    (void)state;
    int16_t before[MC_GAIN_COUNT];
    for (unsigned g = 0; g < (unsigned)MC_GAIN_COUNT; g++) {
        before[g] = mc_get_gain(&mc, (mc_gain_t)g);
    }
    assert_false(mc_set_gain(&mc, MC_GAIN_COUNT, 100));
    assert_false(mc_set_gain(&mc, (mc_gain_t)200, 100));
    assert_false(mc_set_gain(&mc, MC_GAIN_SPD_KP, -1));
    assert_false(mc_set_gain(&mc, MC_GAIN_CUR_KI, (int16_t)-32768));
    assert_int_equal(mc_get_gain(&mc, MC_GAIN_COUNT), 0);
    step_with(nominal());
    for (unsigned g = 0; g < (unsigned)MC_GAIN_COUNT; g++) {
        assert_int_equal(mc_get_gain(&mc, (mc_gain_t)g), before[g]);
    }
    assert_int_equal(mc.slow.pi_w.p.kp, MC_SPD_KP);
    /* a PI without its integral is outside the region a client may post (mc.h note 3) */
    assert_false(mc_set_gain(&mc, MC_GAIN_SPD_KI, 0));
}

static void test_a_request_posted_twice_before_a_step_should_count_once(void **state)
{
    (void)state;
    mc_request(&mc, MC_REQUEST_START_STOP);
    mc_request(&mc, MC_REQUEST_START_STOP);
    step_with(nominal());
    assert_int_equal(st.state, MC_STATE_CALIBRATE);
    step_with(nominal());
    assert_int_equal(st.state, MC_STATE_CALIBRATE);
}

/* ---- protections ------------------------------------------------------------------------ */

/* Phase currents (after the offsets, which are 0 here) giving |i_k| = x on
 * phase k (0: a, 1: b, 2: c = -a - b) with the others sharing the return. */
static mc_adc_frame_t phase_current(unsigned k, int16_t x)
{
    int16_t half = (int16_t)(-x / 2);
    int16_t other = (int16_t)(-x - half);
    switch (k) {
        case 0:
            return frame(x, half, MC_VBUS_NOMINAL_Q15, 0);
        case 1:
            return frame(half, x, MC_VBUS_NOMINAL_Q15, 0);
        default:
            return frame(half, other, MC_VBUS_NOMINAL_Q15, 0); /* ic = -(half + other) = x */
    }
}

static void test_overcurrent_should_trip_at_the_threshold_on_any_phase_in_one_period(void **state)
{
    (void)state;
    const mc_state_t states[] = {MC_STATE_LOCK, MC_STATE_OPEN_LOOP};
    for (unsigned s = 0; s < 2U; s++) {
        for (unsigned k = 0; k < 3U; k++) {
            for (int sign = -1; sign <= 1; sign += 2) {
                mc_init(&mc);
                run_to(states[s]);
                int16_t x = (int16_t)(sign * MC_OVERCURRENT_Q15);
                step_with(phase_current(k, x));
                assert_int_equal(st.state, MC_STATE_FAULT);
                assert_int_equal(st.fault, MC_FAULT_OVERCURRENT);
                assert_off();
            }
        }
    }
}

static void test_overcurrent_should_not_trip_just_below_the_threshold(void **state)
{
    (void)state;
    for (unsigned k = 0; k < 3U; k++) {
        for (int sign = -1; sign <= 1; sign += 2) {
            mc_init(&mc);
            run_to(MC_STATE_OPEN_LOOP);
            int16_t x = (int16_t)(sign * (MC_OVERCURRENT_Q15 - 1));
            step_with(phase_current(k, x));
            assert_int_equal(st.state, MC_STATE_OPEN_LOOP);
        }
    }
}

static void test_undervoltage_should_trip_at_the_threshold_while_running_only(void **state)
{
    (void)state;
    run_to(MC_STATE_LOCK);
    step_with(frame(0, 0, (int16_t)(MC_VBUS_UV_Q15 + 1), 0));
    assert_int_equal(st.state, MC_STATE_LOCK);
    step_with(frame(0, 0, MC_VBUS_UV_Q15, 0));
    assert_int_equal(st.state, MC_STATE_FAULT);
    assert_int_equal(st.fault, MC_FAULT_UNDERVOLTAGE);
    assert_off();
    /* Stopped, a low bus is no fault (the board may be powering down). */
    mc_init(&mc);
    steps(10, frame(0, 0, 0, 0));
    assert_int_equal(st.state, MC_STATE_STOPPED);
}

static void test_overvoltage_should_trip_at_the_threshold_in_any_state(void **state)
{
    (void)state;
    steps(3, frame(0, 0, (int16_t)(MC_VBUS_OV_Q15 - 1), 0));
    assert_int_equal(st.state, MC_STATE_STOPPED);
    step_with(frame(0, 0, MC_VBUS_OV_Q15, 0));
    assert_int_equal(st.state, MC_STATE_FAULT);
    assert_int_equal(st.fault, MC_FAULT_OVERVOLTAGE);

    mc_init(&mc);
    run_to(MC_STATE_OPEN_LOOP);
    step_with(frame(0, 0, (int16_t)(MC_VBUS_OV_Q15 - 1), 0));
    assert_int_equal(st.state, MC_STATE_OPEN_LOOP);
    step_with(frame(0, 0, MC_VBUS_OV_Q15, 0));
    assert_int_equal(st.state, MC_STATE_FAULT);
    assert_int_equal(st.fault, MC_FAULT_OVERVOLTAGE);
    assert_off();
}

static void test_start_should_be_refused_while_the_bus_is_out_of_its_window(void **state)
{
    (void)state;
    mc_request(&mc, MC_REQUEST_START);
    step_with(frame(0, 0, MC_VBUS_UV_Q15, 0));
    assert_int_equal(st.state, MC_STATE_FAULT);
    assert_int_equal(st.fault, MC_FAULT_UNDERVOLTAGE);
    /* Still low: a new START leaves it in FAULT. */
    steps(2, frame(0, 0, MC_VBUS_UV_Q15, 0));
    mc_request(&mc, MC_REQUEST_START);
    step_with(frame(0, 0, MC_VBUS_UV_Q15, 0));
    assert_int_equal(st.state, MC_STATE_FAULT);
    assert_off();
    /* Back in the window: START leaves FAULT and clears the code. */
    mc_request(&mc, MC_REQUEST_START_STOP);
    step_with(nominal());
    assert_int_equal(st.state, MC_STATE_CALIBRATE);
    assert_int_equal(st.fault, MC_FAULT_NONE);
}

static void test_start_from_fault_should_be_refused_while_the_bus_is_still_overvoltage(void **state)
{
    (void)state;
    /* A hardware fault first, then the bus rises: FAULT keeps the first code. */
    mc_request(&mc, MC_REQUEST_HW_FAULT);
    step_with(nominal());
    steps(3, frame(0, 0, MC_VBUS_OV_Q15, 0));
    assert_int_equal(st.state, MC_STATE_FAULT);
    assert_int_equal(st.fault, MC_FAULT_HARDWARE);
    /* START with the bus still at the threshold: FAULT in the same step,
     * now with the present cause; never a period in CALIBRATE. */
    mc_request(&mc, MC_REQUEST_START);
    step_with(frame(0, 0, MC_VBUS_OV_Q15, 0));
    assert_int_equal(st.state, MC_STATE_FAULT);
    assert_int_equal(st.fault, MC_FAULT_OVERVOLTAGE);
    assert_off();
    /* Just below it: the START goes through. */
    mc_request(&mc, MC_REQUEST_START);
    step_with(frame(0, 0, (int16_t)(MC_VBUS_OV_Q15 - 1), 0));
    assert_int_equal(st.state, MC_STATE_CALIBRATE);
    assert_int_equal(st.fault, MC_FAULT_NONE);
}

static void test_hw_fault_should_latch_from_any_state_until_a_new_start(void **state)
{
    (void)state;
    const mc_state_t states[] = {MC_STATE_STOPPED, MC_STATE_CALIBRATE, MC_STATE_LOCK,
                                 MC_STATE_OPEN_LOOP};
    for (unsigned s = 0; s < 4U; s++) {
        mc_init(&mc);
        if (states[s] != MC_STATE_STOPPED) {
            run_to(states[s]);
        }
        mc_request(&mc, MC_REQUEST_HW_FAULT);
        step_with(nominal());
        assert_int_equal(st.state, MC_STATE_FAULT);
        assert_int_equal(st.fault, MC_FAULT_HARDWARE);
        assert_off();
        /* STOP does not leave FAULT; the code stays. */
        mc_request(&mc, MC_REQUEST_STOP);
        steps(100, nominal());
        assert_int_equal(st.state, MC_STATE_FAULT);
        assert_int_equal(st.fault, MC_FAULT_HARDWARE);
        assert_off();
        mc_request(&mc, MC_REQUEST_START);
        step_with(nominal());
        assert_int_equal(st.state, MC_STATE_CALIBRATE);
        assert_int_equal(st.fault, MC_FAULT_NONE);
    }
}

static void test_a_start_in_the_same_frame_as_a_fault_should_not_clear_it(void **state)
{
    (void)state;
    run_to(MC_STATE_LOCK);
    mc_request(&mc, MC_REQUEST_HW_FAULT);
    mc_request(&mc, MC_REQUEST_START);
    step_with(nominal());
    assert_int_equal(st.state, MC_STATE_FAULT);
    /* A second fault keeps the first code. */
    step_with(frame(0, 0, MC_VBUS_OV_Q15, 0));
    assert_int_equal(st.fault, MC_FAULT_HARDWARE);
}

/* ---- pot and references -------------------------------------------------------------------- */

static void test_pot_should_map_linearly_onto_the_speed_reference_range(void **state)
{
    (void)state;
    err_stats_t e;
    err_stats_init(&e);
    for (int32_t p = 0; p <= 32767; p++) {
        double ref = SPEED_REF_MIN_RPM + (SPEED_REF_MAX_RPM - SPEED_REF_MIN_RPM) * p / 32768.0;
        double got = (double)mc_pot_to_speed((int16_t)p) * MC_SPEED_FULLSCALE_RPM / 32768.0;
        err_stats_add(&e, got - ref, (double)p);
    }
    err_stats_print("pot -> speed reference vs linear map", &e, "rpm");
    /* Q15 quantisation of the two ends plus the floor: <= 1.5 LSB. */
    assert_cmp(e.max_abs, <=, 1.5 * MC_SPEED_FULLSCALE_RPM / 32768.0);
    assert_int_equal(mc_pot_to_speed(0), MC_SPEED_REF_MIN_Q15);
    assert_int_equal(mc_pot_to_speed(-5), MC_SPEED_REF_MIN_Q15);
    assert_cmp(mc_pot_to_speed(32767), <=, MC_SPEED_REF_MAX_Q15);
    assert_cmp(mc_pot_to_speed(32767), >=, MC_SPEED_REF_MAX_Q15 - 1);
}

static void test_pot_should_map_linearly_onto_the_torque_reference_range(void **state)
{
    (void)state;
    err_stats_t e;
    err_stats_init(&e);
    for (int32_t p = 0; p <= 32767; p++) {
        double ref = MOTOR_CURRENT_MAX_A * p / 32768.0;
        double got = (double)mc_pot_to_torque((int16_t)p) * BOARD_I_FULLSCALE_A / 32768.0;
        err_stats_add(&e, got - ref, (double)p);
    }
    err_stats_print("pot -> Iq reference vs linear map", &e, "A");
    assert_cmp(e.max_abs, <=, 1.5 * BOARD_I_FULLSCALE_A / 32768.0);
    assert_int_equal(mc_pot_to_torque(-1), 0);
}

static void test_speed_target_should_follow_the_pot_then_the_remote_reference(void **state)
{
    (void)state;
    /* The target is the slow step's: a pot reading or a remote reference
     * posted at a window end comes back at the next (mc.h note 4), so each
     * check runs two windows. */
    const long two = 2L * MC_SLOW_STEP_PERIODS;
    steps(two, frame(0, 0, MC_VBUS_NOMINAL_Q15, 16384));
    assert_int_equal(st.speed_target, mc_pot_to_speed(16384));
    mc_set_reference(&mc, MC_Q15_RPM(1000.0));
    steps(two, frame(0, 0, MC_VBUS_NOMINAL_Q15, 16384));
    assert_int_equal(st.speed_target, MC_Q15_RPM(1000.0));
    /* Clamped to the reference range. */
    mc_set_reference(&mc, 32767);
    steps(two, nominal());
    assert_int_equal(st.speed_target, MC_SPEED_REF_MAX_Q15);
    mc_set_reference(&mc, -100);
    steps(two, nominal());
    assert_int_equal(st.speed_target, MC_SPEED_REF_MIN_Q15);
    mc_request(&mc, MC_REQUEST_REF_POT);
    steps(two, frame(0, 0, MC_VBUS_NOMINAL_Q15, 32767));
    assert_int_equal(st.speed_target, mc_pot_to_speed(32767));
}

/* One owner for the reference (mc.h, mc_status_t.ref_seq): the later of two
 * choices posted within one period wins, and a writer reading the status
 * back finds its own choice at once, before the core has taken it. */
static void test_the_later_choice_of_reference_should_win_and_show_at_once(void **state)
{
    (void)state;
    const long two = 2L * MC_SLOW_STEP_PERIODS;
    mc_status_t s0;
    mc_status(&mc, &s0);
    uint8_t mine = mc_set_reference(&mc, MC_Q15_RPM(1000.0));
    mc_status(&mc, &st);
    assert_true(st.ref_remote);
    assert_int_equal(st.ref_seq, (uint8_t)(s0.ref_seq + 1U));
    assert_int_equal(mine, st.ref_seq); /* the claim it hands back */
    assert_true(mc_reference_held(&st, mine));
    assert_false(mc_reference_held(&st, (uint8_t)(mine - 1U)));
    mc_request(&mc, MC_REQUEST_REF_POT); /* after it, in the same period */
    mc_status(&mc, &st);
    assert_false(st.ref_remote);
    assert_int_equal(st.ref_seq, (uint8_t)(s0.ref_seq + 2U));
    assert_false(mc_reference_held(&st, mine)); /* the pot took it back */
    steps(two, frame(0, 0, MC_VBUS_NOMINAL_Q15, 16384));
    assert_false(st.ref_remote);
    assert_int_equal(st.speed_target, mc_pot_to_speed(16384));
    /* the other order */
    mc_request(&mc, MC_REQUEST_REF_POT);
    mc_set_reference(&mc, MC_Q15_RPM(1000.0));
    steps(two, frame(0, 0, MC_VBUS_NOMINAL_Q15, 16384));
    assert_true(st.ref_remote);
    assert_int_equal(st.speed_target, MC_Q15_RPM(1000.0));
}

/* ---- dead time and applied voltage -------------------------------------------------------------
 */

static void test_deadtime_counts_should_follow_the_current_sign_with_a_linear_band(void **state)
{
    (void)state;
    /* At the programmed dead time and at the ends of what a lock may
     * measure, with the slope the measurement sets (mc.c note 4). */
    const int16_t dts[3] = {MC_DT_COUNTS, MC_DT_COUNTS_MIN, MC_DT_COUNTS_MAX};
    for (int k = 0; k < 3; k++) {
        int16_t dt = dts[k];
        q15_t slope = (k == 0) ? MC_DT_SLOPE : mc_deadtime_slope(dt, MC_DT_BAND_Q15);
        if (k == 0) { /* the run-time slope of the programmed dead time is the constant */
            assert_int_equal(mc_deadtime_slope(dt, MC_DT_BAND_Q15), MC_DT_SLOPE);
        }
        err_stats_t e;
        err_stats_init(&e);
        for (int32_t i = -32768; i <= 32767; i++) {
            double ref;
            if (i >= MC_DT_BAND_Q15) {
                ref = dt;
            } else if (i <= -MC_DT_BAND_Q15) {
                ref = -dt;
            } else {
                ref = (double)dt * i / MC_DT_BAND_Q15;
            }
            int16_t got = mc_deadtime_counts((q15_t)i, dt, slope, MC_DT_BAND_Q15);
            assert_cmp(got, >=, -dt);
            assert_cmp(got, <=, dt);
            err_stats_add(&e, got - ref, (double)i);
        }
        err_stats_print("dead-time correction vs sign with linear band", &e, "counts");
        assert_cmp(e.max_abs, <=, 0.51);
        assert_int_equal(mc_deadtime_counts(0, dt, slope, MC_DT_BAND_Q15), 0);
        assert_int_equal(mc_deadtime_counts(32767, dt, slope, MC_DT_BAND_Q15), dt);
        assert_int_equal(mc_deadtime_counts(-32768, dt, slope, MC_DT_BAND_Q15), -dt);
    }
    printf("measured: dead time %d counts = %.2f %% of the period (a lock may set %d..%d), band %d "
           "LSB = %.3f A\n",
           MC_DT_COUNTS, 100.0 * MC_DT_COUNTS / PWM_DUTY_MAX, MC_DT_COUNTS_MIN, MC_DT_COUNTS_MAX,
           MC_DT_BAND_Q15, MC_DT_BAND_Q15 * BOARD_I_FULLSCALE_A / 32768.0);
}

/* A run-time band (the identification's spin sets one from the inductance
 * it measured, dt + 1 .. 8192): against the double reference dt i / band
 * for every dead time the identification may set up to twice the largest
 * a lock may (0 included), bands from dt + 1 (the slope's largest, just
 * below 2^15) in steps of a tenth up to 8192, the build's and the
 * largest q15; every current within two of the band's edges, and out to
 * full scale in steps. The slope is rounded to half an LSB: in the band
 * that adds up to |i| / 2^16 < band / 2^16 counts to the product's
 * half. */
static void test_deadtime_counts_should_follow_a_run_time_band(void **state)
{
    (void)state;
    long cases = 0;
    double worst = 0.0;
    for (int32_t dt = 0; dt <= 2 * MC_DT_COUNTS_MAX; dt = (dt < 8) ? dt + 1 : dt + 1 + dt / 16) {
        int32_t bands[80];
        int nb = 0;
        for (int32_t b = dt + 1; b <= 8192 && nb < 76; b = (b < dt + 4) ? b + 1 : b + b / 10) {
            bands[nb++] = b;
        }
        bands[nb++] = 8192;
        bands[nb++] = MC_DT_BAND_Q15;
        bands[nb++] = 32767;
        for (int k = 0; k < nb; k++) {
            int32_t band = bands[k];
            if (band <= dt) {
                continue; /* the build's band below a dead time the identification may set */
            }
            q15_t slope = mc_deadtime_slope((int16_t)dt, (q15_t)band);
            double tol = 0.5 + (double)band / 65536.0 + 1e-9;
            assert_cmp(slope, <, 32768);
            assert_cmp(fabs(slope - (double)dt * 32768.0 / band), <=, 0.5);
            for (int32_t i = -32768; i <= 32767; i += (i >= -band - 2 && i <= band + 2) ? 1 : 97) {
                double ref = (i >= band) ? dt : (i <= -band) ? -dt : (double)dt * i / band;
                int16_t got = mc_deadtime_counts((q15_t)i, (int16_t)dt, slope, (q15_t)band);
                double e = fabs(got - ref);
                assert_cmp(got, >=, -dt);
                assert_cmp(got, <=, dt);
                if (e > tol) {
                    fail_msg("dt %ld band %ld i %ld: %d against %.3f", (long)dt, (long)band,
                             (long)i, got, ref);
                }
                worst = (e - (double)band / 65536.0 > worst) ? e - (double)band / 65536.0 : worst;
                cases++;
                if (i < -band - 2 && i + 97 > -band - 2) {
                    i = -band - 2 - 97; /* onto the band's edge */
                }
            }
            assert_int_equal(mc_deadtime_counts((q15_t)band, (int16_t)dt, slope, (q15_t)band), dt);
            assert_int_equal(mc_deadtime_counts((q15_t)-band, (int16_t)dt, slope, (q15_t)band),
                             -dt);
        }
    }
    printf("measured: %ld cases of mc_deadtime_counts with a run-time band, error at most %.3f "
           "counts beyond the slope's rounding\n",
           cases, worst);
}

static void test_deadtime_from_lock_should_scale_the_dead_time_by_the_missed_voltage(void **state)
{
    (void)state;
    /* dt' = dt (1 + avg / dv), the quotient truncated, within
     * [MC_DT_COUNTS_MIN, MC_DT_COUNTS_MAX]; dv <= 0 keeps dt. */
    const q15_t dvs[4] = {1, 37, 1200, 32767};
    long n = 0;
    for (int k = 0; k < 4; k++) {
        q15_t dv = dvs[k];
        for (int16_t dt = MC_DT_COUNTS_MIN; dt <= MC_DT_COUNTS_MAX; dt = (int16_t)(dt + 7)) {
            for (int32_t avg = -3 * (int32_t)dv; avg <= 3 * (int32_t)dv;
                 avg += (dv > 100) ? dv / 50 : 1) {
                double a = (avg > dv) ? dv : (avg < -dv) ? -dv : avg;
                double ref = dt + trunc(a * dt / dv);
                ref = (ref < MC_DT_COUNTS_MIN) ? MC_DT_COUNTS_MIN : ref;
                ref = (ref > MC_DT_COUNTS_MAX) ? MC_DT_COUNTS_MAX : ref;
                assert_int_equal(mc_deadtime_from_lock(dt, avg, dv), (int16_t)ref);
                n++;
            }
        }
    }
    assert_int_equal(mc_deadtime_from_lock(MC_DT_COUNTS, 5000, 0), MC_DT_COUNTS);
    assert_int_equal(mc_deadtime_from_lock(MC_DT_COUNTS, -5000, -3), MC_DT_COUNTS);
    assert_int_equal(mc_deadtime_from_lock(MC_DT_COUNTS, INT32_MAX, 100), MC_DT_COUNTS_MAX);
    assert_int_equal(mc_deadtime_from_lock(MC_DT_COUNTS, INT32_MIN, 100), MC_DT_COUNTS_MIN);
    printf("measured: %ld cases of mc_deadtime_from_lock exact\n", n);
}

static void test_duty_to_voltage_should_match_the_double_precision_reconstruction(void **state)
{
    (void)state;
    err_stats_t e;
    err_stats_init(&e);
    uint32_t rng = 99U;
    const double vfs = MC_VOLTAGE_FULLSCALE_V;
    for (int k = 0; k < 200000; k++) {
        int16_t d[3];
        for (int j = 0; j < 3; j++) {
            d[j] = (int16_t)((int32_t)(test_rand_u32(&rng) % (PWM_DUTY_MAX + 201U)) - 100);
        }
        int16_t vb = (int16_t)(test_rand_u32(&rng) % 32768U);
        double vbus = vb * BOARD_VBUS_FULLSCALE_V / 32768.0;
        double va = d[0] * vbus / PWM_DUTY_MAX;
        double vbb = d[1] * vbus / PWM_DUTY_MAX;
        double vc = d[2] * vbus / PWM_DUTY_MAX;
        double alpha = (2.0 * va - vbb - vc) / 3.0 / vfs * 32768.0;
        double beta = (vbb - vc) / sqrt(3.0) / vfs * 32768.0;
        ab_q15_t v = mc_duty_to_voltage(d, vb);
        if (fabs(alpha) < 32000.0) {
            err_stats_add(&e, v.alpha - alpha, (double)k);
        } else {
            assert_true(alpha > 0 ? v.alpha >= 31990 : v.alpha <= -31990);
        }
        if (fabs(beta) < 32000.0) {
            err_stats_add(&e, v.beta - beta, (double)k);
        }
    }
    err_stats_print("applied voltage from duties and Vbus vs double", &e, "LSB");
    /* Bound: the final rounding (0.5) plus the 16-bit constants' own
     * rounding (0.5 in about 21,000 and 18,000: up to 0.9 LSB at 32,000);
     * the triple product itself is within 2^-10 LSB. */
    assert_cmp(e.max_abs, <=, 1.1);
    int16_t half[3] = {1000, 1000, 1000};
    ab_q15_t z = mc_duty_to_voltage(half, MC_VBUS_NOMINAL_Q15);
    assert_int_equal(z.alpha, 0);
    assert_int_equal(z.beta, 0);
    z = mc_duty_to_voltage(half, -5);
    assert_int_equal(z.alpha, 0);
}

/* ---- stall detector thresholds --------------------------------------------------------------- */

static mc_stall_in_t healthy(void)
{
    mc_stall_in_t in;
    in.speed = MC_Q15_RPM(1500.0);
    in.emf_ratio = 4096;
    in.fw_active = false;
    in.speed_err = 0;
    in.saturated = 0;
    return in;
}

/* Runs the detector n times with `bad`, then once healthy; returns the
 * first fault code seen. */
static uint16_t run_stall(const mc_stall_in_t *bad, unsigned n)
{
    mc_stall_t s;
    memset(&s, 0, sizeof s);
    mc_stall_in_t ok = healthy();
    for (unsigned k = 0; k < n; k++) {
        uint16_t code = mc_stall_check(&s, bad);
        if (code != MC_FAULT_NONE) {
            return code;
        }
    }
    return mc_stall_check(&s, &ok);
}

static void
test_stall_speed_should_trip_below_the_threshold_after_the_persistence_time(void **state)
{
    (void)state;
    mc_stall_in_t in = healthy();
    for (int sign = -1; sign <= 1; sign += 2) {
        in.speed = (q15_t)(sign * (MC_STALL_SPEED_Q15 - 1));
        assert_int_equal(run_stall(&in, MC_STALL_TICKS), MC_FAULT_STALL_SPEED);
        assert_int_equal(run_stall(&in, MC_STALL_TICKS - 1U), MC_FAULT_NONE);
        in.speed = (q15_t)(sign * MC_STALL_SPEED_Q15); /* at the threshold: not below */
        assert_int_equal(run_stall(&in, 1000U), MC_FAULT_NONE);
    }
    printf("measured: stall speed %d LSB = %.0f rpm for %u speed-loop runs = %.0f ms\n",
           MC_STALL_SPEED_Q15, MC_STALL_SPEED_Q15 * MC_SPEED_FULLSCALE_RPM / 32768.0,
           (unsigned)MC_STALL_TICKS, 1000.0 * MC_STALL_TICKS / MC_SPEED_LOOP_HZ);
}

static void test_stall_bemf_should_trip_outside_its_band_and_ignore_the_low_side_in_fw(void **state)
{
    (void)state;
    mc_stall_in_t in = healthy();
    in.emf_ratio = (q15_t)(MC_STALL_BEMF_LO_Q12 - 1);
    assert_int_equal(run_stall(&in, MC_STALL_TICKS), MC_FAULT_STALL_BEMF);
    assert_int_equal(run_stall(&in, MC_STALL_TICKS - 1U), MC_FAULT_NONE);
    in.fw_active = true; /* weakened flux: a low ratio is expected */
    assert_int_equal(run_stall(&in, 1000U), MC_FAULT_NONE);
    in.fw_active = false;
    in.emf_ratio = MC_STALL_BEMF_LO_Q12;
    assert_int_equal(run_stall(&in, 1000U), MC_FAULT_NONE);
    in.emf_ratio = MC_STALL_BEMF_HI_Q12;
    assert_int_equal(run_stall(&in, 1000U), MC_FAULT_NONE);
    in.emf_ratio = (q15_t)(MC_STALL_BEMF_HI_Q12 + 1);
    in.fw_active = true;
    assert_int_equal(run_stall(&in, MC_STALL_TICKS), MC_FAULT_STALL_BEMF);
    assert_int_equal(run_stall(&in, MC_STALL_TICKS - 1U), MC_FAULT_NONE);
}

static void
test_stall_track_should_need_both_the_speed_error_and_a_saturated_speed_loop(void **state)
{
    (void)state;
    mc_stall_in_t in = healthy();
    for (int sign = -1; sign <= 1; sign += 2) {
        in.speed_err = (q15_t)(sign * (MC_STALL_SPEED_ERR_Q15 + 1));
        in.saturated = (int8_t)sign;
        assert_int_equal(run_stall(&in, MC_STALL_TRACK_TICKS), MC_FAULT_STALL_TRACK);
        assert_int_equal(run_stall(&in, MC_STALL_TRACK_TICKS - 1U), MC_FAULT_NONE);
        in.saturated = 0;
        assert_int_equal(run_stall(&in, 1000U), MC_FAULT_NONE);
        in.saturated = (int8_t)-sign;
        in.speed_err = (q15_t)(sign * MC_STALL_SPEED_ERR_Q15);
        assert_int_equal(run_stall(&in, 1000U), MC_FAULT_NONE);
    }
}

/* The speed PI at its limits for `half` runs, then inside them for `gap`
 * runs, flips + 1 times, alternating the limit (the first at +1): the
 * first fault code seen, and in *at the run it came at. */
static uint16_t run_swing(unsigned flips, unsigned half, unsigned gap, unsigned *at)
{
    mc_stall_t s;
    memset(&s, 0, sizeof s);
    mc_stall_in_t in = healthy();
    unsigned k = 0;
    int8_t side = 1;
    for (unsigned f = 0; f <= flips; f++) {
        for (unsigned j = 0; j < half + gap; j++, k++) {
            in.saturated = (j < half) ? side : (int8_t)0;
            uint16_t code = mc_stall_check(&s, &in);
            if (code != MC_FAULT_NONE) {
                *at = k;
                return code;
            }
        }
        side = (int8_t)-side;
    }
    *at = k;
    return MC_FAULT_NONE;
}

static void
test_speed_unstable_should_trip_on_reversals_between_the_limits_each_within_the_gap(void **state)
{
    (void)state;
    unsigned at = 0;
    /* a limit cycle at about 30 Hz: at a limit both ways, no error persisting */
    assert_int_equal(run_swing(MC_SWING_FLIPS, 16U, 0U, &at), MC_FAULT_SPEED_UNSTABLE);
    assert_int_equal(at, MC_SWING_FLIPS * 16U);
    assert_int_equal(run_swing(MC_SWING_FLIPS - 1U, 16U, 0U, &at), MC_FAULT_NONE);
    /* inside the limits between the reversals, up to the gap: still one run */
    unsigned half = 4U;
    unsigned gap = MC_SWING_GAP_TICKS - half;
    assert_int_equal(run_swing(MC_SWING_FLIPS, half, gap, &at), MC_FAULT_SPEED_UNSTABLE);
    /* one run more between reversals ends each run: none, however many */
    assert_int_equal(run_swing(10U * MC_SWING_FLIPS, half, gap + 1U, &at), MC_FAULT_NONE);
    /* always at the same limit (a load step, an overload): not this check's */
    mc_stall_t s;
    memset(&s, 0, sizeof s);
    mc_stall_in_t in = healthy();
    in.saturated = 1;
    for (unsigned k = 0; k < 1000U; k++) {
        assert_int_equal(mc_stall_check(&s, &in), MC_FAULT_NONE);
    }
    printf(
        "measured: SPEED_UNSTABLE after %u reversals, each within %u speed-loop runs = %.0f ms\n",
        (unsigned)MC_SWING_FLIPS, (unsigned)MC_SWING_GAP_TICKS,
        1000.0 * MC_SWING_GAP_TICKS / MC_SPEED_LOOP_HZ);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_mc_init_should_leave_the_core_stopped_with_no_fault, setup),
        cmocka_unit_test_setup(
            test_mc_step_in_stopped_should_give_half_duties_and_outputs_off_whatever_the_frame,
            setup),
        cmocka_unit_test_setup(
            test_mc_request_out_of_range_should_break_its_contract_and_change_nothing, setup),
        cmocka_unit_test_setup(
            test_start_should_discard_the_first_conversions_calibrate_the_offsets_then_lock, setup),
        cmocka_unit_test_setup(test_calibration_should_fault_when_an_offset_is_beyond_the_limit,
                               setup),
        cmocka_unit_test_setup(test_calibration_should_accept_an_offset_at_the_limit, setup),
        cmocka_unit_test_setup(
            test_lock_should_hold_a_fixed_angle_with_the_lock_current_for_the_lock_time, setup),
        cmocka_unit_test_setup(test_lock_should_drive_the_current_towards_its_reference, setup),
        cmocka_unit_test_setup(test_voltage_circle_should_hold_when_vd_jumps_between_periods,
                               setup),
        cmocka_unit_test_setup(test_open_loop_should_advance_the_angle_at_constant_acceleration,
                               setup),
        cmocka_unit_test_setup(test_open_loop_should_retry_a_failed_start_then_fault, setup),
        cmocka_unit_test_setup(
            test_stop_should_reach_stopped_with_outputs_off_from_every_running_state, setup),
        cmocka_unit_test_setup(
            test_start_stop_should_toggle_and_start_should_not_restart_a_running_core, setup),
        cmocka_unit_test_setup(test_set_gain_should_apply_to_d_and_q_together_at_the_next_step_only,
                               setup),
        cmocka_unit_test_setup(test_set_gain_should_refuse_unknown_gains_and_negative_values,
                               setup),
        cmocka_unit_test_setup(test_a_request_posted_twice_before_a_step_should_count_once, setup),
        cmocka_unit_test_setup(
            test_overcurrent_should_trip_at_the_threshold_on_any_phase_in_one_period, setup),
        cmocka_unit_test_setup(test_overcurrent_should_not_trip_just_below_the_threshold, setup),
        cmocka_unit_test_setup(test_undervoltage_should_trip_at_the_threshold_while_running_only,
                               setup),
        cmocka_unit_test_setup(test_overvoltage_should_trip_at_the_threshold_in_any_state, setup),
        cmocka_unit_test_setup(test_start_should_be_refused_while_the_bus_is_out_of_its_window,
                               setup),
        cmocka_unit_test_setup(
            test_start_from_fault_should_be_refused_while_the_bus_is_still_overvoltage, setup),
        cmocka_unit_test_setup(test_hw_fault_should_latch_from_any_state_until_a_new_start, setup),
        cmocka_unit_test_setup(test_a_start_in_the_same_frame_as_a_fault_should_not_clear_it,
                               setup),
        cmocka_unit_test_setup(test_pot_should_map_linearly_onto_the_speed_reference_range, setup),
        cmocka_unit_test_setup(test_pot_should_map_linearly_onto_the_torque_reference_range, setup),
        cmocka_unit_test_setup(test_the_later_choice_of_reference_should_win_and_show_at_once,
                               setup),
        cmocka_unit_test_setup(test_speed_target_should_follow_the_pot_then_the_remote_reference,
                               setup),
        cmocka_unit_test_setup(
            test_deadtime_counts_should_follow_the_current_sign_with_a_linear_band, setup),
        cmocka_unit_test(test_deadtime_counts_should_follow_a_run_time_band),
        cmocka_unit_test(test_deadtime_from_lock_should_scale_the_dead_time_by_the_missed_voltage),
        cmocka_unit_test_setup(
            test_duty_to_voltage_should_match_the_double_precision_reconstruction, setup),
        cmocka_unit_test(
            test_stall_speed_should_trip_below_the_threshold_after_the_persistence_time),
        cmocka_unit_test(
            test_stall_bemf_should_trip_outside_its_band_and_ignore_the_low_side_in_fw),
        cmocka_unit_test(
            test_stall_track_should_need_both_the_speed_error_and_a_saturated_speed_loop),
        cmocka_unit_test(
            test_speed_unstable_should_trip_on_reversals_between_the_limits_each_within_the_gap),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
