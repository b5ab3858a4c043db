/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* smc_update.h - the observer's per-period step, inline: it runs once per PWM period inside
 * mc_step. */
#ifndef SMC_UPDATE_H
#define SMC_UPDATE_H

/* Included by smc.h only (its declarations come first). "note N" is
 * docs/estimator.md, "Derivation", note N. */
#include "atan2.h"

/*
 * Arithmetic of smc_update, per axis (inline here, not in smc.c, so the
 * compiler folds it into mc_step: no call, no second register save):
 *
 *  model   u = sat16(v/2 - e - z) (E_FS = 2 V_FS); i_est = F i + G_mant u
 *          2^g_shift in the accumulator (q15_dsp_mac_shl_r: the second
 *          product shifted in the unsaturated B, |G_mant u 2^g_shift| <=
 *          2^37), saturated at Q31, rounded once (ties up) to Q15.
 *          Saturating u at full scale only acts far outside the sliding
 *          band (|v - e - z| > E_FS = 2 V_FS), where the correction is at
 *          +-Kslide anyway.
 *  switch  err = i_est - i_meas (saturated to 16 bits); outside the band +-Kslide;
 *          inside, Kz_mant err 2^kz_shift rounded to Q15, clamped to
 *          +-Kslide (rounding could step one LSB past it).
 *  stages  foc/lpf.h (32-bit states).
 *  angle   atan2_q31 of the Q31 e_final components (foc/atan2.h): the
 *          angle keeps its resolution at any back-EMF amplitude.
 *  speed   angle steps (angle_sub, in [-pi, pi)) summed in int32: the
 *          window of at most 256 periods sums to at most 2^23.
 * One division (atan2's) and no multiply wider than 16 x 16 in this path.
 */

/* One axis of the digitised model: F i + G (v - e - z), rounded, saturated. */
Q15_INLINE q15_t smc_model(const smc_params_t *p, q15_t i, q15_t v, q15_t e, q15_t z)
{
    /* v is Q15 of V_FS, e and z Q15 of E_FS = 2 V_FS: u = v / 2 - e - z,
     * rounded (the half of an odd v rounds up), saturated. */
    q15_t u = q15_dsp_half_sub2_r(v, e, z);
    /* F i + G u with G = g 2^g_shift, one rounding (both products formed in
     * the accumulator, the second shifted in B). */
    return q15_dsp_mac_shl_r(p->f, i, p->g, u, p->g_shift);
}

/* The switching function: Kslide * sat(err / MaxSMCError); err saturated to
 * 16 bits (any |err| >= max_err <= 32767 is outside the band alike). */
Q15_INLINE q15_t smc_switch(const smc_params_t *p, q15_t err)
{
    q15_t z;
    if (err >= p->max_err) {
        return p->kslide;
    }
    if (err <= (q15_t)(-p->max_err)) {
        return (q15_t)(-p->kslide);
    }
    /* Inside the band |Kz err| < Kslide, so Kz 2^kz_shift err stays below
     * 2^31 in B. Rounding can step one LSB past Kslide: clamped. */
    z = q15_dsp_mac_shl_r(0, 0, p->kz, err, p->kz_shift);
    return q15_clamp(z, (q15_t)(-p->kslide), p->kslide);
}

/*
 * The model back-EMF, unfiltered (note 8). In the linear band
 * z(n) = c (E(n-1) - e(n-1)) + p z(n-1) exactly, so
 * c E(n-1) = z(n) - p z(n-1) + c e(n-1): a back-EMF whose angle does not
 * depend on K. Q15 of E_FS times c (> 0: the angle is what matters),
 * saturated. c is Q12 (smc_update forms it once for both axes).
 */
Q15_INLINE q15_t smc_emf_raw(const smc_t *s, q15_t z, q15_t z_prev, q15_t e_prev)
{
    /* z - p z_prev + c e_prev (c Q12: the product shifted 3 more), one
     * rounding, saturated. */
    return q15_dsp_lac_mac_shl_r(z, s->raw_np, z_prev, s->raw_c, e_prev, 3U);
}

Q15_INLINE void smc_update(smc_t *s, ab_q15_t i_meas, ab_q15_t v_applied)
{
    const smc_params_t *p = s->p;
    angle_q15_t prev = s->theta_raw;
    ab_q15_t z_prev = s->z;
    ab_q15_t e_prev = s->e;

    /* Model, error and correction (z and e from the previous period feed the
     * model step that brings i_est to this sample). */
    s->i_est.alpha = smc_model(p, s->i_est.alpha, v_applied.alpha, s->e.alpha, s->z.alpha);
    s->i_est.beta = smc_model(p, s->i_est.beta, v_applied.beta, s->e.beta, s->z.beta);
    s->z.alpha = smc_switch(p, q15_sub_sat(s->i_est.alpha, i_meas.alpha));
    s->z.beta = smc_switch(p, q15_sub_sat(s->i_est.beta, i_meas.beta));

    /* The two stages (q15_dsp_lpf is lpf_update without its k <= 0 guard:
     * k >= k_min >= 1 here). */
    s->e.alpha = q15_dsp_lpf(&s->e_alpha.state, s->z.alpha, s->k);
    s->e.beta = q15_dsp_lpf(&s->e_beta.state, s->z.beta, s->k);
    (void)q15_dsp_lpf(&s->ef_alpha.state, s->e.alpha, s->k);
    (void)q15_dsp_lpf(&s->ef_beta.state, s->e.beta, s->k);

    if (p->tf_xadv != 0) {
        (void)q15_dsp_lpf(&s->w_alpha.state, smc_emf_raw(s, s->z.alpha, z_prev.alpha, e_prev.alpha),
                          s->k_w);
        (void)q15_dsp_lpf(&s->w_beta.state, smc_emf_raw(s, s->z.beta, z_prev.beta, e_prev.beta),
                          s->k_w);
    }

    /* theta_raw = atan2(-ef_alpha, ef_beta): the back-EMF turned back by
     * 90 degrees points at the rotor flux. Formed as -atan2(ef_alpha,
     * ef_beta), the same binary angle (atan2_q31 is odd in y, and -(-pi)
     * wraps onto -pi), without negating a 32-bit state. */
    s->theta_raw = angle_neg(atan2_q31(s->ef_alpha.state, s->ef_beta.state));

    /* Speed window: the sum of the angle steps; the window end is the
     * caller's (smc_window_end). */
    s->dtheta_sum += (int32_t)angle_sub(s->theta_raw, prev);
    if (s->count < 0xFFFFU) {
        s->count++;
    }

    s->theta = angle_add(s->theta_raw, s->comp);
}

Q15_INLINE void smc_window_end(smc_t *s)
{
    smc_window_t *w = &s->win;
    w->dtheta_sum = s->dtheta_sum;
    w->w_alpha = s->w_alpha.state;
    w->w_beta = s->w_beta.state;
    w->ef_alpha = s->ef_alpha.state;
    w->ef_beta = s->ef_beta.state;
    w->theta_raw = s->theta_raw;
    w->epoch = s->epoch;
    w->full = (s->count == s->p->irp_percalc);
    w->preset = s->preset_pending;
    w->preset_omega = s->preset_omega;
    s->preset_pending = false;
    s->dtheta_sum = 0;
    s->count = 0U;
}

#endif /* SMC_UPDATE_H */
