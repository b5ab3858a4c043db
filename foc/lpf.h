/* lpf.h - first-order low-pass filter y += K (x - y) with a 32-bit state. */
#ifndef LPF_H
#define LPF_H

#include "q15.h"

/*
 * y(n) = y(n-1) + K (x(n) - y(n-1)), K = 2 pi fc Ts in Q15 (0..32767).
 * State: Q31 (value = state / 2^31), so K * (x - y) is kept to 2^-30 and a
 * small input at a small K is not lost (a 16-bit state truncates
 * K (x - y) to zero once |x - y| < 1 / K LSB; see the note in lpf.c).
 *
 * lpf_reset(f, y0)      state = y0 exactly (output y0).
 * lpf_update(f, x, k)   one step; returns the new output.
 *   x: Q15, any value. k: Q15 gain 0..32767 (K < 1); k <= 0 holds the state.
 *   Scaling/overflow: x - y (up to 2) is formed in Q30, K (x - y) from two
 *   16 x 16 products (signed high half, unsigned low half) and rounded once
 *   to Q30 (ties up); the new value lies between y and x, so nothing can
 *   overflow for any x, k, state. No 64-bit arithmetic, no division.
 * lpf_output(f)         the state rounded to Q15 (ties up), saturated.
 *
 * Accuracy (test/foc/test_lpf.c, against the double recurrence with the
 * same K): |state - ref| <= 0.5 / k LSB and |output - ref| <= 0.5 + 0.5 / k
 * LSB (k the raw gain). Measured on steps across the full range, full-scale
 * sines at the cut-off and 10^6 random inputs with a random K every step:
 * output max 0.9993 LSB at k = 1, 0.5006 LSB at k = 16 (Q15(0.0005)),
 * <= 0.5000 LSB for k >= 98; state max 0.4993 / 0.031 / 0.0045 LSB at
 * k = 1 / 16 / 98. A 5-LSB sine at k = Q15(0.003) is tracked to 0.5 LSB
 * (a 16-bit truncating state is off by 8.6 LSB there).
 */
typedef struct {
    q31_t state; /* Q31; bit 0 is always 0 (Q30 resolution, see lpf.c) */
} lpf_t;

void lpf_reset(lpf_t *f, q15_t y0);
q15_t lpf_update(lpf_t *f, q15_t x, q15_t k);
q15_t lpf_output(const lpf_t *f);

#endif /* LPF_H */
