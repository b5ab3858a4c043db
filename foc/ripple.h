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
 * ratio stays below 1. Here the product Vpi * Target is formed exactly in
 * 32 bits and divided once by DCbus (q15_dsp_divsd), which gives V
 * correctly rounded in both branches with no Q15 ratio to overflow.
 *
 * Scaling and overflow: v_pi Q15 of the SVGen full scale; vbus and
 * vbus_target Q15 of BOARD_VBUS_FULLSCALE_V (0..32767). The quotient is
 * range-checked before the division (|Vpi * Target| against 32768 * DCbus,
 * in 32 bits), so divsd never overflows; out-of-range results saturate to
 * [-32768, 32767]. Rounding: nearest, ties up (q15.h).
 * Guards (defined behaviour, never a division by zero):
 *   vbus_target <= 0:  compensation off, V = Vpi.
 *   vbus <= 0:         the limit DCbus -> 0+: V = +32767 for Vpi > 0,
 *                      -32768 for Vpi < 0, 0 for Vpi = 0 (saturated; the
 *                      caller's voltage limit and SVGen clamp follow).
 *   small vbus:        V saturates as soon as |Vpi| Target / DCbus >= 1.
 * Accuracy: |V - Equation 8 (saturated)| <= 0.5 LSB: the correctly rounded
 * value. Measured 0.5000 LSB max (exact ties), 0.16 mean, over 6.9 million
 * DCbus x Target x Vpi grid points, 32 % of them saturated
 * (test/foc/test_ripple.c).
 */

/* One component. */
q15_t ripple_compensate(q15_t v_pi, q15_t vbus, q15_t vbus_target);

/* Both components (AN1078 applies it to Vd and Vq alike). */
dq_q15_t ripple_compensate_dq(dq_q15_t v_pi, q15_t vbus, q15_t vbus_target);

#endif /* RIPPLE_H */
