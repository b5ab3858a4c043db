/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* mc_slow.c - the slow step: speed ramp and PI, field weakening, stall check (mc.h note 4). */
#include "mc_parts.h"

#include <string.h>

#include "park.h"
#include "sincos.h"
#include "vlimit.h"

#if MC_DRIVE
static const pi_params_t mc_pi_spd_params = {
    MC_SPD_KP, MC_SPD_KP_SHIFT, MC_SPD_KI, MC_PI_KC, (q15_t)(-MC_IQ_MAX_Q15), MC_IQ_MAX_Q15,
};

static const fieldweak_params_t mc_fw_params = {
    MC_Q15_RPM(MOTOR_SPEED_NOMINAL_RPM),
    MC_Q15_RPM(MOTOR_SPEED_FW_MAX_RPM),
    MC_FW_TABLE_Q15,
};

#endif

/* Speed-PI Kp schedule (mc_slow_speed_loop): factor sched in Q15 = |speed_ref| /
 * MOTOR_SPEED_KP_FULL_RPM, i.e. speed_q15 * MC_KP_SCHED_K >> 15, formed only
 * for |speed_ref| < MC_KP_FULL_Q15, so the product stays below 2^30. */
#define MC_KP_FULL_Q15  MC_Q15_RPM(MOTOR_SPEED_KP_FULL_RPM)
#define MC_KP_SCHED_ONE Q15(1.0)
#define MC_KP_SCHED_MIN Q15(MC_SPEED_KP_MIN_FRACTION)
#define MC_KP_SCHED_K_  (32768.0 * 32767.0 / (double)MC_KP_FULL_Q15)
MC_CHECK(MOTOR_SPEED_KP_FULL_RPM, MC_KP_SCHED_K_ <= 32768.0 * 32767.0 / 16.0,
         "must be at least 16 Q15 counts of speed");
#define MC_KP_SCHED_K ((int32_t)(MC_KP_SCHED_K_ + 0.5))

/* Pot travel in Q15 speed (speed mode): 0 < span < 32768. */
#define MC_SPEED_REF_SPAN_Q15 ((q15_t)(MC_SPEED_REF_MAX_Q15 - MC_SPEED_REF_MIN_Q15))

/* Total current the speed loop may ask for with field weakening active: 90 %
 * of the software trip, so |(Id, Iq)| never reaches it in steady state. */
#define MC_I_TOTAL_Q15 MC_Q15_AMPS(0.9 * MC_OVERCURRENT_A)

/* Both maps run every period: Q15 x Q15 products, written as 16 x 16 -> 32
 * (gcc narrows the 32-bit form too: avr-gcc -O1 emits the same widening
 * multiply for either, so this states the cost rather than changing it). */
q15_t mc_pot_to_speed(int16_t pot)
{
    q15_t p = (pot < 0) ? 0 : pot;
    return (q15_t)(MC_SPEED_REF_MIN_Q15 + (((int32_t)p * MC_SPEED_REF_SPAN_Q15) >> 15));
}

q15_t mc_pot_to_torque(int16_t pot)
{
    q15_t p = (pot < 0) ? 0 : pot;
    return (q15_t)(((int32_t)p * MC_IQ_MAX_Q15) >> 15);
}

#if MC_DRIVE

q15_t mc_regen_limit(q15_t iq_max, q15_t vbus)
{
    int32_t over = (int32_t)vbus - (int32_t)MC_VBUS_REGEN_Q15;
    if (over <= 0) {
        return iq_max;
    }
    if (over >= (int32_t)MC_VBUS_REGEN_BAND_Q15) {
        return 0;
    }
    /* 0 < band - over < band: the product is below 2^25, and frac below
     * 32767 (band - over <= band - 1, K = 32767 * 2^10 / band rounded) */
    int32_t frac = (((int32_t)MC_VBUS_REGEN_BAND_Q15 - over) * MC_VBUS_REGEN_K) >> 10;
    return q15_mul(iq_max, (q15_t)frac);
}

uint16_t mc_stall_check(mc_stall_t *s, const mc_stall_in_t *in)
{
    uint16_t *cnt = s->cnt;
    cnt[0] = (q15_abs_sat(in->speed) < MC_STALL_SPEED_Q15) ? (uint16_t)(cnt[0] + 1U) : 0U;
    bool emf_bad = (in->emf_ratio > MC_STALL_BEMF_HI_Q12) ||
                   (!in->fw_active && in->emf_ratio < MC_STALL_BEMF_LO_Q12);
    cnt[1] = emf_bad ? (uint16_t)(cnt[1] + 1U) : 0U;
    bool track_bad = q15_abs_sat(in->speed_err) > MC_STALL_SPEED_ERR_Q15 && in->saturated != 0;
    cnt[2] = track_bad ? (uint16_t)(cnt[2] + 1U) : 0U;
    /* Reversals between the limits: the gap counts up to one past its
     * bound (a uint16 that stops there), which ends a run of them. */
    if (s->swing_gap <= MC_SWING_GAP_TICKS) {
        s->swing_gap++;
    }
    if (in->saturated != 0) {
        if (s->swing_side != 0 && in->saturated != s->swing_side) {
            s->swing_flips =
                (s->swing_gap <= MC_SWING_GAP_TICKS) ? (uint8_t)(s->swing_flips + 1U) : (uint8_t)1U;
            s->swing_gap = 0U;
        }
        s->swing_side = in->saturated;
    }
    if (cnt[0] >= MC_STALL_TICKS) {
        return MC_FAULT_STALL_SPEED;
    }
    if (cnt[1] >= MC_STALL_TICKS) {
        return MC_FAULT_STALL_BEMF;
    }
    if (cnt[2] >= MC_STALL_TRACK_TICKS) {
        return MC_FAULT_STALL_TRACK;
    }
    if (s->swing_flips >= MC_SWING_FLIPS) { /* reached at a reversal: the run is live */
        return MC_FAULT_SPEED_UNSTABLE;
    }
    return MC_FAULT_NONE;
}

/* Speed mode: the reference ramped towards the target, field weakening from
 * it (AN1078), the speed PI within what is left of the current budget. */
static void mc_slow_speed_pi(mc_slow_t *sl, const mc_slow_in_t *in, q15_t target, q15_t w,
                             dq_q15_t *ref)
{
    dq_q15_t i_ref;
    /* Ramp the reference towards the target. */
    int32_t diff = (int32_t)target - (int32_t)sl->spd_ref;
    if (diff > MC_SPEED_RAMP_STEP) {
        diff = MC_SPEED_RAMP_STEP;
    } else if (diff < -MC_SPEED_RAMP_STEP) {
        diff = -MC_SPEED_RAMP_STEP;
    }
    /* With the bus high the braking current is limited (below): the
     * reference does not run below the rotor into a speed error the loop
     * may not brake to, it follows the rotor down, and never up (a load
     * that drives the rotor above it is not followed). (The drive turns
     * forward only: references are positive, braking is negative Iq.) */
    int32_t next = (int32_t)sl->spd_ref + diff;
    if (mc_regen_limit(MC_IQ_MAX_Q15, in->vbus) < MC_IQ_MAX_Q15 && next < (int32_t)w) {
        next = (sl->spd_ref < w) ? sl->spd_ref : w;
    }
    sl->spd_ref = (q15_t)next;

    /* Field weakening from the reference (AN1078), then what is left of the
     * current budget for Iq. */
    i_ref.d = fieldweak_id_ref(&sl->fw, sl->spd_ref);
    q15_t iq_max = vlimit_vq_max(i_ref.d, MC_I_TOTAL_Q15);
    if (iq_max > MC_IQ_MAX_Q15) {
        iq_max = MC_IQ_MAX_Q15;
    }
    /* Braking (negative Iq, the rotor turning forward): at most what the
     * bus allows (mc_regen_limit). */
    pi_set_limits(&sl->pi_w, (q15_t)-mc_regen_limit(iq_max, in->vbus), iq_max);
    /* Kp and Ki scheduled on the reference: full above MOTOR_SPEED_KP_FULL_RPM,
     * proportional below it (at least MC_KP_SCHED_MIN): the estimated
     * speed is noisiest at low speed, where a full Kp turns that noise into
     * current and speed ripple. */
    q15_t sched = MC_KP_SCHED_ONE;
    if (sl->spd_ref < MC_KP_FULL_Q15) {
        int32_t f = ((int32_t)q15_abs_sat(sl->spd_ref) * MC_KP_SCHED_K) >> 15;
        sched = (f < MC_KP_SCHED_MIN) ? MC_KP_SCHED_MIN : (q15_t)f;
    }
    sl->pi_w.p.kp = q15_mul(in->spd_kp, sched);
    sl->pi_w.p.ki = q15_mul(in->spd_ki, sched);
    sl->pi_w.p.kc = in->spd_ki;
    i_ref.q = pi_update(&sl->pi_w, sl->spd_ref, w);
    /* After Iq: the floor only asks |Id| + |Iq| <= MC_ID_MIN_Q15, inside
     * the current budget the limit above was computed from. */
    i_ref.d = mc_id_floor(i_ref.d, i_ref.q);
    *ref = i_ref;
}

/* Speed-loop work of the slow step (CLOSED_LOOP): the speed from the
 * estimator's fresh result, the ramp, field weakening, the speed PI (or the
 * torque reference) and the stall check, into out. */
static void mc_slow_speed_loop(mc_slow_t *sl, const smc_result_t *est, const mc_slow_in_t *in,
                               mc_slow_out_t *out)
{
    q15_t w = est->omega;
    dq_q15_t i_ref;

    if (MC_TORQUE_MODE || in->stopping) {
        /* a torque against the rotation brakes: at most what the bus allows.
         * After a STOP: none at all, while the rotor coasts to the release
         * speed; the speed PI then resumes (S2) from zero torque and the
         * ramp from the rotor's speed. */
        q15_t brake = mc_regen_limit(MC_IQ_MAX_Q15, in->vbus);
        i_ref.q = in->stopping ? 0 : out->torque_target;
        if (in->stopping) {
            pi_preset(&sl->pi_w, 0);
            out->release = q15_abs_sat(w) <= mc_release_speed(in->vbus);
        }
        if (i_ref.q < (q15_t)-brake) {
            i_ref.q = (q15_t)-brake;
        }
        sl->spd_ref = w;
        i_ref.d = mc_id_floor(fieldweak_id_ref(&sl->fw, w), i_ref.q);
    } else {
        mc_slow_speed_pi(sl, in, out->speed_target, w, &i_ref);
    }

    /* Stall / loss of synchronisation (note 2). */
    mc_stall_in_t si;
    si.speed = w;
    si.emf_ratio = est->emf_ratio;
    /* The low back-EMF side is waived in field weakening only while the
     * estimator still vouches for its back-EMF: the linear (dead-beat)
     * observer reads the rotor flux, which Id does not weaken, so a valid
     * estimate keeps the ratio near 1 there; a rotor locked in field
     * weakening makes the estimated speed swing by thousands of rpm, so
     * neither the speed nor the tracking condition persists, and only the
     * back-EMF catches it. */
    si.fw_active = q15_abs_sat(sl->spd_ref) > mc_fw_params.speed_nominal && est->valid;
    si.speed_err = MC_TORQUE_MODE ? 0 : q15_sub_sat(sl->spd_ref, w);
    si.saturated = 0;
    if (!MC_TORQUE_MODE) {
        const pi_t *pw = &sl->pi_w;
        si.saturated = (pw->out >= pw->p.out_max) ? 1 : (pw->out <= pw->p.out_min) ? -1 : 0;
    }
    out->fault = mc_stall_check(&sl->stall, &si);
    out->i_ref = i_ref;
    out->speed_ref = sl->spd_ref;
    out->loop = true;
}

void mc_slow_init(mc_slow_t *sl)
{
    pi_init(&sl->pi_w, &mc_pi_spd_params);
    fieldweak_init(&sl->fw, &mc_fw_params);
    sl->spd_ref = MC_SPEED_REF_MIN_Q15;
}

/* OPEN_LOOP: the damping's shift of the forced angle for this window (mc.c
 * note 1), applied by the interrupt with the window's results
 * (mc_slow_apply). It moves the forced angle back by MOTOR_OL_DAMP_S times
 * the rotor's swing speed while the estimate is valid: the forced minus the
 * estimated speed less its slow mean (a high-pass, seeded at the first
 * valid window), so a steady difference, the estimate's bias under a model
 * mismatch, is no swing, and damping it takes torque the load needs. The
 * forced step is the one the interrupt will have when it applies the
 * shift, MC_SLOW_APPLY_PERIODS steps of the ramp after the window end (the
 * ramp holds at its end step), and the estimated one is what the interrupt
 * derives from the same result (mc_set_advance's pred). */
static int16_t mc_slow_ol_damp(mc_slow_t *sl, const smc_result_t *est, const mc_slow_in_t *si)
{
    int32_t shift = 0;
    if (si->state == MC_STATE_OPEN_LOOP && est->valid) {
        uint32_t step = si->ol_step + (uint32_t)MC_SLOW_APPLY_PERIODS * MC_RAMP_STEP_INC;
        if (step > MC_RAMP_STEP_END) {
            step = MC_RAMP_STEP_END;
        }
        /* forced minus estimated speed, angle counts per period (< 2^17) */
        int32_t d = (int32_t)(uint16_t)(step >> 16) - (int32_t)mc_pred_counts(est->omega);
        int32_t d16 = d * 16; /* Q4, < 2^21 */
        if (!sl->ol_dlive) {
            sl->ol_dmean = d16;
            sl->ol_dlive = true;
        }
        sl->ol_dmean += (d16 - sl->ol_dmean) / MC_OL_DAMP_MEAN_N;
        d = (d16 - sl->ol_dmean) / 16; /* |d| < 2^18: held to 2^17 so d K fits */
        if (d > 131071L) {
            d = 131071L;
        } else if (d < -131071L) {
            d = -131071L;
        }
        shift = d * MC_OL_DAMP_K / 16; /* K <= 16000: |d K| < 2^31 */
        if (shift > MC_OL_DAMP_MAX) {
            shift = MC_OL_DAMP_MAX;
        } else if (shift < -MC_OL_DAMP_MAX) {
            shift = -MC_OL_DAMP_MAX;
        }
    } else {
        sl->ol_dlive = false;
    }
    return (int16_t)shift;
}

/* One window's work on the slow step's own state, from the window's
 * inputs and the estimator's fresh result, into the results. A call, not
 * inlined into mc_slow_step: inlined, its saved registers and locals stay
 * on the stack under the estimator's slow step too, the deepest path of
 * the Timer 2 interrupt (docs/performance.md). */
static __attribute__((noinline)) void mc_slow_run(mc_slow_t *sl, const smc_result_t *est,
                                                  const mc_slow_in_t *si, mc_slow_out_t *so)
{
    if (MC_TORQUE_MODE) {
        so->speed_target = MC_SPEED_REF_MIN_Q15;
        so->torque_target = si->ref_from_remote
                                ? q15_clamp(si->ref_remote, (q15_t)(-MC_IQ_MAX_Q15), MC_IQ_MAX_Q15)
                                : mc_pot_to_torque(si->pot);
    } else {
        so->torque_target = 0;
        so->speed_target = si->ref_from_remote ? q15_clamp(si->ref_remote, MC_SPEED_REF_MIN_Q15,
                                                           MC_SPEED_REF_MAX_Q15)
                                               : mc_pot_to_speed(si->pot);
    }
    if (si->epoch != sl->epoch) {
        sl->epoch = si->epoch;
        /* a new run, or the hand-off: the dead-time measurement starts over */
        mc_dtm_reset(&sl->dtm);
        mc_sensor_reset(&sl->sensor);
        so->lock_iq = MC_LOCK_CURRENT_Q15;
        so->lock_done = false;
        if (si->preset) {
            /* Closed loop entered in this window: the speed loop starts from
             * the hand-off (mc_enter_closed_loop). */
            pi_preset(&sl->pi_w, si->preset_iq);
            sl->spd_ref = si->preset_speed_ref;
            memset(&sl->stall, 0, sizeof sl->stall);
        }
    }
    so->loop = false;
    so->fault = MC_FAULT_NONE;
    so->release = false;
    mc_sensor_window(&sl->sensor, si, so);
    /* OPEN_LOOP: the load's share of the ramp current, the measured current
     * on the estimated q axis low-passed over 32 windows (the hand-off's
     * preset, mc_enter_closed_loop). */
    if (si->state == MC_STATE_OPEN_LOOP) {
        q15_t iq = park_forward(si->i_ab, sincos_call(si->theta_est)).q;
        sl->ol_iq_acc += (int32_t)iq - sl->ol_iq_acc / 32; /* |acc| <= 32 * 32768 */
    } else {
        sl->ol_iq_acc = 0;
    }
    so->ol_iq = (q15_t)(sl->ol_iq_acc / 32);
    so->ol_shift = mc_slow_ol_damp(sl, est, si);
    if (MC_DTM_ON && si->state == MC_STATE_LOCK) {
        mc_dtm_window(&sl->dtm, si, so);
    }
    if (si->state == MC_STATE_CLOSED_LOOP) {
        mc_slow_speed_loop(sl, est, si, so);
    }
}

#endif /* MC_DRIVE */

void mc_slow_step(mc_t *mc)
{
    if (!mc->ho.busy) {
        return;
    }
#if MC_DRIVE
    smc_slow_step(&mc->smc);
    mc_slow_run(&mc->slow, &mc->smc.res, &mc->ho.in, &mc->ho.out);
#endif
#if MC_IDENTIFY
    if (mc->ho.in.state == MC_STATE_IDENTIFY) {
        mc_id_window(&mc->id, &mc->ho.in.id, mc->ho.in.vbus, &mc->id.cmd);
    }
#endif
    mc->ho.out.epoch = mc->ho.in.epoch;
    MC_BARRIER(); /* the results are written before the flag hands them back */
    mc->ho.busy = false;
}
