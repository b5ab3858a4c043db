/* lpf.h - first-order low-pass filter y += K (x - y) with a 32-bit state. */
#ifndef LPF_H
#define LPF_H

#include "q15.h"

/*
 * y(n) = y(n-1) + K (x(n) - y(n-1)), K = 2 pi fc Ts in Q15 (0..32767).
 * State: Q31 (value = state / 2^31), so K * (x - y) is kept to 2^-31 and a
 * small input at a small K is not lost (a 16-bit state truncates
 * K (x - y) to zero once |x - y| < 1 / K LSB; see note in lpf.c).
 * lpf_update returns the state rounded to Q15.
 */
typedef struct {
    q31_t state;
} lpf_t;

void lpf_reset(lpf_t *f, q15_t y0);
q15_t lpf_update(lpf_t *f, q15_t x, q15_t k);
q15_t lpf_output(const lpf_t *f);

#endif /* LPF_H */
