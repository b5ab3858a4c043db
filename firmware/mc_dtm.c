/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* mc_dtm.c - the lock's dead-time measurement, once a window in the slow step (mc.c note 4). */
#include "mc_parts.h"

int16_t mc_deadtime_from_lock(int16_t dt, int32_t avg, q15_t dv)
{
    if (dv <= 0) {
        return dt;
    }
    /* |avg| <= dv keeps the quotient within +-dt (the clamp below is
     * narrower anyway); dt * dv < 2^31. */
    if (avg > dv) {
        avg = dv;
    } else if (avg < -dv) {
        avg = -dv;
    }
    int32_t m = (int32_t)dt + (int32_t)q15_dsp_divsd(avg * (int32_t)dt, dv);
    if (m < MC_DT_COUNTS_MIN) {
        m = MC_DT_COUNTS_MIN;
    } else if (m > MC_DT_COUNTS_MAX) {
        m = MC_DT_COUNTS_MAX;
    }
    return (int16_t)m;
}

void mc_dtm_reset(mc_dtm_t *m)
{
    m->phase = MC_DTM_ALIGN;
    m->cnt = 0U;
    m->sum = 0;
    m->mean = 0;
    m->slow = false;
}

/* LOCK, once per window in the slow step (note 4). The rotor's swing
 * reverses where the estimator's alpha voltage (its back-EMF), summed over
 * the window (a 1 ms mean, which also smooths the chatter an inverter with
 * a sharp dead-time edge puts on phase A, whose current sits at zero),
 * crosses its mean over MC_DTM_MEAN windows (the offset phase A's loss
 * leaves in it). Each level's average runs between two reversals, or gives
 * up waiting after MC_DTM_WAIT windows. so->lock_iq is the lock's current
 * reference; so->lock_done, with the dead time, ends the lock. */
void mc_dtm_window(mc_dtm_t *m, const mc_slow_in_t *si, mc_slow_out_t *so)
{
    int32_t a = si->lock_va; /* |.| <= MC_SLOW_STEP_PERIODS x 2^15 */
    m->mean += a - m->mean / MC_DTM_MEAN;
    bool pos = a >= m->mean / MC_DTM_MEAN;
    bool rev = pos != m->pos;
    m->pos = pos;
    m->cnt++;
    switch (m->phase) {
        case MC_DTM_ALIGN:
            /* the first window may start within the lock's last MC_DTM_WAIT windows */
            if (si->timer + (uint32_t)MC_DTM_WAIT * MC_SLOW_STEP_PERIODS >=
                (uint32_t)MC_LOCK_PERIODS) {
                m->phase = MC_DTM_WAIT1;
                m->cnt = 0U;
            }
            break;
        case MC_DTM_WAIT1:
        case MC_DTM_WAIT2:
            if (rev || m->cnt >= MC_DTM_WAIT) {
                m->slow |= !rev;
                m->phase++;
                m->cnt = 0U;
                m->sum = 0;
                m->hi = a; /* each level's own range: its alpha level differs */
                m->lo = a;
            }
            break;
        case MC_DTM_SETTLE2:
            if (m->cnt >= MC_DTM_SETTLE) {
                m->phase = MC_DTM_WAIT2;
                m->cnt = 0U;
            }
            break;
        case MC_DTM_ACC1:
        case MC_DTM_ACC2:
            m->sum += si->lock_vb;
            m->hi = (a > m->hi) ? a : m->hi;
            m->lo = (a < m->lo) ? a : m->lo;
            /* at least MC_DTM_N windows, and not before the lock's end */
            if (m->cnt >= MC_DTM_N && si->timer >= (uint32_t)MC_LOCK_PERIODS &&
                (rev || m->cnt >= MC_DTM_N + 2U * MC_DTM_WAIT)) {
                m->slow |= !rev;
                /* the mean of <= 32767 Q15 samples (mc_derived.h) fits div.sd */
                q15_t u = q15_dsp_divsd(m->sum, (int16_t)(m->cnt * MC_SLOW_STEP_PERIODS));
                m->cnt = 0U;
                if (m->phase == MC_DTM_ACC1) {
                    m->u1 = u;
                    m->range1 = m->hi - m->lo;
                    so->lock_iq = MC_DTM_CURRENT_Q15;
                    m->phase = MC_DTM_SETTLE2;
                } else {
                    /* The model's dead-time voltage on beta: phase B
                     * carries +sqrt(3)/2 of the lock current, C -sqrt(3)/2,
                     * both outside the band (mc_derived.h). */
                    int16_t dv[3];
                    dv[0] = 0;
                    dv[1] = si->dt_counts;
                    dv[2] = (int16_t)(-si->dt_counts);
                    q15_t d = mc_duty_to_voltage(dv, si->vbus).beta;
                    int32_t avg = 4 * (int32_t)u - 3 * (int32_t)m->u1;
                    /* A swing too slow to reverse within the windows
                     * leaves its back-EMF in them: unless the rotor was
                     * nearly still (at each level, the alpha voltage's
                     * range within 1/16 of the dead-time voltage, i.e.
                     * the sums' within MC_SLOW_STEP_PERIODS / 16 of it:
                     * its swing then moves the result by well under 1 %),
                     * the dead time in use is kept. */
                    int32_t range = m->hi - m->lo;
                    range = (range > m->range1) ? range : m->range1;
                    bool still = range * 16 < (int32_t)d * (int32_t)MC_SLOW_STEP_PERIODS;
                    int16_t dt = (m->slow && !still) ? si->dt_counts
                                                     : mc_deadtime_from_lock(si->dt_counts, avg, d);
                    so->dt_counts = dt;
                    so->dt_slope = mc_deadtime_slope(dt, MC_DT_BAND_Q15); /* dt < the band */
                    so->lock_done = true;
                    m->phase = MC_DTM_DONE;
                }
            }
            break;
        default:
            break;
    }
}
