/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* mc_id_isr.c - the identification's interrupt side: its commands into the loops, its sums. */
#include <string.h>

#include "mc_parts.h"

#if MC_IDENTIFY

static const mc_id_params_t mc_id_params = MC_ID_PARAMS_INIT;

/* The sequence's command (mc_id_cmd_t) into the interrupt's loops: at
 * IDENTIFY's entry and MC_SLOW_APPLY_PERIODS after each window end. An open
 * loop sets the PIs' integrals to the voltage (and the injection's present
 * half); the first closed-loop command keeps them (a bumpless hand-over). */
void mc_id_apply(mc_t *mc, const mc_id_cmd_t *c)
{
    pi_t *pis[2];
    uint8_t k;
    pis[0] = &mc->pi_d;
    pis[1] = &mc->pi_q;
    for (k = 0; k < 2U; k++) {
        pis[k]->p.kp = c->kp;
        pis[k]->p.kp_shift = c->kp_shift;
        pis[k]->p.ki = c->ki;
        pis[k]->p.kc = c->ki;
    }
    if (c->open_loop) {
        q15_t inj = (c->inj != 0 && mc->id_isr.sign < 0) ? (q15_t)(-c->inj) : c->inj;
        mc->pi_d.sum = (q31_t)(c->v_d + ((c->inj_q == 0U) ? inj : 0)) * 65536L;
        mc->pi_q.sum = (q31_t)(c->v_q + ((c->inj_q != 0U) ? inj : 0)) * 65536L;
    } else if (mc->id_isr.open) {
        mc->pi_d.sum = (q31_t)c->v_d * 65536L;
        mc->pi_q.sum = 0;
    }
    mc->id_isr.open = c->open_loop;
    if (c->inj_q != mc->id_isr.inj_q || c->inj_half != mc->id_isr.half) {
        mc->id_isr.cnt = 0U;
    }
    mc->id_isr.inj = c->inj;
    mc->id_isr.inj_q = c->inj_q;
    mc->id_isr.half = c->inj_half;
    mc->i_ref = c->i_ref;
    mc->id_isr.inc = (uint32_t)c->accel;
    if (c->dt_counts != mc->dt_counts || c->dt_band != mc->id_isr.dt_band) {
        /* the command's band is above its dead time: the slope below 2^15 */
        mc->dt_counts = c->dt_counts;
        mc->id_isr.dt_band = c->dt_band;
        mc->dt_slope = mc_deadtime_slope(c->dt_counts, c->dt_band);
    }
}

/* IDENTIFY, after CALIBRATE: the rotor's expected axis (d) on beta, the
 * dead time uncompensated while it is measured (mc_id.c note 4). The
 * caller prepares the first period's angle (mc_step_finish). */
void mc_enter_identify(mc_t *mc)
{
    mc_id_cmd_t cmd;
    mc->id_isr.pending = false;
    pi_reset(&mc->pi_d);
    pi_reset(&mc->pi_q);
    mc->epoch = (uint8_t)(mc->epoch + 1U);
    mc->ol_angle = 0x40000000UL; /* 90 degrees */
    mc->ol_damp = 0;
    mc->ol_step = 0U;
    mc->theta_offset = 0;
    mc->id_isr.sign = 1;
    mc->id_isr.z = 1;
    mc->id_isr.z2 = 1;
    mc->id_isr.i_prev = 0;
    mc->id_isr.u_prev = 0;
    mc->id_isr.open = true;
    memset(&mc->id_isr.win, 0, sizeof mc->id_isr.win);
    mc->lock_va = 0;
    mc->lock_vb = 0;
    mc_id_begin(&mc->id, &mc_id_params, &cmd);
    mc_id_apply(mc, &cmd);
    mc_enter(mc, MC_STATE_IDENTIFY);
}

/* An identification ended, or was ended (error: MC_ID_ERROR_*, NONE when
 * the sequence finished): the status for mc_identify_result, the loops
 * back to the build's gains and dead time. Any state may call it; only a
 * run that is going changes. */
void mc_id_stop(mc_t *mc, uint16_t error)
{
    if (mc->state != MC_STATE_IDENTIFY && !mc->id_isr.pending) {
        return;
    }
    mc->id_isr.pending = false;
    mc->id_error = error;
    mc->id_status = (error == MC_ID_ERROR_NONE) ? MC_ID_DONE : MC_ID_FAILED;
    mc_apply_gains(mc);
    mc->pi_d.p.kp_shift = MC_CUR_KP_SHIFT;
    mc->pi_q.p.kp_shift = MC_CUR_KP_SHIFT;
    mc->dt_counts = MC_DT_COUNTS;
    mc->dt_slope = MC_DT_SLOPE;
    mc->id_isr.dt_band = MC_DT_BAND_Q15;
}

bool mc_id_pending(const mc_t *mc)
{
    return mc->id_isr.pending;
}

void mc_id_started(mc_t *mc)
{
    mc->id_isr.pending = mc->state == MC_STATE_CALIBRATE;
    if (!mc->id_isr.pending) {
        mc->id_status = MC_ID_FAILED; /* the bus is out of its window: FAULT */
        mc->id_error = MC_ID_ERROR_FAULT;
    }
}

/* IDENTIFY's work in each period after the duties (mc_step_finish, after
 * mc_estimate): the window's sums and the injected square wave (mc_id.c
 * note 2). v_hist[1] is the command of the period before, u_prev the
 * one before that: over the interval that ends at this sample they acted
 * for MC_SAMPLE_AT and 1 - MC_SAMPLE_AT of a period (mc.h note 2). The
 * injected axis in the stationary frame: d is beta and q -alpha (an axis's
 * sign drops out of its ratio). The two commands are summed apart: how
 * much each moves the current depends on L / R (mc_identify_result). */
void mc_id_period(mc_t *mc)
{
    mc_id_isr_t *s = &mc->id_isr;
    mc_id_win_t *w = &s->win;
    w->i_d += mc->i_dq.d;
    w->i_q += mc->i_dq.q;
    w->u_d += mc->pi_d.out;
    w->u_q += mc->pi_q.out;
    if (s->inj != 0) {
        bool q = s->inj_q != 0U;
        q15_t un = q ? mc->v_hist[1].alpha : mc->v_hist[1].beta;
        q15_t uo = s->u_prev;
        q15_t i = q ? mc->i_ab.alpha : mc->i_ab.beta;
        q15_t ip = s->i_prev;
        /* z: the injected square wave as it acts over this interval, the
         * same weights (Q15): +-1, or +-(W_NEW - W_OLD) across a reversal;
         * w: its sign a quarter cycle earlier, in phase with the current */
        q15_t z = (s->z == s->z2) ? (q15_t)(s->z * 32767)
                                  : (q15_t)(s->z * (MC_VEST_W_NEW - MC_VEST_W_OLD));
        s->u_prev = un;
        s->i_prev = i;
        w->c[0] += q15_dsp_mulss(z, i) >> 15;
        w->c[1] += q15_dsp_mulss(z, ip) >> 15;
        w->c[2] += q15_dsp_mulss(z, un) >> 15;
        w->c[3] += q15_dsp_mulss(z, uo) >> 15;
        if (((s->zh >> (s->half / 2U)) & 1U) != 0U) {
            w->c[4] += i;
            w->c[5] += ip;
            w->c[6] += un;
            w->c[7] += uo;
        } else {
            w->c[4] -= i;
            w->c[5] -= ip;
            w->c[6] -= un;
            w->c[7] -= uo;
        }
        s->zh = (s->zh << 1) | (uint32_t)(s->z > 0);
        s->z2 = s->z;
        s->z = s->sign; /* the sign this period's command carries */
        if (++s->cnt >= s->half) {
            pi_t *pi = q ? &mc->pi_q : &mc->pi_d;
            q31_t step = (q31_t)s->inj * 131072L; /* 2 x inj, Q31 */
            s->cnt = 0U;
            s->sign = (int8_t)-s->sign;
            pi->sum = q31_add_sat(pi->sum, (s->sign > 0) ? step : -step);
        }
    }
}

bool mc_id_take(mc_t *mc)
{
    mc_id_apply(mc, &mc->id.cmd);
    if (!mc->id.cmd.end) {
        return false;
    }
    mc_id_stop(mc, mc->id.error);
    mc_outputs_off(mc);
    mc_enter(mc, MC_STATE_STOPPED);
    return true;
}

void mc_id_post(mc_t *mc)
{
    mc_slow_in_t *si = &mc->ho.in;
    /* the applied voltage on the standing frame's axes: d is beta, q -alpha */
    mc->id_isr.win.v_d = mc->lock_vb;
    mc->id_isr.win.v_q = -mc->lock_va;
    mc->id_isr.win.step = mc->ol_step;
    si->id = mc->id_isr.win;
    si->vbus = mc->vbus;
    memset(&mc->id_isr.win, 0, sizeof mc->id_isr.win);
    mc->lock_va = 0;
    mc->lock_vb = 0;
}

#endif /* MC_IDENTIFY */
