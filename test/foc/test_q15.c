/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_q15.c - every primitive of q15.h and q15_dsp.h against 64-bit integer and double references.
 */
#include "test_support.h"

#include <math.h>
#include <stdio.h>

#include "q15.h"
#include "q15_dsp.h"

/* The constant macros must be usable in constant expressions, at file scope. */
Q15_STATIC_ASSERT(Q15(0.5) == 16384, "Q15(0.5) is 16384");
Q15_STATIC_ASSERT(Q15(-1.0) == -32768, "Q15(-1.0) is -32768");
Q15_STATIC_ASSERT(Q15(1.0) == 32767, "Q15(1.0) saturates to 32767");
Q15_STATIC_ASSERT(ANGLE_Q15_DEG(180) == -32768, "180 degrees is -32768");
static const q15_t file_scope_constants[] = {Q15(0.25), Q15(-0.25), Q15_SCALED(1.5, 4.4),
                                             ANGLE_Q15_DEG(90)};

/* Edge values every sweep includes. */
static const int32_t edges[] = {-32768, -32767, -16385, -16384, -16383, -2,    -1,   0,
                                1,      2,      16383,  16384,  16385,  32766, 32767};
#define N_EDGES ((int)(sizeof edges / sizeof edges[0]))

/* Mismatch counter: dense sweeps count failures and report the first one,
 * instead of one cmocka assertion per sample. */
typedef struct {
    long n;
    long bad;
    int64_t first_a;
    int64_t first_b;
    int64_t first_got;
    int64_t first_want;
} check_t;

static void check_init(check_t *c)
{
    c->n = 0;
    c->bad = 0;
    c->first_a = c->first_b = c->first_got = c->first_want = 0;
}

static void check_eq(check_t *c, int64_t got, int64_t want, int64_t a, int64_t b)
{
    c->n++;
    if (got != want) {
        if (c->bad == 0) {
            c->first_a = a;
            c->first_b = b;
            c->first_got = got;
            c->first_want = want;
        }
        c->bad++;
    }
}

static void check_done(const char *name, const check_t *c)
{
    printf("measured: %s: %ld cases, %ld mismatches\n", name, c->n, c->bad);
    if (c->bad != 0) {
        printf("  first mismatch: a = %lld, b = %lld: got %lld, want %lld\n", (long long)c->first_a,
               (long long)c->first_b, (long long)c->first_got, (long long)c->first_want);
    }
    assert_cmp(c->n, >, 0);
    assert_int_equal(c->bad, 0);
}

/* Visit a dense grid of (a, b): every a, b stepping by `step` from -32768,
 * plus every edge as b, plus every edge as a against every b. */
typedef void (*pair_fn)(check_t *c, int32_t a, int32_t b);

static void sweep_pairs(check_t *c, pair_fn f, int32_t step)
{
    int32_t a;
    int32_t b;
    int k;

    for (a = -32768; a <= 32767; a++) {
        for (b = -32768; b <= 32767; b += step) {
            f(c, a, b);
        }
        for (k = 0; k < N_EDGES; k++) {
            f(c, a, edges[k]);
            f(c, edges[k], a);
        }
    }
}

/* ---- add / sub / neg / abs / sat / clamp -------------------------------- */

static void pair_add_sub(check_t *c, int32_t a, int32_t b)
{
    check_eq(c, q15_add_sat((q15_t)a, (q15_t)b), test_sat16((int64_t)a + b), a, b);
    check_eq(c, q15_sub_sat((q15_t)a, (q15_t)b), test_sat16((int64_t)a - b), a, b);
}

static void test_q15_add_sub_sat_should_match_the_saturated_exact_sum(void **state)
{
    check_t c;
    (void)state;

    check_init(&c);
    sweep_pairs(&c, pair_add_sub, 97); /* 65,536 x 691 pairs, 2 ops each */
    check_done("q15_add_sat / q15_sub_sat, dense grid + all edges", &c);
    assert_cmp(c.n, >, 80000000L);
    assert_int_equal(q15_add_sat(32767, 1), 32767);
    assert_int_equal(q15_add_sat(-32768, -1), -32768);
    assert_int_equal(q15_sub_sat(-32768, 1), -32768);
    assert_int_equal(q15_sub_sat(0, -32768), 32767);
    assert_int_equal(q15_sub_sat(-1, -32768), 32767);
    assert_int_equal(q15_add_sat(-32768, 32767), -1);
}

static void test_q15_neg_abs_sat_should_saturate_minus_32768(void **state)
{
    check_t c;
    int32_t a;
    (void)state;

    check_init(&c);
    for (a = -32768; a <= 32767; a++) {
        check_eq(&c, q15_neg_sat((q15_t)a), test_sat16(-(int64_t)a), a, 0);
        check_eq(&c, q15_abs_sat((q15_t)a), test_sat16(a < 0 ? -(int64_t)a : a), a, 0);
    }
    check_done("q15_neg_sat / q15_abs_sat, all 65536 values", &c);
    assert_int_equal(q15_neg_sat(-32768), 32767);
    assert_int_equal(q15_abs_sat(-32768), 32767);
    assert_int_equal(q15_neg_sat(32767), -32767);
    assert_int_equal(q15_abs_sat(-32767), 32767);
    assert_int_equal(q15_neg_sat(0), 0);
}

static void test_q15_sat_and_clamp_should_bound_their_inputs(void **state)
{
    static const int32_t wide[] = {-2147483647L - 1L,
                                   -65536L,
                                   -32769L,
                                   -32768L,
                                   -32767L,
                                   -1L,
                                   0L,
                                   1L,
                                   32766L,
                                   32767L,
                                   32768L,
                                   65535L,
                                   2147483647L};
    check_t c;
    size_t i;
    int32_t a;
    (void)state;

    check_init(&c);
    for (i = 0U; i < sizeof wide / sizeof wide[0]; i++) {
        check_eq(&c, q15_sat(wide[i]), test_sat16(wide[i]), wide[i], 0);
    }
    for (a = -32768; a <= 32767; a++) {
        check_eq(&c, q15_clamp((q15_t)a, -1000, 2000), test_clamp64(a, -1000, 2000), a, 0);
        check_eq(&c, q15_clamp((q15_t)a, -32768, 32767), a, a, 1);
        check_eq(&c, q15_clamp((q15_t)a, 5, 5), 5, a, 2);
    }
    check_done("q15_sat / q15_clamp", &c);
}

/* ---- multiply ----------------------------------------------------------- */

static void pair_mul(check_t *c, int32_t a, int32_t b)
{
    int64_t p = (int64_t)a * b;
    /* rounded: floor((p + 2^14) / 2^15), ties toward +infinity; truncated: floor */
    check_eq(c, q15_mul((q15_t)a, (q15_t)b),
             test_sat16(test_floor_div(p + 16384, (int64_t)1 << 15)), a, b);
    check_eq(c, q15_mul_trunc((q15_t)a, (q15_t)b), test_sat16(test_floor_div(p, (int64_t)1 << 15)),
             a, b);
    check_eq(c, q15_dsp_mulss((int16_t)a, (int16_t)b), p, a, b);
}

static void test_q15_mul_should_round_to_nearest_with_ties_up_over_a_dense_grid(void **state)
{
    check_t c;
    err_stats_t er;
    err_stats_t et;
    uint32_t seed = 0x0BADF00DU;
    long i;
    (void)state;

    check_init(&c);
    sweep_pairs(&c, pair_mul, 251); /* 65,536 x 262 = 1.7e7 pairs, + edges x all */
    check_done("q15_mul / q15_mul_trunc / q15_dsp_mulss, dense grid + all edges", &c);
    assert_cmp(c.n, >, 3L * 17000000L);

    /* The same rule seen from double: |err| <= 0.5 (rounded), (-1, 0] (trunc). */
    err_stats_init(&er);
    err_stats_init(&et);
    for (i = 0; i < 2000000L; i++) {
        q15_t a = test_rand_i16(&seed);
        q15_t b = test_rand_i16(&seed);
        double exact = (double)a * (double)b / 32768.0;
        if (a == -32768 && b == -32768) {
            continue;
        }
        err_stats_add(&er, (double)q15_mul(a, b) - exact, exact);
        err_stats_add(&et, (double)q15_mul_trunc(a, b) - exact, exact);
        assert_cmp((double)q15_mul_trunc(a, b) - exact, <=, 0.0);
    }
    err_stats_print("q15_mul vs double, 2e6 random pairs", &er, "LSB");
    err_stats_print("q15_mul_trunc vs double, 2e6 random pairs", &et, "LSB");
    assert_cmp(er.max_abs, <=, 0.5);
    assert_cmp(et.max_abs, <, 1.0);

    /* Ties go up (toward +infinity), on both signs. */
    assert_int_equal(q15_mul(1, 16384), 1);   /* +0.5 LSB -> 1 */
    assert_int_equal(q15_mul(-1, 16384), 0);  /* -0.5 LSB -> 0 */
    assert_int_equal(q15_mul(3, 16384), 2);   /* 1.5 -> 2 */
    assert_int_equal(q15_mul(-3, 16384), -1); /* -1.5 -> -1 */
    assert_int_equal(q15_mul_trunc(-1, 16384), -1);
    assert_int_equal(q15_mul_trunc(1, 16383), 0);
    /* -1 x -1 is the only saturation. */
    assert_int_equal(q15_mul(-32768, -32768), 32767);
    assert_int_equal(q15_mul_trunc(-32768, -32768), 32767);
    assert_int_equal(q15_mul(-32768, 32767), -32767);
    assert_int_equal(q15_mul(32767, 32767), 32766);
    assert_int_equal(q15_mul(-32768, 1), -1);
    assert_int_equal(q15_mul_trunc(-32768, 1), -1);
    assert_int_equal(q15_mul(16384, 16384), 8192);
}

static void test_q15_mul_should_be_exhaustive_on_a_subset(void **state)
{
    /* Every a against every b in [-300, 300] and every a against b near +-1. */
    check_t c;
    int32_t a;
    int32_t b;
    (void)state;

    check_init(&c);
    for (a = -32768; a <= 32767; a++) {
        for (b = -300; b <= 300; b++) {
            pair_mul(&c, a, b);
        }
        for (b = 32767 - 100; b <= 32767; b++) {
            pair_mul(&c, a, b);
            pair_mul(&c, a, -b - 1);
        }
    }
    check_done("q15_mul family, every a x b in [-300, 300] and |b| near 1", &c);
}

/* ---- shifts ------------------------------------------------------------- */

static void test_q15_shifts_should_saturate_and_round_as_documented(void **state)
{
    check_t c;
    int32_t a;
    int n;
    (void)state;

    check_init(&c);
    for (a = -32768; a <= 32767; a++) {
        for (n = 0; n <= 15; n++) {
            check_eq(&c, q15_shl_sat((q15_t)a, (uint8_t)n), test_sat16((int64_t)a * (1LL << n)), a,
                     n);
            check_eq(&c, q15_shr((q15_t)a, (uint8_t)n), test_floor_div(a, (int64_t)1 << n), a, n);
            if (n >= 1) {
                check_eq(&c, q15_shr_round((q15_t)a, (uint8_t)n),
                         test_floor_div((int64_t)a + (1LL << (n - 1)), (int64_t)1 << n), a, n);
            }
        }
    }
    check_done("q15_shl_sat / q15_shr / q15_shr_round, every value x every shift", &c);
    assert_int_equal(q15_shl_sat(-1, 15), -32768);
    assert_int_equal(q15_shl_sat(1, 15), 32767);
    assert_int_equal(q15_shl_sat(-32768, 1), -32768);
    assert_int_equal(q15_shl_sat(16384, 1), 32767);
    assert_int_equal(q15_shl_sat(-16384, 1), -32768);
    assert_int_equal(q15_shr(-1, 15), -1);
    assert_int_equal(q15_shr_round(-1, 1), 0); /* -0.5 -> 0 (ties up) */
    assert_int_equal(q15_shr_round(1, 1), 1);  /* 0.5 -> 1 */
    assert_int_equal(q15_shr_round(32767, 1), 16384);
    assert_int_equal(q15_shr_round(-32768, 15), -1);
}

/* ---- Q31 ---------------------------------------------------------------- */

static const int32_t q31_edges[] = {-2147483647L - 1L,
                                    -2147483647L,
                                    -1073741824L,
                                    -65536L,
                                    -32768L,
                                    -1L,
                                    0L,
                                    1L,
                                    32767L,
                                    32768L,
                                    65535L,
                                    1073741824L,
                                    2147450880L,
                                    2147450879L,
                                    2147418112L,
                                    2147483646L,
                                    2147483647L};
#define N_Q31_EDGES ((int)(sizeof q31_edges / sizeof q31_edges[0]))

static int32_t rand_q31(uint32_t *seed)
{
    return (int32_t)test_rand_u32(seed);
}

static void test_q31_add_sub_sat_should_saturate_at_both_ends(void **state)
{
    check_t c;
    uint32_t seed = 0x31313131U;
    int i;
    int j;
    long k;
    (void)state;

    check_init(&c);
    for (i = 0; i < N_Q31_EDGES; i++) {
        for (j = 0; j < N_Q31_EDGES; j++) {
            int32_t a = q31_edges[i];
            int32_t b = q31_edges[j];
            check_eq(&c, q31_add_sat(a, b), test_sat32((int64_t)a + b), a, b);
            check_eq(&c, q31_sub_sat(a, b), test_sat32((int64_t)a - b), a, b);
        }
    }
    for (k = 0; k < 5000000L; k++) {
        int32_t a = rand_q31(&seed);
        int32_t b = rand_q31(&seed);
        /* one in four pairs near the top or the bottom, where it saturates */
        if ((k & 3L) == 0L) {
            b = (int32_t)((uint32_t)b >> 2) ^ (a < 0 ? (int32_t)-1 : 0);
        }
        check_eq(&c, q31_add_sat(a, b), test_sat32((int64_t)a + b), a, b);
        check_eq(&c, q31_sub_sat(a, b), test_sat32((int64_t)a - b), a, b);
    }
    check_done("q31_add_sat / q31_sub_sat, edges x edges + 5e6 random", &c);
    assert_cmp(q31_add_sat(Q31_MAX, 1), ==, Q31_MAX);
    assert_cmp(q31_add_sat(Q31_MIN, -1), ==, Q31_MIN);
    assert_cmp(q31_sub_sat(Q31_MIN, 1), ==, Q31_MIN);
    assert_cmp(q31_sub_sat(0, Q31_MIN), ==, Q31_MAX);
    assert_cmp(q31_sub_sat(-1, Q31_MIN), ==, Q31_MAX);
    assert_cmp(q31_add_sat(Q31_MIN, Q31_MAX), ==, -1);
}

static void pair_q31_mul(check_t *c, int32_t a, int32_t b)
{
    check_eq(c, q31_mul_q15((q15_t)a, (q15_t)b), test_sat32(2LL * a * b), a, b);
}

static void test_q31_mul_q15_should_be_exact_except_minus_one_squared(void **state)
{
    check_t c;
    int32_t a;
    (void)state;

    check_init(&c);
    sweep_pairs(&c, pair_q31_mul, 509);
    for (a = -32768; a <= 32767; a++) {
        check_eq(&c, q31_from_q15((q15_t)a), (int64_t)a * 65536, a, 0);
    }
    check_done("q31_mul_q15 dense grid + edges, q31_from_q15 all values", &c);
    assert_cmp(q31_mul_q15(-32768, -32768), ==, Q31_MAX);
    assert_cmp(q31_mul_q15(-32768, 32767), ==, -2147418112L);
    assert_cmp(q31_mul_q15(32767, 32767), ==, 2147352578L);
    assert_cmp(q31_from_q15(-32768), ==, Q31_MIN);
}

static void test_q31_mac_sat_should_saturate_the_accumulator(void **state)
{
    check_t c;
    uint32_t seed = 0x4D414353U;
    int i;
    int j;
    int k;
    long n;
    (void)state;

    check_init(&c);
    for (i = 0; i < N_Q31_EDGES; i++) {
        for (j = 0; j < N_EDGES; j++) {
            for (k = 0; k < N_EDGES; k++) {
                int32_t acc = q31_edges[i];
                int64_t prod = test_sat32(2LL * edges[j] * edges[k]);
                check_eq(&c, q31_mac_sat(acc, (q15_t)edges[j], (q15_t)edges[k]),
                         test_sat32((int64_t)acc + prod), acc,
                         (int64_t)edges[j] * 65536 + edges[k]);
            }
        }
    }
    for (n = 0; n < 5000000L; n++) {
        int32_t acc = rand_q31(&seed);
        q15_t a = test_rand_i16(&seed);
        q15_t b = test_rand_i16(&seed);
        int64_t prod = test_sat32(2LL * a * b);
        check_eq(&c, q31_mac_sat(acc, a, b), test_sat32((int64_t)acc + prod), acc,
                 (int64_t)a * 65536 + b);
    }
    check_done("q31_mac_sat, edges^3 + 5e6 random", &c);
    assert_cmp(q31_mac_sat(Q31_MAX, 1, 1), ==, Q31_MAX);
    assert_cmp(q31_mac_sat(Q31_MIN, -1, 1), ==, Q31_MIN);
    assert_cmp(q31_mac_sat(Q31_MAX, -32768, -32768), ==, Q31_MAX);
    assert_cmp(q31_mac_sat(Q31_MIN, -32768, -32768), ==, -1);
}

static void test_q15_from_q31_should_round_ties_up_and_saturate(void **state)
{
    check_t c;
    uint32_t seed = 0x51335133U;
    int i;
    long n;
    int32_t a;
    (void)state;

    check_init(&c);
    for (i = 0; i < N_Q31_EDGES; i++) {
        int32_t x = q31_edges[i];
        check_eq(&c, q15_from_q31(x),
                 test_sat16(test_floor_div((int64_t)x + 32768, (int64_t)1 << 16)), x, 0);
        check_eq(&c, q15_from_q31_trunc(x), test_floor_div(x, (int64_t)1 << 16), x, 1);
    }
    for (n = 0; n < 10000000L; n++) {
        int32_t x = rand_q31(&seed);
        check_eq(&c, q15_from_q31(x),
                 test_sat16(test_floor_div((int64_t)x + 32768, (int64_t)1 << 16)), x, 0);
        check_eq(&c, q15_from_q31_trunc(x), test_floor_div(x, (int64_t)1 << 16), x, 1);
    }
    /* every Q15 value, at the tie and one either side of it */
    for (a = -32768; a <= 32767; a++) {
        int32_t base = (int32_t)((uint32_t)a << 16);
        int d;
        for (d = -1; d <= 1; d++) {
            int64_t x64 = (int64_t)base + 32768 + d;
            if (x64 <= 2147483647LL) {
                int32_t x = (int32_t)x64;
                check_eq(&c, q15_from_q31(x),
                         test_sat16(test_floor_div(x64 + 32768, (int64_t)1 << 16)), x, 2);
            }
        }
    }
    check_done("q15_from_q31 / q15_from_q31_trunc, edges + 1e7 random + every tie", &c);
    assert_int_equal(q15_from_q31(0x7FFF8000L), 32767); /* would round to 32768 */
    assert_int_equal(q15_from_q31(0x7FFF7FFFL), 32767);
    assert_int_equal(q15_from_q31(Q31_MAX), 32767);
    assert_int_equal(q15_from_q31(Q31_MIN), -32768);
    assert_int_equal(q15_from_q31(0x8000L), 1);  /* +0.5 LSB -> 1 */
    assert_int_equal(q15_from_q31(-0x8000L), 0); /* -0.5 LSB -> 0 */
    assert_int_equal(q15_from_q31(-0x8001L), -1);
    assert_int_equal(q15_from_q31_trunc(-1L), -1);
}

/* ---- angles ------------------------------------------------------------- */

static int64_t wrap16(int64_t v)
{
    int64_t m = ((v % 65536) + 65536) % 65536;
    return (m >= 32768) ? m - 65536 : m;
}

static void pair_angle(check_t *c, int32_t a, int32_t b)
{
    check_eq(c, angle_add((angle_q15_t)a, (angle_q15_t)b), wrap16((int64_t)a + b), a, b);
    check_eq(c, angle_sub((angle_q15_t)a, (angle_q15_t)b), wrap16((int64_t)a - b), a, b);
}

static void test_angle_add_sub_should_wrap_modulo_one_turn(void **state)
{
    check_t c;
    (void)state;

    check_init(&c);
    sweep_pairs(&c, pair_angle, 331);
    check_done("angle_add / angle_sub, dense grid + edges", &c);
    assert_int_equal(angle_add(32767, 1), -32768);
    assert_int_equal(angle_add(-32768, -1), 32767);
    assert_int_equal(angle_sub(-32768, 1), 32767);
    assert_int_equal(angle_sub(32767, -32768), -1);
    assert_int_equal(angle_sub(-30000, 30000), 5536); /* across -pi: -60000 + 65536 */
    assert_int_equal(angle_sub(30000, -30000), -5536);
    assert_int_equal(angle_add(16384, 16384), -32768);
}

static void test_angle_q15_deg_should_give_the_nearest_binary_angle(void **state)
{
    check_t c;
    int i;
    (void)state;

    assert_int_equal(ANGLE_Q15_DEG(0), 0);
    assert_int_equal(ANGLE_Q15_DEG(90), 16384);
    assert_int_equal(ANGLE_Q15_DEG(-90), -16384);
    assert_int_equal(ANGLE_Q15_DEG(45), 8192);
    assert_int_equal(ANGLE_Q15_DEG(180), -32768);
    assert_int_equal(ANGLE_Q15_DEG(-180), -32768);
    assert_int_equal(ANGLE_Q15_DEG(270), -16384);
    assert_int_equal(ANGLE_Q15_DEG(360), 0);
    assert_int_equal(ANGLE_Q15_DEG(720.0), 0);
    assert_int_equal(ANGLE_Q15_DEG(-540.0), -32768);
    assert_int_equal(ANGLE_Q15_DEG(1), 182); /* 182.04 */
    assert_int_equal(ANGLE_Q15_DEG(-1), -182);
    assert_int_equal(ANGLE_Q15_DEG(88.99), 16200); /* the original code's "90" */
    assert_int_equal(ANGLE_Q15_DEG(179.999), -32768);
    assert_int_equal(file_scope_constants[3], 16384);

    /* A dense grid of degrees (runtime arguments) against the rounded, wrapped value. */
    check_init(&c);
    for (i = -720000; i <= 720000; i += 7) {
        double deg = (double)i / 1000.0;
        double raw = deg * 65536.0 / 360.0;
        int64_t want = wrap16((int64_t)(raw >= 0.0 ? floor(raw + 0.5) : -floor(-raw + 0.5)));
        check_eq(&c, ANGLE_Q15_DEG(deg), want, i, 0);
    }
    check_done("ANGLE_Q15_DEG over -720..720 degrees in 0.007 steps", &c);
}

/* ---- Q15() constant macro ----------------------------------------------- */

static void test_q15_macro_should_round_symmetrically_and_saturate_one(void **state)
{
    check_t c;
    err_stats_t e;
    int i;
    (void)state;

    assert_int_equal(Q15(0.5), 16384);
    assert_int_equal(Q15(-0.5), -16384);
    assert_int_equal(Q15(-1.0), -32768);
    assert_int_equal(Q15(1.0), 32767);
    assert_int_equal(Q15(0.99999), 32767);
    assert_int_equal(Q15(-0.99999), -32768); /* -32767.67 rounds to -32768 */
    assert_int_equal(Q15(0.0), 0);
    assert_int_equal(Q15(-0.0), 0);
    assert_int_equal(Q15(0.25), 8192);
    assert_int_equal(Q15(1.0 / 32768.0), 1);
    assert_int_equal(Q15(-1.0 / 32768.0), -1);
    assert_int_equal(Q15(0.5 / 32768.0), 1);   /* a tie rounds away from zero */
    assert_int_equal(Q15(-0.5 / 32768.0), -1); /* symmetric */
    assert_int_equal(Q15(0.49 / 32768.0), 0);
    assert_int_equal(Q15(32767.49 / 32768.0), 32767);
    assert_int_equal(Q15(32767.5 / 32768.0), 32767); /* would be 32768: saturates */
    assert_int_equal(Q15(0.1), 3277);                /* 3276.8 */
    assert_int_equal(Q15(-0.1), -3277);
    assert_int_equal(Q15_SCALED(1.5, 4.4), 11171); /* 11170.9 */
    assert_int_equal(file_scope_constants[0], 8192);
    assert_int_equal(file_scope_constants[1], -8192);
    assert_int_equal(file_scope_constants[2], 11171);

    /* Dense: Q15(x) is the nearest raw value and Q15(-x) = -Q15(x) below the
     * top. Q15() refuses anything but a constant (its range check is a
     * bit-field width), so the loop runs its rounding, Q15_ROUND_, which is
     * all it adds to a value inside [-1, 1]. */
    check_init(&c);
    err_stats_init(&e);
    for (i = -1000000; i <= 1000000; i++) {
        double x = (double)i / 1000000.0;
        q15_t q = (q15_t)Q15_ROUND_(x);
        err_stats_add(&e, (double)q - x * 32768.0, x);
        if (x * 32768.0 < 32767.5 && x * 32768.0 > -32767.5) {
            check_eq(&c, Q15_ROUND_(-x), -(int64_t)q, i, 0);
        }
    }
    check_done("Q15(x) = -Q15(-x) over 2e6 values in [-1, 1]", &c);
    err_stats_print("Q15(x) - 32768 x over [-1, 1] (1 -> 32767 included)", &e, "LSB");
    assert_cmp(e.max_abs, <=, 1.0); /* 1.0 only at x = 1 */
}

/* ---- divsd twin --------------------------------------------------------- */

static void test_q15_dsp_divsd_should_truncate_toward_zero(void **state)
{
    check_t c;
    uint32_t seed = 0xD1D5D1D5U;
    long n;
    (void)state;

    assert_int_equal(q15_dsp_divsd(7, 2), 3);
    assert_int_equal(q15_dsp_divsd(-7, 2), -3);
    assert_int_equal(q15_dsp_divsd(7, -2), -3);
    assert_int_equal(q15_dsp_divsd(-7, -2), 3);
    assert_int_equal(q15_dsp_divsd(-1, 2), 0);
    /* the largest quotients that fit, both signs, truncated toward zero */
    assert_int_equal(q15_dsp_divsd(1073709055L, 32767), 32767);   /* 32767.99997 */
    assert_int_equal(q15_dsp_divsd(-1073709055L, 32767), -32767); /* not -32768 */
    assert_int_equal(q15_dsp_divsd(1073741824L, -32768), -32768);
    assert_int_equal(q15_dsp_divsd(-1073709056L, -32768), 32767);
    /* a Q15 division: (0.5 << 15) / 0.75 = 0.6667 -> 21845 (21845.33) */
    assert_int_equal(q15_dsp_divsd((int32_t)16384 << 15, 24576), 21845);
    assert_int_equal(q15_dsp_divsd(-((int32_t)16384 << 15), 24576), -21845);

    check_init(&c);
    for (n = 0; n < 10000000L; n++) {
        int16_t den = test_rand_i16(&seed);
        int32_t q = (int32_t)test_rand_i16(&seed);
        int32_t r;
        int32_t aden;
        int64_t num;
        if (den == 0) {
            continue;
        }
        /* a numerator whose quotient is q, plus a remainder of the quotient's sign */
        aden = (den < 0) ? -(int32_t)den : (int32_t)den;
        r = (int32_t)(test_rand_u32(&seed) % (uint32_t)aden);
        num = (int64_t)q * den + (((int64_t)q * den < 0) ? -r : r);
        if (num > 2147483647LL || num < -2147483647LL - 1LL) {
            continue;
        }
        check_eq(&c, q15_dsp_divsd((int32_t)num, den), (int64_t)trunc((double)num / (double)den),
                 num, den);
    }
    check_done("q15_dsp_divsd vs trunc(n / d), 1e7 random pairs with an int16 quotient", &c);
}

/* Gains >= 1 as mantissa and shift: every shift boundary, and the value
 * mant * 2^shift / 32768 within half a mantissa LSB of x over a dense sweep. */
static void test_shift7_and_mant7_should_split_a_gain_into_mantissa_and_shift(void **state)
{
    (void)state;
    assert_int_equal(Q15_SHIFT7_OF(0.0), 0);
    assert_int_equal(Q15_SHIFT7_OF(0.999), 0);
    assert_int_equal(Q15_SHIFT7_OF(1.0), 1);
    assert_int_equal(Q15_SHIFT7_OF(3.999), 2);
    assert_int_equal(Q15_SHIFT7_OF(4.0), 3);
    assert_int_equal(Q15_SHIFT7_OF(64.0), 7);
    assert_int_equal(Q15_SHIFT7_OF(127.99), 7);
    assert_int_equal(Q15_MANT7_OF(0.5), 16384);
    assert_int_equal(Q15_MANT7_OF(3.0), 24576); /* 0.75 * 2^2 */
    assert_int_equal(Q15_MANT7_OF(1.0), 16384); /* 0.5 * 2^1 */
    err_stats_t e;
    err_stats_init(&e);
    /* Q15_MANT7_OF(x) is Q15(x / 2^shift): at run time, its rounding. */
#define MANT7_RUNTIME(x) ((q15_t)Q15_ROUND_((double)(x) / (double)(1L << Q15_SHIFT7_OF(x))))
    for (double x = 0.0; x < 128.0; x += 0.0137) {
        int sh = Q15_SHIFT7_OF(x);
        double val = (double)MANT7_RUNTIME(x) * (double)(1L << sh) / 32768.0;
        double lsb = (double)(1L << sh) / 32768.0;
        assert_true(x < (double)(1L << sh) || sh == 7);
        assert_true(sh == 0 || x >= (double)(1L << (sh - 1)));
        if (MANT7_RUNTIME(x) == Q15_MAX) {
            /* just below a power of two the mantissa rounds to 1.0, which
             * saturates to 0x7FFF (q15.h): under one LSB short */
            assert_cmp(x - val, <, lsb);
            assert_cmp(x, >=, val);
            continue;
        }
        err_stats_add(&e, (val - x) / lsb, x);
    }
    err_stats_print("Q15_MANT7_OF * 2^Q15_SHIFT7_OF vs x in [0, 128), unsaturated", &e,
                    "mantissa LSB");
    assert_cmp(e.max_abs, <=, 0.5 + 1e-9);
    assert_int_equal(Q15_MANT7_OF(3.99999), Q15_MAX);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shift7_and_mant7_should_split_a_gain_into_mantissa_and_shift),
        cmocka_unit_test(test_q15_add_sub_sat_should_match_the_saturated_exact_sum),
        cmocka_unit_test(test_q15_neg_abs_sat_should_saturate_minus_32768),
        cmocka_unit_test(test_q15_sat_and_clamp_should_bound_their_inputs),
        cmocka_unit_test(test_q15_mul_should_round_to_nearest_with_ties_up_over_a_dense_grid),
        cmocka_unit_test(test_q15_mul_should_be_exhaustive_on_a_subset),
        cmocka_unit_test(test_q15_shifts_should_saturate_and_round_as_documented),
        cmocka_unit_test(test_q31_add_sub_sat_should_saturate_at_both_ends),
        cmocka_unit_test(test_q31_mul_q15_should_be_exact_except_minus_one_squared),
        cmocka_unit_test(test_q31_mac_sat_should_saturate_the_accumulator),
        cmocka_unit_test(test_q15_from_q31_should_round_ties_up_and_saturate),
        cmocka_unit_test(test_angle_add_sub_should_wrap_modulo_one_turn),
        cmocka_unit_test(test_angle_q15_deg_should_give_the_nearest_binary_angle),
        cmocka_unit_test(test_q15_macro_should_round_symmetrically_and_saturate_one),
        cmocka_unit_test(test_q15_dsp_divsd_should_truncate_toward_zero),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
