/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* smc.c - sliding-mode observer: rotor angle and speed from alpha/beta currents and voltages.
 * "note N" is docs/estimator.md, "Derivation", note N. */
#include "smc.h"

#include "atan2.h"

/* Fixed design constants of the speed path (notes 7-8). */
#define SMC_LAG_DEADZONE      1024 /* settled: lag steps below 5.6 deg per window are noise */
#define SMC_LAG_TRANSIENT     5461 /* a lag step above 30 deg starts a tracking phase */
#define SMC_STARTUP_WINDOWS   32U  /* tracking phase after reset, preset or a transient */
#define SMC_K_LPF_SHIFT       2U   /* settled: K follows the speed 4 times slower */
#define SMC_K_LPF_SHIFT_START 1U   /* tracking: 2 times slower */
#define SMC_EMF_RAW_K_SHIFT   2    /* the model back-EMF is smoothed with 4 K */

/*
 * Slow side, once per window (smc_slow_step, note 10): the lag
 * correction (one atan2), the speed scaling (note 7), K, the compensation
 * from the transfer functions (notes 3-4: two atan2 calls, seven 32 x 16
 * and a dozen 16 x 16 products), the back-EMF amplitude and one 32 / 16 division for
 * the consistency figure.
 */

/* a * b / 2^15 rounded (ties up), for |a| < 2^30: a = hi 2^15 + lo with
 * lo in 0..32767, so both partial products are 16 x 16. The result keeps
 * a's Q format. */
static int32_t smc_mul_q15(int32_t a, q15_t b)
{
    int16_t hi = (int16_t)(a >> 15);
    int16_t lo = (int16_t)(uint16_t)((uint32_t)a & 0x7FFFUL);
    return q15_dsp_mulss(hi, b) + ((q15_dsp_mulss(lo, b) + (int32_t)0x4000) >> 15);
}

/* x * 2^n for a 32-bit value known to fit after the shift (done unsigned). */
static int32_t smc_shl32(int32_t x, uint8_t n)
{
    return (int32_t)((uint32_t)x << n);
}

/*
 * Sum of angle steps -> Q15 speed: |sum| * kspeed * 2^kspeed_shift / 2^15,
 * rounded, saturated at 32767, sign restored. |sum| = mh 2^15 + ml with
 * mh <= 2^8, so mh kspeed 2^shift is compared against 2^15 before it is
 * formed, and ml kspeed < 2^30 is shifted right by 15 - shift (>= 0).
 */
q15_t smc_speed_from_steps(const smc_params_t *p, int32_t sum)
{
    uint32_t mag = (sum < 0) ? ((uint32_t)0U - (uint32_t)sum) : (uint32_t)sum;
    uint32_t mh = mag >> 15;
    uint32_t ml = mag & 0x7FFFUL;
    uint32_t k = (uint32_t)(uint16_t)p->kspeed;
    uint8_t r = (uint8_t)(15U - p->kspeed_shift);
    uint32_t hi = mh * k; /* < 2^24 */
    uint32_t lo = ml * k; /* < 2^30 */
    uint32_t res;
    if (hi >= (0x8000UL >> p->kspeed_shift)) {
        res = 0x7FFFUL;
    } else {
        res = (hi << p->kspeed_shift) + ((r > 0U) ? ((lo + ((uint32_t)1U << (r - 1U))) >> r) : lo);
        if (res > 0x7FFFUL) {
            res = 0x7FFFUL;
        }
    }
    return (sum < 0) ? (q15_t)(-(int16_t)res) : (q15_t)res;
}

/* A Q30 value in 0 .. 32767.5 * 2^15 to Q15, rounded (no saturation: x^2,
 * sin x and 1 - cos x of a Q15 x stay below it). */
static q15_t smc_round_q15(int32_t v)
{
    return (q15_t)((v + (int32_t)0x4000) >> 15);
}

/* atan2_q31 once in this file: the slow side's three arctangents share one
 * copy (its body is some hundred words; a call costs a few cycles). */
static angle_q15_t smc_atan2(int32_t y, int32_t x)
{
    return atan2_q31(y, x);
}

/*
 * The phase lead (angle counts, >= 0 for the forward direction) that
 * cancels the lag of the two stages and the loop delay at the frequency x
 * (rad per period, Q15) with coefficient k (Q15): notes 3 and 4.
 *   u = 1 - exp(-j x) = (1 - cos x) + j sin x
 *   D2 = K + (1 - K) u                       (second stage)
 *   D1 = K mdc + B1 u + B2 u^2               (first stage, in the loop)
 *   comp = arg D1 + arg D2 + xadv x
 * The angles need u to a relative precision (at a low speed K and u are
 * both small, and the arctangent reads their ratio), so each power of x is
 * its exact 16 x 16 product with x plus a correction that is a few per
 * cent of it, formed from rounded Q15 copies: sin x = x (1 + cm1) and
 * 1 - cos x = x^2 / 2 (1 + dm1), cm1 = -x^2/6 + x^4/120 and dm1 = -x^2/12 +
 * x^4/360 (the next terms are below 2e-4 of them at x = 1 rad). u, u^2 and
 * D2 are Q30 (|u| < 1 for x <= 1 rad), D1 Q27 (|B1| < 8, mdc < 4, |B2| < 1:
 * every sum below 16). Seven 32 x 16 products where a 32-bit term meets a
 * coefficient; the rest are 16 x 16.
 */
angle_q15_t smc_phase_lead(const smc_params_t *p, q15_t k, q15_t x)
{
    int32_t xx = q15_dsp_mulss(x, x); /* x^2, Q30 exact */
    q15_t x2 = smc_round_q15(xx);
    q15_t x4 = q15_mul(x2, x2);
    q15_t cm1 = (q15_t)(q15_mul(x4, Q15(1.0 / 120.0)) - q15_mul(x2, Q15(1.0 / 6.0)));
    q15_t dm1 = (q15_t)(q15_mul(x4, Q15(1.0 / 360.0)) - q15_mul(x2, Q15(1.0 / 12.0)));
    int32_t ui = smc_shl32((int32_t)x, 15U) + q15_dsp_mulss(x, cm1); /* sin x, Q30 */
    int32_t ur = (xx >> 1) + (q15_dsp_mulss(x2, dm1) >> 1);          /* 1 - cos x, Q30 */
    q15_t ui15 = smc_round_q15(ui);                                  /* Q15 copies */
    q15_t ur15 = smc_round_q15(ur);
    /* u^2 = (ur^2 - ui^2) + j 2 ur ui; ui^2 = x^2 (1 + cm1)^2 = x^2 + x^2 (2 cm1 + cm1^2) */
    int32_t ui2 = xx + q15_dsp_mulss(x2, (q15_t)(2 * cm1 + q15_mul(cm1, cm1)));
    int32_t u2r = q15_dsp_mulss(ur15, ur15) - ui2;
    int32_t u2i = smc_shl32(smc_mul_q15(ur, ui15), 1U);
    q15_t omk = (q15_t)(32768L - (int32_t)k);                 /* 1 - K; k >= 1 so <= 32767 */
    q15_t b1 = q15_add_sat(p->tf_b10, q15_mul(p->tf_b1k, k)); /* Q12 */
    q15_t b2 = q15_mul(p->tf_b2, omk);                        /* Q15 */
    int32_t re2 = smc_shl32((int32_t)k, 15U) + smc_mul_q15(ur, omk);
    int32_t im2 = smc_mul_q15(ui, omk);
    /* K mdc: Q15 x Q12 = Q27. B1 u: Q30 x Q12 / 2^15 = Q27. B2 u^2: Q30 -> Q27. */
    int32_t re1 = q15_dsp_mulss(k, p->tf_mdc) + smc_mul_q15(ur, b1) + (smc_mul_q15(u2r, b2) >> 3);
    int32_t im1 = smc_mul_q15(ui, b1) + (smc_mul_q15(u2i, b2) >> 3);
    angle_q15_t a1 = smc_atan2(im1, re1);
    angle_q15_t a2 = smc_atan2(im2, re2);
    angle_q15_t adv = q15_mul(x, p->tf_xadv);
    return angle_add(angle_add(a1, a2), adv);
}

/* |ef| by alpha-max-plus-beta-min (0.96043 max + 0.39782 min): within
 * +-4 % of the modulus, plenty for a 0.5 .. 2 consistency band (note 5). */
static q15_t smc_magnitude(q15_t a, q15_t b)
{
    q15_t ua = q15_abs_sat(a);
    q15_t ub = q15_abs_sat(b);
    q15_t mx = (ua > ub) ? ua : ub;
    q15_t mn = (ua > ub) ? ub : ua;
    return q15_add_sat(q15_mul(mx, Q15(0.96043387)), q15_mul(mn, Q15(0.39782473)));
}

/* Everything that follows the speed (slow side): K, the compensation, the
 * back-EMF figures and the validity flag, from sl->omega and the window's
 * e_final, into r. */
static void smc_refresh(const smc_params_t *p, smc_slow_t *sl, const smc_window_t *w,
                        smc_result_t *r)
{
    q15_t aw = q15_abs_sat(sl->omega);
    q15_t x = q15_mul(aw, p->k_per_omega);
    uint8_t ksh = (sl->startup > 0U) ? SMC_K_LPF_SHIFT_START : SMC_K_LPF_SHIFT;
    q15_t kx = lpf_update(&sl->k_lpf, x, (q15_t)(p->k_speed_lpf >> ksh));

    q15_t k = (kx > p->k_min) ? kx : p->k_min;
    angle_q15_t lead = smc_phase_lead(p, k, x);
    bool emf_ok = true;

    r->omega = sl->omega;
    r->k = k;
    r->k_w = q15_shl_sat(k, SMC_EMF_RAW_K_SHIFT);
    /* Reverse rotation: the stages' lag changes sign and atan2(-ef_a, ef_b)
     * points at the rotor plus pi (the back-EMF is reversed). */
    r->comp = (sl->omega < 0) ? angle_add(angle_sub(0, lead), Q15_MIN) : lead;

    r->emf_mag = smc_magnitude(q15_from_q31(w->ef_alpha), q15_from_q31(w->ef_beta));
    if (p->emf_gain > 0) {
        uint8_t sh = (uint8_t)(15U - p->emf_shift);
        int32_t expect = q15_dsp_mulss(p->emf_gain, aw);
        int32_t num = smc_shl32((int32_t)r->emf_mag, 12U);
        q15_t den;
        if (sh > 0U) {
            expect = (expect + (int32_t)(1L << (sh - 1U))) >> sh;
        }
        den = q15_sat(expect);
        if (den <= 0 || num >= (int32_t)den * 32767L) {
            r->emf_ratio = Q15_MAX;
        } else {
            r->emf_ratio = q15_dsp_divsd(num, den);
        }
        emf_ok = (r->emf_ratio >= SMC_EMF_RATIO_LO) && (r->emf_ratio <= SMC_EMF_RATIO_HI);
    } else {
        r->emf_ratio = SMC_EMF_RATIO_ONE;
    }
    r->valid = (aw >= p->omega_min) && emf_ok;
}

/* The slow side back to rest (speed 0) or to a preset speed. */
static void smc_slow_restart(const smc_params_t *p, smc_slow_t *sl, q15_t omega)
{
    lpf_reset(&sl->omega_lpf, omega);
    lpf_reset(&sl->k_lpf, q15_mul(q15_abs_sat(omega), p->k_per_omega));
    sl->omega = omega;
    sl->lag = 0;
    sl->lag_valid = false;
    sl->startup = SMC_STARTUP_WINDOWS;
}

/* The fast side takes a set of slow-side results: a window's (smc_apply)
 * or those at rest (speed 0, K at its floor, not valid; smc_reset). */
static void smc_take(smc_t *s, const smc_result_t *r)
{
    s->omega = r->omega;
    s->k = r->k;
    s->k_w = r->k_w;
    s->comp = r->comp;
    s->emf_mag = r->emf_mag;
    s->emf_ratio = r->emf_ratio;
    s->valid = r->valid;
}

void smc_init(smc_t *s, const smc_params_t *p)
{
    smc_window_t w;
    s->p = p;
    /* The raw back-EMF's coefficients (note 8): c = mdc - 1 + p in Q12 (mdc
     * Q12, p Q15) and -p, saturated. */
    s->raw_c = (q15_t)(p->tf_mdc - 4096 + (p->tf_b2 >> 3));
    s->raw_np = q15_neg_sat(p->tf_b2);
    /* The results at rest, once: smc_reset applies them without the cost
     * of a refresh (the slow side computes the same from a reset). */
    w.dtheta_sum = 0;
    w.w_alpha = 0;
    w.w_beta = 0;
    w.ef_alpha = 0;
    w.ef_beta = 0;
    w.theta_raw = 0;
    w.epoch = 0U;
    w.full = false;
    w.preset = false;
    w.preset_omega = 0;
    smc_slow_restart(p, &s->slow, 0);
    smc_refresh(p, &s->slow, &w, &s->rest);
    s->rest.valid = false;
    s->res = s->rest; /* nothing computed yet: the rest results */
    s->epoch = 0U;
    smc_reset(s);
    s->slow.epoch = s->epoch;
}

void smc_reset(smc_t *s)
{
    s->i_est.alpha = 0;
    s->i_est.beta = 0;
    s->z.alpha = 0;
    s->z.beta = 0;
    s->e.alpha = 0;
    s->e.beta = 0;
    lpf_reset(&s->e_alpha, 0);
    lpf_reset(&s->e_beta, 0);
    lpf_reset(&s->ef_alpha, 0);
    lpf_reset(&s->ef_beta, 0);
    lpf_reset(&s->w_alpha, 0);
    lpf_reset(&s->w_beta, 0);
    s->dtheta_sum = 0;
    s->count = 0U;
    s->theta_raw = 0;
    s->theta = 0;
    s->epoch = (uint8_t)(s->epoch + 1U);
    s->preset_pending = false;
    smc_take(s, &s->rest);
}

void smc_preset_speed(smc_t *s, q15_t omega)
{
    s->omega = omega;
    s->dtheta_sum = 0;
    s->count = 0U;
    s->epoch = (uint8_t)(s->epoch + 1U);
    s->preset_pending = true;
    s->preset_omega = omega;
}

void smc_apply(smc_t *s)
{
    /* The results of the last window, if they still belong to this run. */
    if (s->res.epoch == s->epoch) {
        smc_take(s, &s->res);
    }
}

void smc_slow_step(smc_t *s)
{
    const smc_params_t *p = s->p;
    const smc_window_t *w = &s->win;
    smc_slow_t *sl = &s->slow;
    int32_t sum = w->dtheta_sum;

    if (w->epoch != sl->epoch) {
        /* A reset or a preset since the last window. */
        smc_slow_restart(p, sl, w->preset ? w->preset_omega : 0);
        sl->epoch = w->epoch;
    }
    if (p->tf_xadv != 0) {
        /* The lag of theta_raw behind the (lightly filtered) model
         * back-EMF: its change over the window is what the stages'
         * transients added to the angle steps (note 8). */
        int32_t wa = w->w_alpha;
        angle_q15_t lag =
            angle_sub(smc_atan2((wa == Q31_MIN) ? Q31_MAX : -wa, w->w_beta), w->theta_raw);
        int32_t dl = sl->lag_valid ? (int32_t)angle_sub(lag, sl->lag) : 0;
        int32_t dz;
        if (dl > (int32_t)SMC_LAG_TRANSIENT || dl < -(int32_t)SMC_LAG_TRANSIENT) {
            sl->startup = SMC_STARTUP_WINDOWS; /* a transient: track it closely */
        }
        dz = (sl->startup > 0U) ? (int32_t)0 : (int32_t)SMC_LAG_DEADZONE;
        sl->lag_valid = true;
        if (dl > dz) {
            sum += dl - dz;
        } else if (dl < -dz) {
            sum += dl + dz;
        }
        sl->lag = lag;
    }
    if (w->full) {
        /* A window cut short by a reset or preset measures no speed. */
        sl->omega = lpf_update(&sl->omega_lpf, smc_speed_from_steps(p, sum), p->k_speed_lpf);
    }
    smc_refresh(p, sl, w, &s->res);
    s->res.epoch = w->epoch;
    if (sl->startup > 0U) {
        sl->startup--;
    }
}
