/* pi.c - PI controller with Kc anti-windup (AN1078 "PI Control"). */
#include "pi.h"

#define PI_KP_SHIFT_MAX 7U

/* sat32(sum + p * 2^n), n in 0..7, exact: the sum the dsPIC forms in its
 * 40-bit accumulator (guard bits) before it saturates on the store. A
 * separately saturated p * 2^n would be wrong: Sum = 0.6 plus a true
 * P term of -1.5 must give -0.9, not -0.4 (note 2). */
static q31_t pi_sum_shifted_sat(q31_t sum, q31_t p, uint8_t n)
{
    q31_t hi = sum >> n;                                                /* floor(sum / 2^n) */
    uint32_t lo = (uint32_t)sum & (((uint32_t)1U << n) - (uint32_t)1U); /* 0..2^n - 1 */
    q31_t v = q31_add_sat(hi, p);                                       /* U = v 2^n + lo */
    if (n == 0U) {
        return v; /* lo = 0; q31_add_sat already saturated the true sum */
    }
    q31_t lim = (q31_t)((uint32_t)1U << (31U - n)); /* 2^(31 - n), n >= 1 */
    if (v >= lim) {
        return Q31_MAX;
    }
    if (v < -lim) {
        return Q31_MIN;
    }
    return (q31_t)(((uint32_t)v << n) | lo); /* in range: exact (q15.h note 2) */
}

void pi_set_limits(pi_t *pi, q15_t out_min, q15_t out_max)
{
    pi->p.out_max = out_max;
    pi->p.out_min = (out_min > out_max) ? out_max : out_min;
}

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

q15_t pi_update(pi_t *pi, q15_t ref, q15_t meas)
{
    uint8_t shift = (pi->p.kp_shift > PI_KP_SHIFT_MAX) ? PI_KP_SHIFT_MAX : pi->p.kp_shift;
    q15_t err = q15_sub_sat(ref, meas);

    /* U = Sum + Kp 2^shift Err (Q31). */
    q31_t u = pi_sum_shifted_sat(pi->sum, q31_mul_q15(pi->p.kp, err), shift);

    /* Out = clamp(round(U)). */
    q15_t out = q15_clamp(q15_from_q31(u), pi->p.out_min, pi->p.out_max);

    /* Exc = U - Out, rounded to Q15 for the multiplier (note 1): inside the
     * limits |U - round(U)| <= 0.5 LSB rounds to 0, so Kc acts only while
     * the output is limited. */
    q15_t exc = q15_from_q31(q31_sub_sat(u, q31_from_q15(out)));

    /* Sum += Ki Err - Kc Exc. */
    q31_t sum = q31_mac_sat(pi->sum, pi->p.ki, err);
    sum = q31_sub_sat(sum, q31_mul_q15(pi->p.kc, exc));

    pi->sum = sum;
    pi->out = out;
    return out;
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
 * 2. pi_sum_shifted_sat: with sum = hi 2^n + lo (hi = sum >> n, 0 <= lo <
 *    2^n) the true U = (hi + p) 2^n + lo. v = hi + p saturates only when
 *    |hi + p| >= 2^31, and then U is far outside the Q31 range with the
 *    same sign, so the saturated v still decides correctly. U fits 32 bits
 *    iff -2^(31-n) <= v < 2^(31-n); then v 2^n has n zero low bits and
 *    OR-ing lo adds it. For n = 0 the saturated sum is U itself. No 64-bit
 *    arithmetic is needed (the dsPIC's accumulator has 8 guard bits; a
 *    proportional gain up to 2^7 and Sum together use 39 of them).
 */
