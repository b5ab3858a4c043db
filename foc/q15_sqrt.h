/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* q15_sqrt.h - integer and Q15 square roots, rounded to nearest. */
#ifndef Q15_SQRT_H
#define Q15_SQRT_H

#include "q15.h"

/*
 * q15_isqrt_u32(n): round(sqrt(n)) for any 32-bit n, 0..65536 (n >=
 * 0xFFFF0001 gives 65536). n is scaled by a power of 4 into [2^28, 2^30),
 * a 49-entry table seeds one Newton step (one div.ud), and the result is
 * stepped onto the exact rounding by comparing r^2 +- r with n (q15_sqrt.c
 * notes): one division instead of a bit-by-bit loop (cycles:
 * docs/performance.md, "Divisions and square roots per period").
 *
 * q15_sqrt(x): sqrt of a Q15 value, Q15: round(sqrt(x * 32768)).
 *   x <= 0 gives 0 (the square root of a negative value is not defined;
 *   0 is the nearest non-negative answer). x = 32767 gives 32767.
 *   Scaling and overflow: x * 2^15 < 2^30 fits 32 bits; the result is
 *   < 32767.5, so it always fits q15_t. Error <= 0.5 LSB. Both are checked
 *   by test/foc/test_vlimit.c (q15_sqrt on all 32,768 non-negative inputs;
 *   q15_isqrt_u32 against round(sqrt(n)) on every n < 2^20, every k^2 - 1
 *   .. k^2 + k + 1 and 10^6 random n), which prints the measured figures
 *   (docs/foc_control_blocks.md, "Measured accuracy").
 */
uint32_t q15_isqrt_u32(uint32_t n);
q15_t q15_sqrt(q15_t x);

#endif /* Q15_SQRT_H */
