/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* vec_foc.c - 16-bit check vectors for q15.h and every foc/ block that is present. */
/* check16-requires: foc/q15.h */
#include "emit.h"

#include "q15.h"

/*
 * One section per primitive group and per block.
 *
 * Inputs: the int16 edges of emit.h first (all pairs where a block takes
 * two), then a seeded xorshift stream. Every section re-seeds, so its
 * vectors do not depend on the sections before it.
 */

/* ---- q15.h / q15_dsp.h primitives ---------------------------------------- */

#define N_EDGES32 12U
static const int32_t edges32[N_EDGES32] = {(int32_t)(-0x7FFFFFFFL - 1L),
                                           -0x7FFFFFFFL,
                                           -0x40000000L,
                                           -32769L,
                                           -32768L,
                                           -1L,
                                           0L,
                                           1L,
                                           32767L,
                                           32768L,
                                           0x40000000L,
                                           0x7FFFFFFFL};

static int32_t edge32_or_rand(uint32_t k)
{
    if (k < N_EDGES32) {
        return edges32[k];
    }
    /* Half the random values near the int16 range, where q15_sat decides. */
    if ((k & 1U) != 0U) {
        return (int32_t)vec_rand_between(-32768, 32767) * (int32_t)2 -
               (int32_t)vec_rand_between(-2, 2);
    }
    return (int32_t)vec_rand_u32();
}

static void vec_q15_sat(void)
{
    uint32_t k;
    emit_section("q15_sat");
    vec_seed(0x51U);
    for (k = 0U; k < 600U; k++) {
        int32_t x = edge32_or_rand(k);
        emit_i32(x);
        emit_sep();
        emit_i16(q15_sat(x));
        emit_end();
    }
}

static void vec_q15_add_sub(void)
{
    uint32_t k;
    emit_section("q15_add_sub_neg_abs");
    vec_seed(0x52U);
    for (k = 0U; k < 2000U; k++) {
        int16_t a;
        int16_t b;
        if (!vec_edge_pair(k, &a, &b)) {
            a = vec_rand_i16();
            b = vec_rand_i16();
        }
        emit_i16(a);
        emit_i16(b);
        emit_sep();
        emit_i16(q15_add_sat(a, b));
        emit_i16(q15_sub_sat(a, b));
        emit_i16(q15_neg_sat(a));
        emit_i16(q15_abs_sat(a));
        emit_i16(q15_clamp(a, (b < 0) ? b : (int16_t)-b, (b < 0) ? (int16_t) - (b + 1) : b));
        emit_end();
    }
}

static void vec_q15_mul(void)
{
    uint32_t k;
    emit_section("q15_mul");
    vec_seed(0x53U);
    for (k = 0U; k < 3000U; k++) {
        int16_t a;
        int16_t b;
        if (!vec_edge_pair(k, &a, &b)) {
            a = vec_rand_i16();
            b = vec_rand_i16();
        }
        emit_i16(a);
        emit_i16(b);
        emit_sep();
        emit_i32(q15_dsp_mulss(a, b));
        emit_i16(q15_mul(a, b));
        emit_i16(q15_mul_trunc(a, b));
        emit_i32(q31_mul_q15(a, b));
        emit_end();
    }
}

static void vec_q15_shift(void)
{
    uint32_t k;
    emit_section("q15_shift");
    vec_seed(0x54U);
    for (k = 0U; k < 120U; k++) {
        int16_t a = vec_edge_or_rand(k);
        uint8_t n;
        for (n = 0U; n < 16U; n++) {
            emit_i16(a);
            emit_u8(n);
            emit_sep();
            emit_i16(q15_shl_sat(a, n));
            emit_i16(q15_shr(a, n));
            emit_i16((n > 0U) ? q15_shr_round(a, n) : a);
            emit_end();
        }
    }
}

static void vec_q31(void)
{
    uint32_t k;
    emit_section("q31_add_sub_mac_conv");
    vec_seed(0x55U);
    for (k = 0U; k < 2000U; k++) {
        int32_t a;
        int32_t b;
        int16_t x = vec_edge_or_rand(k % 64U);
        int16_t y = vec_rand_i16();
        if (k < N_EDGES32 * N_EDGES32) {
            a = edges32[k / N_EDGES32];
            b = edges32[k % N_EDGES32];
        } else {
            a = (int32_t)vec_rand_u32();
            b = (int32_t)vec_rand_u32();
        }
        emit_i32(a);
        emit_i32(b);
        emit_i16(x);
        emit_i16(y);
        emit_sep();
        emit_i32(q31_add_sat(a, b));
        emit_i32(q31_sub_sat(a, b));
        emit_i32(q31_mac_sat(a, x, y));
        emit_i32(q31_from_q15(x));
        emit_i16(q15_from_q31(a));
        emit_i16(q15_from_q31_trunc(a));
        emit_end();
    }
}

static void vec_angle(void)
{
    uint32_t k;
    emit_section("angle_add_sub");
    vec_seed(0x56U);
    for (k = 0U; k < 1000U; k++) {
        int16_t a;
        int16_t b;
        if (!vec_edge_pair(k, &a, &b)) {
            a = vec_rand_i16();
            b = vec_rand_i16();
        }
        emit_i16(a);
        emit_i16(b);
        emit_sep();
        emit_i16(angle_add(a, b));
        emit_i16(angle_sub(a, b));
        emit_end();
    }
}

static void vec_divsd(void)
{
    uint32_t k = 0U;
    emit_section("dsp_divsd");
    vec_seed(0x57U);
    while (k < 1000U) {
        /* Only inside the contract: den != 0 and the quotient fits int16. */
        int16_t q = vec_rand_i16();
        uint16_t mag; /* |den|, 1..32767 */
        int16_t den;
        int32_t rem;
        int32_t num;
        if ((k & 3U) == 0U) {
            mag = (uint16_t)(1U + vec_rand_u16() % 8U);
        } else {
            mag = (uint16_t)(1U + vec_rand_u16() % 32767U);
        }
        den = ((vec_rand_u16() & 1U) != 0U) ? (int16_t) - (int16_t)mag : (int16_t)mag;
        /* num = q * den + rem with |rem| < |den| and rem of num's sign. */
        num = (int32_t)q * den;
        rem = (int32_t)(vec_rand_u16() % mag);
        if (num < 0 || (num == 0 && (k & 1U) != 0U)) {
            rem = -rem;
        }
        num += rem;
        emit_i32(num);
        emit_i16(den);
        emit_sep();
        emit_i16(q15_dsp_divsd(num, den));
        emit_end();
        k++;
    }
}

/* ---- q15_dsp.h accumulator primitives ---------------------------------------- */
/* Each primitive inside its contract (q15_dsp.h); through XC16 these run the
 * built-in bodies on the simulated dsPIC, on the AVR and the PC the twins. */

/* Edge triple k (k < VEC_N_EDGES^3), else three random values. */
static void vec_edge_triple(uint32_t k, int16_t *a, int16_t *b, int16_t *c)
{
    if (k < VEC_N_EDGES * VEC_N_EDGES * VEC_N_EDGES) {
        *a = vec_edges[k / (VEC_N_EDGES * VEC_N_EDGES)];
        *b = vec_edges[(k / VEC_N_EDGES) % VEC_N_EDGES];
        *c = vec_edges[k % VEC_N_EDGES];
        return;
    }
    *a = vec_rand_i16();
    *b = vec_rand_i16();
    *c = vec_rand_i16();
}

static void vec_dsp_sat16(void)
{
    uint32_t k;
    emit_section("dsp_add_sub_neg_dbl_sub2");
    vec_seed(0x58U);
    for (k = 0U; k < 3000U; k++) {
        int16_t a;
        int16_t b;
        int16_t c;
        vec_edge_triple(k, &a, &b, &c);
        emit_i16(a);
        emit_i16(b);
        emit_i16(c);
        emit_sep();
        emit_i16(q15_dsp_add_sat(a, b));
        emit_i16(q15_dsp_sub_sat(a, b));
        emit_i16(q15_dsp_neg_sat(a));
        emit_i16(q15_dsp_dbl_sub2_sat(a, b, c));
        emit_i16(angle_neg(a));
        emit_end();
    }
}

static void vec_dsp_products(void)
{
    uint32_t k;
    emit_section("dsp_mpy_mac_msc_lac");
    vec_seed(0x59U);
    for (k = 0U; k < 3000U; k++) {
        int16_t a;
        int16_t b;
        int16_t c;
        int16_t d = vec_edge_or_rand(k % 16U);
        vec_edge_triple(k, &a, &b, &c);
        emit_i16(a);
        emit_i16(b);
        emit_i16(c);
        emit_i16(d);
        emit_sep();
        emit_i16(q15_dsp_mpy_r(a, b));
        emit_i16(q15_dsp_mac2_r(a, b, c, d));
        emit_i16(q15_dsp_msc2_r(a, b, c, d));
        emit_i16(q15_dsp_mulsu_r(a, (uint16_t)b));
        emit_i16(q15_dsp_lac_mac_r(a, c, d));
        emit_i16(q15_dsp_half_sub2_r(a, b, c));
        emit_i16(q15_dsp_x2y_gain_r(a, b, (int16_t)((uint16_t)c & 0x3FFFU)));
        emit_end();
    }
}

static void vec_dsp_shifted(void)
{
    uint32_t k;
    emit_section("dsp_mac_shl");
    vec_seed(0x5AU);
    for (k = 0U; k < 3200U; k++) {
        uint8_t n = (uint8_t)(k % 16U);
        int16_t x = vec_edge_or_rand((k / 16U) % 24U);
        int16_t a = vec_rand_i16();
        int16_t b = vec_edge_or_rand(k % 13U);
        int16_t c = vec_edge_or_rand(k % 17U);
        int16_t d = vec_rand_i16();
        /* |2 c d 2^n| < 2^39: |d| below 2^(23 - n) for n > 8. */
        if (n > 8U) {
            d = (int16_t)(d >> (n - 8U));
        }
        emit_i16(x);
        emit_i16(a);
        emit_i16(b);
        emit_i16(c);
        emit_i16(d);
        emit_u8(n);
        emit_sep();
        emit_i16(q15_dsp_mac_shl_r(a, b, c, d, n));
        emit_i16(q15_dsp_lac_mac_shl_r(x, a, b, c, d, n));
        emit_end();
    }
}

static void vec_dsp_mul3_counts(void)
{
    uint32_t k;
    emit_section("dsp_mul3_q30_counts");
    vec_seed(0x5BU);
    for (k = 0U; k < 3000U; k++) {
        int16_t a;
        int16_t b;
        int16_t c;
        int8_t s = (int8_t) - (int8_t)(k % 8U);
        uint32_t x = vec_rand_u32() & 0x3FFFFFFFUL;
        uint16_t p = (uint16_t)(vec_rand_u16() & 0x7FFFU);
        vec_edge_triple(k, &a, &b, &c);
        b = (int16_t)((uint16_t)b & 0x7FFFU); /* b, c >= 0 */
        c = (int16_t)((uint16_t)c & 0x7FFFU);
        if (k < 64U) {
            x = (k < 32U) ? 0x3FFFFFFFUL : 0UL;
            p = (uint16_t)((k & 1U) != 0U ? 32767U : (k & 31U));
        }
        emit_i16(a);
        emit_i16(b);
        emit_i16(c);
        emit_u8((uint8_t)s);
        emit_u32(x);
        emit_u16(p);
        emit_sep();
        emit_i16(q15_dsp_mul3_r(a, b, c, s));
        emit_u16(q15_dsp_q30_counts(x, p));
        emit_end();
    }
}

static void vec_dsp_pi_lpf(void)
{
    uint32_t k;
    emit_section("dsp_pi_lpf");
    vec_seed(0x5CU);
    for (k = 0U; k < 3000U; k++) {
        int16_t e;
        int16_t kp;
        int16_t ki;
        int16_t kc = vec_rand_i16();
        int16_t l1 = vec_rand_i16();
        int16_t l2 = vec_rand_i16();
        int16_t lo = (l1 < l2) ? l1 : l2;
        int16_t hi = (l1 < l2) ? l2 : l1;
        uint8_t n = (uint8_t)(k % 8U);
        int32_t s = edge32_or_rand(k % 40U);
        int32_t y = edge32_or_rand((k / 3U) % 40U);
        int16_t kf = (int16_t)(vec_rand_u16() & 0x7FFFU);
        int16_t out;
        int16_t yf;
        vec_edge_triple(k, &e, &kp, &ki);
        if ((k & 7U) == 0U) {
            kf = (int16_t)((k & 8U) != 0U ? 32767 : (k & 16U) != 0U ? 1 : 0);
        }
        emit_i16(e);
        emit_i16(kp);
        emit_i16(ki);
        emit_i16(kc);
        emit_i16(lo);
        emit_i16(hi);
        emit_u8(n);
        emit_i32(s);
        emit_i32(y);
        emit_i16(kf);
        emit_sep();
        out = q15_dsp_pi(&s, e, kp, n, ki, kc, lo, hi);
        yf = q15_dsp_lpf(&y, e, kf);
        emit_i16(out);
        emit_i32(s);
        emit_i16(yf);
        emit_i32(y);
        emit_end();
    }
}

static void vec_dsp_divud_clz(void)
{
    uint32_t k;
    emit_section("dsp_divud_clz16");
    vec_seed(0x5DU);
    for (k = 0U; k < 1000U; k++) {
        /* Inside the contract: den != 0, quotient < 2^16. */
        uint16_t den = (uint16_t)(vec_rand_u16() | 1U);
        uint32_t q = vec_rand_u16();
        uint32_t num = q * den + (uint32_t)(vec_rand_u16() % den);
        uint16_t v = (k < 16U) ? (uint16_t)(1U << k) : (uint16_t)(vec_rand_u16() >> (k % 16U));
        if (v == 0U) {
            v = 1U;
        }
        emit_u32(num);
        emit_u16(den);
        emit_u16(v);
        emit_sep();
        emit_u16(q15_dsp_divud(num, den));
        emit_u8(q15_dsp_clz16(v));
        emit_end();
    }
}

/* Compile-time constants: the avr-gcc build folds these with a 32-bit
 * double (q15.h note 3); a difference here names the constant's index. */
static const int16_t q15_constants[] = {
    Q15(0.0),
    Q15(1.0),
    Q15(-1.0),
    Q15(0.5),
    Q15(-0.5),
    Q15(0.57735026918962576), /* 1/sqrt(3) */
    Q15(0.86602540378443865), /* sqrt(3)/2 */
    Q15(0.70710678118654752), /* 1/sqrt(2) */
    Q15(0.31830988618379067), /* 1/pi */
    Q15(0.99999),
    Q15(-0.99999),
    Q15(0.000015),
    Q15(2.0 * 3.14159265358979 * 100.0 / 20000.0),
    Q15_SCALED(1.5, 4.4),
    Q15_SCALED(-2.2, 4.4),
    Q15_SCALED(24.0, 70.0),
    ANGLE_Q15_DEG(0.0),
    ANGLE_Q15_DEG(30.0),
    ANGLE_Q15_DEG(60.0),
    ANGLE_Q15_DEG(90.0),
    ANGLE_Q15_DEG(120.0),
    ANGLE_Q15_DEG(180.0),
    ANGLE_Q15_DEG(-90.0),
    ANGLE_Q15_DEG(-120.0),
    ANGLE_Q15_DEG(359.0),
};

static void vec_constants(void)
{
    uint16_t k;
    emit_section("q15_constants");
    for (k = 0U; k < (uint16_t)(sizeof q15_constants / sizeof q15_constants[0]); k++) {
        emit_u16(k);
        emit_sep();
        emit_i16(q15_constants[k]);
        emit_end();
    }
}

/* ---- blocks ---------------------------------------------------------------- */

#include "sincos.h"

static void vec_sincos(void)
{
    uint32_t k;
    emit_section("sincos");
    /* Exhaustive: every one of the 65,536 angles. */
    for (k = 0U; k < 65536UL; k++) {
        int16_t theta = (int16_t)(uint16_t)k;
        sincos_q15_t sc = sincos_compute(theta);
        emit_i16(theta);
        emit_sep();
        emit_i16(sc.sin);
        emit_i16(sc.cos);
        emit_end();
    }
}

#include "clarke.h"

static void vec_clarke(void)
{
    uint32_t k;
    emit_section("clarke");
    vec_seed(0xC1U);
    for (k = 0U; k < 3000U; k++) {
        int16_t ia;
        int16_t ib;
        ab_q15_t ab;
        if (vec_edge_pair(k, &ia, &ib)) {
            /* every pair of edges first; then the cases below */
        } else if ((k & 1U) != 0U) {
            /* A balanced set inside the range: |ia + ib| <= 32767. */
            ia = vec_rand_between(-16384, 16383);
            ib = vec_rand_between(-16384, 16383);
        } else {
            ia = vec_rand_i16();
            ib = vec_rand_i16();
        }
        ab = clarke_forward(ia, ib);
        emit_i16(ia);
        emit_i16(ib);
        emit_sep();
        emit_i16(ab.alpha);
        emit_i16(ab.beta);
        emit_end();
    }
}

#include "park.h"
#include "sincos.h"

static sincos_q15_t park_sc(uint32_t k)
{
    sincos_q15_t sc;
    if ((k & 1U) != 0U) {
        return sincos_compute(vec_rand_i16());
    }
    if (k < VEC_N_EDGES * VEC_N_EDGES) {
        sc.sin = vec_edges[(k * 7U) % VEC_N_EDGES];
        sc.cos = vec_edges[(k * 3U + 5U) % VEC_N_EDGES];
    } else {
        sc.sin = vec_rand_i16();
        sc.cos = vec_rand_i16();
    }
    return sc;
}

static void vec_park(void)
{
    uint32_t k;
    emit_section("park");
    vec_seed(0xA1U);
    for (k = 0U; k < 4000U; k++) {
        ab_q15_t ab;
        dq_q15_t dq;
        ab_q15_t back;
        sincos_q15_t sc;
        if (!vec_edge_pair(k, &ab.alpha, &ab.beta)) {
            ab.alpha = vec_rand_i16();
            ab.beta = vec_rand_i16();
        }
        sc = park_sc(k);
        dq = park_forward(ab, sc);
        back = park_inverse(dq, sc);
        emit_i16(ab.alpha);
        emit_i16(ab.beta);
        emit_i16(sc.sin);
        emit_i16(sc.cos);
        emit_sep();
        emit_i16(dq.d);
        emit_i16(dq.q);
        emit_i16(back.alpha);
        emit_i16(back.beta);
        emit_end();
    }
}

#include "pi.h"

static void vec_pi(void)
{
    uint32_t seq;
    emit_section("pi");
    vec_seed(0x91U);
    for (seq = 0U; seq < 60U; seq++) {
        pi_params_t p;
        pi_t pi;
        uint16_t step;
        int16_t lim_a = vec_edge_or_rand(seq);
        int16_t lim_b = vec_rand_i16();
        p.kp = (int16_t)(vec_rand_u16() >> 1);
        p.kp_shift = (uint8_t)(seq % 8U);
        p.ki = (int16_t)(vec_rand_u16() >> ((seq & 1U) != 0U ? 1U : 6U));
        p.kc = ((seq % 3U) == 0U) ? p.ki : (int16_t)(vec_rand_u16() >> 1);
        if ((seq % 5U) == 0U) {
            lim_a = -32768;
            lim_b = 32767;
        }
        p.out_min = (lim_a < lim_b) ? lim_a : lim_b;
        p.out_max = (lim_a < lim_b) ? lim_b : lim_a;
        pi_init(&pi, &p);
        for (step = 0U; step < 100U; step++) {
            int16_t ref;
            int16_t meas;
            int16_t out;
            if (step == 50U) {
                /* Narrow the limits at run time, as field weakening does. */
                int16_t lo = vec_rand_between(-32768, 0);
                pi_set_limits(&pi, lo, vec_rand_between(lo, 32767));
            }
            if (step == 75U) {
                pi_preset(&pi, vec_rand_i16());
            }
            if (step == 90U && (seq & 3U) == 0U) {
                pi_reset(&pi);
            }
            if ((step / 20U) % 2U == 0U) {
                /* A held error, to wind the integral into the limits. */
                ref = vec_edges[(seq + step / 20U) % VEC_N_EDGES];
                meas = vec_edges[(seq * 3U + 1U) % VEC_N_EDGES];
            } else {
                ref = vec_rand_i16();
                meas = vec_rand_i16();
            }
            out = pi_update(&pi, ref, meas);
            emit_i16(ref);
            emit_i16(meas);
            emit_sep();
            emit_i16(out);
            emit_i32(pi.sum);
            emit_i16(pi.out);
            emit_end();
        }
    }
}

#include "svgen.h"

static void vec_svgen(void)
{
    static const uint16_t periods[] = {1U, 2U, 3U, 1000U, 1473U, 2000U, 32766U, 32767U};
    uint32_t k;
    emit_section("svgen");
    vec_seed(0x5EU);
    for (k = 0U; k < 5000U; k++) {
        ab_q15_t v;
        svgen_out_t out;
        uint16_t period;
        if (vec_edge_pair(k, &v.alpha, &v.beta)) {
            /* every pair of edges first; then the cases below */
        } else if ((k & 1U) != 0U) {
            /* Inside the linear region mostly: |v| <= about 0.7. */
            v.alpha = vec_rand_between(-23000, 23000);
            v.beta = vec_rand_between(-23000, 23000);
        } else {
            v.alpha = vec_rand_i16();
            v.beta = vec_rand_i16();
        }
        if ((k % 3U) == 0U) {
            period = (uint16_t)vec_rand_between(1, 32767);
        } else {
            period = periods[k % (sizeof periods / sizeof periods[0])];
        }
        svgen_update(v, period, &out);
        emit_i16(v.alpha);
        emit_i16(v.beta);
        emit_u16(period);
        emit_sep();
        emit_u16(out.duty[0]);
        emit_u16(out.duty[1]);
        emit_u16(out.duty[2]);
        emit_u8(out.sector);
        emit_bool(out.clamped);
        emit_end();
    }
}

#include "lpf.h"

static void vec_lpf(void)
{
    static const int16_t gains[] = {0, 1, 2, 100, 1000, 16384, 32766, 32767};
    uint32_t seq;
    emit_section("lpf");
    vec_seed(0x1FU);
    for (seq = 0U; seq < 40U; seq++) {
        lpf_t f;
        uint16_t step;
        int16_t k = (seq < 8U) ? gains[seq] : (int16_t)(vec_rand_u16() >> 1);
        int16_t target = vec_edge_or_rand(seq);
        lpf_reset(&f, vec_edge_or_rand(seq + 3U));
        emit_i32(f.state);
        emit_sep();
        emit_i16(lpf_output(&f));
        emit_end();
        for (step = 0U; step < 100U; step++) {
            /* A step input with noise on odd sequences. */
            int16_t x =
                ((seq & 1U) != 0U) ? q15_add_sat(target, vec_rand_between(-64, 64)) : target;
            int16_t y;
            if (step == 60U) {
                target = vec_rand_i16();
            }
            y = lpf_update(&f, x, k);
            emit_i16(x);
            emit_i16(k);
            emit_sep();
            emit_i16(y);
            emit_i32(f.state);
            emit_i16(lpf_output(&f));
            emit_end();
        }
    }
}

#include "atan2.h"

static void vec_atan2(void)
{
    uint32_t k;
    emit_section("atan2_q15");
    vec_seed(0xC0U);
    for (k = 0U; k < 6000U; k++) {
        int16_t y;
        int16_t x;
        if (vec_edge_pair(k, &y, &x)) {
            /* every pair of edges first; then the cases below */
        } else if (k < VEC_N_EDGES * VEC_N_EDGES + 81U) {
            /* Every small vector in [-4, 4]^2. */
            y = (int16_t)((int16_t)((k - VEC_N_EDGES * VEC_N_EDGES) / 9U) - 4);
            x = (int16_t)((int16_t)((k - VEC_N_EDGES * VEC_N_EDGES) % 9U) - 4);
        } else if ((k & 1U) != 0U) {
            /* Random lengths: shift both by the same random amount. */
            uint8_t sh = (uint8_t)(vec_rand_u16() % 15U);
            y = (int16_t)(vec_rand_i16() >> sh);
            x = (int16_t)(vec_rand_i16() >> sh);
        } else {
            y = vec_rand_i16();
            x = vec_rand_i16();
        }
        emit_i16(y);
        emit_i16(x);
        emit_sep();
        emit_i16(atan2_q15(y, x));
        emit_end();
    }
    emit_section("atan2_q31");
    vec_seed(0xC1U);
    for (k = 0U; k < 6000U; k++) {
        int32_t y;
        int32_t x;
        if (k < 16U) {
            /* The 32-bit extremes against each other and 0. */
            static const int32_t ext[4] = {INT32_MIN, -1L, 0L, INT32_MAX};
            y = ext[k / 4U];
            x = ext[k % 4U];
        } else {
            /* Random lengths from 1 to 32 bits. */
            uint8_t sh = (uint8_t)(vec_rand_u16() % 32U);
            uint32_t ry = vec_rand_u32();
            uint32_t rx = vec_rand_u32();
            y = (int32_t)ry >> sh;
            x = (int32_t)rx >> sh;
        }
        emit_i32(y);
        emit_i32(x);
        emit_sep();
        emit_i16(atan2_q31(y, x));
        emit_end();
    }
}

#include "q15_sqrt.h"

static void vec_q15_sqrt(void)
{
    static const uint32_t edges[] = {0UL,          1UL,          2UL,          3UL,
                                     4UL,          0x3FFFFFFFUL, 0x40000000UL, 0xFFFE0001UL,
                                     0xFFFF0000UL, 0xFFFF7FFFUL, 0xFFFF8000UL, 0xFFFFFFFFUL};
    uint32_t k;
    emit_section("q15_isqrt_u32");
    vec_seed(0x5AU);
    for (k = 0U; k < 3000U; k++) {
        uint32_t n;
        if (k < sizeof edges / sizeof edges[0]) {
            n = edges[k];
        } else if ((k % 3U) == 0U) {
            /* Around a perfect square and around a midpoint k^2 + k. */
            uint32_t r = vec_rand_u16();
            n = r * r + r + (uint32_t)(k % 5U) - 2U;
        } else {
            uint32_t r = vec_rand_u32(); /* two draws, sequenced (emit.h) */
            n = r >> (vec_rand_u16() % 32U);
        }
        emit_u32(n);
        emit_sep();
        emit_u32(q15_isqrt_u32(n));
        emit_end();
    }
    emit_section("q15_sqrt");
    /* Exhaustive over the non-negative inputs, plus the negative edges. */
    for (k = 0U; k < 32768UL + 4U; k++) {
        int16_t x = (k < 32768UL) ? (int16_t)k : vec_edges[k - 32768UL];
        emit_i16(x);
        emit_sep();
        emit_i16(q15_sqrt(x));
        emit_end();
    }
}

#include "fieldweak.h"

static void vec_fieldweak(void)
{
    uint32_t set;
    emit_section("fieldweak");
    vec_seed(0xF3U);
    for (set = 0U; set < 48U; set++) {
        fieldweak_params_t p;
        fieldweak_t fw;
        uint16_t i;
        /* Spans: disabled (equal, inverted, negative nominal), 1 count, full, random. */
        switch (set % 8U) {
            case 0U:
                p.speed_nominal = vec_rand_between(0, 32767);
                p.speed_max = p.speed_nominal;
                break;
            case 1U:
                p.speed_nominal = vec_rand_between(-32768, -1);
                p.speed_max = 32767;
                break;
            case 2U:
                p.speed_nominal = vec_rand_between(0, 32766);
                p.speed_max = (int16_t)(p.speed_nominal + 1);
                break;
            case 3U:
                p.speed_nominal = 0;
                p.speed_max = 32767;
                break;
            case 4U:
                p.speed_nominal = vec_rand_between(1, 32767);
                p.speed_max = vec_rand_between(0, p.speed_nominal);
                break;
            default:
                p.speed_nominal = vec_rand_between(0, 32000);
                p.speed_max = vec_rand_between((int16_t)(p.speed_nominal + 1), 32767);
                break;
        }
        for (i = 0U; i < FIELDWEAK_TABLE_SIZE; i++) {
            if ((set % 6U) == 5U) {
                /* Extreme steps: alternate the table between the rails. */
                p.id_table[i] = ((i & 1U) != 0U) ? 32767 : -32768;
            } else if (i == 0U) {
                p.id_table[i] = 0;
            } else {
                p.id_table[i] = vec_rand_i16();
            }
        }
        fieldweak_init(&fw, &p);
        emit_i16(p.speed_nominal);
        emit_i16(p.speed_max);
        emit_sep();
        emit_u16(fw.span);
        emit_end();
        for (i = 0U; i < 100U; i++) {
            int16_t speed;
            if (i < VEC_N_EDGES) {
                speed = vec_edges[i];
            } else if (i < VEC_N_EDGES + 6U) {
                /* At and next to both ends of the table. */
                int16_t end = (i & 1U) != 0U ? p.speed_nominal : p.speed_max;
                speed = q15_add_sat(end, (int16_t)((int16_t)(i % 3U) - 1));
            } else {
                speed = vec_rand_i16();
            }
            emit_i16(speed);
            emit_sep();
            emit_i16(fieldweak_id_ref(&fw, speed));
            emit_end();
        }
    }
}

#include "ripple.h"

static void vec_ripple(void)
{
    uint32_t k;
    emit_section("ripple");
    vec_seed(0x81U);
    for (k = 0U; k < 5000U; k++) {
        int16_t v;
        int16_t vbus;
        int16_t target;
        dq_q15_t dq;
        dq_q15_t dq_out;
        if (k < VEC_N_EDGES * VEC_N_EDGES * VEC_N_EDGES) {
            v = vec_edges[k / (VEC_N_EDGES * VEC_N_EDGES)];
            vbus = vec_edges[(k / VEC_N_EDGES) % VEC_N_EDGES];
            target = vec_edges[k % VEC_N_EDGES];
        } else if ((k & 1U) != 0U) {
            /* The working region: bus within +-30 % of the target. */
            target = vec_rand_between(8000, 30000);
            vbus = q15_add_sat(target,
                               vec_rand_between((int16_t) - (target / 3), (int16_t)(target / 3)));
            v = vec_rand_i16();
        } else {
            v = vec_rand_i16();
            vbus = vec_rand_i16();
            target = vec_rand_i16();
        }
        dq.d = v;
        dq.q = vec_rand_i16();
        dq_out = ripple_compensate_dq(dq, vbus, target);
        emit_i16(v);
        emit_i16(dq.q);
        emit_i16(vbus);
        emit_i16(target);
        emit_sep();
        emit_i16(ripple_compensate(v, vbus, target));
        emit_i16(dq_out.d);
        emit_i16(dq_out.q);
        emit_end();
    }
}

#include "vlimit.h"

static void vec_vlimit(void)
{
    uint32_t k;
    emit_section("vlimit");
    vec_seed(0x7CU);
    for (k = 0U; k < 4000U; k++) {
        int16_t vd;
        int16_t vmax;
        if (vec_edge_pair(k, &vd, &vmax)) {
            /* every pair of edges first; then the cases below */
        } else if ((k & 1U) != 0U) {
            vmax = vec_rand_between(0, 32767);
            vd = vec_rand_between((int16_t)-vmax, vmax);
        } else {
            vd = vec_rand_i16();
            vmax = vec_rand_i16();
        }
        emit_i16(vd);
        emit_i16(vmax);
        emit_sep();
        emit_i16(vlimit_vq_max(vd, vmax));
        emit_end();
    }
}

void vec_foc(void)
{
    vec_q15_sat();
    vec_q15_add_sub();
    vec_q15_mul();
    vec_q15_shift();
    vec_q31();
    vec_angle();
    vec_divsd();
    vec_dsp_sat16();
    vec_dsp_products();
    vec_dsp_shifted();
    vec_dsp_mul3_counts();
    vec_dsp_pi_lpf();
    vec_dsp_divud_clz();
    vec_constants();
    vec_sincos();
    vec_clarke();
    vec_park();
    vec_pi();
    vec_svgen();
    vec_lpf();
    vec_atan2();
    vec_q15_sqrt();
    vec_fieldweak();
    vec_ripple();
    vec_vlimit();
}
