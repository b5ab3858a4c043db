/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_pi.c - pi_update against a double model of AN1078's PI equations. */
#include "test_support.h"

#include <math.h>
#include <stdio.h>

#include "pi.h"

/*
 * The reference is the same five equations in double precision, in LSB of
 * Q15 (raw units), with the saturations the header specifies (Err to Q15,
 * U and Sum to the Q31 range, Exc to Q15) but no rounding anywhere:
 *   Err = sat15(ref - meas); U = sat31(Sum + Kp 2^s Err);
 *   Out = clamp(U, lo, hi); Exc = sat15(U - Out);
 *   Sum = sat31(sat31(Sum + Ki Err) - Kc Exc).
 * Bound (pi.c note 1): U is rounded to Q15 (0.5 LSB) and Exc is rounded
 * before the Kc product, which leaves at most 0.5 LSB in Sum (the saturated
 * integral contracts with 1 - Kc, the linear one adds Ki Err exactly), so
 * |Out - reference| <= 1 LSB.
 */
#define PI_BOUND_LSB 1.0

#define Q31_HI_LSB (32768.0 - 1.0 / 65536.0)

typedef struct {
    double kp, ki, kc, lo, hi; /* gains as real numbers, limits in LSB */
    double sum;                /* LSB */
} pi_model_t;

static double clampd(double x, double lo, double hi)
{
    return (x > hi) ? hi : ((x < lo) ? lo : x);
}

static void model_init(pi_model_t *m, const pi_params_t *p)
{
    m->kp = q15_to_double(p->kp) * (double)(1U << p->kp_shift);
    m->ki = q15_to_double(p->ki);
    m->kc = q15_to_double(p->kc);
    m->lo = (double)p->out_min;
    m->hi = (double)p->out_max;
    m->sum = 0.0;
}

static double model_update(pi_model_t *m, q15_t ref, q15_t meas)
{
    double err = clampd((double)ref - (double)meas, -32768.0, 32767.0);
    double u = clampd(m->sum + m->kp * err, -32768.0, Q31_HI_LSB);
    double out = clampd(u, m->lo, m->hi);
    double exc = clampd(u - out, -32768.0, 32767.0);
    double s = clampd(m->sum + m->ki * err, -32768.0, Q31_HI_LSB);
    m->sum = clampd(s - m->kc * exc, -32768.0, Q31_HI_LSB);
    return out;
}

static pi_params_t params(q15_t kp, uint8_t shift, q15_t ki, q15_t kc, q15_t lo, q15_t hi)
{
    pi_params_t p;
    p.kp = kp;
    p.kp_shift = shift;
    p.ki = ki;
    p.kc = kc;
    p.out_min = lo;
    p.out_max = hi;
    return p;
}

/* Random gains and limits; open-loop random ref/meas and a closed loop
 * through a first-order plant fed by the fixed-point output (both
 * controllers see the same measurement). */
static void test_pi_update_should_match_the_double_model_over_random_sequences(void **state)
{
    (void)state;
    uint32_t rng = 0x1234567U;
    err_stats_t e;
    err_stats_init(&e);
    long saturated_steps = 0;
    for (int trial = 0; trial < 400; trial++) {
        q15_t lo = test_rand_i16(&rng);
        q15_t hi = test_rand_i16(&rng);
        if (lo > hi) {
            q15_t t = lo;
            lo = hi;
            hi = t;
        }
        if (trial % 4 == 0) {
            lo = -32768;
            hi = 32767;
        }
        uint8_t shift = (uint8_t)(test_rand_u32(&rng) % 8U);
        q15_t kp = (q15_t)(test_rand_u32(&rng) % 32768U);
        q15_t ki = (q15_t)(test_rand_u32(&rng) % 4000U);
        q15_t kc;
        switch (trial % 3) {
            case 0:
                kc = ki;
                break;
            case 1:
                kc = 0;
                break;
            default:
                kc = (q15_t)(test_rand_u32(&rng) % 32768U);
                break;
        }
        pi_params_t p = params(kp, shift, ki, kc, lo, hi);
        pi_t pi;
        pi_model_t m;
        pi_init(&pi, &p);
        model_init(&m, &p);
        bool closed = (trial % 2) == 0;
        double y = 0.0;
        q15_t ref = test_rand_i16(&rng);
        for (int n = 0; n < 2000; n++) {
            q15_t meas;
            if (n % 200 == 0) {
                ref = test_rand_i16(&rng);
            }
            if (closed) {
                meas = q15_sat((int32_t)lround(y));
            } else {
                meas = test_rand_i16(&rng);
            }
            q15_t out = pi_update(&pi, ref, meas);
            double mo = model_update(&m, ref, meas);
            err_stats_add(&e, (double)out - mo, (double)trial);
            if (out == lo || out == hi) {
                saturated_steps++;
            }
            y += 0.05 * ((double)out - y);
            if (n == 1000 && trial % 5 == 0) {
                /* Limits changed at run time, as the core does with Vq. */
                q15_t nlo = q15_sat((int32_t)lo / 2);
                q15_t nhi = q15_sat((int32_t)hi / 2);
                pi_set_limits(&pi, nlo, nhi);
                m.lo = (double)pi.p.out_min;
                m.hi = (double)pi.p.out_max;
            }
        }
    }
    err_stats_print("pi_update vs double model (400 random runs x 2000 steps)", &e, "LSB");
    printf("measured: pi random runs: %ld of %ld steps at a limit\n", saturated_steps, e.n);
    assert_cmp(e.max_abs, <=, PI_BOUND_LSB);
    assert_cmp(saturated_steps, >, e.n / 10); /* the anti-windup path was exercised */
}

/* Open loop: Out(n) = Kp E + (n) Ki E exactly, rounded once. */
static void test_pi_update_should_give_the_textbook_step_response(void **state)
{
    (void)state;
    pi_params_t p = params(Q15(0.25), 1, Q15(0.001), Q15(0.001), -32768, 32767);
    pi_t pi;
    pi_init(&pi, &p);
    const q15_t e_step = Q15(0.3);
    err_stats_t e;
    err_stats_init(&e);
    for (int n = 0; n < 500; n++) {
        q15_t out = pi_update(&pi, e_step, 0);
        double expect = 0.5 * (double)e_step + (double)n * q15_to_double(Q15(0.001)) * e_step;
        err_stats_add(&e, (double)out - expect, n);
    }
    err_stats_print("pi step response vs Kp E + n Ki E", &e, "LSB");
    assert_cmp(e.max_abs, <=, 0.5);
}

/* Closed loop through a first-order plant: the integral removes the error. */
static void test_pi_update_should_drive_the_steady_state_error_to_zero(void **state)
{
    (void)state;
    pi_params_t p = params(Q15(0.5), 0, Q15(0.02), Q15(0.02), Q15(-0.9), Q15(0.9));
    const q15_t refs[] = {Q15(0.5), Q15(-0.3), 1, -1, 0, Q15(0.8999)};
    for (unsigned k = 0; k < sizeof refs / sizeof refs[0]; k++) {
        pi_t pi;
        pi_init(&pi, &p);
        double y = 0.0;
        int last_nonzero = -1;
        for (int n = 0; n < 5000; n++) {
            q15_t meas = q15_sat((int32_t)lround(y));
            q15_t err = q15_sub_sat(refs[k], meas);
            if (err != 0) {
                last_nonzero = n;
            }
            q15_t out = pi_update(&pi, refs[k], meas);
            y += 0.1 * ((double)out - y); /* plant gain 1, pole 0.9 */
        }
        printf("measured: pi closed loop ref %d: last step with error != 0: %d of 5000\n", refs[k],
               last_nonzero);
        assert_cmp(last_nonzero, <, 4000); /* zero error for the last 1000 steps */
    }
}

/* Saturate for 20,000 steps, then reverse the error; count the steps until
 * the output leaves the limit, with and without Kc. */
static int steps_to_leave_limit(q15_t kc, q31_t *sum_at_reversal)
{
    pi_params_t p = params(Q15(0.5), 0, Q15(0.01), kc, Q15(-0.3), Q15(0.3));
    pi_t pi;
    pi_init(&pi, &p);
    for (int n = 0; n < 20000; n++) {
        q15_t out = pi_update(&pi, Q15(0.5), 0);
        if (n >= 10) { /* Kp E = 0.25 alone is below the limit at first */
            assert_int_equal(out, Q15(0.3));
        }
    }
    *sum_at_reversal = pi.sum;
    for (int n = 0; n < 100000; n++) {
        if (pi_update(&pi, Q15(-0.1), 0) < Q15(0.3)) {
            return n + 1;
        }
    }
    return -1;
}

static void test_pi_update_should_leave_the_limit_quickly_after_windup_only_with_kc(void **state)
{
    (void)state;
    q31_t sum_kc;
    q31_t sum_nokc;
    int with_kc = steps_to_leave_limit(Q15(0.01), &sum_kc);
    int without_kc = steps_to_leave_limit(0, &sum_nokc);

    /* With Kc = Ki the saturated steady state is U = Out + Err = 0.8, so
     * Sum = 0.8 - Kp 0.5 = 0.55; after the reversal U = Sum - 0.05 decays
     * with factor (1 - Kc) toward Out + Err = 0.2 and crosses 0.3 after
     * 1 + ln(0.3 / 0.1) / -ln(1 - Kc) = 110.2 calls. */
    double kc = q15_to_double(Q15(0.01));
    double predicted = 1.0 + log(0.3 / 0.1) / -log(1.0 - kc);
    printf("measured: pi windup: Sum after 20000 saturated steps = %.5f (Kc = Ki), %.5f (Kc = 0)\n",
           q31_to_double(sum_kc), q31_to_double(sum_nokc));
    printf("measured: pi windup: steps to leave the limit after the error reverses: %d with Kc "
           "= Ki (predicted %.1f), %d with Kc = 0\n",
           with_kc, predicted, without_kc);
    assert_cmp(fabs(q31_to_double(sum_kc) - 0.55), <, 2.0 / 32768.0);
    assert_cmp(with_kc, >, 0);
    assert_cmp(fabs((double)with_kc - predicted), <=, 1.0);
    assert_cmp(q31_to_double(sum_nokc), >, 0.999); /* wound up to the accumulator limit */
    assert_cmp(without_kc, >, 5 * with_kc);
}

static void test_pi_update_should_stop_at_both_limits_and_follow_new_limits(void **state)
{
    (void)state;
    pi_params_t p = params(Q15(0.9), 2, Q15(0.05), Q15(0.05), Q15(-0.4), Q15(0.6));
    pi_t pi;
    pi_init(&pi, &p);
    for (int n = 0; n < 1000; n++) {
        assert_int_equal(pi_update(&pi, 32767, -32768), Q15(0.6));
    }
    /* Reversed: the integral parked one error above the limit unwinds, and
     * the output never leaves [out_min, out_max] on the way. */
    for (int n = 0; n < 1000; n++) {
        q15_t out = pi_update(&pi, -32768, 32767);
        assert_cmp(out, >=, Q15(-0.4));
        assert_cmp(out, <=, Q15(0.6));
    }
    assert_int_equal(pi.out, Q15(-0.4));
    pi_set_limits(&pi, Q15(-0.1), Q15(0.1));
    assert_int_equal(pi_update(&pi, -32768, 32767), Q15(-0.1));
    pi_set_limits(&pi, -32768, 32767);
    for (int n = 0; n < 2000; n++) {
        (void)pi_update(&pi, -32768, 32767);
    }
    assert_int_equal(pi.out, -32768);
    for (int n = 0; n < 2000; n++) {
        (void)pi_update(&pi, 32767, -32768);
    }
    assert_int_equal(pi.out, 32767);
    /* Inverted limits: both become out_max. */
    pi_set_limits(&pi, Q15(0.5), Q15(0.2));
    assert_int_equal(pi.p.out_min, Q15(0.2));
    assert_int_equal(pi.p.out_max, Q15(0.2));
    assert_int_equal(pi_update(&pi, -32768, 32767), Q15(0.2));
}

/* Err = ref - meas must saturate, not wrap, at the extremes. */
static void test_pi_update_should_saturate_the_error_at_the_extremes(void **state)
{
    (void)state;
    pi_params_t p = params(32767, 0, 0, 0, -32768, 32767);
    pi_t pi;
    pi_init(&pi, &p);
    /* Err = 65535 saturates to 32767: Out = round(32767 * 32767 / 32768). */
    assert_int_equal(pi_update(&pi, 32767, -32768), 32766);
    /* Err = -65535 saturates to -32768: Out = -32767 (a wrap would give +1). */
    assert_int_equal(pi_update(&pi, -32768, 32767), -32767);
    assert_int_equal(pi_update(&pi, -32768, -32768), 0);
    assert_int_equal(pi_update(&pi, 32767, 32767), 0);
}

static void test_pi_update_should_scale_kp_by_its_shift_and_saturate(void **state)
{
    (void)state;
    for (uint8_t shift = 0; shift <= 7; shift++) {
        pi_params_t p = params(Q15(0.75), shift, 0, 0, -32768, 32767);
        pi_t pi;
        pi_init(&pi, &p);
        for (int32_t e = -32768; e <= 32767; e += 7) {
            q15_t out = pi_update(&pi, (q15_t)e, 0);
            double expect = 0.75 * (double)(1U << shift) * (double)e;
            expect = clampd(floor(expect + 0.5), -32768.0, 32767.0);
            assert_int_equal(out, (int)expect);
        }
    }
    /* The largest gain on the largest error: the Q31 accumulator saturates;
     * reversed, the P term (-128) outweighs the saturated Sum (+1) at once. */
    pi_params_t p = params(32767, 7, 32767, 0, -32768, 32767);
    pi_t pi;
    pi_init(&pi, &p);
    for (int n = 0; n < 10; n++) {
        assert_int_equal(pi_update(&pi, 32767, -32768), 32767);
    }
    assert_int_equal(pi.sum, Q31_MAX);
    for (int n = 0; n < 3; n++) {
        assert_int_equal(pi_update(&pi, -32768, 32767), -32768);
    }
    /* kp_shift above 7 is treated as 7. */
    p = params(Q15(0.5), 12, 0, 0, -32768, 32767);
    pi_init(&pi, &p);
    assert_int_equal(pi.p.kp_shift, 7);
    assert_int_equal(pi_update(&pi, 100, 0), 6400);
}

static void test_pi_preset_should_hand_over_without_a_bump(void **state)
{
    (void)state;
    pi_params_t p = params(Q15(0.3), 1, Q15(0.01), Q15(0.01), Q15(-0.5), Q15(0.5));
    pi_t pi;
    pi_init(&pi, &p);
    pi_preset(&pi, Q15(0.2));
    assert_int_equal(pi.out, Q15(0.2));
    assert_int_equal(pi_update(&pi, 1234, 1234), Q15(0.2));
    assert_int_equal(pi_update(&pi, 1234, 1234), Q15(0.2));
    pi_preset(&pi, Q15(-0.8)); /* outside the limits: output clamped */
    assert_int_equal(pi.out, Q15(-0.5));
    assert_int_equal(pi.sum, q31_from_q15(Q15(-0.8)));
    pi_reset(&pi);
    assert_int_equal(pi.sum, 0);
    assert_int_equal(pi.out, 0);
    assert_int_equal(pi_update(&pi, 0, 0), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pi_update_should_match_the_double_model_over_random_sequences),
        cmocka_unit_test(test_pi_update_should_give_the_textbook_step_response),
        cmocka_unit_test(test_pi_update_should_drive_the_steady_state_error_to_zero),
        cmocka_unit_test(test_pi_update_should_leave_the_limit_quickly_after_windup_only_with_kc),
        cmocka_unit_test(test_pi_update_should_stop_at_both_limits_and_follow_new_limits),
        cmocka_unit_test(test_pi_update_should_saturate_the_error_at_the_extremes),
        cmocka_unit_test(test_pi_update_should_scale_kp_by_its_shift_and_saturate),
        cmocka_unit_test(test_pi_preset_should_hand_over_without_a_bump),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
