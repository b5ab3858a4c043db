/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* pi.c - PI controller with Kc anti-windup (AN1078 "PI Control"). */
#include "pi.h"

void pi_reset(pi_t *pi)
{
    pi->sum = 0;
    pi->out = 0;
}

void pi_init(pi_t *pi, const pi_params_t *params)
{
    pi->p = *params;
    if (pi->p.kp_shift > PI_KP_SHIFT_MAX) {
        pi->p.kp_shift = PI_KP_SHIFT_MAX;
    }
    pi_set_limits(pi, params->out_min, params->out_max);
    pi_reset(pi);
}

void pi_preset(pi_t *pi, q15_t sum)
{
    pi->sum = q31_from_q15(sum);
    pi->out = q15_clamp(sum, pi->p.out_min, pi->p.out_max);
}

/*
 * Notes
 *
 * 1. Accuracy. Against a double-precision model of the same five equations
 *    (real-valued Err, U, Out = clamp(U), Exc = U - Out, Sum), driven by
 *    random reference/measurement sequences with random gains and limits,
 *    the output differs by at most 1 LSB (test_pi.c prints the measured
 *    figure; note the rounding of U to Q15 alone is 0.5 LSB). Ki Err is an
 *    exact Q31 product, so the integral carries no rounding error while the
 *    output is inside the limits; the only other rounding is Exc to Q15,
 *    whose error is removed again by the Kc feedback (the saturated Sum is
 *    a contraction with factor 1 - Kc) instead of accumulating.
 *    Exc saturates at +-1.0 (only when a limit is more than 1.0 away from
 *    U); the correction then keeps its sign and is merely slower.
 *
 * 2. U. Kp Err 2^shift is formed in the dsPIC's B accumulator, which runs
 *    unsaturated (8 guard bits: |2 Kp Err 2^7| <= 2^38), and added to Sum in
 *    A, which saturates at the Q31 range only then (q15_dsp_pi). A
 *    separately saturated P term would be wrong: Sum = 0.6 plus a true P
 *    term of -1.5 must give -0.9, not -0.4.
 */
