/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* mc.c - the motor-control core's 50 us path: one PWM period, mc_step_control and mc_step_finish.
 */
#include "mc_parts.h"

#include "clarke.h"
#include "park.h"
#include "ripple.h"
#include "sincos.h"
#include "svgen.h"
#include "vlimit.h"

/*
 * One call of mc_step(), in order (AN1078 Figure 27, plus what it lacked):
 *   1. take the frame and the posted requests;
 *   2. remove the current offsets; ic = -ia - ib;
 *   3. protections: overcurrent (any phase, this sample), bus over- and
 *      under-voltage, FLTA (MC_REQUEST_HW_FAULT); any of them -> FAULT with
 *      the outputs off in this very step;
 *   4. the state machine (STOPPED -> CALIBRATE -> LOCK -> OPEN_LOOP ->
 *      CLOSED_LOOP; FAULT from anywhere);
 *   5. in LOCK, OPEN_LOOP and CLOSED_LOOP: Clarke, Park, the estimator fed
 *      the applied voltage, d PI, Vq limit from the voltage circle, q PI,
 *      ripple compensation (ENVOLTRIPPLE), inverse Park at the angle the
 *      voltage will be applied at, SVGen, dead-time compensation;
 *   6. every MC_SLOW_STEP_PERIODS periods, the window end: this window's
 *      inputs out to the slow step, whose results come back
 *      MC_SLOW_APPLY_PERIODS periods later (mc.h note 4).
 * mc_slow_step() (mc_slow.c), once per window outside the interrupt: the
 * estimator's speed and compensation, the speed ramp, speed PI (or the
 * torque reference), field weakening, stall detection. The changes of
 * state are in mc_state.c, called from the period that makes them.
 * Divisions in the per-period path: atan2's ratio, the ripple gain and the
 * circle limit's square root (one div.ud each; docs/performance.md says
 * what the alternatives cost).
 */

/* The dead-time compensation's linear band now (mc_internal.h
 * mc_deadtime_counts): the build's, MC_DT_BAND_Q15, but while an
 * identification runs the one its command sets (mc_id_cmd_t.dt_band),
 * which mc_id_stop puts back; an image without the identification has the
 * constant, its code as before. */
#if MC_IDENTIFY
#define MC_DT_BAND_NOW(mc) ((mc)->id_isr.dt_band)
#else
#define MC_DT_BAND_NOW(mc) MC_DT_BAND_Q15
#endif

#define MC_VMAX_SQ  ((int32_t)MC_VMAX_Q15 * (int32_t)MC_VMAX_Q15)
#define MC_VNEAR_SQ ((int32_t)(MC_VMAX_Q15 * 7L / 8L) * (int32_t)(MC_VMAX_Q15 * 7L / 8L))

/* ---- the mailbox, as the step takes it ----------------------------------------- */

static bool mc_take(mc_t *mc, mc_request_t r)
{
    uint8_t posted = mc->mbox.req_posted[r];
    if (posted == mc->req_taken[r]) {
        return false;
    }
    mc->req_taken[r] = posted;
    return true;
}

/* sin/cos of theta + the closed-loop advance: sc turned by mc->adv_sc. */
Q15_INLINE sincos_q15_t mc_advance(sincos_q15_t sc, sincos_q15_t a)
{
    sincos_q15_t r;
    r.sin = q15_dsp_mac2_r(sc.sin, a.cos, sc.cos, a.sin);
    r.cos = q15_dsp_msc2_r(sc.cos, a.cos, sc.sin, a.sin);
    return r;
}

/* The advance of the voltage in CLOSED_LOOP and its sin/cos, and the
 * angle's one-period prediction (mc.h note 2), from the estimator's speed:
 * recomputed whenever that speed changes (the slow step's results, a
 * preset, a reset), so the period only turns sc and adds pred. */
void mc_set_advance(mc_t *mc)
{
    q15_t w = mc_est_omega(mc);
    mc->adv_sc = sincos_compute(q15_mul(w, MC_ADV_K));
    mc->pred = mc_pred_counts(w);
}

/* ---- pieces of the step ---------------------------------------------------------------- */

/* The estimator's update for this sample, after the duties
 * (mc_step_finish): fed the voltage applied while this sample's current
 * evolved, the two last commands weighted by the time each acted between
 * the samples (MC_VEST_W_*, mc.h note 2); then this period's command, from
 * the effective duties mc_current_control left, joins the history. */
Q15_INLINE void mc_estimate(mc_t *mc)
{
    ab_q15_t v;
    v.alpha =
        q15_dsp_mac2_r(mc->v_hist[0].alpha, MC_VEST_W_NEW, mc->v_hist[1].alpha, MC_VEST_W_OLD);
    v.beta = q15_dsp_mac2_r(mc->v_hist[0].beta, MC_VEST_W_NEW, mc->v_hist[1].beta, MC_VEST_W_OLD);
    mc_est_update(mc, mc->i_ab, v);
    mc->v_hist[1] = mc->v_hist[0];
    mc->v_hist[0] = mc_duty_to_voltage(mc->eff, mc->vbus);
}

/* One phase's duty, clamped to [0, hi], and what the inverter will really
 * apply: the duty less the dead-time loss dt (the estimator's input, formed
 * in mc_estimate). A phase at 0, or at 100 % (hi_still_switches false),
 * does not switch and loses nothing; A and B at the shunt window's limit
 * still switch. */
Q15_INLINE void mc_duty_set(mc_t *mc, uint8_t k, int16_t d, int16_t dt, int16_t hi,
                            bool hi_still_switches)
{
    if (d <= 0) {
        d = 0;
        dt = 0;
    } else if (d >= hi) {
        d = hi;
        if (!hi_still_switches) {
            dt = 0;
        }
    }
    mc->duty[k] = (uint16_t)d;
    mc->eff[k] = (int16_t)(d - dt);
}

/* The q current PI's step against +-vq_max (the circle limit, note 3): at
 * +-Vmax away from the circle, at the limit near it and for a redo, the
 * two inlined copies the three ways need. */
Q15_INLINE q15_t mc_q_step(mc_t *mc, q15_t err_q, q15_t vq_max)
{
    pi_set_limits(&mc->pi_q, (q15_t)(-vq_max), vq_max);
    return pi_step(&mc->pi_q, err_q);
}

/* Current loops and modulation, for one period with the outputs on, at
 * the angle mc_prepare made ready: mc->theta (this sample's), its
 * sin/cos sc and the voltage's sin/cos scv. */
Q15_INLINE void mc_current_control(mc_t *mc, sincos_q15_t sc, sincos_q15_t scv)
{
    mc->i_dq = park_forward(mc->i_ab, sc);

    /* The references are meant on the estimated rotor axes; while the
     * hand-off difference is bled off the transforms run at the estimated
     * angle plus theta_offset, so turn the references by -theta_offset into
     * that frame (note 1): the current vector, hence the torque, does not
     * depend on how far the bleed has come. */
    dq_q15_t ref = mc->i_ref;
    if (mc->theta_offset != 0) {
        ab_q15_t r;
        r.alpha = mc->i_ref.d;
        r.beta = mc->i_ref.q;
        ref = park_forward(r, sincos_call(mc->theta_offset));
    }
    mc->i_ref_frame = ref;

    /* d first, then q gets what is left of the voltage circle (AN1078):
     * |Vq| <= sqrt(Vmax^2 - Vd^2). If the previous period's vector was near
     * the circle, the limit is formed first and the q PI runs once against
     * it; otherwise the q PI runs against +-Vmax and, only if its output
     * leaves the circle, is redone against the limit (note 3: AN1078's bits
     * either way, the square root only near the circle, before the duties
     * at most once). */
    bool near = q15_dsp_mulss(mc->pi_q.out, mc->pi_q.out) >=
                MC_VNEAR_SQ - q15_dsp_mulss(mc->pi_d.out, mc->pi_d.out);
    dq_q15_t v;
    q15_t err_d = q15_sub_sat(ref.d, mc->i_dq.d);
    q15_t err_q = q15_sub_sat(ref.q, mc->i_dq.q);
    /* the current-sensor check's window sums (note 5): the loops' own errors */
    mc->sens_d += err_d;
    mc->sens_q += err_q;
    v.d = pi_step(&mc->pi_d, err_d);
    if (!near) {
        q31_t sum_q = mc->pi_q.sum;
        v.q = mc_q_step(mc, err_q, MC_VMAX_Q15);
        if (q15_dsp_mulss(v.q, v.q) > MC_VMAX_SQ - q15_dsp_mulss(v.d, v.d)) {
            mc->pi_q.sum = sum_q; /* redone below, against the limit */
            near = true;
            if (mc->circle_redos != UINT16_MAX) {
                mc->circle_redos++;
            }
        }
    }
    if (near) {
        v.q = mc_q_step(mc, err_q, vlimit_vq_max(v.d, MC_VMAX_Q15));
    }
    if (MC_VOLTAGE_RIPPLE) {
        /* The gain mc_prepare formed from the previous sample's bus. */
        v.d = ripple_apply(v.d, mc->ripple_gain);
        v.q = ripple_apply(v.q, mc->ripple_gain);
    }
    mc->v_dq = v;

    /* Voltage at the angle it will be applied at. */
    ab_q15_t v_ab = park_inverse(v, scv);
    svgen_out_t sv;
    svgen_update(v_ab, PWM_DUTY_MAX, &sv);

    /* Phase currents predicted at the same angle: the signs the dead time
     * will see (measured d/q current, rotated). */
    ab_q15_t ip = park_inverse(mc->i_dq, scv);
    q15_t iph[3];
    iph[0] = ip.alpha;
    iph[1] = q15_dsp_mac2_r(ip.alpha, MC_MINUS_HALF, ip.beta, MC_SQRT3_2); /* -a/2 + b sqrt3/2 */
    iph[2] = q15_dsp_msc2_r(ip.alpha, MC_MINUS_HALF, ip.beta, MC_SQRT3_2); /* -a/2 - b sqrt3/2 */

    /* 16-bit arithmetic: PWM_DUTY_MAX plus the dead-time counts fits int16
     * (mc_derived.h checks it). */
    int16_t dt0 = mc_deadtime_counts(iph[0], mc->dt_counts, mc->dt_slope, MC_DT_BAND_NOW(mc));
    int16_t dt1 = mc_deadtime_counts(iph[1], mc->dt_counts, mc->dt_slope, MC_DT_BAND_NOW(mc));
    int16_t dt2 = mc_deadtime_counts(iph[2], mc->dt_counts, mc->dt_slope, MC_DT_BAND_NOW(mc));
    int16_t d0 = (int16_t)sv.duty[0];
    int16_t d1 = (int16_t)sv.duty[1];
    int16_t d2 = (int16_t)sv.duty[2];
    if (MC_DEADTIME_COMP) {
        d0 = (int16_t)(d0 + dt0);
        d1 = (int16_t)(d1 + dt1);
        d2 = (int16_t)(d2 + dt2);
    }
    /* Shunt window (mc_derived.h MC_DUTY_SAMPLE_MAX): phases A and B, the
     * measured ones, must leave their low-side switch on long enough before
     * the next sample. A duty above the limit first moves the three down by
     * the same amount (a common-mode shift: the line voltages, hence the
     * motor's voltage, do not change), as far as the smallest duty allows;
     * what is still above is clamped below, which cuts the voltage (the
     * estimator is fed what is applied). */
    int16_t ex = (int16_t)(((d0 > d1) ? d0 : d1) - MC_DUTY_SAMPLE_MAX);
    if (ex > 0) {
        int16_t lo = (d0 < d1) ? d0 : d1;
        lo = (d2 < lo) ? d2 : lo;
        int16_t sh = (ex < lo) ? ex : lo;
        if (sh > 0) {
            d0 = (int16_t)(d0 - sh);
            d1 = (int16_t)(d1 - sh);
            d2 = (int16_t)(d2 - sh);
        }
    }
    mc_duty_set(mc, 0U, d0, dt0, MC_DUTY_SAMPLE_MAX, true);
    mc_duty_set(mc, 1U, d1, dt1, MC_DUTY_SAMPLE_MAX, true);
    mc_duty_set(mc, 2U, d2, dt2, (int16_t)PWM_DUTY_MAX, false);
}

/* OPEN_LOOP, IDENTIFY: the forced angle one step of inc further, its sin/cos
 * into *sc and the voltage's, advanced by 1.5 - MC_SAMPLE_AT periods of
 * the forced speed (the step is below 2^15 counts: the MOTOR_RAMP_END_RPM
 * and MC_ID_SPEED_MAX_RPM checks), into scv_next. */
Q15_INLINE angle_q15_t mc_forced_angle(mc_t *mc, uint32_t inc, sincos_q15_t *sc)
{
    mc->ol_step += inc;
    mc->ol_angle += mc->ol_step;
    angle_q15_t th = (angle_q15_t)(int16_t)(uint16_t)(mc->ol_angle >> 16);
    *sc = sincos_compute(th);
    angle_q15_t adv = q15_mul((q15_t)(uint16_t)(mc->ol_step >> 16), MC_ADV_PERIODS);
    mc->scv_next = (adv != 0) ? sincos_compute(angle_add(th, adv)) : *sc;
    return th;
}

/* The next period's angles and bus ripple gain, at the end of this one
 * (mc_step_finish), so that the part of the step before the duties does
 * not compute them: theta_next (the angle of the next sample), its sin/cos,
 * the sin/cos of the angle the next voltage acts at (theta_next plus the
 * advance), and the ripple gain from this sample's bus, 50 us older than
 * the next one, against a voltage that acts 0.5 to 1.5 periods after it.
 *   LOCK         the lock angle 0, no advance;
 *   OPEN_LOOP    the forced angle one more step of the ramp on, advanced
 *                by (1.5 - MC_SAMPLE_AT) steps;
 *   IDENTIFY     the same with the identification's acceleration (ol_inc);
 *   CLOSED_LOOP  the hand-off difference bled one step further; the
 *                estimator's angle of this sample plus the difference, one
 *                period of the estimated speed on (mc.h note 2), advanced
 *                by a rotation by adv_sc (set once per window).
 * Called in those four states only (the outputs on). */
Q15_INLINE void mc_prepare(mc_t *mc)
{
    angle_q15_t th;
    sincos_q15_t sc;
    if (MC_DRIVE && mc->state == MC_STATE_CLOSED_LOOP) {
        int16_t off = mc->theta_offset;
        if (off > MC_BLEED_STEP) {
            off = (int16_t)(off - MC_BLEED_STEP);
        } else if (off < -MC_BLEED_STEP) {
            off = (int16_t)(off + MC_BLEED_STEP);
        } else {
            off = 0;
        }
        mc->theta_offset = off;
        th = angle_add(angle_add(mc_est_theta(mc), off), mc->pred);
        sc = sincos_compute(th);
        mc->scv_next = mc_advance(sc, mc->adv_sc);
    } else if (MC_DRIVE && mc->state == MC_STATE_OPEN_LOOP) {
        th = mc_forced_angle(mc, MC_RAMP_STEP_INC, &sc);
#if MC_IDENTIFY
    } else if (!MC_DRIVE || mc->state == MC_STATE_IDENTIFY) {
        th = mc_forced_angle(mc, mc->id_isr.inc, &sc);
#endif
    } else { /* LOCK */
        th = 0;
        sc = sincos_compute(th);
        mc->scv_next = sc;
    }
    mc->theta_next = th;
    mc->sc_next = sc;
    if (MC_VOLTAGE_RIPPLE) {
        mc->ripple_gain = ripple_gain(mc->vbus, MC_VBUS_NOMINAL_Q15);
    }
}

/* CALIBRATE: after calib_wait periods of coasting, sum the two current
 * readings over MC_CALIB_PERIODS (mc_calibrate, before the duties); the
 * period that took the last one ends it after the duties
 * (mc_calibrate_end, from mc_step_finish), so its divisions and the lock's
 * preparation never delay a duty write. A call, not inlined: its 32-bit
 * sums would otherwise be copied into each of its three callers. */
static __attribute__((noinline)) void mc_calibrate(mc_t *mc, const mc_adc_frame_t *in)
{
    if (mc->timer >= mc->calib_wait && mc->timer - mc->calib_wait < (uint32_t)MC_CALIB_PERIODS) {
        mc->offset_acc_a += in->ia;
        mc->offset_acc_b += in->ib;
    }
}

/* OPEN_LOOP at the end speed: hold it until the estimate is valid, for at
 * most MC_HANDOFF_WAIT_PERIODS (note 1), then retry or fault. */
static void mc_ramp_end(mc_t *mc)
{
    mc->ol_step = MC_RAMP_STEP_END;
    /* the estimated speed within the tolerance of the forced one, counts per period */
    int32_t step = (int32_t)(uint16_t)(MC_RAMP_STEP_END >> 16);
    int32_t diff = (int32_t)mc->pred - step;
    bool agrees = mc_est_valid(mc) && diff * 256 <= step * MC_HANDOFF_TOL_Q8 &&
                  -diff * 256 <= step * MC_HANDOFF_TOL_Q8;
    mc->agree = agrees ? (uint16_t)(mc->agree + (mc->agree != 0xFFFFU)) : 0U;
    if (mc->agree > MC_HANDOFF_AGREE_PERIODS) {
        mc_enter_closed_loop(mc);
    } else if (mc->timer < MC_RAMP_PERIODS + MC_HANDOFF_WAIT_PERIODS) {
        /* keep turning at the end speed */
    } else if ((int)mc->retries < (int)MC_START_RETRIES) {
        mc->retries++;
        mc_begin_calibration(mc, MC_RETRY_CALIB_WAIT);
    } else {
        mc_fault(mc, MC_FAULT_START_FAILED);
    }
}

/* OPEN_LOOP, with the slow step's results (mc_slow_apply): the forced
 * angle moved by the damping's shift for the window (note 1), the previous
 * shift taken out. The slow step forms it (mc_slow.c), so its 32-bit
 * arithmetic stays out of the interrupt. */
Q15_INLINE void mc_ol_damp(mc_t *mc, int16_t shift)
{
    mc->ol_angle += (uint32_t)((int32_t)shift - (int32_t)mc->ol_damp) << 16;
    mc->ol_damp = shift;
}

/* Current-sensor plausibility (note 5), every period with the outputs
 * on: the window's count of the periods with the q PI at its voltage limit
 * (the error sums are the current loops', mc_current_control), for the
 * slow step (mc_sensor_window). */
Q15_INLINE void mc_sensor_sum(mc_t *mc)
{
    if (pi_at_limit(&mc->pi_q)) {
        mc->sens_qsat++;
    }
}

/* MC_SLOW_APPLY_PERIODS after a window end (mc.h note 4): the slow step's
 * results in. */
static void mc_slow_apply(mc_t *mc)
{
    const mc_slow_out_t *so = &mc->ho.out;
    if (mc->ho.busy) {
        mc_fault(mc, MC_FAULT_OVERRUN); /* the slow step has not finished in time */
        return;
    }
    if (!mc->slow_posted) {
        return; /* no window posted since mc_init */
    }
    if (MC_DRIVE) {
        mc_est_apply(mc);
        mc_set_advance(mc);
    }
    if (MC_DRIVE && mc->state == MC_STATE_OPEN_LOOP) {
        if (so->epoch == mc->epoch) {
            mc_ol_damp(mc, so->ol_shift);
        }
        mc->ol_iq = so->ol_iq;
    }
    mc->speed_target = so->speed_target;
    mc->torque_target = so->torque_target;
    if (MC_DTM_ON && mc->state == MC_STATE_LOCK && so->epoch == mc->epoch) {
        mc->i_ref.q = so->lock_iq;
        if (so->lock_done) {
            mc->dt_counts = so->dt_counts;
            mc->dt_slope = so->dt_slope;
            mc->lock_done = true; /* OPEN_LOOP from the next period */
        }
    }
    if (MC_IDENTIFY && mc->state == MC_STATE_IDENTIFY && so->epoch == mc->epoch && mc_id_take(mc)) {
        return; /* the sequence is over: STOPPED */
    }
    if (so->sensor_fault && so->epoch == mc->epoch && mc->outputs_on) {
        mc_fault(mc, MC_FAULT_CURRENT_SENSOR);
        return;
    }
    if (so->loop && so->epoch == mc->epoch && mc->state == MC_STATE_CLOSED_LOOP) {
        mc->i_ref = so->i_ref;
        mc->speed_ref = so->speed_ref;
        if (so->fault != MC_FAULT_NONE) {
            mc_fault(mc, so->fault);
        } else if (so->release && mc->stopping) {
            mc_stop(mc); /* the rotor is below the release speed */
        }
    }
}

/* The window end (mc.h note 4): this window's inputs out to the slow step. */
static void mc_window_end(mc_t *mc)
{
    mc_slow_in_t *si = &mc->ho.in;
    if (mc->ho.busy) {
        mc_fault(mc, MC_FAULT_OVERRUN); /* the slow step of the last window never finished */
        return;
    }
    mc_est_window_end(mc);
    si->epoch = mc->epoch;
    si->state = mc->state;
    si->pot = mc->pot;
    si->ref_remote = mc->mbox.ref_remote;
    si->ref_from_remote = mc->ref_from_remote;
    si->spd_kp = mc->spd_kp_base;
    si->spd_ki = mc->spd_ki_base;
    si->preset = mc->preset_pending;
    si->preset_iq = mc->preset_iq;
    si->preset_speed_ref = mc->preset_speed_ref;
    si->ol_step = mc->ol_step;
    si->i_ab = mc->i_ab;
    si->theta_est = mc_est_theta(mc);
    si->sens_d = mc->sens_d;
    si->sens_q = mc->sens_q;
    si->sens_qsat = mc->sens_qsat;
    si->sens_ref = mc->i_ref_frame;
    si->est_valid = mc_est_valid(mc);
    si->emf_ratio = mc_est_emf_ratio(mc);
    si->speed_est = mc_est_omega(mc);
    mc->sens_d = 0;
    mc->sens_q = 0;
    mc->sens_qsat = 0U;
    if (MC_IDENTIFY && mc->state == MC_STATE_IDENTIFY) {
        mc_id_post(mc);
    }
    if (MC_DTM_ON && mc->state == MC_STATE_LOCK) { /* mc_dtm_window's inputs, LOCK's only */
        si->lock_va = mc->lock_va;
        si->lock_vb = mc->lock_vb;
        si->timer = mc->timer;
        si->dt_counts = mc->dt_counts;
        mc->lock_va = 0;
        mc->lock_vb = 0;
    }
    si->vbus = mc->vbus; /* the dead-time measurement's, and the braking limit's */
    si->stopping = mc->stopping;
    mc->preset_pending = false;
    mc->slow_posted = true;
    MC_BARRIER(); /* every field above is written before the flag hands it over */
    mc->ho.busy = true;
}

/* |i| >= MC_OVERCURRENT_Q15, with |-32768| counted as 32767 (q15_abs_sat),
 * as two compares. */
/* The period's outputs: every path writes all of them. */
Q15_INLINE void mc_output(const mc_t *mc, mc_pwm_out_t *out)
{
    out->duty[0] = mc->duty[0];
    out->duty[1] = mc->duty[1];
    out->duty[2] = mc->duty[2];
    out->outputs_on = mc->outputs_on;
}

Q15_INLINE bool mc_overcurrent(q15_t i)
{
    return i >= MC_OVERCURRENT_Q15 || i <= (q15_t)(-MC_OVERCURRENT_Q15);
}

/* ---- one period: the control part --------------------------------------------- */

/* The requests the main loop posted since the last period (mc.h note 1). */
typedef struct {
    bool toggle;   /* START_STOP: start when stopped or faulted, else stop */
    bool start;    /* START */
    bool stop;     /* STOP */
    bool hw_fault; /* HW_FAULT */
    bool identify; /* IDENTIFY (in STOPPED: refused in any other state) */
} mc_events_t;

/* Takes the posted requests into ev, applies posted gains and the choice
 * of reference. */
static void mc_take_events(mc_t *mc, mc_events_t *ev)
{
    ev->toggle = false;
    ev->start = false;
    ev->stop = false;
    ev->hw_fault = false;
    ev->identify = false;
    uint8_t rseq = mc->mbox.req_seq;
    if (rseq != mc->req_seen) { /* something was posted (mc.h note 1) */
        mc->req_seen = rseq;
        ev->toggle = mc_take(mc, MC_REQUEST_START_STOP);
        ev->hw_fault = mc_take(mc, MC_REQUEST_HW_FAULT);
        ev->start = mc_take(mc, MC_REQUEST_START);
        ev->stop = mc_take(mc, MC_REQUEST_STOP);
        ev->identify = mc_take(mc, MC_REQUEST_IDENTIFY);
        if (ev->identify && (!MC_IDENTIFY || mc->state != MC_STATE_STOPPED)) {
            ev->identify = false;
            if (!MC_IDENTIFY) {
                mc->id_status = MC_ID_FAILED; /* not in this build: nothing else changes */
                mc->id_error = MC_ID_ERROR_UNAVAILABLE;
            } else if (mc->state != MC_STATE_IDENTIFY && !mc_id_pending(mc)) {
                mc->id_status = MC_ID_FAILED; /* refused: nothing else changes */
                mc->id_error = MC_ID_ERROR_NOT_STOPPED;
            }
        }
        uint8_t gseq = mc->mbox.gain_seq;
        if (gseq != mc->gain_seen) {
            mc->gain_seen = gseq;
            mc_apply_gains(mc);
        }
        uint8_t seq = mc->mbox.ref_seq;
        if (seq != mc->ref_seen) {
            mc->ref_seen = seq;
            mc->ref_from_remote = !mc->mbox.ref_to_pot;
        }
    }
}

/* The frame in the core's terms: offsets off, ic from the other two. */
static void mc_measure(mc_t *mc, const mc_adc_frame_t *in)
{
    mc->vbus = in->vbus;
    mc->pot = in->pot;
    mc->ia = q15_sub_sat(in->ia, mc->offset_a);
    mc->ib = q15_sub_sat(in->ib, mc->offset_b);
    mc->ic = q15_dsp_dbl_sub2_sat(0, mc->ia, mc->ib); /* -ia - ib, saturated once */
}

/* The protections, in every state, before anything is driven: the one
 * place the period's faults are raised. */
static void mc_protect(mc_t *mc, const mc_events_t *ev)
{
    bool running = mc_driving(mc->state);
    if (ev->hw_fault) {
        mc_fault(mc, MC_FAULT_HARDWARE);
    }
    if (running) {
        if (mc_overcurrent(mc->ia) || mc_overcurrent(mc->ib) || mc_overcurrent(mc->ic)) {
            mc_fault(mc, MC_FAULT_OVERCURRENT);
        } else if (mc->vbus <= MC_VBUS_UV_Q15) {
            mc_fault(mc, MC_FAULT_UNDERVOLTAGE);
        }
    }
    if (mc->vbus >= MC_VBUS_OV_Q15) {
        mc_fault(mc, MC_FAULT_OVERVOLTAGE);
    }
}

/* A START, from STOPPED or from FAULT once the cause is gone: CALIBRATE,
 * whose first period this is. The bus is checked here too: from STOPPED
 * the overvoltage protection has already tripped, but in FAULT it records
 * nothing (the first cause stays), so a START with the bus still out of
 * its window enters FAULT again with that cause. Once a start, so a call
 * rather than a copy in each state handler that starts. */
static __attribute__((noinline)) void mc_start(mc_t *mc, const mc_adc_frame_t *in)
{
    if (mc->vbus <= MC_VBUS_UV_Q15 || mc->vbus >= MC_VBUS_OV_Q15) {
        mc_enter_fault(mc,
                       (mc->vbus >= MC_VBUS_OV_Q15) ? MC_FAULT_OVERVOLTAGE : MC_FAULT_UNDERVOLTAGE);
        return;
    }
    mc->fault = MC_FAULT_NONE;
    mc->retries = 0U;
    mc_begin_calibration(mc, MC_CALIB_SKIP_PERIODS);
    mc_calibrate(mc, in);
}

/* The state handlers: the period's events in the state the protections
 * left, and its work. Each returns true when the current loops run this
 * period (the driving states). */

/* A START of the identification: MC_REQUEST_IDENTIFY, or in the
 * commissioning image (MC_DRIVE 0) any START. CALIBRATE, IDENTIFY pending. */
static void mc_start_identify(mc_t *mc, const mc_adc_frame_t *in)
{
    mc->id_status = MC_ID_RUNNING;
    mc->id_error = MC_ID_ERROR_NONE;
    mc_start(mc, in);
    if (MC_IDENTIFY) { /* the call folds away without it, at -O0 too */
        mc_id_started(mc);
    }
}

static bool mc_on_stopped(mc_t *mc, const mc_events_t *ev, const mc_adc_frame_t *in)
{
    bool start = ev->toggle || ev->start;
    if (MC_DRIVE && start) {
        mc_start(mc, in);
    } else if (MC_IDENTIFY && (start || ev->identify)) {
        mc_start_identify(mc, in);
    }
    return false;
}

static bool mc_on_fault(mc_t *mc, const mc_events_t *ev, const mc_adc_frame_t *in)
{
    /* timer > 0: not the fault raised by this very frame. */
    if ((ev->toggle || ev->start) && mc->timer > 0U) {
        if (MC_DRIVE) {
            mc_start(mc, in);
        } else {
            mc_start_identify(mc, in);
        }
    }
    return false;
}

static bool mc_on_calibrate(mc_t *mc, const mc_events_t *ev, const mc_adc_frame_t *in)
{
    if (ev->toggle || ev->stop) {
        mc_stop(mc);
    } else {
        mc_calibrate(mc, in);
    }
    return false;
}

/* LOCK: once the lock is done, OPEN_LOOP with the ramp current; this
 * period still at the lock angle. */
static bool mc_on_lock(mc_t *mc, const mc_events_t *ev)
{
    if (ev->toggle || ev->stop) {
        mc_stop(mc);
        return false;
    }
    if (MC_DTM_ON ? mc->lock_done : mc->timer >= MC_LOCK_PERIODS) {
        mc->i_ref.q = MC_RAMP_CURRENT_Q15;
        mc_enter(mc, MC_STATE_OPEN_LOOP);
    }
    return true;
}

/* A STOP (or S2) in a running state: in CLOSED_LOOP above the release
 * speed (UserParms.h MC_STOP_RELEASE_FRACTION) zero torque, the slow step
 * releasing the outputs once the rotor is below it (mc_slow_apply);
 * while stopping, S2 takes the speed loop back. Out of the common path. */
static bool mc_on_stop(mc_t *mc, const mc_events_t *ev)
{
    if (MC_DRIVE && mc->state == MC_STATE_CLOSED_LOOP) {
        if (mc->stopping) {
            mc->stopping = ev->stop; /* S2 again: the speed loop back */
            return true;
        }
        if (q15_abs_sat(mc_est_omega(mc)) > mc_release_speed(mc->vbus)) {
            mc->stopping = true;
            return true;
        }
    }
    mc_stop(mc);
    return false;
}

/* OPEN_LOOP, CLOSED_LOOP and IDENTIFY: their changes of state come from
 * the finishing part and the slow step. */
static bool mc_on_running(mc_t *mc, const mc_events_t *ev)
{
    if (ev->toggle || ev->stop) {
        return mc_on_stop(mc, ev);
    }
    return true;
}

static bool mc_dispatch(mc_t *mc, const mc_events_t *ev, const mc_adc_frame_t *in)
{
    /* the driving states first: their periods are the ones that count */
    mc_state_t s = mc->state;
    if (s == MC_STATE_CLOSED_LOOP || s == MC_STATE_OPEN_LOOP || s == MC_STATE_IDENTIFY) {
        return mc_on_running(mc, ev);
    }
    switch (s) {
        case MC_STATE_LOCK:
            return mc_on_lock(mc, ev);
        case MC_STATE_STOPPED:
            return mc_on_stopped(mc, ev, in);
        case MC_STATE_CALIBRATE:
            return mc_on_calibrate(mc, ev, in);
        default: /* FAULT */
            return mc_on_fault(mc, ev, in);
    }
}

/* The current loops, at the angle the previous period's mc_step_finish
 * prepared (mc_prepare, also after the period that ended CALIBRATE). */
static void mc_control(mc_t *mc)
{
    mc->outputs_on = true;
    mc->i_ab = clarke_forward(mc->ia, mc->ib);
    mc->theta = mc->theta_next;
    mc_current_control(mc, mc->sc_next, mc->scv_next);
}

void mc_step_control(mc_t *mc, const mc_adc_frame_t *in, mc_pwm_out_t *out)
{
    mc_events_t ev;
    mc_take_events(mc, &ev);
    mc_measure(mc, in);
    mc_protect(mc, &ev);
    if (mc_dispatch(mc, &ev, in)) {
        mc_control(mc);
    }
    mc_output(mc, out);
}

bool mc_step_finish(mc_t *mc, mc_pwm_out_t *out)
{
    bool turned_off = false;
    /* The outputs are on exactly when mc_step_control ran the loops. */
    if (mc->outputs_on) {
        mc_estimate(mc);
        if (MC_DRIVE) {
            mc_sensor_sum(mc);
        }
        if (MC_DRIVE && mc->state == MC_STATE_OPEN_LOOP && mc->ol_step >= MC_RAMP_STEP_END) {
            mc_ramp_end(mc);
        }
        if (mc->sums_on) { /* the dead-time measurement's (note 4), the identification's */
            mc->lock_va += mc->v_hist[0].alpha;
            mc->lock_vb += mc->v_hist[0].beta;
            if (MC_IDENTIFY && mc->state == MC_STATE_IDENTIFY) {
                mc_id_period(mc);
            }
        }
    }
    {
        uint32_t t = mc->timer + 1U;
        // cppcheck-suppress knownConditionTrueFalse ; at 2^32 - 1 periods (2.5 days) t wraps to 0
        if (t != 0U) {
            mc->timer = t; /* saturates at 2^32 - 1 */
        }
    }

    /* 6. The slow step's results MC_SLOW_APPLY_PERIODS after a window end,
     * and the window end every MC_SLOW_STEP_PERIODS calls since mc_init. */
    mc->slow_div++;
    if (mc->slow_div == MC_SLOW_APPLY_PERIODS) {
        mc_slow_apply(mc);
    }
    if (mc->slow_div >= MC_SLOW_STEP_PERIODS) {
        mc->slow_div = 0U;
        mc_window_end(mc);
    }
    bool prepare = mc->outputs_on;
    if (!prepare) {
        /* Off, or a fault raised here (a failed start, a stall, an
         * overrun) has just turned the outputs off: so does *out, at once.
         * CALIBRATE ends here once it has its samples; the next period
         * (LOCK's or IDENTIFY's first) turns the outputs on at the angle
         * prepared below. */
        if (mc->state == MC_STATE_CALIBRATE &&
            mc->timer == (uint32_t)mc->calib_wait + (uint32_t)MC_CALIB_PERIODS) {
            mc_calibrate_end(mc);
            prepare = mc_driving(mc->state);
        }
        turned_off = out->outputs_on;
        mc_output(mc, out);
    }
    if (prepare) {
        mc_prepare(mc); /* one call: inline */
    }
    return turned_off;
}

void mc_step(mc_t *mc, const mc_adc_frame_t *in, mc_pwm_out_t *out)
{
    mc_step_control(mc, in, out);
    (void)mc_step_finish(mc, out);
}

/*
 * Notes
 *
 * 1. Hand-off. At the end of the ramp the forced speed is held until the
 *    estimator reports a valid angle and the rotor follows: its estimated
 *    speed within MC_HANDOFF_SPEED_TOL of the forced speed for
 *    MC_HANDOFF_AGREE_S without a break (a rotor that slipped poles, or sits
 *    still while the estimator reads its own model errors as back-EMF, can
 *    flicker valid), at most MC_HANDOFF_WAIT_S; no agreement by then is a
 *    failed start, retried after the rotor has coasted for MC_RETRY_COAST_S,
 *    MC_START_RETRIES times, then FAULT START_FAILED. The estimator has run
 *    for the whole start-up on the measured currents and the applied
 *    voltages, so its angle is already the rotor's; the forced angle is not
 *    (the rotor runs at a load angle behind the current vector). The
 *    difference is kept as theta_offset and bled to zero at
 *    MC_HANDOFF_BLEED_DEG_PER_S, the references turned so that the current
 *    vector stays on the estimated axes, and the speed PI starts with its
 *    integral at the load's low-passed share of the ramp current plus a
 *    margin (mc_enter_closed_loop says why).
 *    Open-loop damping: a rotor pulled by a current at a forced angle is an
 *    undamped spring and mass; with little friction it swings about the
 *    forced angle for the whole ramp, and a hand-off that meets it swinging
 *    stalls (docs/tuning.md, "Behind the defaults"). Once the estimate is
 *    valid, each window moves the forced angle back by MOTOR_OL_DAMP_S
 *    times the rotor's excess speed (mc_slow_ol_damp forms the shift,
 *    mc_ol_damp applies it): the torque then falls as the rotor runs ahead
 *    and rises as it falls behind, a viscous damping of the swing. The
 *    excess is taken less its mean over MC_OL_DAMP_MEAN_WINDOWS: under a
 *    model mismatch the estimate reads steadily high or low, and damping
 *    that bias held the forced angle back by a steady amount, the torque a
 *    loaded start needed.
 *
 * 2. Stall detection runs at the speed-loop rate in CLOSED_LOOP; each
 *    condition must hold for consecutive runs: estimated |speed| below
 *    MC_STALL_SPEED_MIN_RPM (MC_STALL_TIME_S); the estimator's back-EMF
 *    ratio (|e| over what Ke predicts at the estimated speed) above
 *    MC_STALL_BEMF_HIGH_FRACTION or, outside field weakening (where the
 *    weakened flux lowers it legitimately), below MC_STALL_BEMF_LOW_FRACTION
 *    (MC_STALL_TIME_S); the speed error above MC_STALL_SPEED_ERROR_RPM with
 *    the speed PI at its limit (MC_STALL_TRACK_TIME_S). A speed loop too
 *    hot for its rotor limit-cycles at the Iq limit with an error that
 *    passes through zero twice a cycle, which the tracking check never
 *    sees persist: MC_SWING_FLIPS reversals of the speed PI between its
 *    limits, each within MC_SWING_GAP_S of the last, are SPEED_UNSTABLE.
 *
 * 3. The circle limit. With lim = round(sqrt(Vmax^2 - Vd^2)), AN1078's q PI
 *    gives Out = clamp(round(U), -lim, lim). Its square root (one division
 *    inside, q15_sqrt.h) stands between the d PI and the duty write, so it
 *    is paid at most once there, and only near the circle:
 *    - previous period's |V| >= 7/8 Vmax: lim first, one q PI run: Out.
 *    - otherwise a first run against +-Vmax gives Out1 = clamp(round(U),
 *      -Vmax, Vmax). If Out1^2 + Vd^2 <= Vmax^2, then |Out1| <=
 *      sqrt(Vmax^2 - Vd^2), so |Out1| <= lim (an integer below a real is
 *      below its rounding), and either Out1 = round(U) (not clamped, hence
 *      not clamped by lim either) or Out1 = +-Vmax with Vd = 0, lim = Vmax:
 *      in both cases Out1 is Out, with the same U, Exc and integral.
 *      Otherwise the integral is restored and the step redone against +-lim
 *      (counted in circle_redos): a jump onto the circle from more than
 *      1/8 Vmax inside in one period, a transient's exception.
 *    The redo costs a second q PI run and the square root before the write;
 *    running at the circle (field weakening, the top speed) costs the
 *    square root alone (docs/board.md "Timing" has the write instants).
 *
 * 4. The dead time, measured at every lock (MC_DEADTIME_MEASURE). The
 *    inverter's voltage loss in a phase is the dead time's share of the bus
 *    by the sign of its current, plus the switches' delays and the diodes'
 *    drop; the core adds back what it believes (MC_DEADTIME_COMP) and feeds
 *    the estimator the duty less that loss, so an error in it is an
 *    applied-voltage error the estimator reads as back-EMF, at every speed
 *    and load. PWM_DEADTIME_NS is only what the PWM module is told, and on
 *    a high-voltage bus the difference is a large share of the back-EMF at
 *    the lowest closed-loop speed (docs/tuning.md, "Behind the defaults").
 *    At the lock the rotor is at rest and its current I is on beta,
 *    +-sqrt(3)/2 I in phases B and C, both outside the band, so the real
 *    voltage on beta is R I exactly, and the estimator's voltage u (what
 *    the duties less the modelled loss give) misses it by (g - 1) D, D the
 *    model's dead-time voltage on beta and g the real loss over the
 *    modelled one: u = R I + (g - 1) D. At I and at 3/4 I, R drops out:
 *    (g - 1) D = 4 u2 - 3 u1, each u averaged over MC_DTM_N periods (the
 *    last of the lock, and after MC_DTM_SETTLE periods at 3/4 I). The
 *    diodes' drop and the switches' delays are part of g, the switches'
 *    on-resistance part of R; the rotor does not move when the current
 *    falls to 3/4 (it rests where the torque is zero at any current, and a
 *    passive load holds no torque at rest), and a rotor still swinging
 *    about the lock angle puts its back-EMF on alpha, not on beta (its q
 *    axis points along alpha there). The interrupt only sums the
 *    estimator's voltage over each window (lock_va, lock_vb); the slow step
 *    finds the reversals, switches the level (slow_out.lock_iq) and forms
 *    the result (mc_slow_deadtime), which, within a quarter to twice the
 *    programmed dead time, is compensated and modelled from its window's
 *    apply on (dt_counts, dt_slope; reported in mc_status_t), and ends the
 *    lock (lock_done). Not
 *    covered: a loss that changes with temperature while running (the
 *    next start measures it again), and a real loss whose shape near zero
 *    current differs from the band's.
 *
 * 5. Current-sensor plausibility. The overcurrent check reads the
 *    sensors, so a sensor that stops following its current (a dead
 *    amplifier frozen at one code, an open input reading its bias) hides
 *    the current it should limit: the current PI winds up to the voltage
 *    limit and the real current runs to Vmax / R, which can be beyond the
 *    trip. A live sensor lets the current loops make the
 *    measured current follow the reference within a few periods (their
 *    bandwidth is 2000 to 4600 rad/s); a failed one does not. Every period
 *    with the outputs on, the interrupt adds the error on d and q to the
 *    window's sums and counts the periods with the q PI at its voltage
 *    limit (mc_sensor_sum: two 32-bit adds and a compare); once per window
 *    the slow step judges them (mc_slow_sensor). A window fails when the
 *    mean error on either axis exceeds half the reference's larger
 *    component plus MC_SENSOR_FLOOR_Q15 (the 1 ms mean averages out a
 *    low-inductance motor's current noise; at the start the means are
 *    low-passed over MC_SENSOR_START_WINDOWS too, so that a rotor still
 *    spinning from a failed attempt, whose back-EMF the lock's loop cannot
 *    hold, does not count). In CLOSED_LOOP the voltage circle can leave q
 *    short of its reference by any amount, legitimately: field weakening,
 *    a load or a sagging bus that asks more than the bus can drive (the
 *    speed then sags and the speed PI winds the reference up to its limit
 *    while the current stays where the voltage holds it). So a window with
 *    the q PI at its limit for most of its periods is judged on d and on
 *    the estimator instead: it fails when d does or when the estimator
 *    does not vouch for its estimate at the window end (smc_valid: the
 *    speed above its minimum and the back-EMF within its band of what Ke
 *    predicts), which a model fed a failed sensor's currents soon stops
 *    doing, while a healthy drive held at the circle keeps it. In
 *    CLOSED_LOOP a window also fails when the two measured phases are out
 *    of balance (mc_sensor_unbalanced): a turning rotor's phases carry the
 *    same RMS current, a failed sensor's reading stops following its
 *    phase, so the mean squares of ia and ib (one sample per window,
 *    low-passed over 8) differ by more than 8:1 while the larger is above
 *    a quarter of the floor (an unloaded motor's current stays below the
 *    floor itself). This is what catches a sensor that fails at light load or
 *    low speed, where the current errors stay small for tens of
 *    milliseconds. It rests near electrical frequencies that are multiples
 *    of half the window rate (one sample per window then sees one phase of
 *    the sine), for the filters' first two time constants in CLOSED_LOOP,
 *    and it needs the 8:1: a current vector that swings in the rotor frame
 *    at the electrical frequency (a hand-off or a step on a heavy rotor)
 *    pulsates in the stator instead of turning and unbalances the phases
 *    by up to 5:1 for a while. A rotor stopped in CLOSED_LOOP (locked,
 *    stalled) leaves the estimate spinning on no back-EMF, and its frame
 *    turning under the current loops makes errors like a failed sensor's:
 *    while the back-EMF ratio reads below the stall check's low fraction,
 *    failing windows are held and the stall check decides (for its first
 *    MC_SENSOR_DEFER_WINDOWS - 1 windows provisionally: they count after
 *    all if the back-EMF comes back, as a failed sensor's swinging ratio
 *    does), unless the phases are out of balance (a stopped rotor's
 *    healthy phases are not; a sensor failed at low speed, whose estimate
 *    also loses its back-EMF, is) and have been for the balance filters'
 *    two time constants of the low back-EMF (the current's step at a
 *    sudden stop fills them with a transient that reads as any ratio,
 *    test_mc_sensor). Failing
 *    windows count 2, passing ones -1: MC_SENSOR_TIME_S of failure net sets
 *    slow_out.sensor_fault, applied as MC_FAULT_CURRENT_SENSOR. A phase-A
 *    sensor failed during LOCK reads what the phase carries there (the
 *    lock's current is on beta: none in phase A), so it shows, and trips,
 *    once the ramp turns the current. Not covered: a gain error or a
 *    slowly drifting offset (the loop then regulates the wrong current,
 *    consistently).
 */
