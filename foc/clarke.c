/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* clarke.c - amplitude-invariant Clarke transform from two phase currents. */
#include "clarke.h"

/*
 * beta = (ia + 2 ib) / sqrt(3), computed as u = ia + 2 ib (|u| <= 98,304)
 * times 1/sqrt(3) in Q16 (37,837: in Q15 the constant would be 18,919 and
 * its own rounding would cost up to 0.73 LSB at |beta| = 1; in Q16 it
 * costs 0.2 LSB). The gain 37,837 / 2^16 = (2^15 + 5,069) / 2^16 is applied
 * on the accumulator as u 2^15 plus 5,069 u (q15_dsp_x2y_gain_r), exact in
 * 40 bits (|2 u 37,837| < 2^33), rounded once and saturated by the store,
 * so beta is the exact rounded result clamped to Q15.
 */

Q15_STATIC_ASSERT(CLARKE_INV_SQRT3_Q16 >= 32768L && CLARKE_INV_SQRT3_Q16 - 32768L < 16384L,
                  "clarke: the Q16 gain must be 2^15 + c with 0 <= c < 2^14");
