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

/* G = Target / DCbus, unsigned Q15 (32768 = 1), once per period. */
uint16_t ripple_gain(q15_t vbus, q15_t vbus_target);

/* V = Vpi G, rounded, saturated. */
q15_t ripple_apply(q15_t v_pi, uint16_t gain);

/* One component: ripple_apply(v_pi, ripple_gain(vbus, vbus_target)). */
q15_t ripple_compensate(q15_t v_pi, q15_t vbus, q15_t vbus_target);

/* Both components with one gain (AN1078 applies it to Vd and Vq alike). */
dq_q15_t ripple_compensate_dq(dq_q15_t v_pi, q15_t vbus, q15_t vbus_target);

#endif /* RIPPLE_H */
