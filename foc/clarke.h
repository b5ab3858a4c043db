/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* clarke.h - Clarke transform: two measured phase currents to alpha/beta. */
#ifndef CLARKE_H
#define CLARKE_H

#include "frames.h"

/*
 * clarke_forward(ia, ib): amplitude-invariant Clarke with ic = -ia - ib.
 *   alpha = ia
 *   beta  = (ia + 2 ib) / sqrt(3)
 *   Inputs and outputs Q15 of the same full scale, any int16 values.
 *   Scaling/overflow: u = ia + 2 ib (|u| <= 98,304) times 1/sqrt(3) in Q16
 *   (37,837) is formed exactly (q15_dsp_x2y_gain_r), rounded to nearest
 *   (ties up) and saturated: beta saturates exactly where the rounded
 *   result leaves Q15, i.e. only for |ia + 2 ib| > sqrt(3) full scale
 *   (inputs that are not a balanced three-phase set); it never wraps.
 *   Accuracy (test/foc/test_clarke_park.c, 3.9e7 input pairs plus every
 *   edge row; it prints the measured figures): alpha exact; |beta - (ia + 2 ib)/sqrt(3)| <= 0.7 LSB
 *   (0.5 rounding + 0.2 from the constant); saturated cases equal the
 *   clamped exact value. On a rounded balanced set of any amplitude, beta
 *   is within 1.57 LSB of A sin(theta).
 *   Cost: two accumulator loads and two multiply-accumulates, no division.
 */
#define CLARKE_INV_SQRT3_Q16 ((int32_t)37837) /* round(65536 / sqrt(3)) */

Q15_INLINE ab_q15_t clarke_forward(q15_t ia, q15_t ib)
{
    ab_q15_t out;
    out.alpha = ia;
    /* round((ia + 2 ib) 37837 / 2^16), saturated: the gain's excess over
     * 2^15 (5069) as two products on the accumulator. */
    out.beta = q15_dsp_x2y_gain_r(ia, ib, (int16_t)(CLARKE_INV_SQRT3_Q16 - 32768));
    return out;
}

#endif /* CLARKE_H */
