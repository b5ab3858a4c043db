/* vlimit.c - voltage-circle limit: the Vq bound left once Vd is applied. */
#include "vlimit.h"

#include "q15_sqrt.h"

q15_t vlimit_vq_max(q15_t vd, q15_t vmax)
{
    if (vmax <= 0) {
        return 0;
    }
    q15_t d = q15_clamp(vd, (q15_t)(-vmax), vmax);
    /* Vmax^2 - Vd^2 in Q30, exact, 0..(2^15 - 1)^2; its integer square root
     * is Q15 and <= vmax (note 1). */
    int32_t n = q15_dsp_mulss(vmax, vmax) - q15_dsp_mulss(d, d);
    return (q15_t)q15_isqrt_u32((uint32_t)n);
}

/*
 * Notes
 *
 * 1. sqrt(n / 2^30) * 2^15 = sqrt(n): no rescaling, one rounding, so the
 *    error is <= 0.5 LSB (test_vlimit.c prints the measured figure). With
 *    |d| <= vmax, n <= vmax^2 and round(sqrt(n)) <= vmax: the limit never
 *    exceeds Vmax, and at d = 0 it is Vmax exactly.
 */
