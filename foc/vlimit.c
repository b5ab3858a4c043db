/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* vlimit.c - voltage-circle limit: the Vq bound left once Vd is applied. */
#include "vlimit.h"

/*
 * Notes
 *
 * 1. sqrt(n / 2^30) * 2^15 = sqrt(n): no rescaling, one rounding, so the
 *    error is <= 0.5 LSB (test_vlimit.c prints the measured figure). With
 *    |d| <= vmax, n <= vmax^2 and round(sqrt(n)) <= vmax: the limit never
 *    exceeds Vmax, and at d = 0 it is Vmax exactly.
 */
