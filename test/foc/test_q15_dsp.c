/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_q15_dsp.c - every q15_dsp.h primitive against an exact 64-bit reference of its documented
 * formula, over all edge combinations and a seeded random stream. */
#include "test_support.h"

#include <stdio.h>

#include "q15.h"
#include "q15_dsp.h"

/*
 * The references below are written from the formulas in q15_dsp.h's header
 * comment, with exact int64 arithmetic and an explicit floor division, not
 * from the portable bodies: where the two disagree, one of them is wrong.
 * Where a primitive documents a bound against the exact real value (the
 * triple product, SVGen's counts, the filter), that bound is checked too.
 *
 * Inputs: every combination of the edge values (pairs, triples and, for
 * four operands, quadruples), then a random stream where half of the
 * operands sit near an edge (edge +- 0..3), where saturation decides.
 */

static const int16_t edges[] = {-32768, -32767, -16385, -16384, -16383, -2,    -1,   0,
                                1,      2,      16383,  16384,  16385,  32766, 32767};
#define N_EDGES ((int)(sizeof edges / sizeof edges[0]))

#define N_RANDOM 400000L

/* ---- exact references ----------------------------------------------------- */

/* sac.r: bits 31..16 rounded to nearest, ties up, then the 16-bit clamp. */
static int64_t rnd(int64_t v)
{
    return test_sat16(test_floor_div(v + 32768, 65536));
}

/* Fractional product as the multiplier gives it: 2ab on the Q31 scale. */
static int64_t frac(int64_t a, int64_t b)
{
    return 2 * a * b;
}

/* ---- mismatch counting ------------------------------------------------------ */

typedef struct {
    const char *name;
    long n;
    long bad;
    int64_t in[4];
    int64_t got;
    int64_t want;
} check_t;

static void check_init(check_t *c, const char *name)
{
    c->name = name;
    c->n = 0;
    c->bad = 0;
}

static void check_eq(check_t *c, int64_t got, int64_t want, int64_t a, int64_t b, int64_t x,
                     int64_t y)
{
    c->n++;
    if (got != want) {
        if (c->bad == 0) {
            c->in[0] = a;
            c->in[1] = b;
            c->in[2] = x;
            c->in[3] = y;
            c->got = got;
            c->want = want;
        }
        c->bad++;
    }
}

static void check_done(const check_t *c)
{
    printf("measured: %s: %ld cases, %ld mismatches\n", c->name, c->n, c->bad);
    if (c->bad != 0) {
        printf("  first mismatch: inputs %lld %lld %lld %lld: got %lld, want %lld\n",
               (long long)c->in[0], (long long)c->in[1], (long long)c->in[2], (long long)c->in[3],
               (long long)c->got, (long long)c->want);
    }
    assert_cmp(c->n, >, 0);
    assert_int_equal(c->bad, 0);
}

/* An operand: uniform, or an edge nudged by -3..3 (clamped to int16). */
static int16_t rand_operand(uint32_t *seed)
{
    uint32_t r = test_rand_u32(seed);
    if ((r & 1U) != 0U) {
        return test_rand_i16(seed);
    }
    return (int16_t)test_sat16((int64_t)edges[(r >> 1) % (uint32_t)N_EDGES] +
                               (int64_t)((r >> 8) % 7U) - 3);
}

/* Operand k of case i: the edge grid for the first N_EDGES^m cases. */
static int16_t operand(long i, int m, int k, uint32_t *seed)
{
    long grid = 1;
    long div = 1;
    int j;
    for (j = 0; j < m; j++) {
        grid *= N_EDGES;
    }
    if (i >= grid) {
        return rand_operand(seed);
    }
    for (j = 0; j < k; j++) {
        div *= N_EDGES;
    }
    return edges[(i / div) % N_EDGES];
}

static long n_cases(int m)
{
    long grid = 1;
    int j;
    for (j = 0; j < m; j++) {
        grid *= N_EDGES;
    }
    return grid + N_RANDOM;
}

/* ---- 16-bit saturating arithmetic -------------------------------------------- */

static void test_add_sub_neg_dbl_sub2_should_saturate_the_exact_result_once(void **state)
{
    check_t c;
    uint32_t seed = 0x1234567U;
    long i;
    int32_t a;
    (void)state;

    check_init(&c, "q15_dsp_add_sat / sub_sat / dbl_sub2_sat, edge triples + random");
    for (i = 0; i < n_cases(3); i++) {
        int16_t x = operand(i, 3, 0, &seed);
        int16_t y = operand(i, 3, 1, &seed);
        int16_t z = operand(i, 3, 2, &seed);
        check_eq(&c, q15_dsp_add_sat(x, y), test_sat16((int64_t)x + y), x, y, 0, 0);
        check_eq(&c, q15_dsp_sub_sat(x, y), test_sat16((int64_t)x - y), x, y, 1, 0);
        check_eq(&c, q15_dsp_dbl_sub2_sat(x, y, z), test_sat16(2 * (int64_t)x - y - z), x, y, z, 2);
    }
    check_done(&c);

    check_init(&c, "q15_dsp_neg_sat, all 65536 values");
    for (a = -32768; a <= 32767; a++) {
        check_eq(&c, q15_dsp_neg_sat((int16_t)a), test_sat16(-(int64_t)a), a, 0, 0, 0);
    }
    check_done(&c);

    /* The case the one clamp is for: 2a - b - c back in range after 2a
     * alone would overflow (a clamp of 2a first would give 32767 - 1). */
    assert_int_equal(q15_dsp_dbl_sub2_sat(32767, 32767, 32767), 0);
    assert_int_equal(q15_dsp_dbl_sub2_sat(-32768, -32768, -32768), 0);
    assert_int_equal(q15_dsp_dbl_sub2_sat(20000, 1000, 2000), 32767);
    assert_int_equal(q15_dsp_neg_sat(-32768), 32767);
}

/* ---- products on the accumulator ---------------------------------------------- */

static void test_mpy_mac_msc_should_saturate_each_step_and_round_once(void **state)
{
    check_t c;
    uint32_t seed = 0xACE1U;
    long i;
    (void)state;

    check_init(&c, "q15_dsp_mpy_r / mac2_r / msc2_r / mulsu_r, edge quadruples + random");
    for (i = 0; i < n_cases(4); i++) {
        int16_t a = operand(i, 4, 0, &seed);
        int16_t b = operand(i, 4, 1, &seed);
        int16_t x = operand(i, 4, 2, &seed);
        int16_t y = operand(i, 4, 3, &seed);
        uint16_t g = (uint16_t)y;
        check_eq(&c, q15_dsp_mpy_r(a, b), rnd(test_sat32(frac(a, b))), a, b, 0, 0);
        check_eq(&c, q15_dsp_mac2_r(a, b, x, y),
                 rnd(test_sat32(test_sat32(frac(a, b)) + frac(x, y))), a, b, x, y);
        check_eq(&c, q15_dsp_msc2_r(a, b, x, y),
                 rnd(test_sat32(test_sat32(frac(a, b)) - frac(x, y))), a, b, x, y);
        check_eq(&c, q15_dsp_mulsu_r(a, g), rnd(test_sat32(2 * (int64_t)a * (int64_t)g)), a, g, 0,
                 1);
    }
    check_done(&c);

    /* -1 x -1 is +1 only up to the saturation of A. */
    assert_int_equal(q15_dsp_mpy_r(-32768, -32768), 32767);
    assert_int_equal(q15_dsp_mpy_r(16384, 16384), 8192);
    assert_int_equal(q15_dsp_mulsu_r(32767, 65535), 32767);
    assert_int_equal(q15_dsp_mulsu_r(-32768, 65535), -32768);
}

static void test_lac_mac_and_shifted_sums_should_match_their_formulas(void **state)
{
    check_t c;
    uint32_t seed = 0xBEEF01U;
    long i;
    (void)state;

    check_init(&c, "q15_dsp_lac_mac_r / half_sub2_r / x2y_gain_r, edge triples + random");
    for (i = 0; i < n_cases(3); i++) {
        int16_t x = operand(i, 3, 0, &seed);
        int16_t a = operand(i, 3, 1, &seed);
        int16_t b = operand(i, 3, 2, &seed);
        int16_t gc = (int16_t)((uint16_t)b & 0x3FFFU); /* gain fraction 0 .. 2^14 - 1 */
        check_eq(&c, q15_dsp_lac_mac_r(x, a, b), rnd(test_sat32((int64_t)x * 65536 + frac(a, b))),
                 x, a, b, 0);
        check_eq(&c, q15_dsp_half_sub2_r(x, a, b),
                 rnd(test_sat32(test_sat32((int64_t)x * 32768 - (int64_t)a * 65536) -
                                (int64_t)b * 65536)),
                 x, a, b, 1);
        check_eq(&c, q15_dsp_x2y_gain_r(x, a, gc),
                 rnd(((int64_t)x + 2 * (int64_t)a) * (32768 + (int64_t)gc)), x, a, gc, 2);
    }
    check_done(&c);

    check_init(&c, "q15_dsp_mac_shl_r / lac_mac_shl_r, n = 0..15 within |2cd 2^n| < 2^39");
    for (i = 0; i < 16L * 20000L + 16L * N_EDGES * N_EDGES; i++) {
        uint8_t n = (uint8_t)(i % 16);
        int16_t x = rand_operand(&seed);
        int16_t a = rand_operand(&seed);
        int16_t b = rand_operand(&seed);
        int16_t cc = rand_operand(&seed);
        int16_t d = rand_operand(&seed);
        int64_t cd;
        if (i < 16L * N_EDGES * N_EDGES) {
            cc = edges[(i / 16) % N_EDGES];
            d = edges[(i / (16 * N_EDGES)) % N_EDGES];
        }
        /* The contract: |2 c d 2^n| < 2^39, so |c d| < 2^(38 - n). */
        while (n > 8U && (int64_t)cc * d * 2 * ((int64_t)1 << n) >= ((int64_t)1 << 39)) {
            d = (int16_t)(d / 2);
        }
        while (n > 8U && (int64_t)cc * d * 2 * ((int64_t)1 << n) <= -((int64_t)1 << 39)) {
            d = (int16_t)(d / 2);
        }
        cd = frac(cc, d) * ((int64_t)1 << n);
        check_eq(&c, q15_dsp_mac_shl_r(a, b, cc, d, n),
                 rnd(test_sat32(test_sat32(frac(a, b)) + cd)), a, b, cc, d);
        check_eq(&c, q15_dsp_lac_mac_shl_r(x, a, b, cc, d, n),
                 rnd(test_sat32(test_sat32((int64_t)x * 65536 + frac(a, b)) + cd)), x, a, cc,
                 (int64_t)n);
    }
    check_done(&c);

    /* x + 2y times 1/sqrt(3) (Clarke's beta) at full scale stays in range:
     * (32767 + 2 * 32767) * 0.57735 = 56755 saturates, 16384 + 2 * 8192 gives 18919. */
    assert_int_equal(q15_dsp_x2y_gain_r(32767, 32767, 5070), 32767);
    assert_int_equal(q15_dsp_x2y_gain_r(16384, 8192, 5070), 18919);
}

/* ---- triple product and SVGen's counts: exact model and bound -------------- */

static void test_mul3_r_should_be_within_its_stated_bound_of_the_exact_product(void **state)
{
    check_t c;
    uint32_t seed = 0x77777U;
    long i;
    double worst = 0.0;
    (void)state;

    check_init(&c, "q15_dsp_mul3_r, b, c >= 0, s = -7..0: |err| <= 0.5 + 2^-10 LSB");
    for (i = 0; i < n_cases(3); i++) {
        int16_t a = operand(i, 3, 0, &seed);
        int16_t b = (int16_t)(operand(i, 3, 1, &seed) & 0x7FFF);
        int16_t cc = (int16_t)(operand(i, 3, 2, &seed) & 0x7FFF);
        int8_t s = (int8_t) - (int8_t)(i % 8);
        int16_t got = q15_dsp_mul3_r(a, b, cc, s);
        /* a b c / 2^(30 + s) exactly, as a rational: num / 2^(30 + s). */
        int64_t num = (int64_t)a * b * cc;
        double exact = (double)num / (double)((int64_t)1 << (30 + s));
        double err;
        if (exact >= 32767.0 || exact <= -32768.0) {
            check_eq(&c, got, test_sat16(exact > 0.0 ? 32767 : -32768), a, b, cc, s);
            continue;
        }
        err = (double)got - exact;
        if (err < 0.0) {
            err = -err;
        }
        if (err > worst) {
            worst = err;
        }
        check_eq(&c, err <= 0.5 + 1.0 / 1024.0, 1, a, b, cc, s);
    }
    printf("measured: q15_dsp_mul3_r: max |result - exact| = %.6f LSB\n", worst);
    check_done(&c);
}

static void test_q30_counts_should_round_its_two_partial_products(void **state)
{
    check_t c;
    uint32_t seed = 0x3030U;
    long i;
    double worst = 0.0;
    static const uint32_t xs[] = {0UL, 1UL, 32767UL, 32768UL, 0x20000000UL, 0x3FFFFFFFUL};
    static const uint16_t ps[] = {0U, 1U, 2U, 1000U, 16384U, 32767U};
    (void)state;

    check_init(&c, "q15_dsp_q30_counts, 0 <= x < 2^30, 0 <= p < 2^15");
    for (i = 0; i < 36L + N_RANDOM; i++) {
        uint32_t x;
        uint16_t p;
        int64_t xh;
        int64_t xl;
        uint16_t got;
        double err;
        if (i < 36L) {
            x = xs[i % 6];
            p = ps[i / 6];
        } else {
            x = test_rand_u32(&seed) & 0x3FFFFFFFUL;
            p = (uint16_t)(test_rand_u32(&seed) & 0x7FFFU);
        }
        xh = (int64_t)(x >> 15);
        xl = (int64_t)(x & 0x7FFFUL);
        got = q15_dsp_q30_counts(x, p);
        /* A = 2 xh p + floor(2 xl p / 2^15), rounded at bit 16. */
        check_eq(&c, got, rnd(2 * xh * p + test_floor_div(2 * xl * p, 32768)), (int64_t)x, p, 0, 0);
        err = (double)got - (double)x * (double)p / 1073741824.0;
        if (err < 0.0) {
            err = -err;
        }
        if (err > worst) {
            worst = err;
        }
        check_eq(&c, err <= 0.5 + 1.0 / 65536.0, 1, (int64_t)x, p, 1, 0);
    }
    printf("measured: q15_dsp_q30_counts: max |counts - x p / 2^30| = %.6f\n", worst);
    check_done(&c);
}

/* ---- PI and low-pass steps -------------------------------------------------- */

static void test_pi_should_follow_an1078s_equations_on_the_q31_integral(void **state)
{
    check_t c;
    uint32_t seed = 0x9191U;
    long i;
    (void)state;

    check_init(&c, "q15_dsp_pi, n = 0..7, random gains, limits and integrals");
    for (i = 0; i < N_RANDOM; i++) {
        int16_t e = rand_operand(&seed);
        int16_t kp = rand_operand(&seed);
        int16_t ki = rand_operand(&seed);
        int16_t kc = rand_operand(&seed);
        int16_t l1 = rand_operand(&seed);
        int16_t l2 = rand_operand(&seed);
        int16_t lo = (l1 < l2) ? l1 : l2;
        int16_t hi = (l1 < l2) ? l2 : l1;
        uint8_t n = (uint8_t)(i % 8);
        int32_t s0 = (int32_t)test_rand_u32(&seed);
        int32_t s = s0;
        int64_t u;
        int64_t out;
        int64_t exc;
        int64_t s_want;
        int16_t got;
        if ((i & 3) == 0) {
            s0 = (int32_t)((i & 4) != 0 ? 2147483647L : (-2147483647L - 1L));
            s = s0;
        }
        u = test_sat32((int64_t)s0 + frac(kp, e) * ((int64_t)1 << n));
        out = test_clamp64(rnd(u), lo, hi);
        exc = rnd(test_sat32(u - out * 65536));
        s_want = test_sat32(test_sat32((int64_t)s0 + frac(ki, e)) - frac(kc, exc));
        got = q15_dsp_pi(&s, e, kp, n, ki, kc, lo, hi);
        check_eq(&c, got, out, e, kp, s0, n);
        check_eq(&c, s, s_want, e, ki, kc, s0);
    }
    check_done(&c);
}

static void test_lpf_should_stay_within_two_q31_lsb_above_the_exact_step(void **state)
{
    check_t c;
    uint32_t seed = 0x1F1FU;
    long i;
    (void)state;

    check_init(&c, "q15_dsp_lpf, k = 0..32767: 0 <= y' - exact < 2 Q31 LSB, output rnd(y')");
    for (i = 0; i < N_RANDOM; i++) {
        int32_t y0 = (int32_t)test_rand_u32(&seed);
        int16_t x = rand_operand(&seed);
        int16_t k = (int16_t)(test_rand_u32(&seed) & 0x7FFFU);
        int32_t y = y0;
        int16_t got;
        int64_t hi;
        int64_t lo;
        int64_t d;
        if ((i & 7) == 0) {
            k = (int16_t)((i & 8) != 0 ? 32767 : (i & 16) != 0 ? 1 : 0);
        }
        if ((i & 31) == 1) {
            y0 = (int32_t)((i & 32) != 0 ? 2147483647L : (-2147483647L - 1L));
            y = y0;
        }
        hi = test_floor_div(y0, 65536);
        lo = (int64_t)y0 - hi * 65536;
        got = q15_dsp_lpf(&y, x, k);
        /* Documented model: y - 2k hi + 2k x - floor(2k floor(lo / 2) / 2^15). */
        check_eq(&c, y,
                 (int64_t)y0 - frac(k, hi) + frac(k, x) - test_floor_div(frac(k, lo / 2), 32768),
                 y0, x, k, 0);
        check_eq(&c, got, rnd(y), y0, x, k, 1);
        /* 2^15 (y' - exact) = 2^15 y' - 2^15 y0 - k (x 2^16 - y0) in [0, 2^16):
         * the truncated term is subtracted, so the state ends above. */
        d = (int64_t)y * 32768 - (int64_t)y0 * 32768 - (int64_t)k * ((int64_t)x * 65536 - y0);
        check_eq(&c, d >= 0 && d < 65536, 1, y0, x, k, d);
    }
    check_done(&c);
}

/* ---- divider and bit count --------------------------------------------------- */

static void test_divud_and_clz16_should_match_integer_division_and_a_bit_count(void **state)
{
    check_t c;
    uint32_t seed = 0xD1D1U;
    long i;
    uint32_t v;
    (void)state;

    check_init(&c, "q15_dsp_divud (quotient < 2^16), q15_dsp_clz16 (all 65535 non-zero values)");
    for (i = 0; i < N_RANDOM; i++) {
        uint16_t den = (uint16_t)(test_rand_u32(&seed) & 0xFFFFU);
        uint32_t q = test_rand_u32(&seed) & 0xFFFFU;
        uint32_t num;
        if (den == 0U) {
            den = 1U;
        }
        num = q * den + (test_rand_u32(&seed) % den);
        check_eq(&c, q15_dsp_divud(num, den), (int64_t)(num / den), num, den, 0, 0);
    }
    for (v = 1U; v <= 0xFFFFU; v++) {
        int64_t want = 0;
        while ((v << want & 0x8000U) == 0U) {
            want++;
        }
        check_eq(&c, q15_dsp_clz16((uint16_t)v), want, v, 0, 0, 1);
    }
    check_done(&c);
}

/* ---- angle_neg (q15.h), used with atan2 ------------------------------------ */

static void test_angle_neg_should_negate_modulo_one_turn(void **state)
{
    check_t c;
    int32_t a;
    (void)state;

    check_init(&c, "angle_neg, all 65536 angles");
    for (a = -32768; a <= 32767; a++) {
        int64_t want = (a == -32768) ? -32768 : -(int64_t)a; /* -180 deg is +180 deg */
        check_eq(&c, angle_neg((angle_q15_t)a), want, a, 0, 0, 0);
    }
    check_done(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_add_sub_neg_dbl_sub2_should_saturate_the_exact_result_once),
        cmocka_unit_test(test_mpy_mac_msc_should_saturate_each_step_and_round_once),
        cmocka_unit_test(test_lac_mac_and_shifted_sums_should_match_their_formulas),
        cmocka_unit_test(test_mul3_r_should_be_within_its_stated_bound_of_the_exact_product),
        cmocka_unit_test(test_q30_counts_should_round_its_two_partial_products),
        cmocka_unit_test(test_pi_should_follow_an1078s_equations_on_the_q31_integral),
        cmocka_unit_test(test_lpf_should_stay_within_two_q31_lsb_above_the_exact_step),
        cmocka_unit_test(test_divud_and_clz16_should_match_integer_division_and_a_bit_count),
        cmocka_unit_test(test_angle_neg_should_negate_modulo_one_turn),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
