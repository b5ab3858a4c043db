/* atan2.h - four-quadrant arctangent from one octant table with linear interpolation. */
#ifndef ATAN2_H
#define ATAN2_H

#include "q15.h"

/*
 * atan2_q31(y, x): the angle of the vector (x, y) as a binary angle,
 * -32768..32767 = -pi..pi, like atan2(y, x).
 *   Inputs: any int32 values, INT32_MIN included; only their ratio matters.
 *   Method: |x|, |y| folded into the first octant (min over max), both
 *   shifted right together until the larger fits 16 bits (no shift for
 *   inputs that already fit, so 16-bit vectors keep every bit), the ratio
 *   formed by one 32 / 16 unsigned division to 16 fractional bits, its
 *   arctangent read from a 129-entry table (atan(i / 128), quarter-LSB
 *   units) with linear interpolation, rounded once, then unfolded onto the
 *   octant and quadrant by exact integer steps.
 *   Defined cases: (0, 0) -> 0; (0, x < 0) -> -32768 (= -pi, the binary
 *   angle has no +pi); the axes are exact (0, +-16384, -32768), and so are
 *   the diagonals (+-8192, +-24576). A result within half an LSB of +pi
 *   rounds onto -32768.
 *   Accuracy (test/foc/test_atan2.c, against double atan2 of the same
 *   integers): max |error| <= 1.0 LSB = 0.0055 degrees at every magnitude
 *   for inputs within 16 bits, <= 1.3 LSB for larger ones (atan2.c note 1). Cost: one div.ud, two
 * table reads, one 16 x 16 multiply; 258 bytes of const table. atan2_q15(y, x): the same for int16
 * inputs.
 */
angle_q15_t atan2_q31(int32_t y, int32_t x);
angle_q15_t atan2_q15(int16_t y, int16_t x);

#endif /* ATAN2_H */
