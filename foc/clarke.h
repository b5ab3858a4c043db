/* clarke.h - Clarke transform: two measured phase currents to alpha/beta. */
#ifndef CLARKE_H
#define CLARKE_H

#include "frames.h"

/*
 * clarke_forward(ia, ib): amplitude-invariant Clarke with ic = -ia - ib.
 *   alpha = ia
 *   beta  = (ia + 2 ib) / sqrt(3)
 *   Inputs and outputs Q15 of the same full scale, any int16 values.
 *   Scaling/overflow: u = ia + 2 ib is formed in 32 bits (|u| <= 98,304),
 *   clamped to the range whose beta fits Q15 ([-56,756, 56,755]), then
 *   multiplied by 1/sqrt(3) in Q16 (37,837) and rounded to nearest (ties
 *   up). beta therefore saturates exactly where the rounded result leaves
 *   Q15, i.e. only for |ia + 2 ib| > sqrt(3) full scale (inputs that are
 *   not a balanced three-phase set); it never wraps.
 *   Accuracy (test/foc/test_clarke_park.c, 3.9e7 input pairs plus every
 *   edge row): alpha exact; |beta - (ia + 2 ib)/sqrt(3)| <= 0.7 LSB
 *   (0.5 rounding + 0.2 from the constant; measured 0.694 LSB); saturated
 *   cases equal the clamped exact value. On a rounded balanced set of any
 *   amplitude, beta is within 1.49 LSB of A sin(theta) (bound 1.57 LSB).
 *   Cost: one 32 x 16 multiply, no division.
 */
#define CLARKE_INV_SQRT3_Q16 ((int32_t)37837)  /* round(65536 / sqrt(3)) */
#define CLARKE_U_MAX         ((int32_t)56755)  /* largest u with beta rounding to 32767 */
#define CLARKE_U_MIN         ((int32_t)-56756) /* smallest u with beta rounding to -32768 */
#define CLARKE_ROUND         ((int32_t)0x8000) /* half an LSB of the Q16 product */

Q15_INLINE ab_q15_t clarke_forward(q15_t ia, q15_t ib)
{
    ab_q15_t out;
    int32_t u = (int32_t)ia + (int32_t)2 * (int32_t)ib;

    if (u > CLARKE_U_MAX) {
        u = CLARKE_U_MAX;
    } else if (u < CLARKE_U_MIN) {
        u = CLARKE_U_MIN;
    }
    out.alpha = ia;
    out.beta = (q15_t)((u * CLARKE_INV_SQRT3_Q16 + CLARKE_ROUND) >> 16);
    return out;
}

#endif /* CLARKE_H */
