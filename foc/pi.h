/* pi.h - PI controller with Kc anti-windup, exactly as AN1078 describes it. */
#ifndef PI_H
#define PI_H

#include "q15.h"

/*
 * Per call (AN1078 "PI Control", Figure 9):
 *   Err = ref - meas                        (Q15, formed in 32 bits, saturated)
 *   U   = Sum + Kp * 2^kp_shift * Err       (Q31 accumulator, saturating)
 *   Out = clamp(round(U), out_min, out_max) (Q15)
 *   Exc = U - Out                           (Q31, saturating)
 *   Sum = Sum + Ki * Err - Kc * Exc         (Q31, saturating)
 * Kc * Exc removes from the integral what the limiter has cut off, so the
 * integral stops growing while the output is saturated (anti-windup);
 * AN1078 recommends Kc = Ki for most loops.
 *
 * Gains >= 1 are kept as a Q15 mantissa with the shift named beside it:
 * proportional gain = kp * 2^kp_shift, kp_shift in 0..7.
 */
typedef struct {
    q15_t kp;         /* Q15 proportional gain mantissa */
    uint8_t kp_shift; /* proportional gain exponent, 0..7 */
    q15_t ki;         /* Q15 integral gain per call */
    q15_t kc;         /* Q15 anti-windup gain */
    q15_t out_min;    /* Q15 lower output limit */
    q15_t out_max;    /* Q15 upper output limit, >= out_min */
} pi_params_t;

typedef struct {
    pi_params_t p; /* gains and limits; limits may be changed at run time */
    q31_t sum;     /* Q31 integral (AN1078's qdSum) */
    q15_t out;     /* Q15 last output */
} pi_t;

void pi_init(pi_t *pi, const pi_params_t *params);  /* copy params, reset */
void pi_reset(pi_t *pi);                            /* Sum = 0, Out = 0 */
void pi_preset(pi_t *pi, q15_t sum);                /* Sum = sum (Q15 -> Q31), e.g. bumpless hand-off */
void pi_set_limits(pi_t *pi, q15_t out_min, q15_t out_max);
q15_t pi_update(pi_t *pi, q15_t ref, q15_t meas);

#endif /* PI_H */
