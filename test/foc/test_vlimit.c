/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_vlimit.c - q15_sqrt (exhaustive), q15_isqrt_u32 and the voltage-circle limit. */
#include "test_support.h"

#include <math.h>
#include <stdio.h>

#include "q15_sqrt.h"
#include "vlimit.h"

/* Both functions round once to nearest: |error| <= 0.5 LSB. */
#define SQRT_BOUND_LSB 0.5

static void test_q15_sqrt_should_be_within_half_an_lsb_for_every_non_negative_input(void **state)
{
    (void)state;
    err_stats_t e;
    err_stats_init(&e);
    for (int32_t x = 0; x <= 32767; x++) {
        q15_t y = q15_sqrt((q15_t)x);
        double ref = sqrt((double)x * 32768.0); /* sqrt(x / 2^15) * 2^15 */
        err_stats_add(&e, (double)y - ref, (double)x);
        assert_cmp(y, >=, 0);
    }
    err_stats_print("q15_sqrt, all 32768 non-negative inputs", &e, "LSB");
    assert_int_equal(e.n, 32768);
    assert_cmp(e.max_abs, <=, SQRT_BOUND_LSB);
    assert_int_equal(q15_sqrt(0), 0);
    assert_int_equal(q15_sqrt(32767), 32767);
    assert_int_equal(q15_sqrt(Q15(0.25)), Q15(0.5));
    assert_int_equal(q15_sqrt(8192), 16384);
}

static void test_q15_sqrt_should_return_zero_for_negative_inputs(void **state)
{
    (void)state;
    for (int32_t x = -32768; x < 0; x++) {
        assert_int_equal(q15_sqrt((q15_t)x), 0);
    }
}

/* round(sqrt(n)) is exact in double for 32-bit n (and a tie k + 1/2 is
 * impossible), so the integer root must match it exactly. */
static uint32_t isqrt_ref(uint32_t n)
{
    return (uint32_t)floor(sqrt((double)n) + 0.5);
}

static void test_q15_isqrt_u32_should_round_exactly_over_dense_and_edge_inputs(void **state)
{
    (void)state;
    long n_checked = 0;
    for (uint32_t n = 0; n < (1UL << 20); n++) {
        assert_int_equal(q15_isqrt_u32(n), isqrt_ref(n));
        n_checked++;
    }
    for (uint32_t k = 0; k <= 65535U; k++) {
        uint32_t sq = k * k;
        const uint32_t probes[] = {sq, sq - 1U, sq + 1U, sq + k, sq + k + 1U};
        for (unsigned i = 0; i < 5; i++) {
            if (k == 0 && i == 1) {
                continue;
            }
            assert_int_equal(q15_isqrt_u32(probes[i]), isqrt_ref(probes[i]));
            n_checked++;
        }
    }
    uint32_t rng = 0xACE1U;
    for (long i = 0; i < 1000000; i++) {
        uint32_t n = test_rand_u32(&rng);
        assert_int_equal(q15_isqrt_u32(n), isqrt_ref(n));
        n_checked++;
    }
    assert_int_equal(q15_isqrt_u32(0xFFFFFFFFUL), 65536UL);
    assert_int_equal(q15_isqrt_u32(0xFFFE0001UL), 65535UL);
    printf("measured: q15_isqrt_u32: %ld inputs (all n < 2^20, k^2 + {-1,0,1,k,k+1} for every "
           "k < 2^16, 10^6 random), 0 differences from round(sqrt(n))\n",
           n_checked);
}

static double vq_ref(q15_t vd, q15_t vmax)
{
    double m = (vmax > 0) ? (double)vmax : 0.0;
    double d = fmin(fmax((double)vd, -m), m);
    return sqrt(m * m - d * d);
}

static void test_vlimit_vq_max_should_follow_the_voltage_circle_over_a_grid(void **state)
{
    (void)state;
    err_stats_t e;
    err_stats_init(&e);
    const q15_t fixed_vmax[] = {1, 2, 100, Q15(0.5), Q15(0.9), Q15(0.95), Q15(0.98), 32767};
    for (int32_t iv = 0; iv < 8 + 128; iv++) {
        q15_t vmax = (iv < 8) ? fixed_vmax[iv] : (q15_t)((iv - 8) * 256 + 37);
        for (int32_t vd = -32768; vd <= 32767; vd += 3) {
            q15_t vq = vlimit_vq_max((q15_t)vd, vmax);
            err_stats_add(&e, (double)vq - vq_ref((q15_t)vd, vmax), (double)vd);
            assert_cmp(vq, >=, 0);
            assert_cmp(vq, <=, vmax);
        }
        assert_int_equal(vlimit_vq_max(0, vmax), vmax);
        assert_int_equal(vlimit_vq_max(vmax, vmax), 0);
        assert_int_equal(vlimit_vq_max((q15_t)(-vmax), vmax), 0);
        assert_int_equal(vlimit_vq_max(-32768, vmax), 0);
        assert_int_equal(vlimit_vq_max(32767, vmax), 0);
    }
    err_stats_print("vlimit_vq_max = sqrt(Vmax^2 - Vd^2), 136 Vmax x 21846 Vd", &e, "LSB");
    assert_cmp(e.max_abs, <=, SQRT_BOUND_LSB);
}

static void test_vlimit_vq_max_should_give_zero_for_a_non_positive_vmax(void **state)
{
    (void)state;
    const q15_t vds[] = {-32768, -1, 0, 1, 32767};
    for (unsigned i = 0; i < 5; i++) {
        assert_int_equal(vlimit_vq_max(vds[i], 0), 0);
        assert_int_equal(vlimit_vq_max(vds[i], -1), 0);
        assert_int_equal(vlimit_vq_max(vds[i], -32768), 0);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_q15_sqrt_should_be_within_half_an_lsb_for_every_non_negative_input),
        cmocka_unit_test(test_q15_sqrt_should_return_zero_for_negative_inputs),
        cmocka_unit_test(test_q15_isqrt_u32_should_round_exactly_over_dense_and_edge_inputs),
        cmocka_unit_test(test_vlimit_vq_max_should_follow_the_voltage_circle_over_a_grid),
        cmocka_unit_test(test_vlimit_vq_max_should_give_zero_for_a_non_positive_vmax),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
