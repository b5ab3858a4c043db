/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_ripple.c - ripple_compensate against AN1078 Equation 8 in double precision. */
#include "test_support.h"

#include <math.h>
#include <stdio.h>

#include "ripple.h"

/* Equation 8 as printed, both branches, in LSB; then saturated to Q15. */
static double eq8(q15_t v_pi, q15_t vbus, q15_t target)
{
    double v = (double)v_pi;
    double d = (double)vbus;
    double t = (double)target;
    double r;
    if (t > d) {
        r = v + (t - d) / d * v;
    } else if (d > t) {
        r = t / d * v;
    } else {
        r = v;
    }
    return fmin(fmax(r, -32768.0), 32767.0);
}

/* The gain rounded to Q15 (at most |Vpi| 2^-16 < 0.5 LSB of V) and the
 * product rounded (0.5 LSB): |error| <= 1 LSB after saturation, which the
 * reference applies too, wherever DCbus > Target / 2 (ripple.h). */
#define RIPPLE_BOUND_LSB (1.0 + 1e-9)

/* Equation 8 with the gain capped as ripple.h states (Target / DCbus at
 * most 65535 / 32768). */
static double eq8_capped(q15_t v_pi, q15_t vbus, q15_t target)
{
    double g = (double)target / (double)vbus;
    if (g > 65535.0 / 32768.0) {
        return fmin(fmax((double)v_pi * 65535.0 / 32768.0, -32768.0), 32767.0);
    }
    return eq8(v_pi, vbus, target);
}

static void test_ripple_compensate_should_follow_equation_8_over_a_dense_grid(void **state)
{
    (void)state;
    err_stats_t e;
    err_stats_init(&e);
    long saturated = 0;
    for (int32_t vb = 1; vb <= 32767; vb = (vb < 64) ? vb + 1 : vb + vb / 40 + 1) {
        for (int32_t t = 1; t <= 32767; t = (t < 16) ? t + 1 : t + t / 12 + 1) {
            for (int32_t v = -32768; v <= 32767; v += 331) {
                q15_t out = ripple_compensate((q15_t)v, (q15_t)vb, (q15_t)t);
                double ref = eq8_capped((q15_t)v, (q15_t)vb, (q15_t)t);
                err_stats_add(&e, (double)out - ref, (double)vb);
                if (ref >= 32767.0 || ref <= -32768.0) {
                    saturated++;
                }
            }
            /* The extremes of Vpi. */
            for (int32_t v = 32767; v >= 32760; v--) {
                q15_t vv[2] = {(q15_t)v, (q15_t)(-v - 1)};
                for (int k = 0; k < 2; k++) {
                    q15_t out = ripple_compensate(vv[k], (q15_t)vb, (q15_t)t);
                    err_stats_add(&e, (double)out - eq8_capped(vv[k], (q15_t)vb, (q15_t)t),
                                  (double)vb);
                }
            }
        }
    }
    err_stats_print("ripple_compensate vs Equation 8 (DCbus x Target x Vpi grid)", &e, "LSB");
    printf("measured: ripple grid: %ld of %ld points saturated\n", saturated, e.n);
    assert_cmp(e.n, >, 1000000);
    assert_cmp(saturated, >, 0);
    assert_cmp(e.max_abs, <=, RIPPLE_BOUND_LSB);
}

/* Around the operating point, DCbus rippling +-20 % about the target. */
static void test_ripple_compensate_should_follow_equation_8_around_the_target(void **state)
{
    (void)state;
    err_stats_t e;
    err_stats_init(&e);
    const q15_t target = Q15(0.75);
    for (int32_t vb = Q15(0.6); vb <= Q15(0.9); vb++) {
        for (int32_t v = -32768; v <= 32767; v += 1021) {
            q15_t out = ripple_compensate((q15_t)v, (q15_t)vb, target);
            err_stats_add(&e, (double)out - eq8((q15_t)v, (q15_t)vb, target), (double)vb);
        }
    }
    err_stats_print("ripple_compensate vs Equation 8, DCbus within +-20 % of target", &e, "LSB");
    assert_cmp(e.max_abs, <=, RIPPLE_BOUND_LSB);
}

static void test_ripple_compensate_should_pass_through_at_the_target(void **state)
{
    (void)state;
    for (int32_t v = -32768; v <= 32767; v++) {
        assert_int_equal(ripple_compensate((q15_t)v, Q15(0.6), Q15(0.6)), v);
        assert_int_equal(ripple_compensate((q15_t)v, 32767, 32767), v);
    }
}

static void test_ripple_compensate_should_never_divide_by_zero_or_overflow(void **state)
{
    (void)state;
    const q15_t vs[] = {-32768, -32767, -1000, -1, 0, 1, 1000, 32767};
    for (unsigned i = 0; i < sizeof vs / sizeof vs[0]; i++) {
        q15_t v = vs[i];
        q15_t capped = (q15_t)lround(eq8_capped(v, 1, 32767));
        /* DCbus <= 0 or below Target / 2: the gain stays at its top. */
        assert_int_equal(ripple_compensate(v, 0, Q15(0.5)), capped);
        assert_int_equal(ripple_compensate(v, -1, Q15(0.5)), capped);
        assert_int_equal(ripple_compensate(v, -32768, 32767), capped);
        assert_int_equal(ripple_compensate(v, 1, 32767), capped);
        assert_int_equal(ripple_compensate(v, 1, 2), capped);
        /* Target <= 0: compensation off. */
        assert_int_equal(ripple_compensate(v, Q15(0.5), 0), v);
        assert_int_equal(ripple_compensate(v, Q15(0.5), -32768), v);
    }
    assert_int_equal(ripple_gain(0, Q15(0.5)), 65535);
    assert_int_equal(ripple_gain(Q15(0.5), 0), 32768);
    assert_int_equal(ripple_gain(Q15(0.5), Q15(0.5)), 32768);
    assert_int_equal(ripple_gain(16384, 32767), 65534); /* 1.99994, still exact */
    assert_int_equal(ripple_gain(16383, 32767), 65535); /* above 2 - 2^-16: capped */
    /* DCbus = 1 LSB, Target = 1 LSB: V = Vpi. DCbus = 2, Target = 1: halves,
     * rounded to nearest, ties up. */
    assert_int_equal(ripple_compensate(12345, 1, 1), 12345);
    assert_int_equal(ripple_compensate(3, 2, 1), 2);
    assert_int_equal(ripple_compensate(-3, 2, 1), -1);
    assert_int_equal(ripple_compensate(-32768, 2, 1), -16384);
    /* The largest boost that still fits, and the first that does not. */
    assert_int_equal(ripple_compensate(16383, 16384, 32767), 32765);
    assert_int_equal(ripple_compensate(16384, 16384, 32767), 32767);
    assert_int_equal(ripple_compensate(-16384, 16384, 32767), -32767);
    assert_int_equal(ripple_compensate(-16385, 16384, 32767), -32768);
}

static void test_ripple_compensate_dq_should_treat_both_axes_alike(void **state)
{
    (void)state;
    uint32_t rng = 99U;
    for (int i = 0; i < 100000; i++) {
        dq_q15_t v;
        v.d = test_rand_i16(&rng);
        v.q = test_rand_i16(&rng);
        q15_t vb = test_rand_i16(&rng);
        q15_t t = test_rand_i16(&rng);
        dq_q15_t o = ripple_compensate_dq(v, vb, t);
        assert_int_equal(o.d, ripple_compensate(v.d, vb, t));
        assert_int_equal(o.q, ripple_compensate(v.q, vb, t));
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ripple_compensate_should_follow_equation_8_over_a_dense_grid),
        cmocka_unit_test(test_ripple_compensate_should_follow_equation_8_around_the_target),
        cmocka_unit_test(test_ripple_compensate_should_pass_through_at_the_target),
        cmocka_unit_test(test_ripple_compensate_should_never_divide_by_zero_or_overflow),
        cmocka_unit_test(test_ripple_compensate_dq_should_treat_both_axes_alike),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
