/* park.c - Park and inverse Park rotations with one rounding per output. */
#include "park.h"

/*
 * Each output is two Q15 x Q15 products summed in the Q31 accumulator
 * (q15_dsp_mac2_r / q15_dsp_msc2_r: mpy, mac or msc, sac.r), rounded once
 * to Q15 (ties up) and saturated. The accumulator saturates only where the
 * exact result is already outside [-1, 1) (a vector longer than full scale)
 * or, off by 2^-31, where the first product is -1 x -1; so saturation is
 * clean and never wraps, for every input including -32768 in sc.
 */

dq_q15_t park_forward(ab_q15_t ab, sincos_q15_t sc)
{
    dq_q15_t out;
    out.d = q15_dsp_mac2_r(ab.alpha, sc.cos, ab.beta, sc.sin);
    out.q = q15_dsp_msc2_r(ab.beta, sc.cos, ab.alpha, sc.sin);
    return out;
}

ab_q15_t park_inverse(dq_q15_t dq, sincos_q15_t sc)
{
    ab_q15_t out;
    out.alpha = q15_dsp_msc2_r(dq.d, sc.cos, dq.q, sc.sin);
    out.beta = q15_dsp_mac2_r(dq.d, sc.sin, dq.q, sc.cos);
    return out;
}
