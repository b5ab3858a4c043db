/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* frames.h - value types for the three reference frames (abc, alpha/beta, d/q). */
#ifndef FRAMES_H
#define FRAMES_H

#include "q15.h"

/* Stationary two-axis frame; alpha lies on phase a. Q15 of the quantity's
 * full scale (current: BOARD_I_FULLSCALE_A, voltage: the SVGen full scale). */
typedef struct {
    q15_t alpha;
    q15_t beta;
} ab_q15_t;

/* Rotor frame; d on the rotor flux, q leading d by 90 electrical degrees. */
typedef struct {
    q15_t d;
    q15_t q;
} dq_q15_t;

/* Three phase quantities. */
typedef struct {
    q15_t a;
    q15_t b;
    q15_t c;
} abc_q15_t;

/* sin and cos of one angle, both Q15. */
typedef struct {
    q15_t sin;
    q15_t cos;
} sincos_q15_t;

#endif /* FRAMES_H */
