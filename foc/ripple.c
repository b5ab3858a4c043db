/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* ripple.c - DC-bus ripple compensation of Vd and Vq (AN1078 Equation 8). */
#include "ripple.h"

q15_t ripple_compensate(q15_t v_pi, q15_t vbus, q15_t vbus_target)
{
    return ripple_apply(v_pi, ripple_gain(vbus, vbus_target));
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
