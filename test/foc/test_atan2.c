/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_atan2.c - atan2_q15 and atan2_q31 against double atan2 at every magnitude. */
#include "test_support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "atan2.h"

/* Bounds stated in atan2.c note 1: 0.96 LSB for 16-bit inputs, 1.28 LSB for
 * inputs shifted down from 32 bits. One LSB of the binary angle is
 * 360 / 65536 = 0.0055 degrees. */
#define ATAN2_MAX_ERR_LSB   1.0
#define ATAN2_MAX_ERR32_LSB 1.3
#define LSB_PER_DEG         (65536.0 / 360.0)

/* Error of atan2_q15(y, x) against atan2 of the same integers, in LSB of
 * the binary angle, taking the wrap at +-pi into account. */
static double atan2_err_lsb(int16_t y, int16_t x)
{
    angle_q15_t a = atan2_q15(y, x);
    double ref = atan2((double)y, (double)x);
    return angle_diff_deg(angle_to_rad(a), ref) * LSB_PER_DEG;
}

/* The same for atan2_q31. */
static double atan2_err32_lsb(int32_t y, int32_t x)
{
    angle_q15_t a = atan2_q31(y, x);
    double ref = atan2((double)y, (double)x);
    return angle_diff_deg(angle_to_rad(a), ref) * LSB_PER_DEG;
}

static void print_deg(const char *name, const err_stats_t *e)
{
    printf("measured: %s: max |err| = %.4f LSB = %.5f deg\n", name, e->max_abs,
           e->max_abs / LSB_PER_DEG);
}

static int16_t round_i16(double v)
{
    double r = floor(v + 0.5);
    if (r > 32767.0) {
        return 32767;
    }
    if (r < -32768.0) {
        return -32768;
    }
    return (int16_t)r;
}

static void test_atan2_q15_should_stay_within_bound_at_every_magnitude(void **state)
{
    static const double magnitudes[] = {32.0, 128.0, 1024.0, 8192.0, 32767.0, 32768.0};
    const int n_angles = 4096;
    size_t m;
    err_stats_t all;
    (void)state;

    err_stats_init(&all);
    for (m = 0U; m < sizeof magnitudes / sizeof magnitudes[0]; m++) {
        err_stats_t e;
        char name[96];
        int k;
        err_stats_init(&e);
        for (k = 0; k < n_angles; k++) {
            /* Offset by a third of a step so the axes are not the only hits. */
            double th = 2.0 * M_PI * ((double)k + 0.33) / (double)n_angles - M_PI;
            int16_t x = round_i16(magnitudes[m] * cos(th));
            int16_t y = round_i16(magnitudes[m] * sin(th));
            double err = atan2_err_lsb(y, x);
            err_stats_add(&e, err, th * 180.0 / M_PI);
            err_stats_add(&all, err, magnitudes[m]);
        }
        (void)snprintf(name, sizeof name, "atan2_q15 4096 angles at magnitude %.0f", magnitudes[m]);
        err_stats_print(name, &e, "LSB");
        print_deg(name, &e);
        assert_cmp(e.max_abs, <=, ATAN2_MAX_ERR_LSB);
    }
    assert_int_equal(all.n, 6L * n_angles);
}

static void test_atan2_q15_should_stay_within_bound_with_a_minus_32768_component(void **state)
{
    err_stats_t e;
    int32_t v;
    (void)state;

    err_stats_init(&e);
    for (v = -32768; v <= 32767; v++) {
        err_stats_add(&e, atan2_err_lsb(-32768, (int16_t)v), (double)v);
        err_stats_add(&e, atan2_err_lsb((int16_t)v, -32768), (double)v);
        err_stats_add(&e, atan2_err_lsb(32767, (int16_t)v), (double)v);
        err_stats_add(&e, atan2_err_lsb((int16_t)v, 32767), (double)v);
    }
    err_stats_print("atan2_q15 on the full-scale square (one component -32768 or 32767)", &e,
                    "LSB");
    print_deg("atan2_q15 on the full-scale square", &e);
    assert_cmp(e.max_abs, <=, ATAN2_MAX_ERR_LSB);
}

static void test_atan2_q15_should_stay_within_bound_for_a_million_random_pairs(void **state)
{
    /* Bins by the larger magnitude: bin b holds max(|x|,|y|) in [2^b, 2^(b+1)). */
    err_stats_t bins[16];
    err_stats_t all;
    uint32_t seed = 0x2468ACE1U;
    long i;
    int b;
    (void)state;

    err_stats_init(&all);
    for (b = 0; b < 16; b++) {
        err_stats_init(&bins[b]);
    }
    for (i = 0; i < 1000000L; i++) {
        int16_t x = test_rand_i16(&seed);
        int16_t y = test_rand_i16(&seed);
        int32_t mag;
        double err;
        /* Half of the pairs are shrunk by a random shift so every magnitude
         * bin is populated, not only the top one. */
        if ((i & 1L) != 0L) {
            uint8_t sh = (uint8_t)(test_rand_u32(&seed) % 15U);
            x = (int16_t)(x >> sh);
            y = (int16_t)(y >> sh);
        }
        mag = abs((int)x) > abs((int)y) ? abs((int)x) : abs((int)y);
        if (mag == 0) {
            continue;
        }
        err = atan2_err_lsb(y, x);
        for (b = 0; b < 15 && (mag >> (b + 1)) != 0; b++) {
        }
        err_stats_add(&bins[b], err, (double)mag);
        err_stats_add(&all, err, (double)mag);
    }
    for (b = 0; b < 16; b++) {
        if (bins[b].n > 0) {
            printf("measured: atan2_q15 random pairs, max(|x|,|y|) in [%ld, %ld]: max |err| = "
                   "%.4f LSB = %.5f deg, mean |err| = %.4f LSB, n = %ld\n",
                   1L << b, (2L << b) - 1L, bins[b].max_abs, bins[b].max_abs / LSB_PER_DEG,
                   err_stats_mean_abs(&bins[b]), bins[b].n);
        }
    }
    err_stats_print("atan2_q15 all random pairs", &all, "LSB");
    assert_cmp(all.n, >, 990000L);
    for (b = 5; b < 16; b++) { /* from 32 LSB up, the stated bound */
        assert_cmp(bins[b].max_abs, <=, ATAN2_MAX_ERR_LSB);
    }
}

static void test_atan2_q15_should_stay_within_bound_for_tiny_vectors_below_32_lsb(void **state)
{
    /* Every vector with both components in [-31, 31]: the ratio does not
     * depend on the length, so they meet the same bound as large ones. */
    err_stats_t e;
    int x;
    int y;
    (void)state;

    err_stats_init(&e);
    for (y = -31; y <= 31; y++) {
        for (x = -31; x <= 31; x++) {
            if (x != 0 || y != 0) {
                err_stats_add(&e, atan2_err_lsb((int16_t)y, (int16_t)x), (double)(y * 100 + x));
            }
        }
    }
    err_stats_print("atan2_q15 all vectors with |x|,|y| <= 31 (at = 100 y + x)", &e, "LSB");
    print_deg("atan2_q15 magnitude 1..31", &e);
    assert_cmp(e.max_abs, <=, ATAN2_MAX_ERR_LSB);
}

static void test_atan2_q15_should_answer_the_origin_and_the_axes_exactly(void **state)
{
    (void)state;

    assert_int_equal(atan2_q15(0, 0), 0);
    assert_int_equal(atan2_q15(0, 1), 0);
    assert_int_equal(atan2_q15(0, 32767), 0);
    assert_int_equal(atan2_q15(0, -1), -32768); /* -pi: the binary angle has no +pi */
    assert_int_equal(atan2_q15(0, -32768), -32768);
    assert_int_equal(atan2_q15(1, 0), 16384);
    assert_int_equal(atan2_q15(32767, 0), 16384);
    assert_int_equal(atan2_q15(-1, 0), -16384);
    assert_int_equal(atan2_q15(-32768, 0), -16384);
}

static void test_atan2_q15_should_give_exact_diagonals(void **state)
{
    /* Odd multiples of 45 degrees land on the exact binary angle at every
     * magnitude (|x| = |y| is answered without the division). */
    static const int16_t mags[] = {1, 32, 1000, 32767};
    size_t i;
    err_stats_t e;
    (void)state;

    err_stats_init(&e);
    for (i = 0U; i < sizeof mags / sizeof mags[0]; i++) {
        int16_t v = mags[i];
        int16_t nv = (int16_t)-v;
        err_stats_add(&e, (double)angle_sub(atan2_q15(v, v), 8192), (double)v);
        err_stats_add(&e, (double)angle_sub(atan2_q15(v, nv), 24576), (double)v);
        err_stats_add(&e, (double)angle_sub(atan2_q15(nv, nv), -24576), (double)v);
        err_stats_add(&e, (double)angle_sub(atan2_q15(nv, v), -8192), (double)v);
    }
    err_stats_add(&e, (double)angle_sub(atan2_q15(-32768, -32768), -24576), -32768.0);
    err_stats_print("atan2_q15 diagonals vs the exact binary angle", &e, "LSB");
    assert_cmp(e.max_abs, ==, 0.0);
}

static void test_atan2_q15_should_define_the_unit_y_vectors(void **state)
{
    /* y = +-1 against the largest x: the true angle is 1/32767 rad = 0.32 LSB. */
    (void)state;

    assert_int_equal(atan2_q15(1, 32767), 0);
    assert_int_equal(atan2_q15(-1, 32767), 0);
    /* Next to -pi: both sides round onto -32768 or +32767, within 1 LSB of pi. */
    assert_cmp(fabs(atan2_err_lsb(1, -32768)), <=, ATAN2_MAX_ERR_LSB);
    assert_cmp(fabs(atan2_err_lsb(-1, -32768)), <=, ATAN2_MAX_ERR_LSB);
    assert_int_equal(atan2_q15(1, 1), 8192);
    assert_int_equal(atan2_q15(1, -1), 24576);
    /* pi - 0.32 LSB rounds onto the wrap: -32768 (the binary angle has no +pi). */
    assert_int_equal(atan2_q15(1, -32768), -32768);
    assert_int_equal(atan2_q15(-1, -32768), -32768); /* -pi + 0.32 LSB */
}

static void test_atan2_q31_should_stay_within_bound_at_every_magnitude(void **state)
{
    /* Bins by the larger magnitude, 2^b .. 2^(b+1) - 1 for b = 0..31: random
     * pairs, each scaled down by a random shift, plus INT32_MIN components. */
    err_stats_t bins[32];
    err_stats_t all;
    uint32_t seed = 0x13579BDFU;
    long i;
    int b;
    (void)state;

    err_stats_init(&all);
    for (b = 0; b < 32; b++) {
        err_stats_init(&bins[b]);
    }
    for (i = 0; i < 1000000L; i++) {
        int32_t x = (int32_t)test_rand_u32(&seed);
        int32_t y = (int32_t)test_rand_u32(&seed);
        uint8_t sh = (uint8_t)(test_rand_u32(&seed) % 31U);
        double mag;
        double err;
        if ((i & 7L) == 0L) {
            x = (i & 8L) ? INT32_MIN : x; /* a -2^31 component, unshifted */
            y = (i & 8L) ? y : INT32_MIN;
        } else {
            x = x >> sh;
            y = y >> sh;
        }
        mag = fmax(fabs((double)x), fabs((double)y));
        if (mag == 0.0) {
            continue;
        }
        err = atan2_err32_lsb(y, x);
        for (b = 0; b < 31 && mag >= (double)(2UL << b); b++) {
        }
        err_stats_add(&bins[b], err, mag);
        err_stats_add(&all, err, mag);
    }
    for (b = 0; b < 32; b++) {
        if (bins[b].n > 0) {
            printf("measured: atan2_q31 random pairs, max(|x|,|y|) in [2^%d, 2^%d): max |err| = "
                   "%.4f LSB = %.5f deg, n = %ld\n",
                   b, b + 1, bins[b].max_abs, bins[b].max_abs / LSB_PER_DEG, bins[b].n);
            assert_cmp(bins[b].max_abs, <=, ((b < 16) ? ATAN2_MAX_ERR_LSB : ATAN2_MAX_ERR32_LSB));
        }
    }
    err_stats_print("atan2_q31 all random pairs", &all, "LSB");
    assert_cmp(all.n, >, 990000L);
}

static void test_atan2_q31_should_agree_with_atan2_q15_on_16_bit_inputs(void **state)
{
    uint32_t seed = 0x0BADF00DU;
    long i;
    (void)state;

    for (i = 0; i < 200000L; i++) {
        int16_t x = test_rand_i16(&seed);
        int16_t y = test_rand_i16(&seed);
        assert_int_equal(atan2_q31(y, x), atan2_q15(y, x));
    }
    assert_int_equal(atan2_q31(0, INT32_MIN), -32768);
    assert_int_equal(atan2_q31(INT32_MIN, 0), -16384);
    assert_int_equal(atan2_q31(INT32_MIN, INT32_MIN), -24576);
    assert_int_equal(atan2_q31(INT32_MAX, INT32_MAX), 8192);
    assert_int_equal(atan2_q31(0, 0), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_atan2_q15_should_stay_within_bound_at_every_magnitude),
        cmocka_unit_test(test_atan2_q15_should_stay_within_bound_with_a_minus_32768_component),
        cmocka_unit_test(test_atan2_q15_should_stay_within_bound_for_a_million_random_pairs),
        cmocka_unit_test(test_atan2_q15_should_stay_within_bound_for_tiny_vectors_below_32_lsb),
        cmocka_unit_test(test_atan2_q15_should_answer_the_origin_and_the_axes_exactly),
        cmocka_unit_test(test_atan2_q15_should_give_exact_diagonals),
        cmocka_unit_test(test_atan2_q15_should_define_the_unit_y_vectors),
        cmocka_unit_test(test_atan2_q31_should_stay_within_bound_at_every_magnitude),
        cmocka_unit_test(test_atan2_q31_should_agree_with_atan2_q15_on_16_bit_inputs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
