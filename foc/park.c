/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* park.c - Park and inverse Park: the functions are inline in park.h. */
#include "park.h"

/*
 * Each output is two Q15 x Q15 products summed in the Q31 accumulator, rounded
 * once to Q15 (ties up) and saturated. The accumulator saturates only where
 * the exact result is already outside [-1, 1) (a vector longer than full
 * scale) or, off by 2^-31, where the first product is -1 x -1; so saturation
 * is clean and never wraps, for every input including -32768 in sc.
 */
