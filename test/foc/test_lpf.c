/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_lpf.c - lpf_update against the double recurrence y += K (x - y). */
#include "test_support.h"

#include <math.h>
#include <stdio.h>

#include "lpf.h"

/*
 * Bound (stated in lpf.h): each update lands 0 to 2 Q31 LSB = 0 to 2^-15 LSB
 * of Q15 above the exact step (q15_dsp.h note 1); a first-order filter with
 * pole 1 - K sums those to at most 2^-15 / (k / 32768) = 1 / k LSB in the
 * state, and the Q15 output adds its own half-LSB rounding. So
 * |output - reference| <= 0.5 + 1 / k LSB and 0 <= state - reference <=
 * 1 / k LSB, k the raw Q15 gain.
 */
static double state_bound_lsb(q15_t k)
{
    return 1.0 / (double)k + 1e-9;
}

static double output_bound_lsb(q15_t k)
{
    return 0.5 + state_bound_lsb(k);
}

/* The reference, in LSB of Q15: y += (k / 32768) (x - y). */
static double ref_update(double y, q15_t x, q15_t k)
{
    return y + q15_to_double(k) * ((double)x - y);
}

static double state_lsb(const lpf_t *f)
{
    return (double)f->state / 65536.0;
}

typedef struct {
    err_stats_t out;
    err_stats_t st;
} lpf_errs_t;

static void errs_init(lpf_errs_t *e)
{
    err_stats_init(&e->out);
    err_stats_init(&e->st);
}

/* One step of the filter and of the reference, recording both errors. */
static double step_both(lpf_t *f, double y, q15_t x, q15_t k, lpf_errs_t *e, double at)
{
    q15_t out = lpf_update(f, x, k);
    y = ref_update(y, x, k);
    err_stats_add(&e->out, (double)out - y, at);
    err_stats_add(&e->st, state_lsb(f) - y, at);
    assert_int_equal(out, lpf_output(f));
    return y;
}

static const q15_t gains[] = {1, Q15(0.0005), Q15(0.003), Q15(0.01), Q15(0.1), Q15(0.5), 32767};

static void test_lpf_update_should_follow_the_double_recurrence_on_steps(void **state)
{
    static const q15_t from[] = {0, -32768, 32767, 100};
    static const q15_t to[] = {32767, 32767, -32768, -7};
    size_t g;
    (void)state;

    for (g = 0U; g < sizeof gains / sizeof gains[0]; g++) {
        q15_t k = gains[g];
        lpf_errs_t e;
        char name[96];
        size_t s;
        /* 12 time constants, so the tail near the target is covered too. */
        long n = 12L * 32768L / (long)k + 10L;

        errs_init(&e);
        for (s = 0U; s < sizeof from / sizeof from[0]; s++) {
            lpf_t f;
            double y = (double)from[s];
            long i;
            lpf_reset(&f, from[s]);
            for (i = 0; i < n; i++) {
                y = step_both(&f, y, to[s], k, &e, (double)i);
            }
            assert_cmp(fabs((double)lpf_output(&f) - (double)to[s]), <=, 1.0);
        }
        (void)snprintf(name, sizeof name, "lpf steps, K = %d (output)", k);
        err_stats_print(name, &e.out, "LSB");
        (void)snprintf(name, sizeof name, "lpf steps, K = %d (Q31 state)", k);
        err_stats_print(name, &e.st, "LSB");
        assert_cmp(e.out.max_abs, <=, output_bound_lsb(k));
        assert_cmp(e.st.max_abs, <=, state_bound_lsb(k));
    }
}

static void test_lpf_update_should_follow_the_double_recurrence_on_sines(void **state)
{
    size_t g;
    (void)state;

    for (g = 0U; g < sizeof gains / sizeof gains[0]; g++) {
        q15_t k = gains[g];
        lpf_errs_t e;
        char name[96];
        lpf_t f;
        double y = 0.0;
        long i;
        /* Full-scale sine at the filter's cut-off (omega = K rad/sample),
         * with a floor of 50 samples per period; three periods plus settling. */
        double w = (q15_to_double(k) < 2.0 * M_PI / 50.0) ? q15_to_double(k) : 2.0 * M_PI / 50.0;
        long n = (long)(6.0 * M_PI / w) + 5L * 32768L / (long)k;
        if (n > 2000000L) {
            n = 2000000L;
        }

        errs_init(&e);
        lpf_reset(&f, 0);
        for (i = 0; i < n; i++) {
            q15_t x = (q15_t)lround(32767.0 * sin(w * (double)i));
            y = step_both(&f, y, x, k, &e, (double)i);
        }
        (void)snprintf(name, sizeof name, "lpf full-scale sine at cut-off, K = %d (output)", k);
        err_stats_print(name, &e.out, "LSB");
        assert_cmp(e.out.max_abs, <=, output_bound_lsb(k));
        assert_cmp(e.st.max_abs, <=, state_bound_lsb(k));
    }
}

/* What a 16-bit state with a truncating product does: y += (K (x - y)) >> 15. */
static q15_t lpf16_update(q15_t y, q15_t x, q15_t k)
{
    return q15_add_sat(y, q15_mul_trunc(k, q15_sub_sat(x, y)));
}

static void test_lpf_update_should_track_a_5_lsb_sine_that_a_16_bit_state_loses(void **state)
{
    const q15_t k = Q15(0.003);
    const double w = q15_to_double(k); /* at the cut-off: output ~3.5 LSB */
    lpf_errs_t e;
    err_stats_t e16;
    lpf_t f;
    q15_t y16 = 0;
    double y = 0.0;
    double peak = 0.0;
    long i;
    const long n = 5L * (long)(2.0 * M_PI / w);
    (void)state;

    errs_init(&e);
    err_stats_init(&e16);
    lpf_reset(&f, 0);
    for (i = 0; i < n; i++) {
        q15_t x = (q15_t)lround(5.0 * sin(w * (double)i));
        y = step_both(&f, y, x, k, &e, (double)i);
        y16 = lpf16_update(y16, x, k);
        err_stats_add(&e16, (double)y16 - y, (double)i);
        if (i > n / 2 && fabs(y) > peak) {
            peak = fabs(y);
        }
    }
    printf("measured: lpf 5-LSB sine at K = %d: reference peak %.3f LSB\n", k, peak);
    err_stats_print("lpf 5-LSB sine, Q31 state (output)", &e.out, "LSB");
    err_stats_print("lpf 5-LSB sine, Q31 state (state)", &e.st, "LSB");
    err_stats_print("lpf 5-LSB sine, 16-bit truncating state (for comparison)", &e16, "LSB");
    assert_cmp(peak, >, 3.0); /* the reference really carries a signal */
    assert_cmp(e.out.max_abs, <=, output_bound_lsb(k));
    assert_cmp(e.st.max_abs, <=, state_bound_lsb(k));
    assert_cmp(e16.max_abs, >, 2.0); /* the sweep is able to see the 16-bit failure */
}

static void test_lpf_update_should_follow_random_inputs_and_changing_gains(void **state)
{
    /* The estimator changes K every period (adaptive filter). */
    uint32_t seed = 0x13579BDFU;
    lpf_errs_t e;
    lpf_t f;
    double y = 0.0;
    long i;
    const q15_t k_min = 16;
    (void)state;

    errs_init(&e);
    lpf_reset(&f, 0);
    for (i = 0; i < 1000000L; i++) {
        q15_t x = test_rand_i16(&seed);
        q15_t k = (q15_t)(k_min + (q15_t)(test_rand_u32(&seed) % (uint32_t)(32768 - k_min)));
        y = step_both(&f, y, x, k, &e, (double)i);
    }
    err_stats_print("lpf random x, random K in [16, 32767], 10^6 steps (output)", &e.out, "LSB");
    err_stats_print("lpf random x, random K in [16, 32767], 10^6 steps (state)", &e.st, "LSB");
    assert_cmp(e.out.max_abs, <=, output_bound_lsb(k_min));
    assert_cmp(e.st.max_abs, <=, state_bound_lsb(k_min));
}

static void test_lpf_update_should_hold_the_state_when_k_is_zero(void **state)
{
    static const q15_t y0s[] = {0, 1, -1, 32767, -32768, 12345};
    uint32_t seed = 0xBEEF1234U;
    size_t j;
    (void)state;

    for (j = 0U; j < sizeof y0s / sizeof y0s[0]; j++) {
        lpf_t f;
        q31_t s0;
        int i;
        lpf_reset(&f, y0s[j]);
        s0 = f.state;
        assert_int_equal(lpf_output(&f), y0s[j]);
        for (i = 0; i < 10000; i++) {
            assert_int_equal(lpf_update(&f, test_rand_i16(&seed), 0), y0s[j]);
        }
        assert_int_equal(lpf_update(&f, 32767, 0), y0s[j]);
        assert_int_equal(lpf_update(&f, -32768, 0), y0s[j]);
        /* A negative gain is outside the contract and is treated as 0. */
        assert_int_equal(lpf_update(&f, 32767, -5), y0s[j]);
        assert_int_equal(lpf_update(&f, -32768, Q15_MIN), y0s[j]);
        assert_cmp(f.state, ==, s0);
    }
}

static void test_lpf_update_should_not_overflow_at_the_extremes(void **state)
{
    /* Full-scale square wave at the largest gain: x - y spans almost 2. */
    lpf_errs_t e;
    lpf_t f;
    double y = -32768.0;
    int i;
    (void)state;

    errs_init(&e);
    lpf_reset(&f, -32768);
    for (i = 0; i < 1000; i++) {
        q15_t x = ((i / 3) % 2 == 0) ? 32767 : -32768;
        y = step_both(&f, y, x, 32767, &e, (double)i);
    }
    err_stats_print("lpf +-full-scale square at K = 32767 (output)", &e.out, "LSB");
    assert_cmp(e.out.max_abs, <=, output_bound_lsb(32767));

    lpf_reset(&f, 32767);
    assert_int_equal(lpf_update(&f, 32767, 32767), 32767);
    assert_int_equal(lpf_update(&f, 32767, 32767), 32767);
    assert_int_equal(lpf_output(&f), 32767);
    lpf_reset(&f, -32768);
    assert_int_equal(lpf_update(&f, -32768, 32767), -32768);
    assert_int_equal(lpf_output(&f), -32768);
    /* One step from -1 to the top at K = 32767: y = -1 + (32767/32768) 2. */
    lpf_reset(&f, -32768);
    assert_int_equal(lpf_update(&f, 32767, 32767), 32765);
    lpf_reset(&f, 32767);
    assert_int_equal(lpf_update(&f, -32768, 32767), -32766);
}

static void test_lpf_reset_should_set_the_output_exactly(void **state)
{
    int32_t v;
    lpf_t f;
    (void)state;

    for (v = -32768; v <= 32767; v++) {
        lpf_reset(&f, (q15_t)v);
        assert_int_equal(lpf_output(&f), v);
        assert_cmp(f.state, ==, (q31_t)v * 65536L);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lpf_update_should_follow_the_double_recurrence_on_steps),
        cmocka_unit_test(test_lpf_update_should_follow_the_double_recurrence_on_sines),
        cmocka_unit_test(test_lpf_update_should_track_a_5_lsb_sine_that_a_16_bit_state_loses),
        cmocka_unit_test(test_lpf_update_should_follow_random_inputs_and_changing_gains),
        cmocka_unit_test(test_lpf_update_should_hold_the_state_when_k_is_zero),
        cmocka_unit_test(test_lpf_update_should_not_overflow_at_the_extremes),
        cmocka_unit_test(test_lpf_reset_should_set_the_output_exactly),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
