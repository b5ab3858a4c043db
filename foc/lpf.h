/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* lpf.h - first-order low-pass filter y += K (x - y) with a 32-bit state. */
#ifndef LPF_H
#define LPF_H

#include "q15.h"

/*
 * y(n) = y(n-1) + K (x(n) - y(n-1)), K = 2 pi fc Ts in Q15 (0..32767).
 * State: Q31 (value = state / 2^31), so K * (x - y) is kept to 2^-30 and a
 * small input at a small K is not lost (a 16-bit state truncates
 * K (x - y) to zero once |x - y| < 1 / K LSB; see the note in lpf.c).
 * The step is q15_dsp_lpf: on the dsPIC four accumulator operations.
 *
 * lpf_reset(f, y0)      state = y0 exactly (output y0).
 * lpf_update(f, x, k)   one step; returns the new output.
 *   x: Q15, any value. k: Q15 gain 0..32767 (K < 1); k <= 0 holds the state.
 *   Scaling/overflow: y - K y + K x with the state split into its high
 *   and low words, three exact products and one truncated one (K times the
 *   low word, q15_dsp.h note 1): each step is at most 2 Q31 LSB above the
 *   exact one, never below; the new value lies between y and x, so nothing
 *   can overflow for any x, k, state. No division.
 * lpf_output(f)         the state rounded to Q15 (ties up), saturated.
 *
 * Accuracy (test/foc/test_lpf.c, against the double recurrence with the
 * same K): 0 <= state - ref <= 1 / k LSB and |output - ref| <= 0.5 + 1 / k
 * LSB (k the raw gain): 1.5 LSB at k = 1, below 0.51 LSB for k >= 98 (the
 * observer runs at k >= 429). test_lpf.c prints the measured figures on
 * steps, full-scale sines, a 5-LSB sine (which a 16-bit truncating state
 * loses) and random inputs with a random K every step.
 */
typedef struct {
    q31_t state; /* Q31 */
} lpf_t;

Q15_INLINE void lpf_reset(lpf_t *f, q15_t y0)
{
    f->state = q31_from_q15(y0);
}

Q15_INLINE q15_t lpf_update(lpf_t *f, q15_t x, q15_t k)
{
    if (k <= 0) {
        return q15_from_q31(f->state);
    }
    return q15_dsp_lpf(&f->state, x, k);
}

Q15_INLINE q15_t lpf_output(const lpf_t *f)
{
    return q15_from_q31(f->state);
}

#endif /* LPF_H */
