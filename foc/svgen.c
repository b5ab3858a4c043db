/* svgen.c - space-vector modulation with AN1078's modified inverse Clarke. */
#include "svgen.h"

#define SVGEN_PERIOD_MAX 32767U

/* sqrt(3) / 2 in Q15 (28378). */
#define SVGEN_SQRT3_2 Q15(0.86602540378443865)

/* 1.0 on the Q30 scale of the r's (a Q15 x Q15 product). */
#define SVGEN_ONE_Q30 0x40000000UL

/* round(x * p / 2^30) for x <= 2^30, p <= 32767, without a 64-bit product:
 * x = xh 2^15 + xl, so x p / 2^30 = (xh p + xl p / 2^15) / 2^15, both partial
 * products in the accumulator (q15_dsp_q30_counts); the inner floor costs
 * less than 2^-15 count. x = 2^30 (xh = 2^15, beyond a signed multiplier
 * operand) is the whole period. */
Q15_INLINE uint16_t svgen_counts(uint32_t x, uint16_t p)
{
    return (x >= SVGEN_ONE_Q30) ? p : q15_dsp_q30_counts(x, p);
}

void svgen_update(ab_q15_t v, uint16_t period, svgen_out_t *out)
{
    uint16_t p = (period > SVGEN_PERIOD_MAX) ? (uint16_t)SVGEN_PERIOD_MAX : period;

    /* CalcRef on the Q30 scale, exact: r1 = beta, r2 = (sqrt3 alpha - beta)/2,
     * r3 = (-sqrt3 alpha - beta)/2, so r1 + r2 + r3 = 0 holds exactly and
     * the sign tests below agree with each other (note 2). */
    int32_t a = q15_dsp_mulss(v.alpha, SVGEN_SQRT3_2);
    int32_t b_half = (int32_t)v.beta * 16384L;
    int32_t r1 = (int32_t)v.beta * 32768L;
    int32_t r2 = a - b_half;
    int32_t r3 = -a - b_half;

    /* Sector from the signs; x, y >= 0 are the bounding components: the
     * highest phase leads the middle one by x, the middle leads the lowest
     * by y (fractions of the period). hi/mid/lo index the phases. */
    int32_t x;
    int32_t y;
    uint8_t sector;
    uint8_t hi;
    uint8_t mid;
    uint8_t lo;
    if (r1 > 0 || (r1 == 0 && r2 >= 0)) {
        if (r2 > 0 || r1 == 0) {
            sector = 1; /* [0, 60): a >= b >= c */
            x = r2;
            y = r1;
            hi = 0U;
            mid = 1U;
            lo = 2U;
        } else if (r3 < 0) {
            sector = 2; /* [60, 120): b >= a >= c */
            x = -r2;
            y = -r3;
            hi = 1U;
            mid = 0U;
            lo = 2U;
        } else {
            sector = 3; /* [120, 180): b >= c >= a */
            x = r1;
            y = r3;
            hi = 1U;
            mid = 2U;
            lo = 0U;
        }
    } else {
        if (r2 < 0) {
            sector = 4; /* [180, 240): c >= b >= a */
            x = -r1;
            y = -r2;
            hi = 2U;
            mid = 1U;
            lo = 0U;
        } else if (r3 > 0) {
            sector = 5; /* [240, 300): c >= a >= b */
            x = r3;
            y = r2;
            hi = 2U;
            mid = 0U;
            lo = 1U;
        } else {
            sector = 6; /* [300, 360): a >= c >= b */
            x = -r3;
            y = -r1;
            hi = 0U;
            mid = 2U;
            lo = 1U;
        }
    }

    /* T1 (x) and T1 + T2 (x + y) in counts. x + y is the largest
     * line-to-line voltage, < 1.52 on the Q30 scale (< 2^31) for any input. */
    uint32_t ux = (uint32_t)x;
    uint32_t us = ux + (uint32_t)y;
    uint16_t t_x;
    uint16_t t_xy;
    if (us <= SVGEN_ONE_Q30) {
        t_x = svgen_counts(ux, p);
        t_xy = svgen_counts(us, p); /* >= t_x: svgen_counts is monotone */
        out->clamped = false;
    } else {
        /* Outside the hexagon: keep the ratio x : y, make x + y = period.
         * s16 in [16384, 23170], x16 <= s16, so the numerator fits 31 bits
         * and the quotient is <= p (note 3). */
        int16_t s16 = (int16_t)((us + 0x8000UL) >> 16);
        int16_t x16 = (int16_t)((ux + 0x8000UL) >> 16);
        int32_t num = (int32_t)x16 * (int32_t)p + (int32_t)(s16 / 2);
        t_x = (uint16_t)q15_dsp_divsd(num, s16);
        t_xy = p;
        out->clamped = true;
    }

    /* Centred: the lowest phase starts (p - T1 - T2) / 2 in. */
    uint16_t d_lo = (uint16_t)((uint16_t)(p - t_xy) / 2U);
    uint16_t d_mid = (uint16_t)(d_lo + (uint16_t)(t_xy - t_x));
    out->duty[lo] = d_lo;
    out->duty[mid] = d_mid;
    out->duty[hi] = (uint16_t)(d_mid + t_x);
    out->sector = sector;
}

/*
 * Notes
 *
 * 1. Accuracy (test_svgen.c prints the measured figures). The line-to-line
 *    voltages rebuilt from the duties, (d_a - d_b) / period etc., differ from
 *    the requested vector's r2, r1, r3 by at most 1 + 2.5e-6 period counts:
 *    T1 and T1 + T2 are each rounded once, to 0.5 count, T2 is their
 *    difference, and the Q15 sqrt(3)/2 (28378, 2.4e-6 high) adds up to 0.08
 *    count at period 32767. Measured over 1.8 million random vectors in the
 *    hexagon per period (>= 10^5 in every sector): 1.003 counts at 2000,
 *    1.000 at 1000, 1.06 at 32767 (mean 0.28). (max + min duty) is period or period - 1 (the lowest
 * duty is floored to a whole count); the zero vector gives period / 2 (floored) on all three
 * phases. Clamped vectors keep their angle to within 1.155 (0.5 + period / 16384) / period rad
 * (note 3): measured 0.019 deg at period 2000, 0.036 at 1000, 0.004 at 32767.
 *
 * 2. With sqrt(3)/2 quantised, the r's are not the exact line-to-line
 *    voltages, but they are computed without rounding, so r1 + r2 + r3 = 0
 *    exactly and the sector tests are consistent: x and y are never
 *    negative, and a vector on a sector boundary (one of x, y = 0) gives the
 *    same duties from either neighbour.
 *
 * 3. Over-modulation arithmetic: x + y > 2^30 and < 1.52 * 2^30, so
 *    s16 = round((x + y) / 2^16) is 16384..23170 and x16 <= s16;
 *    x16 * p + s16 / 2 < 23170 * 32768 < 2^31, and the quotient, rounded
 *    to nearest, is at most p <= 32767: in range for div.sd. The ratio's
 *    operands have 14 to 15 bits, so T1 / period is within 1 / 16384 of
 *    x / (x + y), plus the quotient's 0.5 count.
 */
