/* cordic.h - four-quadrant arctangent by CORDIC on a normalised vector. */
#ifndef CORDIC_H
#define CORDIC_H

#include "q15.h"

/*
 * cordic_atan2(y, x): the angle of the vector (x, y) as a binary angle,
 * -32768..32767 = -pi..pi, like atan2(y, x).
 *   Inputs: any int16 values (Q15 or raw; only their ratio matters).
 *   Both are first shifted left by the leading-sign count of the larger
 *   magnitude, so accuracy does not depend on the vector's length.
 *   Defined cases: (0, 0) -> 0; (0, x < 0) -> -32768 (= -pi, the binary
 *   angle has no +pi); axes are exact.
 *   Accuracy: stated in cordic.c, proven by test/foc/test_cordic.c.
 */
angle_q15_t cordic_atan2(int16_t y, int16_t x);

#endif /* CORDIC_H */
