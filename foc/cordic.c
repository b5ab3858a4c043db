/* cordic.c - atan2 by CORDIC vectoring on a normalised 32-bit vector. */
#include "cordic.h"

/*
 * Method
 *  1. Axes and the origin are answered directly (exact, see cordic.h).
 *  2. |x| and |y| (uint16_t, so |-32768| = 32768 is representable) are
 *     shifted left, together, until the larger has its top bit at bit 28
 *     (bit 29 only for a -32768 component): s = 14 + the leading-zero count
 *     of (|x| | |y|) within 15 bits. The shift is lossless, so the angle of
 *     the normalised vector is exactly the angle of the input.
 *  3. A vector with x < 0 is turned by pi (both components negated, pi put
 *     into the angle) so the CORDIC only sees the right half-plane, where
 *     its +-99.9 degree convergence range is enough.
 *  4. CORDIC_ITERATIONS vectoring steps drive y to 0, accumulating
 *     +-atan(2^-i) from a const table in a 32-bit binary angle (2^32 per
 *     turn, wrapping modulo 2^32 in uint32_t on purpose).
 *  5. The 32-bit angle is rounded to the 16-bit binary angle (ties up).
 *
 * Overflow: after step 2 |x|, |y| <= 2^29, so |v| <= 2^29.5; the CORDIC
 * gain is 1.6468, so every intermediate component stays below
 * 1.6468 * 2^29.5 = 1.25e9 < 2^31. Right shifts of negative y are
 * arithmetic (q15.h). No division, no float.
 *
 * Accuracy (test/foc/test_cordic.c): after n steps the residual angle is at
 * most atan(2^-(n-1)); for n = 15 that is 0.64 LSB of the 16-bit angle,
 * plus 0.5 LSB for the final rounding; the datapath truncation (a few units
 * of 2^-29 rad) adds nothing visible. Measured max |error| 1.136 LSB
 * (0.0062 degrees) at every magnitude from 1 LSB to full scale; 16 steps
 * would give about 0.8 LSB for one more iteration.
 *
 * Cost: 15 iterations of two 32-bit shifts and three 32-bit add/subtracts;
 * the table is 15 x 4 = 60 bytes of const data.
 */

#define CORDIC_ITERATIONS 15U

/* atan(2^-i) as a 32-bit binary angle: round(atan(2^-i) / (2 pi) * 2^32). */
static const uint32_t cordic_atan_table[CORDIC_ITERATIONS] = {
    536870912UL, 316933406UL, 167458907UL, 85004756UL, 42667331UL,
    21354465UL,  10679838UL,  5340245UL,   2670163UL,  1335087UL,
    667544UL,    333772UL,    166886UL,    83443UL,    41722UL,
};

#define CORDIC_QUARTER  ((angle_q15_t)16384)
#define CORDIC_HALF_U32 0x80000000UL

angle_q15_t cordic_atan2(int16_t y, int16_t x)
{
    uint16_t ax;
    uint16_t ay;
    uint16_t m;
    uint8_t shift = 14U;
    int32_t xr;
    int32_t yr;
    uint32_t angle = 0UL;
    uint8_t i;

    if (y == 0) {
        return (x < 0) ? Q15_MIN : 0; /* (0, 0) -> 0; the negative x axis -> -pi */
    }
    if (x == 0) {
        return (y > 0) ? CORDIC_QUARTER : (angle_q15_t)(-CORDIC_QUARTER);
    }

    ax = (uint16_t)((x < 0) ? -(int32_t)x : (int32_t)x); /* 1..32768 */
    ay = (uint16_t)((y < 0) ? -(int32_t)y : (int32_t)y);

    /* Leading-zero count of the larger magnitude, by halving steps. */
    m = (uint16_t)(ax | ay);
    if (m < 0x0080U) {
        m = (uint16_t)(m << 8);
        shift = (uint8_t)(shift + 8U);
    }
    if (m < 0x0800U) {
        m = (uint16_t)(m << 4);
        shift = (uint8_t)(shift + 4U);
    }
    if (m < 0x2000U) {
        m = (uint16_t)(m << 2);
        shift = (uint8_t)(shift + 2U);
    }
    if (m < 0x4000U) {
        shift = (uint8_t)(shift + 1U);
    }
    xr = (int32_t)((uint32_t)ax << shift); /* <= 2^29 */
    yr = (int32_t)((uint32_t)ay << shift);

    /* Right half-plane: (x, y) -> (-x, -y) = (|x|, -y) when x < 0, and pi
     * goes into the angle. y's sign after that is sign(y) xor sign(x). */
    if (x < 0) {
        angle = CORDIC_HALF_U32;
    }
    if ((y < 0) != (x < 0)) {
        yr = -yr;
    }

    for (i = 0U; i < CORDIC_ITERATIONS; i++) {
        int32_t xs = xr >> i;
        int32_t ys = yr >> i;
        if (yr > 0) { /* rotate clockwise by atan(2^-i) */
            xr += ys;
            yr -= xs;
            angle += cordic_atan_table[i];
        } else { /* counter-clockwise */
            xr -= ys;
            yr += xs;
            angle -= cordic_atan_table[i];
        }
    }

    /* 32-bit -> 16-bit binary angle, rounded (ties up), wrapping. */
    return (angle_q15_t)(int16_t)(uint16_t)((angle + 0x8000UL) >> 16);
}
