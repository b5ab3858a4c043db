/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* lpf.c - first-order low-pass filter: the functions are inline in lpf.h. */
#include "lpf.h"

/*
 * The step is q15_dsp_lpf (q15_dsp.h note 1): with the Q31 state
 * y = hi 2^16 + lo, y + K (x 2^16 - y) = y - 2k hi + 2k x - k lo / 2^15,
 * three exact fractional products and the last one truncated, at most
 * 2 Q31 LSB too little subtracted, so the state runs at most 1 / k Q15 LSB above the exact
 * recurrence and never below it. A negative K (outside the contract) is
 * treated as 0.
 *
 * Resolution: the update is exact to 2^-30, so with K = 1 LSB (2^-15) the
 * filter still moves while |x - y| > 2^-16 (half a Q15 LSB); a 16-bit state
 * with truncating products stops moving once |x - y| < 1 / K LSB (32,768 LSB
 * at K = 1 LSB, 334 LSB at K = Q15(0.003)) and loses a small signal entirely.
 */
