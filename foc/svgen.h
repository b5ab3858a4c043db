/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* svgen.h - space-vector modulation with AN1078's modified inverse Clarke. */
#ifndef SVGEN_H
#define SVGEN_H

#include "frames.h"

/*
 * Voltage scale: |v| = 1.0 (Q15 full scale) is the largest vector of the
 * linear region, the circle inscribed in the SVM hexagon, i.e. a phase
 * voltage amplitude of Vbus / sqrt(3) (a line-to-line amplitude of Vbus).
 *
 * CalcRef (modified inverse Clarke, alpha and beta swapped):
 *   r1 = beta
 *   r2 = ( sqrt(3) alpha - beta) / 2
 *   r3 = (-sqrt(3) alpha - beta) / 2
 * On this scale r1, r2, r3 are exactly the requested line-to-line voltages
 * v_bc, v_ab, v_ca in units of Vbus. The signs of r1..r3 give the sector;
 * the two components bounding it are the active-vector on-times T1 and T2
 * as fractions of the period. Duties are centred: the lowest phase gets
 * (period - T1 - T2) / 2, the middle one T2 more, the highest T1 more, so
 * (max duty + min duty) = period within 1 count in the linear region.
 *
 * Sectors (angle of v from the alpha axis; on a boundary either neighbour
 * gives the same duties):
 *   1: [0, 60)  2: [60, 120)  3: [120, 180)  4: [180, 240)  5: [240, 300)
 *   6: [300, 360) degrees. The zero vector reports sector 1.
 *
 * Output: duty[k] in 0..period counts for a centre-aligned PWM whose duty
 * register spans 0..period for 0..100 % (PDCx units on the dsPIC: phase k's
 * mean voltage vs the negative rail = duty[k] / period * Vbus).
 * Over-modulation (T1 + T2 > 1, the vector outside the hexagon) scales T1
 * and T2 down in proportion so that T1 + T2 = period: the vector keeps its
 * angle and lands on the hexagon; clamped is set. Never wrapped.
 *
 * Scaling and overflow: alpha, beta Q15 (any value, including -32768 on
 * both); the r's are formed exactly in 32 bits (Q30, sqrt(3)/2 as
 * Q15 28378), T1 and T2 are rounded once to counts; the over-modulation
 * ratio uses one q15_dsp_divsd whose quotient is <= period by construction.
 * No intermediate can overflow for any input.
 * Accuracy (svgen.c note 1, checked by test/foc/test_svgen.c; measured
 * figures: docs/foc_control_blocks.md, "Measured accuracy"): the
 * line-to-line voltages rebuilt from the duties are within 1 + 2.5e-6 period
 * counts of the requested ones; a clamped vector's angle is within
 * 0.02 deg at period 2000 (0.04 at 1000, 0.005 at 32767).
 */
typedef struct {
    uint16_t duty[3]; /* phases a, b, c: 0..period */
    uint8_t sector;   /* 1..6, sector of the requested vector (table above) */
    bool clamped;     /* true when the vector was outside the hexagon */
} svgen_out_t;

/* svgen_update(v, period, out): period: duty counts for 100 %, 1..32767
 * (larger values are treated as 32767; 0 gives all duties 0). */
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

Q15_INLINE void svgen_update(ab_q15_t v, uint16_t period, svgen_out_t *out)
{
    uint16_t p = (period > SVGEN_PERIOD_MAX) ? (uint16_t)SVGEN_PERIOD_MAX : period;

    /* CalcRef on the Q30 scale, exact: r1 = beta, r2 = (sqrt3 alpha - beta)/2,
     * r3 = (-sqrt3 alpha - beta)/2, so r1 + r2 + r3 = 0 holds exactly and
     * the sign tests below agree with each other (svgen.c note 2). */
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
         * and the quotient is <= p (svgen.c note 3). */
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

#endif /* SVGEN_H */
