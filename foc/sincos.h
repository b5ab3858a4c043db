/* sincos.h - sine and cosine of a binary angle: table plus linear interpolation. */
#ifndef SINCOS_H
#define SINCOS_H

#include "frames.h"

/*
 * sincos_compute(theta) -> {sin(theta), cos(theta)}, both Q15.
 *   theta: angle_q15_t, one turn = 2^16 (any value is valid; it wraps).
 *   Output: Q15 in [-32767, 32767]; sin(pi/2) is 0x7FFF, never +1.0.
 *   Method: a quarter... (see sincos.c) table indexed by the top bits of
 *   theta, linear interpolation on the low bits, rounded to nearest.
 *   Accuracy: stated in sincos.c and proven over all 65,536 angles by
 *   test/foc/test_sincos.c.
 */
sincos_q15_t sincos_compute(angle_q15_t theta);

#endif /* SINCOS_H */
