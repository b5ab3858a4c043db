/* ripple.c - DC-bus ripple compensation of Vd and Vq (AN1078 Equation 8). */
#include "ripple.h"

q15_t ripple_compensate(q15_t v_pi, q15_t vbus, q15_t vbus_target)
{
    if (vbus_target <= 0) {
        return v_pi; /* compensation off */
    }
    if (vbus <= 0) {
        /* The limit DCbus -> 0+ of Vpi Target / DCbus: full scale, signed. */
        if (v_pi > 0) {
            return Q15_MAX;
        }
        return (v_pi < 0) ? Q15_MIN : 0;
    }

    /* n = Vpi Target (Q30, exact); V = n / DCbus (Q15). Every product here
     * has 16-bit operands, so each is one mul.ss on the dsPIC, not a 32 x 32
     * multiply. */
    int32_t n = q15_dsp_mulss(v_pi, vbus_target);
    int32_t d = (int32_t)vbus;

    /* Range check first, so div.sd never overflows (note 1). */
    if (n >= q15_dsp_mulss(Q15_MAX, vbus)) {
        return Q15_MAX;
    }
    if (n < q15_dsp_mulss(Q15_MIN, vbus)) {
        return Q15_MIN;
    }

    /* Truncated quotient -> floor -> round to nearest, ties up. */
    int16_t q16 = q15_dsp_divsd(n, vbus); /* -32768..32766 (note 1) */
    int32_t q = (int32_t)q16;
    int32_t r = n - q15_dsp_mulss(q16, vbus);
    if (r < 0) {
        q--;
        r += d;
    }
    if (2L * r >= d) {
        q++;
    }
    return (q15_t)q;
}

dq_q15_t ripple_compensate_dq(dq_q15_t v_pi, q15_t vbus, q15_t vbus_target)
{
    dq_q15_t v;
    v.d = ripple_compensate(v_pi.d, vbus, vbus_target);
    v.q = ripple_compensate(v_pi.q, vbus, vbus_target);
    return v;
}

/*
 * Notes
 *
 * 1. Ranges. |n| <= 32768 * 32767 < 2^30. After the checks
 *    -32768 d <= n < 32767 d, so the truncated quotient is in
 *    [-32768, 32766] (fits div.sd's 16-bit result), the floor is >= -32768
 *    and the rounded value <= 32767. The remainder satisfies |r| < d <=
 *    32767, so q * d and 2 r fit 32 bits. 32767 d and -32768 d fit 32 bits.
 *    Accuracy: the result is the correctly rounded Vpi Target / DCbus,
 *    |error| <= 0.5 LSB (test_ripple.c prints the measured figure).
 *
 * 2. Cost on the dsPIC: one mul.ss for n, two for the range limits, one
 *    div.sd (18 cycles), one mul.ss for the remainder; per component, once
 *    per PWM period.
 */
