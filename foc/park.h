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
 *   sc: sin/cos of the rotor angle (sincos_compute). Each output is the sum
 *   of two Q15 products formed in a 32-bit accumulator, rounded once to
 *   nearest and saturated (|d| or |q| can reach sqrt(2) of full scale only
 *   for a vector outside the unit circle). Error <= 0.5 LSB + the error of sc.
 */
dq_q15_t park_forward(ab_q15_t ab, sincos_q15_t sc);
ab_q15_t park_inverse(dq_q15_t dq, sincos_q15_t sc);

#endif /* PARK_H */
