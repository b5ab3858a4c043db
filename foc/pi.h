/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* pi.h - PI controller with Kc anti-windup, exactly as AN1078 describes it. */
#ifndef PI_H
#define PI_H

#include "q15.h"

/*
 * Per call (AN1078 "PI Control", Figure 9):
 *   Err = ref - meas                        (Q15, formed in 32 bits, saturated)
 *   U   = Sum + Kp * 2^kp_shift * Err       (Q31 accumulator, saturating)
 *   Out = clamp(round(U), out_min, out_max) (Q15)
 *   Exc = U - Out                           (Q31, saturating; rounded to Q15
 *                                            for the Kc product, as the
 *                                            dsPIC's 16-bit multiplier takes it)
 *   Sum = Sum + Ki * Err - Kc * Exc         (Q31, saturating)
 * Kc * Exc removes from the integral what the limiter has cut off, so the
 * integral stops growing while the output is saturated (anti-windup);
 * AN1078 recommends Kc = Ki for most loops. With Kc = Ki the saturated
 * steady state is U = Out + Err (while that is inside +-1.0): the integral
 * parks one error beyond the limit instead of running away. Once the error
 * reverses, U decays toward the new Out + Err with factor (1 - Kc) per
 * call, so the output leaves the limit within a few 1/Kc calls however
 * long it was saturated (test_pi.c checks it with Kc = Ki = 0.01 after
 * 20,000 saturated calls, against the prediction and Kc = 0; figures:
 * docs/foc_control_blocks.md, "Measured accuracy").
 *
 * Gains >= 1 are kept as a Q15 mantissa with the shift named beside it:
 * proportional gain = kp * 2^kp_shift, kp_shift in 0..7 (larger values are
 * treated as 7). Ki and Kc are per-call gains in Q15 (0..32767).
 *
 * Scaling and overflow (pi_update): ref, meas, out Q15 of the loop's full
 * scale. Err saturates to [-32768, 32767] (ref = 32767, meas = -32768 gives
 * 32767, not a wrap). Kp * Err is an exact Q31 product; Sum + Kp * Err *
 * 2^kp_shift is formed exactly (as in the dsPIC's 40-bit accumulator, whose
 * guard bits hold a gain up to 2^7) and only then saturated to Q31, so a
 * large P term is never clipped before Sum is added. The Sum updates
 * saturate like the accumulator with SATA = 1. U is rounded to Q15 (nearest, ties up, q15.h)
 * and clamped to the limits. Nothing wraps for any input or gain.
 * Accuracy: |Out - double model of these same equations| <= 1 LSB (pi.c
 * note 1), checked over 800,000 steps of 400 random runs (random gains,
 * kp_shift 0..7, limits changed at run time, open and closed loop) in
 * test/foc/test_pi.c, which prints the measured figures
 * (docs/foc_control_blocks.md, "Measured accuracy").
 */
typedef struct {
    q15_t kp;         /* Q15 proportional gain mantissa, 0..32767 */
    uint8_t kp_shift; /* proportional gain exponent, 0..7 */
    q15_t ki;         /* Q15 integral gain per call, 0..32767 */
    q15_t kc;         /* Q15 anti-windup gain, 0..32767 (AN1078: = ki) */
    q15_t out_min;    /* Q15 lower output limit */
    q15_t out_max;    /* Q15 upper output limit, >= out_min */
} pi_params_t;

typedef struct {
    pi_params_t p; /* gains and limits; limits may be changed at run time */
    q31_t sum;     /* Q31 integral (AN1078's qdSum) */
    q15_t out;     /* Q15 last output */
} pi_t;

/* Copy params (limits through pi_set_limits), then pi_reset. */
void pi_init(pi_t *pi, const pi_params_t *params);

/* Sum = 0, Out = 0. */
void pi_reset(pi_t *pi);

/* Sum = sum (Q15 -> Q31, exact), Out = sum clamped to the limits: a bumpless
 * hand-off, e.g. the speed integrator preset to the open-loop current at
 * closed-loop entry, so the first pi_update with Err = 0 returns sum
 * (clamped). */
void pi_preset(pi_t *pi, q15_t sum);

/* New output limits, used from the next pi_update on (the core limits Vq
 * after Vd every period). out_min > out_max is a caller error, handled by
 * setting both limits to out_max. The state is not touched: Kc unwinds a Sum
 * left beyond a tightened limit. */
Q15_INLINE void pi_set_limits(pi_t *pi, q15_t out_min, q15_t out_max)
{
    pi->p.out_max = out_max;
    pi->p.out_min = (out_min > out_max) ? out_max : out_min;
}

#define PI_KP_SHIFT_MAX 7U /* a larger kp_shift is treated as 7 */

/* One PI step on the error err = ref - meas, saturated (notes in pi.c);
 * returns Out (also kept in pi->out). For a caller that uses the error too
 * (the core's current-sensor sums). */
Q15_INLINE q15_t pi_step(pi_t *pi, q15_t err)
{
    uint8_t shift = (pi->p.kp_shift > PI_KP_SHIFT_MAX) ? PI_KP_SHIFT_MAX : pi->p.kp_shift;
    /* U in 40 bits, Out clamped, Exc rounded for the multiplier, the
     * integral updated: q15_dsp_pi (pi.c notes 1 and 2). */
    q15_t out = q15_dsp_pi(&pi->sum, err, pi->p.kp, shift, pi->p.ki, pi->p.kc, pi->p.out_min,
                           pi->p.out_max);
    pi->out = out;
    return out;
}

/* One PI step (notes in pi.c); returns Out (also kept in pi->out). */
Q15_INLINE q15_t pi_update(pi_t *pi, q15_t ref, q15_t meas)
{
    return pi_step(pi, q15_sub_sat(ref, meas));
}

/* Whether the last output sat at a limit (the loop asked for more than it may give). */
Q15_INLINE bool pi_at_limit(const pi_t *pi)
{
    return pi->out >= pi->p.out_max || pi->out <= pi->p.out_min;
}

#endif /* PI_H */
