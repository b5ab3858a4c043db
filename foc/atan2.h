/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* atan2.h - four-quadrant arctangent from one octant table with linear interpolation. */
#ifndef ATAN2_H
#define ATAN2_H

#include "q15.h"

/*
 * atan2_q31(y, x): the angle of the vector (x, y) as a binary angle,
 * -32768..32767 = -pi..pi, like atan2(y, x).
 *   Inputs: any int32 values, INT32_MIN included; only their ratio matters.
 *   Method: |x|, |y| folded into the first octant (min over max), both
 *   shifted right together until the larger fits 16 bits (no shift for
 *   inputs that already fit, so 16-bit vectors keep every bit), the ratio
 *   formed by one 32 / 16 unsigned division to 16 fractional bits, its
 *   arctangent read from a 129-entry table (atan(i / 128), quarter-LSB
 *   units) with linear interpolation, rounded once, then unfolded onto the
 *   octant and quadrant by exact integer steps.
 *   Defined cases: (0, 0) -> 0; (0, x < 0) -> -32768 (= -pi, the binary
 *   angle has no +pi); the axes are exact (0, +-16384, -32768), and so are
 *   the diagonals (+-8192, +-24576). A result within half an LSB of +pi
 *   rounds onto -32768.
 *   Accuracy (test/foc/test_atan2.c, against double atan2 of the same
 *   integers): max |error| <= 1.0 LSB = 0.0055 degrees at every magnitude
 *   for inputs within 16 bits, <= 1.3 LSB for larger ones (atan2.c note 1). Cost: one div.ud, two
 * table reads, one 16 x 16 multiply; 258 bytes of const table. atan2_q15(y, x): the same for int16
 * inputs.
 */

#define ATAN2_TABLE_SIZE 129U

/* round(4 atan(i / 128) 32768 / pi), i = 0..128 (atan2.c). */
extern const uint16_t atan2_table[ATAN2_TABLE_SIZE];

#define ATAN2_FRAC_BITS 9U /* 16-bit ratio = 7 index bits + 9 fraction bits */
#define ATAN2_EIGHTH    8192U
#define ATAN2_QUARTER   16384U
#define ATAN2_HALF      32768U

/* Angle of (den, num) for 0 <= num <= den, den > 0: 0..8192 LSB. */
Q15_INLINE uint16_t atan2_octant(uint16_t num, uint16_t den)
{
    uint16_t r;
    uint16_t i;
    uint16_t f;
    uint16_t q;
    if (num == den) {
        return ATAN2_EIGHTH; /* the 16-bit ratio below would be 65536 */
    }
    /* num < den: num 2^16 / den < 2^16, in range for div.ud (atan2.c note 1). */
    r = q15_dsp_divud((uint32_t)num << 16, den);
    i = (uint16_t)(r >> ATAN2_FRAC_BITS); /* 0..127 */
    f = (uint16_t)(r & ((1U << ATAN2_FRAC_BITS) - 1U));
    /* q = t + round(step f / 2^9) as t 2^16 + 2 step (f 2^6) on the
     * accumulator, rounded: t <= table[127] = 32604, step <= 326 and f 2^6
     * <= 32704 are signed 16-bit operands. The store saturates q at 32767
     * only where the exact q is 32768 (i = 127, f = 511), and both give
     * 8192 below. */
    q = (uint16_t)q15_dsp_lac_mac_r((int16_t)atan2_table[i],
                                    (int16_t)(uint16_t)(atan2_table[i + 1U] - atan2_table[i]),
                                    (int16_t)(f << (16U - ATAN2_FRAC_BITS - 1U)));
    return (uint16_t)((q + 2U) >> 2); /* quarter LSB -> LSB, rounded */
}

/* v >> sh for sh in 1..15, from its two 16-bit halves (16-bit shifts only:
 * the dsPIC has a 16-bit barrel shifter, and a 32-bit shift by a variable
 * amount costs a loop). */
Q15_INLINE uint16_t atan2_shr16(uint32_t v, uint8_t sh)
{
    uint16_t hi = (uint16_t)(v >> 16);
    uint16_t lo = (uint16_t)v;
    return (uint16_t)((uint16_t)(hi << (16U - sh)) | (uint16_t)(lo >> sh));
}

Q15_INLINE angle_q15_t atan2_q31(int32_t y, int32_t x)
{
    uint32_t ux = (x < 0) ? ((uint32_t)0U - (uint32_t)x) : (uint32_t)x;
    uint32_t uy = (y < 0) ? ((uint32_t)0U - (uint32_t)y) : (uint32_t)y;
    uint16_t mh = (uint16_t)((ux | uy) >> 16);
    uint16_t nx;
    uint16_t ny;
    uint16_t a;
    if (mh == 0U) {
        if ((ux | uy) == 0U) {
            return 0; /* (0, 0) */
        }
        nx = (uint16_t)ux; /* both fit 16 bits: every bit kept */
        ny = (uint16_t)uy;
    } else {
        /* Shift both so the larger fits 16 bits: sh = 1..16 (16 only for a
         * -2^31 component). */
        uint8_t sh = (uint8_t)(16U - q15_dsp_clz16(mh));
        if (sh < 16U) {
            nx = atan2_shr16(ux, sh);
            ny = atan2_shr16(uy, sh);
        } else {
            nx = (uint16_t)(ux >> 16);
            ny = (uint16_t)(uy >> 16);
        }
    }
    if (ny <= nx) {
        a = atan2_octant(ny, nx);
    } else {
        a = (uint16_t)(ATAN2_QUARTER - atan2_octant(nx, ny));
    }
    if (x < 0) {
        a = (uint16_t)(ATAN2_HALF - a);
    }
    if (y < 0) {
        a = (uint16_t)(0U - a);
    }
    return (angle_q15_t)(int16_t)a; /* q15.h note 2 */
}

Q15_INLINE angle_q15_t atan2_q15(int16_t y, int16_t x)
{
    return atan2_q31((int32_t)y, (int32_t)x);
}

#endif /* ATAN2_H */
