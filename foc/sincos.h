/* sincos.h - sine and cosine of a binary angle: table plus linear interpolation. */
#ifndef SINCOS_H
#define SINCOS_H

#include "frames.h"

/*
 * sincos_compute(theta) -> {sin(theta), cos(theta)}, both Q15.
 *   theta: angle_q15_t, one turn = 2^16 (any value is valid; it wraps).
 *   Output: Q15 in [-32767, 32767]; sin(pi/2) is 0x7FFF, never +1.0, so
 *   either output can be negated without saturating.
 *   Method: a const quarter-wave table of 129 entries (258 bytes of flash,
 *   128 steps per quarter turn) indexed by bits 13..7 of theta, linear
 *   interpolation on bits 6..0, rounded to nearest (ties up); quadrant
 *   symmetry gives the rest, and cos(x) = sin(x + pi/2) uses the same path.
 *   Odd/even symmetry is exact: sin(-x) = -sin(x), cos(-x) = cos(x).
 *   Accuracy (test/foc/test_sincos.c, all 65,536 angles, against
 *   32768 sin / cos in double): max |error| <= 1.5 LSB (measured 1.44 LSB,
 *   4.4e-5 of full scale); exact at 0, 90, 180 and 270 degrees (0, +-32767);
 *   32768 |sin^2 + cos^2 - 1| <= 4.25 LSB (measured 3.56). The original AN1078 table (128
 *   entries per turn) gives about 10 LSB.
 *   Cost: four table reads and two 16 x 16 multiplies, no division.
 */
sincos_q15_t sincos_compute(angle_q15_t theta);

#endif /* SINCOS_H */
