/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* mc_sensor.c - the current-sensor check's judgement, once a window in the slow step (mc.c note 5).
 */
#include "mc_parts.h"

/* The phase balance (note 5), CLOSED_LOOP, once per window: true when the
 * two measured phases' mean squares differ by more than 8:1 while the larger
 * is above MC_SENSOR_BAL_FLOOR (a quarter of the error floor, squared). A
 * turning rotor's healthy phases carry the same RMS current; a stuck, open
 * or dead sensor's reading stops following its phase. */
static bool mc_sensor_unbalanced(mc_sensor_t *s, const mc_slow_in_t *si)
{
    /* halves of ia = alpha and ib = sqrt3/2 beta - alpha/2 (Q15, |.| < 2^15) */
    q15_t ah = (q15_t)(si->i_ab.alpha / 2);
    q15_t bh = q15_sub_sat(q15_mul(si->i_ab.beta, MC_SQRT3_2 / 2), (q15_t)(si->i_ab.alpha / 4));
    q15_t r = (q15_t)(q15_abs_sat(si->speed_est) % MC_SENSOR_BAL_SYNC16);
    int32_t big, small;
    /* squares of the halves, Q15: <= 2^13; the filters stay below 2^(13 + MC_SENSOR_BAL_SHIFT) */
    s->sa += (int32_t)q15_mul(ah, ah) - (s->sa >> MC_SENSOR_BAL_SHIFT);
    s->sb += (int32_t)q15_mul(bh, bh) - (s->sb >> MC_SENSOR_BAL_SHIFT);
    if (r < MC_SENSOR_BAL_BAND16 || r > MC_SENSOR_BAL_UPPER16) {
        return false; /* one sample per window cannot tell the phases apart here */
    }
    if (s->bal_n < MC_SENSOR_BAL_REFILL) {
        s->bal_n++; /* the filters fill from 0 in CLOSED_LOOP's first windows */
        return false;
    }
    big = (s->sa > s->sb) ? s->sa : s->sb;
    small = (s->sa > s->sb) ? s->sb : s->sa;
    return big >> MC_SENSOR_BAL_SHIFT > MC_SENSOR_BAL_FLOOR && small < big / 8;
}

void mc_sensor_reset(mc_sensor_t *s)
{
    s->fd = 0;
    s->fq = 0;
    s->cnt = 0U;
}

/* Current-sensor plausibility, once per window (note 5): did the measured
 * current follow the current loops? */
void mc_sensor_window(mc_sensor_t *s, const mc_slow_in_t *si, mc_slow_out_t *so)
{
    int32_t ed = si->sens_d; /* window sums: |.| < MC_SLOW_STEP_PERIODS x 2^16 */
    int32_t eq = si->sens_q;
    q15_t rd = q15_abs_sat(si->sens_ref.d);
    q15_t rq = q15_abs_sat(si->sens_ref.q);
    /* half the reference's larger component plus the floor (half of it at
     * the start, whose errors are low-passed further), per period, as a
     * window sum (< 2^15 x MC_SLOW_STEP_PERIODS) */
    int32_t flr = (si->state == MC_STATE_CLOSED_LOOP) ? (int32_t)MC_SENSOR_FLOOR_Q15
                                                      : (int32_t)MC_SENSOR_FLOOR_Q15 / 2;
    int32_t thr = ((int32_t)((rd > rq) ? rd : rq) / 2 + flr) * (int32_t)MC_SLOW_STEP_PERIODS;
    bool bad, unbalanced = false, hold = false;
    if (si->state != MC_STATE_CLOSED_LOOP) {
        /* the balance filters and the back-EMF count are CLOSED_LOOP's */
        s->sa = 0;
        s->sb = 0;
        s->bal_n = 0U;
        s->emf_low = 0U;
        s->low_n = 0U;
        s->pend = 0U;
    }
    if (!mc_driving(si->state) || si->state == MC_STATE_IDENTIFY) {
        s->cnt = 0U;
        so->sensor_fault = false;
        return;
    }
    if (si->state != MC_STATE_CLOSED_LOOP) {
        /* at the start, over MC_SENSOR_START_WINDOWS windows too */
        s->fd += (ed - s->fd) / MC_SENSOR_START_WINDOWS;
        s->fq += (eq - s->fq) / MC_SENSOR_START_WINDOWS;
        ed = s->fd;
        eq = s->fq;
    }
    ed = (ed < 0) ? -ed : ed;
    eq = (eq < 0) ? -eq : eq;
    if (si->state == MC_STATE_CLOSED_LOOP && 2U * si->sens_qsat > MC_SLOW_STEP_PERIODS) {
        /* q at the voltage limit for most of the window: the circle, not
         * the sensor, may hold its current short of the reference, by any
         * amount (a bus or a load the speed asks too much of), so q's error
         * says nothing. The d axis, which the limit serves first, still
         * does, and so does the estimator: a model fed a failed sensor's
         * currents soon stops vouching for its estimate. */
        bad = ed > thr || !si->est_valid;
    } else {
        bad = ed > thr || eq > thr;
    }
    if (si->state == MC_STATE_CLOSED_LOOP) {
        unbalanced = mc_sensor_unbalanced(s, si);
    }
    /* A rotor stopped in CLOSED_LOOP (locked, stalled) leaves the
     * estimate spinning with no back-EMF behind it: the frame turns under
     * the current loops and their errors look like a failed sensor's. The
     * stall check owns that case. While the back-EMF reads below
     * MC_STALL_BEMF_LO_Q12 of the speed's, a failing window is held,
     * neither counted nor forgiven: provisionally for the first
     * MC_SENSOR_DEFER_WINDOWS - 1 windows (counted after all if the
     * back-EMF comes back: a failed sensor on a turning rotor leaves its
     * back-EMF behind, the ratio swings, it does not stay low), for good
     * from the MC_SENSOR_DEFER_WINDOWS-th on. The phase balance overrides
     * the hold (a stopped rotor's healthy phases stay balanced; a sensor
     * failed at low speed, whose estimate also loses its back-EMF, does
     * not), but only once its filters have had two time constants of the
     * low back-EMF's current: the current's step at a sudden stop fills
     * them with one or two samples of a transient many times the current
     * before it, which reads as any ratio. */
    if (si->state == MC_STATE_CLOSED_LOOP && si->emf_ratio < MC_STALL_BEMF_LO_Q12) {
        if (s->emf_low < MC_SENSOR_DEFER_WINDOWS) {
            s->emf_low++;
        }
        if (s->low_n < MC_SENSOR_BAL_REFILL) {
            s->low_n++;
        }
    } else {
        if (s->pend > 0U && s->emf_low < MC_SENSOR_DEFER_WINDOWS) {
            /* the back-EMF came back: the held windows count after all */
            uint8_t c = (uint8_t)(s->cnt + 2U * s->pend);
            s->cnt = (c < MC_SENSOR_TRIP) ? c : MC_SENSOR_TRIP;
        }
        s->emf_low = 0U;
        s->low_n = 0U;
        s->pend = 0U;
    }
    if (unbalanced && (s->emf_low == 0U || s->low_n >= MC_SENSOR_BAL_REFILL)) {
        bad = true; /* no deferring */
    } else if ((bad || unbalanced) && s->emf_low > 0U) {
        bad = false;
        hold = true;
        if (s->emf_low < MC_SENSOR_DEFER_WINDOWS) {
            s->pend++; /* at most MC_SENSOR_DEFER_WINDOWS - 1 */
        } else {
            s->pend = 0U;
        }
    }
    if (bad && MC_SENSOR_CHECK) {
        if (s->cnt < MC_SENSOR_TRIP) {
            s->cnt = (uint8_t)(s->cnt + 2U);
        }
    } else if (s->cnt > 0U && !hold) {
        s->cnt--;
    }
    so->sensor_fault = s->cnt >= MC_SENSOR_TRIP;
}
