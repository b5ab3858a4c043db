/* ripple.c - DC-bus ripple compensation of Vd and Vq (AN1078 Equation 8). */
#include "ripple.h"

#define RIPPLE_ONE      32768U /* G = 1 */
#define RIPPLE_GAIN_MAX 65535U

uint16_t ripple_gain(q15_t vbus, q15_t vbus_target)
{
    uint32_t num;
    if (vbus_target <= 0) {
        return RIPPLE_ONE; /* compensation off */
    }
    if (vbus <= 0) {
        return RIPPLE_GAIN_MAX;
    }
    /* G = round(Target 2^15 / DCbus): the quotient fits div.ud's 16 bits
     * exactly when the numerator is below DCbus 2^16 (note 1). */
    num = ((uint32_t)(uint16_t)vbus_target << 15) + (uint32_t)((uint16_t)vbus >> 1);
    if (num >= ((uint32_t)(uint16_t)vbus << 16)) {
        return RIPPLE_GAIN_MAX;
    }
    return q15_dsp_divud(num, (uint16_t)vbus);
}

q15_t ripple_apply(q15_t v_pi, uint16_t gain)
{
    /* |Vpi G| < 2^31: one signed x unsigned 16 x 16 product. */
    int32_t p = (int32_t)v_pi * (int32_t)gain;
    return q15_sat((p + (int32_t)0x4000) >> 15);
}

q15_t ripple_compensate(q15_t v_pi, q15_t vbus, q15_t vbus_target)
{
    return ripple_apply(v_pi, ripple_gain(vbus, vbus_target));
}

dq_q15_t ripple_compensate_dq(dq_q15_t v_pi, q15_t vbus, q15_t vbus_target)
{
    uint16_t g = ripple_gain(vbus, vbus_target);
    dq_q15_t v;
    v.d = ripple_apply(v_pi.d, g);
    v.q = ripple_apply(v_pi.q, g);
    return v;
}

/*
 * Notes
 *
 * 1. Ranges. Target 2^15 + DCbus / 2 < 2^30 fits 32 bits; the rounded
 *    quotient is below 2^16 iff that numerator is below DCbus 2^16, i.e.
 *    Target / DCbus < 2 - 2^-16 (about): the test is exact, so div.ud
 *    never overflows. Vpi G: |Vpi| <= 2^15, G < 2^16, |product| < 2^31.
 *
 * 2. Cost on the dsPIC: one div.ud (18 cycles) per period for both
 *    components, one mul.su and a rounding per component.
 */
