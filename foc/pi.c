/* pi.c - PI controller with Kc anti-windup (AN1078 "PI Control"). */
#include "pi.h"

#define PI_KP_SHIFT_MAX 7U

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
    /* U = Sum + Kp 2^shift Err (Q31), formed in 40 bits, then saturated (note 2). */
    q31_t u = q15_dsp_add_shl(pi->sum, pi->p.kp, err, shift);
    /* Out = clamp(round(U)). */
    q15_t out = q15_clamp(q15_from_q31(u), pi->p.out_min, pi->p.out_max);
    /* Exc = U - Out, rounded to Q15 for the multiplier (note 1): inside the
     * limits |U - round(U)| <= 0.5 LSB rounds to 0, so Kc acts only while
     * the output is limited. */
    q15_t exc = q15_dsp_sub_r(u, out);
    /* Sum += Ki Err - Kc Exc. */
    pi->sum = q15_dsp_mac_msc(pi->sum, pi->p.ki, err, pi->p.kc, exc);
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
 * 2. U. Kp Err 2^shift is formed in the dsPIC's B accumulator, which runs
 *    unsaturated (8 guard bits: |2 Kp Err 2^7| <= 2^38), and added to Sum in
 *    A, which saturates at the Q31 range only then (q15_dsp_add_shl). A
 *    separately saturated P term would be wrong: Sum = 0.6 plus a true P
 *    term of -1.5 must give -0.9, not -0.4.
 */
