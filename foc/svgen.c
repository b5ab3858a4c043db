/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* svgen.c - space-vector modulation with AN1078's modified inverse Clarke. */
#include "svgen.h"

/*
 * Notes
 *
 * 1. Accuracy (test_svgen.c prints the measured figures). The line-to-line
 *    voltages rebuilt from the duties, (d_a - d_b) / period etc., differ from
 *    the requested vector's r2, r1, r3 by at most 1 + 2.5e-6 period counts:
 *    T1 and T1 + T2 are each rounded once, to 0.5 count, T2 is their
 *    difference, and the Q15 sqrt(3)/2 (28378, 2.4e-6 high) adds up to 0.08
 *    count at period 32767. Measured over 1.8 million random vectors in the
 *    hexagon per period (>= 10^5 in every sector): 1.003 counts at 2000,
 *    1.000 at 1000, 1.06 at 32767 (mean 0.28). (max + min duty) is period or period - 1 (the lowest
 * duty is floored to a whole count); the zero vector gives period / 2 (floored) on all three
 * phases. Clamped vectors keep their angle to within 1.155 (0.5 + period / 16384) / period rad
 * (note 3): measured 0.019 deg at period 2000, 0.036 at 1000, 0.004 at 32767.
 *
 * 2. With sqrt(3)/2 quantised, the r's are not the exact line-to-line
 *    voltages, but they are computed without rounding, so r1 + r2 + r3 = 0
 *    exactly and the sector tests are consistent: x and y are never
 *    negative, and a vector on a sector boundary (one of x, y = 0) gives the
 *    same duties from either neighbour.
 *
 * 3. Over-modulation arithmetic: x + y > 2^30 and < 1.52 * 2^30, so
 *    s16 = round((x + y) / 2^16) is 16384..23170 and x16 <= s16;
 *    x16 * p + s16 / 2 < 23170 * 32768 < 2^31, and the quotient, rounded
 *    to nearest, is at most p <= 32767: in range for div.sd. The ratio's
 *    operands have 14 to 15 bits, so T1 / period is within 1 / 16384 of
 *    x / (x + y), plus the quotient's 0.5 count.
 */
