/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* mc_id_units.c - the identification's results in engineering units, for the main loop. */
#include <string.h>

#include "mc_parts.h"

#if MC_IDENTIFY
/* The identification's results in engineering units (mc_id.c note 1): each
 * a ratio of the sequence's sums times one constant, rounded once here. */
#define MC_ID_Z_FS_ (MC_VOLTAGE_FULLSCALE_V / BOARD_I_FULLSCALE_A) /* ohm */
/* R = dv / di Z_FS: micro-ohms */
#define MC_ID_K_R ((int64_t)(MC_ID_Z_FS_ * 1e6 + 0.5))
/* L = (zu - R zm / 2) / zi Ts Z_FS: nanohenries */
#define MC_ID_K_L ((int64_t)(MC_ID_Z_FS_ * MC_TS_S * 1e9 + 0.5))
/* Td = sqrt(3)/2 v0 / vbus (V_FS / VBUS_FS) Ts: ns (v0, vbus in Q15) */
#define MC_ID_K_DT                                                                                 \
    ((int64_t)(0.8660254037844386 * MC_VOLTAGE_FULLSCALE_V / BOARD_VBUS_FULLSCALE_V * MC_TS_S *    \
                   1e9 +                                                                           \
               0.5))
/* Ke = sqrt(3) E_phase / rpm: E = m / 2^19 V_FS, rpm = x 60 / (2^32 Ts p): microvolts per rpm */
#define MC_ID_K_KE                                                                                 \
    ((int64_t)(1.7320508075688772 * MC_VOLTAGE_FULLSCALE_V * 1e6 * MC_TS_S * MOTOR_POLE_PAIRS *    \
                   8192.0 / 60.0 +                                                                 \
               0.5))
/* J = 3/4 p^2 psi di / alpha_e, psi = m / 2^19 V_FS / (x 2 pi / (2^32 Ts)),
 * di = t / 32768 I_FS, alpha_e = accel 2 pi / (2^32 Ts^2): 1e-9 kg m^2 */
#define MC_ID_K_J                                                                                  \
    ((int64_t)(0.75 * MOTOR_POLE_PAIRS * MOTOR_POLE_PAIRS * MC_VOLTAGE_FULLSCALE_V *               \
                   BOARD_I_FULLSCALE_A * MC_TS_S * MC_TS_S * MC_TS_S * 35184372088832.0 /          \
                   (39.47841760435743 * 32768.0) * 1e9 +                                           \
               0.5))

/* The rotor's vibration under the q injection (mc_identify_result), Q16:
 * 1.5 (60 / (sqrt(3) 2 pi 1e6))^2 Ts^2 / pi^2 x 1e18 (nH ng m^2 per (uV/rpm)^2) */
#define MC_ID_K_VIB                                                                                \
    ((int64_t)(1.5 * 60.0 * 60.0 / (3.0 * 39.47841760435743 * 1e12) * MC_TS_S * MC_TS_S /          \
                   9.869604401089358 * 1e18 * 65536.0 +                                            \
               0.5))

static uint32_t mc_id_u32(int64_t v)
{
    return (v <= 0) ? (uint32_t)0 : (v > (int64_t)UINT32_MAX) ? (uint32_t)UINT32_MAX : (uint32_t)v;
}

/* L of one axis (0 d, 1 q), nH, from the exact discrete model of the RL
 * circuit under the injection (mc_id.c note 2). Between two samples the
 * current decays by alpha = exp(-h), h = Ts R / L, towards u / R, the
 * voltage u_o of the period before acting for the first 1 - a of the
 * interval and u_n for the last a (a = MC_SAMPLE_AT):
 *   i_n = alpha i_n-1 + (g_o u_o + g_n u_n) / R,
 *   g_n = 1 - exp(-a h), g_o = (1 - exp(-(1 - a) h)) exp(-a h).
 * Correlated with the two instruments z and w (a quarter cycle apart) and
 * the voltages weighted g_o : g_n, that is two linear equations in alpha
 * and beta = (g_o + g_n) / R; the weights depend on h, so the solve is
 * repeated from the difference quotient's weights (a, 1 - a), four times.
 * L = Ts (g_o + g_n) / (beta h). The R found this way is the axis's own at
 * the injection's frequency, the apparent resistance of a phase current
 * inside the dead-time band included; the model holds where L / R is a
 * period or less, where a difference quotient does not. */
static uint32_t mc_id_inductance(const mc_id_t *id, uint8_t ax)
{
    int64_t c[8], big = 1;
    int64_t wn = MC_VEST_W_NEW, wo = MC_VEST_W_OLD; /* Q15 weights of u_n, u_o */
    uint32_t l = 0U;
    uint8_t k, sh = 0, it;
    for (k = 0; k < 8U; k++) {
        c[k] = id->l_c[ax][k];
        big = (c[k] > big) ? c[k] : (-c[k] > big) ? -c[k] : big;
    }
    while ((big >> sh) >= ((int64_t)1 << 20)) { /* products below 2^40 */
        sh++;
    }
    for (k = 0; k < 8U; k++) {
        c[k] >>= sh;
    }
    for (it = 0; it < 4U; it++) {
        /* the weighted voltage's correlations, then [c0; c4] = [c1 u1; c5 u2] [alpha; beta] */
        int64_t u1 = (wn * c[2] + wo * c[3]) >> 15, u2 = (wn * c[6] + wo * c[7]) >> 15;
        int64_t det = c[1] * u2 - c[5] * u1;
        int64_t an = c[0] * u2 - c[4] * u1;     /* alpha det */
        int64_t bn = c[1] * c[4] - c[5] * c[0]; /* beta det */
        uint32_t en, eo;
        if (det < 0) {
            det = -det;
            an = -an;
            bn = -bn;
        }
        if (an <= 0 || an >= det || bn <= 0) {
            return 0U; /* not a decay (0 < alpha < 1, beta > 0): no inductance */
        }
        /* alpha in Q22 (an < 2^41): below 2^63 shifted */
        uint32_t nl = mc_id_neg_ln_q24((uint32_t)((an * ((int64_t)1 << 22) / det) << 8));
        if (nl == 0U) {
            return 0U;
        }
        /* the weights at this h: g_n = 1 - e^(-a h), g_o = (1 - e^(-(1-a) h)) e^(-a h),
         * normalized to a sum of 2^15 */
        en = mc_id_exp_neg_q30((uint32_t)(((int64_t)nl * MC_VEST_W_NEW) >> 15));
        eo = mc_id_exp_neg_q30((uint32_t)(((int64_t)nl * MC_VEST_W_OLD) >> 15));
        {
            int64_t gn = ((int64_t)1 << 30) - en;
            int64_t go = ((((int64_t)1 << 30) - eo) * en) >> 30;
            int64_t gs = gn + go;
            wn = gn * 32768 / gs;
            wo = 32768 - wn;
            /* L / (Ts Z_FS) = (g_o + g_n) / (beta h) = gs det / (bn h), h = nl 2^-24 */
            l = mc_id_u32(((det * ((int64_t)1 << 24) / bn) * (gs >> 10) >> 20) * MC_ID_K_L / nl);
        }
    }
    return l;
}

void mc_identify_result(const mc_t *mc, mc_id_result_t *r)
{
    const mc_id_t *id = &mc->id;
    memset(r, 0, sizeof *r);
    r->status = (mc_id_status_t)mc->id_status;
    r->error = mc->id_error;
    r->pole_pairs = (uint8_t)MOTOR_POLE_PAIRS;
    if (r->status != MC_ID_DONE || id->di <= 0) {
        return;
    }
    r->rs_uohm = mc_id_u32((int64_t)id->dv * MC_ID_K_R / id->di);
    r->ld_nh = mc_id_inductance(id, 0U);
    r->lq_nh = mc_id_inductance(id, 1U);
    /* where L / R is hundreds of periods the decay per period is too
     * close to 1 for the exact model's solve, and the difference quotient
     * (the sequence's own) is as good as exact */
    if (r->ld_nh == 0U) {
        r->ld_nh = mc_id_u32((int64_t)id->l_dq[0] * MC_ID_K_L / 4096);
    }
    if (r->lq_nh == 0U) {
        r->lq_nh = mc_id_u32((int64_t)id->l_dq[1] * MC_ID_K_L / 4096);
    }
    /* LQ's rotor stood at phi = atan(i_q / i_d) to its d axis: the q
     * injection saw Lq cos^2 phi + Ld sin^2 phi (mc_id.c note 2) */
    {
        int64_t d2 = (int64_t)(id->lq_i[0] / 256) * (id->lq_i[0] / 256);
        int64_t q2 = (int64_t)(id->lq_i[1] / 256) * (id->lq_i[1] / 256);
        if (d2 > 0) {
            r->lq_nh = mc_id_u32((((int64_t)r->lq_nh * (d2 + q2)) - (int64_t)r->ld_nh * q2) / d2);
        }
    }
    if (id->vbus > 0 && id->nwin > 0) {
        uint32_t dt = mc_id_u32((int64_t)id->v0 * MC_ID_K_DT /
                                ((int64_t)id->nwin * MC_SLOW_STEP_PERIODS * id->vbus));
        r->deadtime_ns = (uint16_t)((dt > 65535U) ? 65535U : dt);
    }
    if (id->x2 > id->x1) {
        int64_t dm = (int64_t)id->m2 - id->m1, dx = (int64_t)id->x2 - (int64_t)id->x1;
        r->ke_uv_per_rpm = mc_id_u32(dm * MC_ID_K_KE / dx);
        /* the slope of the torque current against the acceleration, Q16 (a
         * least-squares line: its intercept, friction, drops out) */
        int64_t den = (int64_t)id->j_n * id->j_aa - (int64_t)id->j_a * id->j_a;
        if (den > 0) {
            int64_t k = ((int64_t)id->j_n * id->j_ia - (int64_t)id->j_i * id->j_a) * 65536 / den;
            int64_t a = dm * MC_ID_K_J / dx;
            /* up minus down at the spin's acceleration: 2 ID_A_UNIT k */
            r->j_ng_m2 = mc_id_u32(a * 64 * k / ((int64_t)id->p->accel * 65536));
        }
    }
    /* The q injection's torque shakes the rotor: its back-EMF, in
     * antiphase, took 1.5 p^2 psi^2 / (w^2 J) off Lq (mc_id.c note 2),
     * w = pi / (half Ts) the injection's; with psi from Ke:
     * 1.5 (60 / (sqrt(3) 2 pi 1e6))^2 (half Ts / pi)^2 / J: nH from uV/rpm,
     * ng m^2 (p cancels) */
    if (r->j_ng_m2 > 0U) {
        int64_t ke = r->ke_uv_per_rpm, half = id->lq_half;
        r->lq_nh = mc_id_u32((int64_t)r->lq_nh +
                             ke * ke * half * half * MC_ID_K_VIB / ((int64_t)r->j_ng_m2 * 65536));
    }
    r->ls_nh = (uint32_t)(((uint64_t)r->ld_nh + r->lq_nh + 1U) / 2U);
}
#else
void mc_identify_result(const mc_t *mc, mc_id_result_t *r)
{
    memset(r, 0, sizeof *r);
    r->status = (mc_id_status_t)mc->id_status;
    r->error = mc->id_error;
    r->pole_pairs = (uint8_t)MOTOR_POLE_PAIRS;
}
#endif /* MC_IDENTIFY */
