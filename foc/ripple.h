/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* ripple.h - DC-bus ripple compensation of Vd and Vq (AN1078 Equation 8). */
#ifndef RIPPLE_H
#define RIPPLE_H

#include "frames.h"

/*
 * AN1078 Equation 8, with DCbus the measured and Target the required bus
 * voltage and Vpi a PI output (Vd or Vq):
 *   Target > DCbus:  V = Vpi + (Target - DCbus) / DCbus * Vpi
 *   DCbus > Target:  V = Target / DCbus * Vpi
 * Both branches are the same quantity, V = Vpi * Target / DCbus (and
 * V = Vpi when they are equal); the note splits them only so that its Q15
 * ratio stays below 1. Here the gain G = Target / DCbus is formed once per
 * period by one 32 / 16 division (ripple_gain) and each component is one
 * product (ripple_apply), so Vd and Vq cost one division together.
 *
 * Scaling and overflow: v_pi Q15 of the SVGen full scale; vbus and
 * vbus_target Q15 of BOARD_VBUS_FULLSCALE_V (0..32767). G is an unsigned
 * Q15 in 0..65535 (0 .. 2 - 2^-15), rounded to nearest; V = Vpi G rounded
 * to nearest (ties up), saturated to [-32768, 32767].
 * Range: the compensation boosts at most by 2 - 2^-15, i.e. it follows the
 * bus down to half the target (far below any undervoltage trip); below
 * that, and for vbus <= 0, G stays at its top. vbus_target <= 0 switches it
 * off (G = 1 exactly, V = Vpi).
 * Accuracy: |V - Equation 8 (saturated)| <= 1 LSB where DCbus > Target / 2
 * (G's rounding moves V by at most |Vpi| 2^-16 < 0.5 LSB, the product's
 * rounding 0.5 more); test/foc/test_ripple.c prints the measured figure.
 * Equation 8's own input, a 10-bit bus reading, is 32 LSB coarse.
 */

#define RIPPLE_ONE      32768U /* G = 1 */
#define RIPPLE_GAIN_MAX 65535U

/* G = Target / DCbus, unsigned Q15 (32768 = 1), once per period (ripple.c notes). */
Q15_INLINE uint16_t ripple_gain(q15_t vbus, q15_t vbus_target)
{
    uint32_t num;
    if (vbus_target <= 0) {
        return RIPPLE_ONE; /* compensation off */
    }
    if (vbus <= 0) {
        return RIPPLE_GAIN_MAX;
    }
    /* G = round(Target 2^15 / DCbus): the quotient fits div.ud's 16 bits
     * exactly when the numerator is below DCbus 2^16 (ripple.c note 1). */
    num = ((uint32_t)(uint16_t)vbus_target << 15) + (uint32_t)((uint16_t)vbus >> 1);
    if (num >= ((uint32_t)(uint16_t)vbus << 16)) {
        return RIPPLE_GAIN_MAX;
    }
    return q15_dsp_divud(num, (uint16_t)vbus);
}

/* V = Vpi G, rounded, saturated. */
Q15_INLINE q15_t ripple_apply(q15_t v_pi, uint16_t gain)
{
    /* |Vpi G| < 2^31: one signed x unsigned 16 x 16 product, rounded and
     * saturated in the accumulator. */
    return q15_dsp_mulsu_r(v_pi, gain);
}

/* One component: ripple_apply(v_pi, ripple_gain(vbus, vbus_target)). */
q15_t ripple_compensate(q15_t v_pi, q15_t vbus, q15_t vbus_target);

/* Both components with one gain (AN1078 applies it to Vd and Vq alike). */
Q15_INLINE dq_q15_t ripple_compensate_dq(dq_q15_t v_pi, q15_t vbus, q15_t vbus_target)
{
    uint16_t g = ripple_gain(vbus, vbus_target);
    dq_q15_t v;
    v.d = ripple_apply(v_pi.d, g);
    v.q = ripple_apply(v_pi.q, g);
    return v;
}

#endif /* RIPPLE_H */
