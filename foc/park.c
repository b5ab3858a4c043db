/* park.c - Park and inverse Park rotations with one rounding per output. */
#include "park.h"

/*
 * Each output is two Q15 x Q15 products summed in a Q31 accumulator
 * (q31_mul_q15 + q31_add_sat / q31_sub_sat, i.e. MAC with SATA = 1), then
 * rounded once to Q15 (ties up) and saturated by q15_from_q31. The
 * accumulator saturates only where the exact result is already outside
 * [-1, 1) (a vector longer than full scale) or, off by 2^-31, where a
 * product is -1 x -1; so saturation is clean and never wraps, for every
 * input including -32768 in sc. On the dsPIC this is two MACs and one sacr.
 */

dq_q15_t park_forward(ab_q15_t ab, sincos_q15_t sc)
{
    dq_q15_t out;
    q31_t d = q31_mac_sat(q31_mul_q15(ab.alpha, sc.cos), ab.beta, sc.sin);
    q31_t q = q31_sub_sat(q31_mul_q15(ab.beta, sc.cos), q31_mul_q15(ab.alpha, sc.sin));

    out.d = q15_from_q31(d);
    out.q = q15_from_q31(q);
    return out;
}

ab_q15_t park_inverse(dq_q15_t dq, sincos_q15_t sc)
{
    ab_q15_t out;
    q31_t alpha = q31_sub_sat(q31_mul_q15(dq.d, sc.cos), q31_mul_q15(dq.q, sc.sin));
    q31_t beta = q31_mac_sat(q31_mul_q15(dq.d, sc.sin), dq.q, sc.cos);

    out.alpha = q15_from_q31(alpha);
    out.beta = q15_from_q31(beta);
    return out;
}
