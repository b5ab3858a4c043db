/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* q15_dsp.h - the dsPIC's multiplier, divider and DSP accumulators: XC16 built-ins on the chip,
 * bit-identical C elsewhere. */
#ifndef Q15_DSP_H
#define Q15_DSP_H

#include <stdint.h>

/* The small functions of the 50 us path are defined in their headers with
 * Q15_INLINE (as CMSIS-DSP does for its Park, Clarke and PID): XC16 inlines
 * them at every optimisation level (always_inline survives the -O1 and -Os
 * that switch ordinary inlining off), the PC build leaves it to gcc. */
#if defined(__XC16__)
#define Q15_INLINE static inline __attribute__((always_inline))
#else
#define Q15_INLINE static inline
#endif

/*
 * This is the only place the core touches a compiler intrinsic. Every
 * function has two bodies that must return the same bits for every input:
 * the XC16 one (built-ins, under __XC16__) and a portable twin. make
 * check-16bit compares the twin on a 16-bit-int target with the PC, and the
 * same vectors run through the XC16 build on a dsPIC33F instruction
 * simulator (docs/performance.md).
 *
 * Multiplier and divider (CORCON does not affect these):
 *   q15_dsp_mulss(a, b)  16 x 16 -> 32 signed product, exact (mul.ss).
 *                        |result| <= 2^30, cannot overflow.
 *   q15_dsp_divsd(n, d)  32 / 16 -> 16 signed quotient, truncated toward
 *                        zero (div.sd). The caller guarantees d != 0 and
 *                        that the quotient fits in int16_t: the dsPIC
 *                        traps on d == 0 and returns garbage on overflow.
 *                        The portable twin has the same contract and does
 *                        not check it (outside it, e.g. d == 0, the host
 *                        build is undefined, which UBSan reports in tests);
 *                        every caller documents how it keeps to it.
 *   q15_dsp_divud(n, d)  32 / 16 -> 16 unsigned quotient, truncated
 *                        (div.ud); same contract: d != 0, quotient < 2^16.
 *   q15_dsp_clz16(v)     leading zeros of a non-zero 16-bit value, 0..15
 *                        (ff1l - 1); v == 0 is outside the contract.
 *
 * The accumulators (40 bits each), with CORCON as hal_init() sets it once
 * (HAL_CORCON_SET): IF = 0, fractional products, a * b gives 2ab on the
 * Q31 scale; US = 0, signed operands; SATA = 1 with ACCSAT = 0, every
 * write to A saturates at the Q31 range [-2^31, 2^31 - 1] (-1 x -1 = 2^31
 * saturates to 2^31 - 1 when it lands in A); SATB = 0, B is an unsaturated
 * scratch with 8 guard bits, used only where the value stays below 2^39;
 * SATDW = 1, a store of an accumulator saturates to 16 bits; RND = 1,
 * sac.r rounds to nearest, ties up (q15.h's rule). Each primitive below is
 * a complete load-compute-store sequence: nothing is left in an
 * accumulator between calls, so any context may use them (the ADC
 * interrupt, being a non-leaf interrupt function, has XC16 save and
 * restore both accumulators around it). sat31() below is the clamp to the
 * Q31 range; "round" is (v + 2^15) >> 16 followed by the 16-bit clamp.
 *
 *   q15_dsp_mpy_r(a, b)          round(sat31(2ab)): q15_mul, mpy + sac.r
 *   q15_dsp_mac2_r(a, b, c, d)   round(sat31(sat31(2ab) + 2cd))
 *   q15_dsp_msc2_r(a, b, c, d)   round(sat31(sat31(2ab) - 2cd))
 *   q15_dsp_add_sat(a, b), q15_dsp_sub_sat(a, b)
 *                                sat16(a + b), sat16(a - b): lac, lac, add or
 *                                sub, sac
 *   q15_dsp_neg_sat(a)           sat16(-a): lac, clr, sub, sac
 *   q15_dsp_dbl_sub2_sat(a, b, c)
 *                                sat16(2a - b - c), exact before the one
 *                                clamp (formed in the unsaturated B: lac,
 *                                two mac by -1.0, sac)
 *   q15_dsp_q30_counts(x, p)     round((2 xh p + floor(xl p / 2^14)) / 2^16)
 *                                with x = xh 2^15 + xl, for 0 <= x < 2^30
 *                                and 0 <= p <= 32767: a Q30 fraction of p
 *                                counts (SVGen's on-times), both partial
 *                                products in the accumulator
 *   q15_dsp_mulsu_r(a, g)        sat16(round(a g / 2^15)) for an unsigned
 *                                Q15 g (0..65535 = 0..2): mul.su, the 32-bit
 *                                product loaded into A, shifted, sac.r
 *   q15_dsp_mul3_r(a, b, c, s)   round(a b c / 2^(30 + s)), saturated to 16
 *                                bits, for b, c >= 0 and s in -7..0 (a
 *                                triple product: b c in A, split, times a
 *                                in A and B; within 2^-10 LSB of exact)
 *   q15_dsp_half_sub2_r(v, a, b) round(sat31(v 2^15 - a 2^16 - b 2^16)):
 *                                v / 2 - a - b rounded (ties up), saturated
 *   q15_dsp_mac_shl_r(a, b, c, d, n)
 *                                round(sat31(sat31(2ab) + 2cd 2^n)): a Q15
 *                                sum with a coefficient c 2^n >= 1 (n in
 *                                0..15, and |2cd 2^n| < 2^39)
 *   q15_dsp_lac_mac_r(x, a, b)   round(sat31(x 2^16 + 2ab)): x plus a Q15
 *                                product, rounded once
 *   q15_dsp_x2y_gain_r(x, y, c)  sat16(round((x + 2y)(2^15 + c) / 2^16)):
 *                                x + 2y times a Q16 gain 1 + c / 2^15 in
 *                                [1, 1.5) (0 <= c < 2^14), exact before the
 *                                rounding, formed in the unsaturated B
 *   q15_dsp_lac_mac_shl_r(x, a, b, c, d, n)
 *                                round(sat31(sat31(x 2^16 + 2ab) + 2cd 2^n)),
 *                                the same with a Q15 term x
 *   q15_dsp_pi(s, e, kp, n, ki, kc, lo, hi)
 *                                AN1078's PI step on the Q31 integral *s
 *                                (foc/pi.h has the equations): U = sat31(*s
 *                                + 2 kp e 2^n) formed in 40 bits (n in
 *                                0..7), Out = clamp(round(U), lo, hi),
 *                                Exc = round(sat31(U - Out 2^16)),
 *                                *s = sat31(sat31(*s + 2 ki e) - 2 kc Exc);
 *                                returns Out
 *   q15_dsp_lpf(y, x, k)         *y = *y + k (x 2^16 - *y) / 2^15 on a Q31
 *                                state, k in 0..32767 (note 1); returns the
 *                                new state rounded to Q15
 *
 * XC16 cannot copy one accumulator to the other: where gcc's common
 * subexpression elimination finds the same __builtin_lac (same operand, same
 * shift) in two primitives inlined into one function, it shares the result
 * and XC16 stops with "Automatic generation of DSP instructions not yet
 * supported". The bodies avoid loading an operand another primitive of
 * the same path loads (dbl_sub2_sat subtracts b and c as products by -1.0).
 *
 * The portable bodies widen before multiplying, which is what makes them
 * correct where int is 16 bits (avr-gcc, XC16): `a * b` of two int16_t is a
 * 16-bit product there. They model the 40-bit accumulator in int64_t.
 */

/* ---- portable model of the accumulator -------------------------------------- */

Q15_INLINE int32_t q15_dsp_sat31_(int64_t v)
{
    if (v > (int64_t)INT32_MAX) {
        return INT32_MAX;
    }
    if (v < (int64_t)INT32_MIN) {
        return INT32_MIN;
    }
    return (int32_t)v;
}

/* sac.r: round the Q31 part to Q15 (ties up), saturate to 16 bits. */
Q15_INLINE int16_t q15_dsp_round_(int64_t v)
{
    int64_t r = (v + 0x8000) >> 16;
    if (r > 32767) {
        return 32767;
    }
    if (r < -32768) {
        return -32768;
    }
    return (int16_t)r;
}

/* The fractional product 2ab, exact (2^31 for -1 x -1). */
Q15_INLINE int64_t q15_dsp_frac_(int16_t a, int16_t b)
{
    return 2 * (int64_t)((int32_t)a * (int32_t)b);
}

#if defined(__XC16__)

/* The two accumulators, as XC16 names them (file-scope register variables;
 * the built-ins require `volatile`, which gcc's -Wall questions for a
 * register variable: here it is what XC16 documents). */
#pragma GCC diagnostic ignored "-Wvolatile-register-var"
register volatile int16_t q15_dsp_acca_ asm("A");
register volatile int16_t q15_dsp_accb_ asm("B");

/* ACCAL, the low word of A (data sheet: SFR 0x0022 on every dsPIC30F/33F):
 * lac loads the high word, this store completes a 32-bit load. */
#define Q15_DSP_ACCAL_ (*(volatile uint16_t *)0x0022)

typedef union {
    int32_t l;
    uint16_t w[2]; /* little-endian: w[0] low, w[1] high */
} q15_dsp_w32_;

Q15_INLINE void q15_dsp_load_a_(int32_t v)
{
    q15_dsp_w32_ u;
    u.l = v;
    q15_dsp_acca_ = __builtin_lac((int16_t)u.w[1], 0);
    Q15_DSP_ACCAL_ = u.w[0];
}

Q15_INLINE int32_t q15_dsp_read_a_(void)
{
    q15_dsp_w32_ u;
    u.w[0] = (uint16_t)__builtin_ACCL(q15_dsp_acca_);
    u.w[1] = (uint16_t)__builtin_ACCH(q15_dsp_acca_);
    return u.l;
}

Q15_INLINE int32_t q15_dsp_mulss(int16_t a, int16_t b)
{
    return __builtin_mulss(a, b);
}

Q15_INLINE int16_t q15_dsp_divsd(int32_t num, int16_t den)
{
    return __builtin_divsd(num, den);
}

Q15_INLINE uint16_t q15_dsp_divud(uint32_t num, uint16_t den)
{
    return __builtin_divud(num, den);
}

Q15_INLINE uint8_t q15_dsp_clz16(uint16_t v)
{
    return (uint8_t)(__builtin_ff1l(v) - 1U);
}

Q15_INLINE int16_t q15_dsp_mpy_r(int16_t a, int16_t b)
{
    q15_dsp_acca_ = __builtin_mpy(a, b, 0, 0, 0, 0, 0, 0);
    return __builtin_sacr(q15_dsp_acca_, 0);
}

Q15_INLINE int16_t q15_dsp_mac2_r(int16_t a, int16_t b, int16_t c, int16_t d)
{
    q15_dsp_acca_ = __builtin_mpy(a, b, 0, 0, 0, 0, 0, 0);
    q15_dsp_acca_ = __builtin_mac(q15_dsp_acca_, c, d, 0, 0, 0, 0, 0, 0, 0, 0);
    return __builtin_sacr(q15_dsp_acca_, 0);
}

Q15_INLINE int16_t q15_dsp_msc2_r(int16_t a, int16_t b, int16_t c, int16_t d)
{
    q15_dsp_acca_ = __builtin_mpy(a, b, 0, 0, 0, 0, 0, 0);
    q15_dsp_acca_ = __builtin_msc(q15_dsp_acca_, c, d, 0, 0, 0, 0, 0, 0, 0, 0);
    return __builtin_sacr(q15_dsp_acca_, 0);
}

Q15_INLINE int16_t q15_dsp_add_sat(int16_t a, int16_t b)
{
    q15_dsp_accb_ = __builtin_lac(b, 0);
    q15_dsp_acca_ = __builtin_lac(a, 0);
    q15_dsp_acca_ = __builtin_addab(q15_dsp_acca_, q15_dsp_accb_);
    return __builtin_sac(q15_dsp_acca_, 0);
}

Q15_INLINE int16_t q15_dsp_sub_sat(int16_t a, int16_t b)
{
    q15_dsp_accb_ = __builtin_lac(b, 0);
    q15_dsp_acca_ = __builtin_lac(a, 0);
    q15_dsp_acca_ = __builtin_subab(q15_dsp_acca_, q15_dsp_accb_);
    return __builtin_sac(q15_dsp_acca_, 0);
}

Q15_INLINE int16_t q15_dsp_neg_sat(int16_t a)
{
    q15_dsp_accb_ = __builtin_lac(a, 0);
    q15_dsp_acca_ = __builtin_clr();
    q15_dsp_acca_ = __builtin_subab(q15_dsp_acca_, q15_dsp_accb_); /* 2^31 saturates */
    return __builtin_sac(q15_dsp_acca_, 0);
}

Q15_INLINE int16_t q15_dsp_dbl_sub2_sat(int16_t a, int16_t b, int16_t c)
{
    /* b and c subtracted as products with -1.0 (2 x (-2^15) x b = -b 2^16,
     * exact): no lac of b or c that gcc could share with another
     * primitive's, which XC16 cannot copy between accumulators. */
    q15_dsp_accb_ = __builtin_lac(a, -1); /* 2a 2^16: up to 2^32, B has 8 guard bits */
    q15_dsp_accb_ = __builtin_mac(q15_dsp_accb_, b, (int16_t)-32768, 0, 0, 0, 0, 0, 0, 0, 0);
    q15_dsp_accb_ = __builtin_mac(q15_dsp_accb_, c, (int16_t)-32768, 0, 0, 0, 0, 0, 0, 0, 0);
    return __builtin_sac(q15_dsp_accb_, 0);
}

Q15_INLINE uint16_t q15_dsp_q30_counts(uint32_t x, uint16_t p)
{
    q15_dsp_accb_ = __builtin_mpy((int16_t)(uint16_t)(x & 0x7FFFUL), (int16_t)p, 0, 0, 0, 0, 0, 0);
    q15_dsp_accb_ = __builtin_sftac(q15_dsp_accb_, 15);
    q15_dsp_acca_ = __builtin_mpy((int16_t)(uint16_t)(x >> 15), (int16_t)p, 0, 0, 0, 0, 0, 0);
    q15_dsp_acca_ = __builtin_addab(q15_dsp_acca_, q15_dsp_accb_);
    return (uint16_t)__builtin_sacr(q15_dsp_acca_, 0);
}

Q15_INLINE int16_t q15_dsp_mulsu_r(int16_t a, uint16_t g)
{
    q15_dsp_load_a_(__builtin_mulsu(a, g));             /* |a g| < 2^31 */
    q15_dsp_acca_ = __builtin_sftac(q15_dsp_acca_, -1); /* A saturates */
    return __builtin_sacr(q15_dsp_acca_, 0);
}

Q15_INLINE int16_t q15_dsp_mul3_r(int16_t a, int16_t b, int16_t c, int8_t s)
{
    int16_t ph;
    int16_t pl;
    q15_dsp_acca_ = __builtin_mpy(b, c, 0, 0, 0, 0, 0, 0);        /* P = 2bc < 2^31 */
    ph = __builtin_ACCH(q15_dsp_acca_);                           /* P >> 16 */
    pl = (int16_t)((uint16_t)__builtin_ACCL(q15_dsp_acca_) >> 1); /* (P mod 2^16) / 2 */
    q15_dsp_accb_ = __builtin_mpy(a, pl, 0, 0, 0, 0, 0, 0);
    q15_dsp_accb_ = __builtin_sftac(q15_dsp_accb_, 15); /* pl is half the low word */
    q15_dsp_acca_ = __builtin_mpy(a, ph, 0, 0, 0, 0, 0, 0);
    q15_dsp_acca_ = __builtin_addab(q15_dsp_acca_, q15_dsp_accb_); /* 2 a P / 2^16 */
    switch (s) { /* sac.r takes its shift as a literal; s is a constant */
        case -7:
            return __builtin_sacr(q15_dsp_acca_, -7);
        case -6:
            return __builtin_sacr(q15_dsp_acca_, -6);
        case -5:
            return __builtin_sacr(q15_dsp_acca_, -5);
        case -4:
            return __builtin_sacr(q15_dsp_acca_, -4);
        case -3:
            return __builtin_sacr(q15_dsp_acca_, -3);
        case -2:
            return __builtin_sacr(q15_dsp_acca_, -2);
        case -1:
            return __builtin_sacr(q15_dsp_acca_, -1);
        default:
            return __builtin_sacr(q15_dsp_acca_, 0);
    }
}

Q15_INLINE int16_t q15_dsp_half_sub2_r(int16_t v, int16_t a, int16_t b)
{
    q15_dsp_acca_ = __builtin_lac(v, 1); /* v 2^16 >> 1: exact in 40 bits */
    q15_dsp_accb_ = __builtin_lac(a, 0);
    q15_dsp_acca_ = __builtin_subab(q15_dsp_acca_, q15_dsp_accb_);
    q15_dsp_accb_ = __builtin_lac(b, 0);
    q15_dsp_acca_ = __builtin_subab(q15_dsp_acca_, q15_dsp_accb_);
    return __builtin_sacr(q15_dsp_acca_, 0);
}

Q15_INLINE int16_t q15_dsp_mac_shl_r(int16_t a, int16_t b, int16_t c, int16_t d, uint8_t n)
{
    q15_dsp_accb_ = __builtin_mpy(c, d, 0, 0, 0, 0, 0, 0);
    q15_dsp_accb_ = __builtin_sftac(q15_dsp_accb_, -(int16_t)n); /* B unsaturated */
    q15_dsp_acca_ = __builtin_mpy(a, b, 0, 0, 0, 0, 0, 0);
    q15_dsp_acca_ = __builtin_addab(q15_dsp_acca_, q15_dsp_accb_);
    return __builtin_sacr(q15_dsp_acca_, 0);
}

Q15_INLINE int16_t q15_dsp_lac_mac_r(int16_t x, int16_t a, int16_t b)
{
    q15_dsp_acca_ = __builtin_lac(x, 0);
    q15_dsp_acca_ = __builtin_mac(q15_dsp_acca_, a, b, 0, 0, 0, 0, 0, 0, 0, 0);
    return __builtin_sacr(q15_dsp_acca_, 0);
}

Q15_INLINE int16_t q15_dsp_x2y_gain_r(int16_t x, int16_t y, int16_t c)
{
    /* B = 2 (x + 2y)(2^15 + c) = x 2^16 + y 2^17 + 2cx + 2(2c)y < 2^35. */
    q15_dsp_accb_ = __builtin_lac(y, -1); /* up to 2^32: B, unsaturated */
    q15_dsp_acca_ = __builtin_lac(x, 0);
    q15_dsp_accb_ = __builtin_addab(q15_dsp_accb_, q15_dsp_acca_);
    q15_dsp_accb_ = __builtin_mac(q15_dsp_accb_, x, c, 0, 0, 0, 0, 0, 0, 0, 0);
    q15_dsp_accb_ = __builtin_mac(q15_dsp_accb_, y, (int16_t)(2 * c), 0, 0, 0, 0, 0, 0, 0, 0);
    return __builtin_sacr(q15_dsp_accb_, 1);
}

Q15_INLINE int16_t q15_dsp_lac_mac_shl_r(int16_t x, int16_t a, int16_t b, int16_t c, int16_t d,
                                         uint8_t n)
{
    q15_dsp_accb_ = __builtin_mpy(c, d, 0, 0, 0, 0, 0, 0);
    q15_dsp_accb_ = __builtin_sftac(q15_dsp_accb_, -(int16_t)n); /* B unsaturated */
    q15_dsp_acca_ = __builtin_lac(x, 0);
    q15_dsp_acca_ = __builtin_mac(q15_dsp_acca_, a, b, 0, 0, 0, 0, 0, 0, 0, 0);
    q15_dsp_acca_ = __builtin_addab(q15_dsp_acca_, q15_dsp_accb_);
    return __builtin_sacr(q15_dsp_acca_, 0);
}

Q15_INLINE int16_t q15_dsp_pi(int32_t *s, int16_t e, int16_t kp, uint8_t n, int16_t ki, int16_t kc,
                              int16_t lo, int16_t hi)
{
    int16_t out;
    int16_t exc;
    q15_dsp_accb_ = __builtin_mpy(kp, e, 0, 0, 0, 0, 0, 0);
    q15_dsp_accb_ = __builtin_sftac(q15_dsp_accb_, -(int16_t)n); /* B unsaturated */
    q15_dsp_load_a_(*s);
    q15_dsp_acca_ = __builtin_addab(q15_dsp_acca_, q15_dsp_accb_); /* U, saturated */
    out = __builtin_sacr(q15_dsp_acca_, 0);
    out = (out > hi) ? hi : ((out < lo) ? lo : out);
    q15_dsp_accb_ = __builtin_lac(out, 0);
    q15_dsp_acca_ = __builtin_subab(q15_dsp_acca_, q15_dsp_accb_); /* U - Out */
    exc = __builtin_sacr(q15_dsp_acca_, 0);
    q15_dsp_load_a_(*s);
    q15_dsp_acca_ = __builtin_mac(q15_dsp_acca_, ki, e, 0, 0, 0, 0, 0, 0, 0, 0);
    q15_dsp_acca_ = __builtin_msc(q15_dsp_acca_, kc, exc, 0, 0, 0, 0, 0, 0, 0, 0);
    *s = q15_dsp_read_a_();
    return out;
}

Q15_INLINE int16_t q15_dsp_lpf(int32_t *y, int16_t x, int16_t k)
{
    q15_dsp_w32_ u;
    u.l = *y;
    q15_dsp_accb_ = __builtin_mpy(k, (int16_t)(u.w[0] >> 1), 0, 0, 0, 0, 0, 0);
    q15_dsp_accb_ = __builtin_sftac(q15_dsp_accb_, 15);
    q15_dsp_acca_ = __builtin_lac((int16_t)u.w[1], 0);
    Q15_DSP_ACCAL_ = u.w[0];
    q15_dsp_acca_ = __builtin_msc(q15_dsp_acca_, k, (int16_t)u.w[1], 0, 0, 0, 0, 0, 0, 0, 0);
    q15_dsp_acca_ = __builtin_mac(q15_dsp_acca_, k, x, 0, 0, 0, 0, 0, 0, 0, 0);
    q15_dsp_acca_ = __builtin_subab(q15_dsp_acca_, q15_dsp_accb_);
    *y = q15_dsp_read_a_();
    return __builtin_sacr(q15_dsp_acca_, 0);
}

#else

Q15_INLINE int32_t q15_dsp_mulss(int16_t a, int16_t b)
{
    return (int32_t)a * (int32_t)b;
}

Q15_INLINE int16_t q15_dsp_divsd(int32_t num, int16_t den)
{
    /* C99 division truncates toward zero, as div.sd does. */
    return (int16_t)(num / (int32_t)den);
}

Q15_INLINE uint16_t q15_dsp_divud(uint32_t num, uint16_t den)
{
    return (uint16_t)(num / (uint32_t)den);
}

Q15_INLINE uint8_t q15_dsp_clz16(uint16_t v)
{
    uint8_t n = 0U;
    if (v < 0x0100U) {
        v = (uint16_t)(v << 8);
        n = 8U;
    }
    if (v < 0x1000U) {
        v = (uint16_t)(v << 4);
        n = (uint8_t)(n + 4U);
    }
    if (v < 0x4000U) {
        v = (uint16_t)(v << 2);
        n = (uint8_t)(n + 2U);
    }
    if (v < 0x8000U) {
        n = (uint8_t)(n + 1U);
    }
    return n;
}

Q15_INLINE int16_t q15_dsp_mpy_r(int16_t a, int16_t b)
{
    return q15_dsp_round_(q15_dsp_sat31_(q15_dsp_frac_(a, b)));
}

Q15_INLINE int16_t q15_dsp_mac2_r(int16_t a, int16_t b, int16_t c, int16_t d)
{
    int64_t acc = q15_dsp_sat31_(q15_dsp_frac_(a, b));
    return q15_dsp_round_(q15_dsp_sat31_(acc + q15_dsp_frac_(c, d)));
}

Q15_INLINE int16_t q15_dsp_msc2_r(int16_t a, int16_t b, int16_t c, int16_t d)
{
    int64_t acc = q15_dsp_sat31_(q15_dsp_frac_(a, b));
    return q15_dsp_round_(q15_dsp_sat31_(acc - q15_dsp_frac_(c, d)));
}

Q15_INLINE int16_t q15_dsp_add_sat(int16_t a, int16_t b)
{
    return q15_dsp_round_(((int64_t)a + (int64_t)b) * 65536);
}

Q15_INLINE int16_t q15_dsp_sub_sat(int16_t a, int16_t b)
{
    return q15_dsp_round_(((int64_t)a - (int64_t)b) * 65536);
}

Q15_INLINE int16_t q15_dsp_neg_sat(int16_t a)
{
    return q15_dsp_round_(-(int64_t)a * 65536);
}

Q15_INLINE int16_t q15_dsp_dbl_sub2_sat(int16_t a, int16_t b, int16_t c)
{
    return q15_dsp_round_((2 * (int64_t)a - (int64_t)b - (int64_t)c) * 65536);
}

Q15_INLINE uint16_t q15_dsp_q30_counts(uint32_t x, uint16_t p)
{
    int64_t xh = (int64_t)(x >> 15);
    int64_t xl = (int64_t)(x & 0x7FFFUL);
    int64_t acc = 2 * xh * (int64_t)p + ((2 * xl * (int64_t)p) >> 15);
    return (uint16_t)q15_dsp_round_(acc);
}

Q15_INLINE int16_t q15_dsp_mulsu_r(int16_t a, uint16_t g)
{
    return q15_dsp_round_(q15_dsp_sat31_((int64_t)a * (int64_t)g * 2));
}

Q15_INLINE int16_t q15_dsp_mul3_r(int16_t a, int16_t b, int16_t c, int8_t s)
{
    int64_t p = q15_dsp_frac_(b, c); /* 2bc, b, c >= 0: below 2^31 */
    int64_t ph = p >> 16;
    int64_t pl = (p & 0xFFFF) >> 1;
    int64_t acc = q15_dsp_sat31_(2 * (int64_t)a * ph + ((2 * (int64_t)a * pl) >> 15));
    /* sac.r with a left shift of -s: bits 31..16 of acc 2^-s, rounded. */
    return q15_dsp_round_(acc * ((int64_t)1 << (uint8_t)(-s)));
}

Q15_INLINE int16_t q15_dsp_half_sub2_r(int16_t v, int16_t a, int16_t b)
{
    /* Each step fits 40 bits; A saturates after each subtraction. */
    int64_t acc = q15_dsp_sat31_((int64_t)v * 32768 - (int64_t)a * 65536);
    return q15_dsp_round_(q15_dsp_sat31_(acc - (int64_t)b * 65536));
}

Q15_INLINE int16_t q15_dsp_mac_shl_r(int16_t a, int16_t b, int16_t c, int16_t d, uint8_t n)
{
    int64_t acc = q15_dsp_sat31_(q15_dsp_frac_(a, b));
    return q15_dsp_round_(q15_dsp_sat31_(acc + q15_dsp_frac_(c, d) * ((int64_t)1 << n)));
}

Q15_INLINE int16_t q15_dsp_lac_mac_r(int16_t x, int16_t a, int16_t b)
{
    return q15_dsp_round_(q15_dsp_sat31_((int64_t)x * 65536 + q15_dsp_frac_(a, b)));
}

Q15_INLINE int16_t q15_dsp_x2y_gain_r(int16_t x, int16_t y, int16_t c)
{
    /* sac.r with a right shift of 1: bits 32..17 of B, rounded. */
    int64_t b = 2 * ((int64_t)x + 2 * (int64_t)y) * (32768 + (int64_t)c);
    return q15_dsp_round_(b >> 1);
}

Q15_INLINE int16_t q15_dsp_lac_mac_shl_r(int16_t x, int16_t a, int16_t b, int16_t c, int16_t d,
                                         uint8_t n)
{
    int64_t acc = q15_dsp_sat31_((int64_t)x * 65536 + q15_dsp_frac_(a, b));
    return q15_dsp_round_(q15_dsp_sat31_(acc + q15_dsp_frac_(c, d) * ((int64_t)1 << n)));
}

Q15_INLINE int16_t q15_dsp_pi(int32_t *s, int16_t e, int16_t kp, uint8_t n, int16_t ki, int16_t kc,
                              int16_t lo, int16_t hi)
{
    /* |2 kp e 2^n| <= 2^38: the P term shifted in B without loss (n <= 7). */
    int64_t u = q15_dsp_sat31_((int64_t)*s + q15_dsp_frac_(kp, e) * ((int64_t)1 << n));
    int16_t out = q15_dsp_round_(u);
    int16_t exc;
    int64_t acc;
    out = (out > hi) ? hi : ((out < lo) ? lo : out);
    exc = q15_dsp_round_(q15_dsp_sat31_(u - (int64_t)out * 65536));
    acc = q15_dsp_sat31_((int64_t)*s + q15_dsp_frac_(ki, e));
    *s = q15_dsp_sat31_(acc - q15_dsp_frac_(kc, exc));
    return out;
}

Q15_INLINE int16_t q15_dsp_lpf(int32_t *y, int16_t x, int16_t k)
{
    int32_t hi = *y >> 16; /* arithmetic (q15.h) */
    uint16_t lo = (uint16_t)((uint32_t)*y & 0xFFFFU);
    /* B = 2 k (lo / 2) >> 15: k lo / 2^15 with lo's last bit and the rest
     * truncated, 0 <= B < 2^16 (note 1). */
    int64_t b = q15_dsp_frac_(k, (int16_t)(lo >> 1)) >> 15;
    int64_t acc = (int64_t)*y - q15_dsp_frac_(k, (int16_t)hi) + q15_dsp_frac_(k, x) - b;
    *y = (int32_t)acc; /* never saturates: note 1 */
    return q15_dsp_round_(acc);
}

#endif

/*
 * Notes
 *
 * 1. q15_dsp_lpf. With the state y = hi 2^16 + lo (lo unsigned) and
 *    k' = k / 2^15, the exact step is y + k' (x 2^16 - y) = y - 2k hi +
 *    2k x - k lo / 2^15. The first three terms are exact accumulator
 *    operations (lac/ACCAL, msc, mac); the last is formed in B from lo / 2
 *    (a signed multiplier operand must be below 2^15) and shifted right by
 *    15, which truncates: what it subtracts is short, so the new state is
 *    above the exact step by e in [0, 2) Q31 LSB (k / 2^15 for the
 *    dropped bit plus the truncation). In steady state
 *    that leaves the state e 2^15 / k Q31 LSB = e / (2k) Q15 LSB above its
 *    input: below 0.003 LSB at the observer's smallest gain (k = 429) and
 *    one LSB at k = 1. Range: for 0 <= k < 2^15 every partial sum lies
 *    between y and x 2^16 + lo (both in the Q31 range), so A never
 *    saturates and the int32 store of the twin is exact.
 */

#endif /* Q15_DSP_H */
