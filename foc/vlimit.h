/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* vlimit.h - voltage-circle limit: the Vq bound left once Vd is applied. */
#ifndef VLIMIT_H
#define VLIMIT_H

#include "frames.h"
#include "q15_sqrt.h"

/*
 * AN1078 limits Vd first (to +-Vmax, e.g. 0.95 of the SVGen full scale) and
 * gives Vq what is left of the voltage circle:
 *   vq_max = sqrt(Vmax^2 - Vd^2)
 * so |(Vd, Vq)| <= Vmax. AN1078's use, every period:
 *   pi_set_limits(&pi_q, -vq_max, vq_max) with vq_max = vlimit_vq_max(vd, vmax)
 * (the core pays it only near the circle: firmware/mc.c note 3).
 *
 * vlimit_vq_max(vd, vmax): vmax Q15 (<= 0 gives 0); vd Q15, clamped to
 * [-vmax, vmax] first, so vd = -32768 is harmless. Returns Q15 in 0..vmax.
 * Scaling and overflow: Vmax^2 - Vd^2 is formed exactly in 32 bits (Q30,
 * 0..(2^15 - 1)^2) and its rounded integer square root is already Q15
 * (q15_isqrt_u32), so there is a single rounding. Error <= 0.5 LSB
 * (test/foc/test_vlimit.c, 136 Vmax x 21,846 Vd; it prints the measured
 * figures).
 */
Q15_INLINE q15_t vlimit_vq_max(q15_t vd, q15_t vmax)
{
    if (vmax <= 0) {
        return 0;
    }
    q15_t d = q15_clamp(vd, (q15_t)(-vmax), vmax);
    /* Vmax^2 - Vd^2 in Q30, exact, 0..(2^15 - 1)^2; its integer square root
     * is Q15 and <= vmax (vlimit.c note 1). */
    int32_t n = q15_dsp_mulss(vmax, vmax) - q15_dsp_mulss(d, d);
    return (q15_t)q15_isqrt_u32((uint32_t)n);
}

#endif /* VLIMIT_H */
