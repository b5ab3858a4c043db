/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* park.h - Park (alpha/beta -> d/q) and inverse Park (d/q -> alpha/beta). */
#ifndef PARK_H
#define PARK_H

#include "frames.h"

/*
 * park_forward(ab, sc):
 *   d =  alpha cos + beta sin
 *   q = -alpha sin + beta cos
 * park_inverse(dq, sc):
 *   alpha = d cos - q sin
 *   beta  = d sin + q cos
 *   sc: sin/cos of the rotor angle (sincos_compute), Q15; all inputs any
 *   int16 values.
 *   Scaling/overflow: each output is the sum of two Q15 x Q15 products in
 *   the Q31 accumulator (q15_dsp_mac2_r / q15_dsp_msc2_r: mpy, mac or msc,
 *   sac.r on the dsPIC), rounded once to nearest (ties up) and saturated. |d| or |q| can reach
 * sqrt(2) of full scale for a vector outside the unit circle: the result then saturates to the
 * correct side, never wraps (also with -32768 in sc, where -1 x -1 saturates). Accuracy
 * (test/foc/test_clarke_park.c, all 65,536 angles x 70 vectors; it prints
 * the measured figures):
 *   <= 0.5 LSB against the exact value with the same sc;
 *   against the true angle, inside the unit circle, <= 0.5 + sqrt(2) x 1.5
 *   = 2.62 LSB. Round trip
 *   park_inverse(park_forward(v)) is within |v_k| 4.25 / 32768 + 1.21 LSB of
 *   each component v_k, the 4.25 coming from
 *   sin^2 + cos^2 != 1 in sincos_compute.
 *   Cost: four 16 x 16 multiplies per call, no division.
 */
Q15_INLINE dq_q15_t park_forward(ab_q15_t ab, sincos_q15_t sc)
{
    dq_q15_t out;
    out.d = q15_dsp_mac2_r(ab.alpha, sc.cos, ab.beta, sc.sin);
    out.q = q15_dsp_msc2_r(ab.beta, sc.cos, ab.alpha, sc.sin);
    return out;
}

Q15_INLINE ab_q15_t park_inverse(dq_q15_t dq, sincos_q15_t sc)
{
    ab_q15_t out;
    out.alpha = q15_dsp_msc2_r(dq.d, sc.cos, dq.q, sc.sin);
    out.beta = q15_dsp_mac2_r(dq.d, sc.sin, dq.q, sc.cos);
    return out;
}

#endif /* PARK_H */
