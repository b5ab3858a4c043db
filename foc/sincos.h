/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sincos.h - sine and cosine of a binary angle: table plus linear interpolation. */
#ifndef SINCOS_H
#define SINCOS_H

#include "frames.h"

/*
 * sincos_compute(theta) -> {sin(theta), cos(theta)}, both Q15.
 *   theta: angle_q15_t, one turn = 2^16 (any value is valid; it wraps).
 *   Output: Q15 in [-32767, 32767]; sin(pi/2) is 0x7FFF, never +1.0, so
 *   either output can be negated without saturating.
 *   Method: a const quarter-wave table of 129 entries plus one pad (260
 *   bytes of flash, 128 steps per quarter turn) indexed by bits 13..7 of theta, linear
 *   interpolation on bits 6..0, rounded to nearest (ties up); quadrant
 *   symmetry gives the rest, and cos(x) = sin(x + pi/2) uses the same path.
 *   Odd/even symmetry is exact: sin(-x) = -sin(x), cos(-x) = cos(x).
 *   Accuracy (test/foc/test_sincos.c, all 65,536 angles, against
 *   32768 sin / cos in double; it prints the measured figures): max |error|
 *   <= 1.5 LSB; exact at 0, 90, 180 and 270 degrees (0, +-32767);
 *   32768 |sin^2 + cos^2 - 1| <= 4.25 LSB. Why 128 steps per quarter turn:
 *   AN1078's 128 entries per turn give about 10 LSB (docs/foc_math_blocks.md).
 *   Cost: four table reads and two 16 x 16 multiplies, no division.
 */
#define SINCOS_INDEX_BITS 7U /* 128 intervals per quarter turn */
#define SINCOS_FRAC_BITS  7U /* 14 bits of quadrant angle - 7 index bits */
#define SINCOS_QUARTER    0x4000U
#define SINCOS_FRAC_MASK  ((1U << SINCOS_FRAC_BITS) - 1U)
#define SINCOS_TABLE_SIZE ((1U << SINCOS_INDEX_BITS) + 2U)

/* round(32768 sin(i pi / 256)), i = 0..128, and a pad entry (sincos.c). */
extern const q15_t sincos_table[SINCOS_TABLE_SIZE];

/* sin of a binary angle given as uint16_t (one turn = 2^16). */
Q15_INLINE q15_t sincos_sin_u16(uint16_t a)
{
    uint16_t quadrant = (uint16_t)(a >> 14);
    uint16_t r = (uint16_t)(a & (SINCOS_QUARTER - 1U)); /* 0..2^14 - 1 */
    uint16_t idx;
    uint16_t frac;
    int16_t mag;

    if ((quadrant & 1U) != 0U) {
        r = (uint16_t)(SINCOS_QUARTER - r); /* 1..2^14: mirror about pi/2 */
    }
    idx = (uint16_t)(r >> SINCOS_FRAC_BITS);
    frac = (uint16_t)(r & SINCOS_FRAC_MASK);
    mag = sincos_table[idx];
    /* idx + 1 <= 129: r = 2^14 reads the pad with frac 0. step in -1..402
     * (the pad's -1 only ever times 0), step * frac + 64 <= 51,118: an
     * unsigned 16-bit product, rounded ties up. No branch on frac. */
    uint16_t step = (uint16_t)(sincos_table[idx + 1U] - mag);
    uint16_t add =
        (uint16_t)((uint16_t)(step * frac + (1U << (SINCOS_FRAC_BITS - 1U))) >> SINCOS_FRAC_BITS);
    mag = (int16_t)(mag + (int16_t)add); /* between two entries: <= 32767 */
    return ((quadrant & 2U) != 0U) ? (q15_t)(-mag) : mag;
}

Q15_INLINE sincos_q15_t sincos_compute(angle_q15_t theta)
{
    sincos_q15_t out;
    uint16_t a = (uint16_t)theta;

    out.sin = sincos_sin_u16(a);
    out.cos = sincos_sin_u16((uint16_t)(a + SINCOS_QUARTER)); /* cos x = sin(x + pi/2) */
    return out;
}

/* sincos_compute as a call, bit for bit: for the paths that run once a
 * window or outside CLOSED_LOOP's periods, where one copy of the body
 * matters more than the call's cycles (docs/performance.md, "fourth round"). */
sincos_q15_t sincos_call(angle_q15_t theta);

#endif /* SINCOS_H */
