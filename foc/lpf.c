/* lpf.c - first-order low-pass filter y += K (x - y) with a 32-bit state. */
#include "lpf.h"

/*
 * The state is a Q31 whose bit 0 is always 0 (lpf_reset writes y0 * 2^16 and
 * every update adds an even number), so state >> 1 is an exact Q30 copy of it.
 * All arithmetic is done in Q30 because x - y spans (-2, 2):
 *
 *   diff = x * 2^15 - state / 2          Q30, |diff| < 2^31: fits int32_t
 *   diff = hi * 2^16 + lo                hi int16_t, lo uint16_t (0..65535)
 *   inc  = K diff / 2^15                 Q30, rounded to nearest (ties up)
 *        = 2 (K hi) + (K lo + 2^14) >> 15
 *   state = (state / 2 + inc) * 2
 *
 * K hi is one signed 16 x 16 product (|K hi| < 2^30, doubled < 2^31), K lo one
 * unsigned 16 x 16 product (< 2^31 with the rounding half), so the update
 * needs no 64-bit arithmetic. Overflow: for 0 <= K < 1 the exact new value
 * lies between the old state and x, both inside [-2^30, 2^30 - 2^15] in Q30,
 * and rounding moves it by at most half a Q30 LSB, so the sum fits and the
 * doubling back to Q31 cannot wrap, whatever x, K and the state are.
 * A negative K (outside the contract) is treated as 0.
 *
 * Resolution: the update is exact to 2^-30, so with K = 1 LSB (2^-15) the
 * filter still moves while |x - y| > 2^-16 (half a Q15 LSB); a 16-bit state
 * with truncating products stops moving once |x - y| < 1 / K LSB (32,768 LSB
 * at K = 1 LSB, 334 LSB at K = Q15(0.003)) and loses a small signal entirely.
 */

void lpf_reset(lpf_t *f, q15_t y0)
{
    f->state = q31_from_q15(y0);
}

q15_t lpf_update(lpf_t *f, q15_t x, q15_t k)
{
    int32_t y30 = f->state >> 1;                 /* exact, bit 0 is 0 */
    int32_t diff = (q31_from_q15(x) >> 1) - y30; /* Q30, no overflow */
    int16_t hi = (int16_t)(diff >> 16);          /* -32768..32767 */
    uint16_t lo = (uint16_t)((uint32_t)diff & 0xFFFFUL);
    uint16_t ku = (k > 0) ? (uint16_t)k : 0U;      /* 0..32767 */
    int32_t p_hi = q15_dsp_mulss((int16_t)ku, hi); /* |p_hi| < 2^30 */
    uint32_t p_lo = (uint32_t)ku * (uint32_t)lo;   /* < 2^31 - 2^16 */
    int32_t inc = (p_hi + p_hi) + (int32_t)((p_lo + 0x4000UL) >> 15);

    y30 += inc;
    f->state = (q31_t)((uint32_t)y30 << 1);
    return q15_from_q31(f->state);
}

q15_t lpf_output(const lpf_t *f)
{
    return q15_from_q31(f->state);
}
