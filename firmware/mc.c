/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* mc.c - the motor-control core: state machine, protections, current and speed loops. */
#include <string.h>

#include "mc.h"
#include "mc_internal.h"

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
 * mc_slow_step(), once per window outside the interrupt: the estimator's
 * speed and compensation, the speed ramp, speed PI (or the torque
 * reference), field weakening, stall detection.
 * Divisions in the per-period path: atan2's ratio, the ripple gain and the
 * circle limit's square root (one div.ud each; docs/performance.md says
 * what the alternatives cost).
 */

/* ---- constant parameters (compile-time, mc_derived.h) --------------------- */

static const smc_params_t mc_smc_params = MC_SMC_PARAMS_INIT;

static const pi_params_t mc_pi_cur_params = {
    MC_CUR_KP, MC_CUR_KP_SHIFT, MC_CUR_KI, MC_PI_KC, (q15_t)(-MC_VMAX_Q15), MC_VMAX_Q15,
};

static const pi_params_t mc_pi_spd_params = {
    MC_SPD_KP, MC_SPD_KP_SHIFT, MC_SPD_KI, MC_PI_KC, (q15_t)(-MC_IQ_MAX_Q15), MC_IQ_MAX_Q15,
};

static const fieldweak_params_t mc_fw_params = {
    MC_Q15_RPM(MOTOR_SPEED_NOMINAL_RPM),
    MC_Q15_RPM(MOTOR_SPEED_FW_MAX_RPM),
    MC_FW_TABLE_Q15,
};

/* Inverse-Park advance (mc.h note 2): the sample is taken at MC_SAMPLE_AT
 * of period n, the voltage computed from it acts over the whole period n+1,
 * centred (1.5 - MC_SAMPLE_AT) Ts after the sample (0.96 Ts on the MCLV),
 * so it is rotated by that much. In binary angle counts: speed_q15 *
 * 2 (1.5 - a) omega_fs Ts (omega_fs in Hz); open loop: the forced step per
 * period times (1.5 - a). */
#define MC_ADV_PERIODS_ (1.5 - MC_SAMPLE_AT)
#define MC_ADV_K_       (2.0 * MC_ADV_PERIODS_ * MC_OMEGA_FS_HZ * MC_TS_S)
MC_CHECK(MC_SPEED_FULLSCALE_RPM, MC_ADV_K_ < 1.0,
         "the advance at full speed must be < pi (PWM too slow for the speed range)");
#define MC_ADV_K Q15(MC_ADV_K_)
/* The estimator's angle is one sample old when the current loops use it
 * (mc.h note 2): one period of the estimated speed, speed_q15 * 2
 * omega_fs Ts angle counts. */
#define MC_PRED_K_ (2.0 * MC_OMEGA_FS_HZ * MC_TS_S)
MC_CHECK(MC_SPEED_FULLSCALE_RPM, MC_PRED_K_ < 1.0,
         "one period at full speed must be < pi (PWM too slow for the speed range)");
#define MC_PRED_K      Q15(MC_PRED_K_)
#define MC_ADV_PERIODS Q15(MC_ADV_PERIODS_)
/* The open-loop step per period (binary angle counts) must stay below 2^15
 * for the advance's Q15 product: the ramp's end below half the PWM rate. */
MC_CHECK(MOTOR_RAMP_END_RPM, (double)MOTOR_RAMP_END_RPM *MOTOR_POLE_PAIRS / 60.0 * MC_TS_S < 0.5,
         "the ramp's end must be below half the PWM frequency (electrical)");

/* The voltage the current evolved under between the previous sample and
 * this one (mc.h note 2): the duty of period n-1 (computed two steps ago,
 * v_hist[1]) for the part of the interval before the boundary, 1 - a, and
 * the one of period n (computed one step ago, v_hist[0]) for the part
 * after it, a. Weights sum to exactly 1.0, so a steady voltage passes
 * unchanged. */
#define MC_VEST_W_NEW Q15(MC_SAMPLE_AT)
#define MC_VEST_W_OLD ((q15_t)(32768L - (long)MC_VEST_W_NEW))

#if MC_IDENTIFY
static const mc_id_params_t mc_id_params = MC_ID_PARAMS_INIT;
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

#define MC_TIMER_MAX 0xFFFFFFFFUL

/* A compiler barrier: the stores before it are not moved after it. Every
 * supported compiler (gcc, clang, XC16's gcc) understands it; the dsPIC
 * executes stores in order. */
#define MC_BARRIER() __asm__ __volatile__("" ::: "memory")

/* The voltage circle on the Q30 scale of a Q15 x Q15 product (note 3):
 * Vmax^2, and (7/8 Vmax)^2, past which a period's vector is near it. */
#define MC_VMAX_SQ  ((int32_t)MC_VMAX_Q15 * (int32_t)MC_VMAX_Q15)
#define MC_VNEAR_SQ ((int32_t)(MC_VMAX_Q15 * 7L / 8L) * (int32_t)(MC_VMAX_Q15 * 7L / 8L))

/* sqrt(3) / 2 and -1/2 in Q15, for the phase currents from alpha/beta. */
#define MC_SQRT3_2    Q15(0.86602540378443865)
#define MC_MINUS_HALF Q15(-0.5)

/* ---- pure helpers (mc_internal.h) ------------------------------------------ */

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

bool mc_reference_held(const mc_status_t *st, uint8_t seq)
{
    return st->ref_remote && st->ref_seq == seq;
}

uint16_t mc_stall_check(uint16_t cnt[3], const mc_stall_in_t *in)
{
    cnt[0] = (q15_abs_sat(in->speed) < MC_STALL_SPEED_Q15) ? (uint16_t)(cnt[0] + 1U) : 0U;
    bool emf_bad = (in->emf_ratio > MC_STALL_BEMF_HI_Q12) ||
                   (!in->fw_active && in->emf_ratio < MC_STALL_BEMF_LO_Q12);
    cnt[1] = emf_bad ? (uint16_t)(cnt[1] + 1U) : 0U;
    bool track_bad = q15_abs_sat(in->speed_err) > MC_STALL_SPEED_ERR_Q15 && in->saturated;
    cnt[2] = track_bad ? (uint16_t)(cnt[2] + 1U) : 0U;
    if (cnt[0] >= MC_STALL_TICKS) {
        return MC_FAULT_STALL_SPEED;
    }
    if (cnt[1] >= MC_STALL_TICKS) {
        return MC_FAULT_STALL_BEMF;
    }
    if (cnt[2] >= MC_STALL_TRACK_TICKS) {
        return MC_FAULT_STALL_TRACK;
    }
    return MC_FAULT_NONE;
}

/* ---- the mailbox ------------------------------------------------------------- */

static bool mc_take(mc_t *mc, mc_request_t r)
{
    uint8_t posted = mc->req_posted[r];
    if (posted == mc->req_taken[r]) {
        return false;
    }
    mc->req_taken[r] = posted;
    return true;
}

void mc_request(mc_t *mc, mc_request_t r)
{
    if (r == MC_REQUEST_REF_POT) {
        /* a choice of reference like mc_set_reference, on the same
         * sequence: of the two, the later one wins even within a period */
        mc->ref_to_pot = true;
        mc->ref_remote_seq = (uint8_t)(mc->ref_remote_seq + 1U);
        mc->req_seq = (uint8_t)(mc->req_seq + 1U); /* last: mc.h note 1 */
    } else if ((unsigned)r < (unsigned)MC_REQUEST_COUNT) {
        mc->req_posted[r] = (uint8_t)(mc->req_posted[r] + 1U);
        mc->req_seq = (uint8_t)(mc->req_seq + 1U); /* after the request: mc.h note 1 */
    }
}

uint8_t mc_set_reference(mc_t *mc, int16_t ref)
{
    uint8_t seq = (uint8_t)(mc->ref_remote_seq + 1U);
    mc->ref_remote = ref;
    mc->ref_to_pot = false;
    mc->ref_remote_seq = seq;
    mc->req_seq = (uint8_t)(mc->req_seq + 1U); /* last: mc.h note 1 */
    return seq;
}

bool mc_set_gain(mc_t *mc, mc_gain_t g, int16_t value)
{
    if ((unsigned)g >= (unsigned)MC_GAIN_COUNT || value < 0) {
        return false;
    }
    mc->gain_posted[g] = value;
    mc->gain_seq = (uint8_t)(mc->gain_seq + 1U);
    mc->req_seq = (uint8_t)(mc->req_seq + 1U); /* last: mc.h note 1 */
    return true;
}

int16_t mc_get_gain(const mc_t *mc, mc_gain_t g)
{
    return ((unsigned)g < (unsigned)MC_GAIN_COUNT) ? mc->gain_posted[g] : 0;
}

/* Apply the posted gains (mc.h note 3). */
static void mc_apply_gains(mc_t *mc)
{
    q15_t kp = mc->gain_posted[MC_GAIN_CUR_KP];
    q15_t ki = mc->gain_posted[MC_GAIN_CUR_KI];
    mc->pi_d.p.kp = kp;
    mc->pi_q.p.kp = kp;
    mc->pi_d.p.ki = ki;
    mc->pi_q.p.ki = ki;
    mc->pi_d.p.kc = ki;
    mc->pi_q.p.kc = ki;
    mc->spd_kp_base = mc->gain_posted[MC_GAIN_SPD_KP]; /* to the slow step at the window end */
    mc->spd_ki_base = mc->gain_posted[MC_GAIN_SPD_KI];
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
static void mc_set_advance(mc_t *mc)
{
    q15_t w = smc_omega(&mc->smc);
    mc->adv_sc = sincos_compute(q15_mul(w, MC_ADV_K));
    mc->pred = q15_mul(w, MC_PRED_K);
}

/* ---- state changes --------------------------------------------------------------- */

static void mc_prepare(mc_t *mc);

/* The states that drive the motor, outputs on: LOCK, OPEN_LOOP, CLOSED_LOOP,
 * IDENTIFY (consecutive in MC_STATE_LIST: one unsigned compare). */
Q15_STATIC_ASSERT(MC_STATE_OPEN_LOOP == MC_STATE_LOCK + 1 &&
                      MC_STATE_CLOSED_LOOP == MC_STATE_LOCK + 2 &&
                      MC_STATE_IDENTIFY == MC_STATE_LOCK + 3,
                  "mc_driving needs LOCK, OPEN_LOOP, CLOSED_LOOP, IDENTIFY consecutive");
Q15_INLINE bool mc_driving(mc_state_t s)
{
    return (unsigned)s - (unsigned)MC_STATE_LOCK <=
           (unsigned)MC_STATE_IDENTIFY - (unsigned)MC_STATE_LOCK;
}

static void mc_enter(mc_t *mc, mc_state_t s)
{
    mc->state = s;
    mc->timer = 0U;
    /* the window's voltage sums: the dead-time measurement's, the identification's */
    mc->sums_on = s == MC_STATE_IDENTIFY || (MC_DTM_ON && s == MC_STATE_LOCK);
}

/* Everything the power stage and the loops hold, back to rest. */
static void mc_outputs_off(mc_t *mc)
{
    mc->outputs_on = false;
    mc->duty[0] = PWM_DUTY_MAX / 2U;
    mc->duty[1] = PWM_DUTY_MAX / 2U;
    mc->duty[2] = PWM_DUTY_MAX / 2U;
    mc->v_dq.d = 0;
    mc->v_dq.q = 0;
    mc->i_ref.d = 0;
    mc->i_ref.q = 0;
    mc->v_hist[0].alpha = 0;
    mc->v_hist[0].beta = 0;
    mc->v_hist[1] = mc->v_hist[0];
    pi_reset(&mc->pi_d);
    pi_reset(&mc->pi_q);
    mc->epoch = (uint8_t)(mc->epoch + 1U); /* the slow step's results of this run are void */
    mc->preset_pending = false;
#if MC_IDENTIFY
    mc->id_inj = 0;
    mc->ol_inc = 0U;
#endif
}

static void mc_id_stop(mc_t *mc, uint16_t error);

/* FAULT's entry: the cause recorded, the outputs off. */
static void mc_enter_fault(mc_t *mc, uint16_t code)
{
    mc->fault = code;
    mc_id_stop(mc, MC_ID_ERROR_FAULT);
    mc_outputs_off(mc);
    mc_enter(mc, MC_STATE_FAULT);
}

/* A fault raised in any state; in FAULT the first cause stays. */
static void mc_fault(mc_t *mc, uint16_t code)
{
    if (mc->state != MC_STATE_FAULT) {
        mc_enter_fault(mc, code);
    }
}

/* CALIBRATE, after coasting for `wait` periods. */
static void mc_begin_calibration(mc_t *mc, uint16_t wait)
{
    mc_outputs_off(mc);
    mc->calib_wait = wait;
    mc->offset_acc_a = 0;
    mc->offset_acc_b = 0;
    mc_enter(mc, MC_STATE_CALIBRATE);
}

static void mc_stop(mc_t *mc)
{
    mc_id_stop(mc, MC_ID_ERROR_ABORTED);
    mc_outputs_off(mc);
    mc_enter(mc, MC_STATE_STOPPED);
}

static void mc_enter_lock(mc_t *mc)
{
    pi_reset(&mc->pi_d);
    pi_reset(&mc->pi_q);
    smc_reset(&mc->smc);
    mc_set_advance(mc);
    mc->epoch = (uint8_t)(mc->epoch + 1U);
    mc->ol_angle = 0U;
    mc->ol_damp = 0;
    mc->ol_dlive = false;
    mc->ol_dmean = 0;
    mc->agree = 0U;
    mc->ol_iq = 0;
    mc->lock_done = false;
    mc->lock_va = 0;
    mc->lock_vb = 0;
    mc->ol_step = 0U;
    mc->theta = 0;
    mc->theta_offset = 0;
    /* AN1078: the torque current at a fixed angle; the rotor settles with
     * its d axis on the current vector, 90 degrees ahead of the forced d
     * axis, which is where the ramp's load angle starts from. */
    mc->i_ref.d = 0;
    mc->i_ref.q = MC_LOCK_CURRENT_Q15;
    mc_enter(mc, MC_STATE_LOCK);
    mc_prepare(mc); /* the outputs turn on with the lock's first period */
}

/* Id reference with the light-load floor (UserParms.h MC_ID_MIN_A): at
 * least MC_ID_MIN_Q15 - |iq| of negative Id, so the current vector is never
 * shorter than MC_ID_MIN_Q15 / sqrt 2 and the phase currents stay outside
 * the dead-time band, where the inverter's voltage loss depends only on
 * the current's sign and the estimator's applied voltage is exact. Under
 * load (|iq| >= MC_ID_MIN_Q15) it is off and costs no torque. id <= 0
 * (field weakening), |iq| <= 32767: no overflow. */
static q15_t mc_id_floor(q15_t id, q15_t iq)
{
    int32_t f = (int32_t)MC_ID_MIN_Q15 - (int32_t)q15_abs_sat(iq); /* > -32768 */
    return ((int32_t)id > -f) ? (q15_t)(-f) : id;
}

static void mc_enter_closed_loop(mc_t *mc)
{
    angle_q15_t est = smc_theta(&mc->smc);
    /* The forced angle stays the reference; the difference is bled off. */
    mc->theta_offset = angle_sub(mc->theta, est);
    /* The rotor turns at the forced speed on average; the estimator's
     * window speed is noisier than that, so both start from it. */
    smc_preset_speed(&mc->smc, MC_RAMP_END_Q15);
    mc_set_advance(mc);
    mc->speed_ref =
        (MC_RAMP_END_Q15 < MC_SPEED_REF_MIN_Q15) ? MC_SPEED_REF_MIN_Q15 : MC_RAMP_END_Q15;
    /* The speed PI starts from the load's share of the ramp current, the
     * measured current on the estimated q axis low-passed over 32 windows
     * by the slow step (ol_iq), plus a quarter of the ramp current, within
     * 0..I_ramp: one sample swings with the rotor about the forced angle,
     * the low-passed one alone falls short of a stick-slip load, and the
     * whole ramp current (AN1078's preset) overshoots an unloaded motor
     * (docs/tuning.md, "Behind the defaults"). The slow step presets the PI
     * with it; until its first result arrives, the references are what the
     * preset PI puts out. */
    mc->i_ref.q =
        q15_clamp(q15_add_sat(mc->ol_iq, (q15_t)(MC_RAMP_CURRENT_Q15 / 4)), 0, MC_RAMP_CURRENT_Q15);
    mc->i_ref.d = mc_id_floor(0, mc->i_ref.q); /* what the first speed-loop run will set */
    mc->epoch = (uint8_t)(mc->epoch + 1U);
    mc->preset_pending = true;
    mc->preset_iq = mc->i_ref.q;
    mc->preset_speed_ref = mc->speed_ref;
    mc_enter(mc, MC_STATE_CLOSED_LOOP);
}

/* ---- pieces of the step ---------------------------------------------------------------- */

/* Speed-loop work of the slow step (CLOSED_LOOP): the speed from the
 * estimator's fresh result, the ramp, field weakening, the speed PI (or the
 * torque reference) and the stall check, into out. */
static void mc_slow_speed_loop(mc_t *mc, const smc_result_t *est, mc_slow_out_t *out)
{
    q15_t w = est->omega;
    dq_q15_t i_ref;

#if defined(TORQUEMODE)
    i_ref.q = out->torque_target;
    mc->spd_ref = w;
    i_ref.d = mc_id_floor(fieldweak_id_ref(&mc->fw, w), i_ref.q);
#else
    /* Ramp the reference towards the target. */
    int32_t diff = (int32_t)out->speed_target - (int32_t)mc->spd_ref;
    if (diff > MC_SPEED_RAMP_STEP) {
        diff = MC_SPEED_RAMP_STEP;
    } else if (diff < -MC_SPEED_RAMP_STEP) {
        diff = -MC_SPEED_RAMP_STEP;
    }
    mc->spd_ref = (q15_t)((int32_t)mc->spd_ref + diff);

    /* Field weakening from the reference (AN1078), then what is left of the
     * current budget for Iq. */
    i_ref.d = fieldweak_id_ref(&mc->fw, mc->spd_ref);
    q15_t iq_max = vlimit_vq_max(i_ref.d, MC_I_TOTAL_Q15);
    if (iq_max > MC_IQ_MAX_Q15) {
        iq_max = MC_IQ_MAX_Q15;
    }
    pi_set_limits(&mc->pi_w, (q15_t)(-iq_max), iq_max);
    /* Kp and Ki scheduled on the reference: full above MOTOR_SPEED_KP_FULL_RPM,
     * proportional below it (at least MC_KP_SCHED_MIN): the estimated
     * speed is noisiest at low speed, where a full Kp turns that noise into
     * current and speed ripple. */
    q15_t sched = MC_KP_SCHED_ONE;
    if (mc->spd_ref < MC_KP_FULL_Q15) {
        int32_t f = ((int32_t)q15_abs_sat(mc->spd_ref) * MC_KP_SCHED_K) >> 15;
        sched = (f < MC_KP_SCHED_MIN) ? MC_KP_SCHED_MIN : (q15_t)f;
    }
    mc->pi_w.p.kp = q15_mul(mc->slow_in.spd_kp, sched);
    mc->pi_w.p.ki = q15_mul(mc->slow_in.spd_ki, sched);
    mc->pi_w.p.kc = mc->slow_in.spd_ki;
    i_ref.q = pi_update(&mc->pi_w, mc->spd_ref, w);
    /* After Iq: the floor only asks |Id| + |Iq| <= MC_ID_MIN_Q15, inside
     * the current budget the limit above was computed from. */
    i_ref.d = mc_id_floor(i_ref.d, i_ref.q);
#endif

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
    si.fw_active = q15_abs_sat(mc->spd_ref) > mc_fw_params.speed_nominal && est->valid;
#if defined(TORQUEMODE)
    si.speed_err = 0;
    si.saturated = false;
#else
    si.speed_err = q15_sub_sat(mc->spd_ref, w);
    si.saturated = pi_at_limit(&mc->pi_w);
#endif
    out->fault = mc_stall_check(mc->stall_cnt, &si);
    out->i_ref = i_ref;
    out->speed_ref = mc->spd_ref;
    out->loop = true;
}

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
    smc_update(&mc->smc, mc->i_ab, v);
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

/* The q current PI's step against +-vq_max (the circle limit, note 3). Its
 * three call sites are the three ways to that limit: each inlined, so the
 * near-circle path does not pay for saving the integral the redo needs. */
Q15_INLINE q15_t mc_q_step(mc_t *mc, q15_t ref_q, q15_t vq_max)
{
    pi_set_limits(&mc->pi_q, (q15_t)(-vq_max), vq_max);
    return pi_update(&mc->pi_q, ref_q, mc->i_dq.q);
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
        ref = park_forward(r, sincos_compute(mc->theta_offset));
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
    v.d = pi_update(&mc->pi_d, ref.d, mc->i_dq.d);
    if (near) {
        v.q = mc_q_step(mc, ref.q, vlimit_vq_max(v.d, MC_VMAX_Q15));
    } else {
        q31_t sum_q = mc->pi_q.sum;
        v.q = mc_q_step(mc, ref.q, MC_VMAX_Q15);
        if (q15_dsp_mulss(v.q, v.q) > MC_VMAX_SQ - q15_dsp_mulss(v.d, v.d)) {
            mc->pi_q.sum = sum_q;
            v.q = mc_q_step(mc, ref.q, vlimit_vq_max(v.d, MC_VMAX_Q15));
            if (mc->circle_redos != UINT16_MAX) {
                mc->circle_redos++;
            }
        }
    }
#if defined(ENVOLTRIPPLE)
    /* The gain mc_prepare formed from the previous sample's bus. */
    v.d = ripple_apply(v.d, mc->ripple_gain);
    v.q = ripple_apply(v.q, mc->ripple_gain);
#endif
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
    int16_t dt0 = mc_deadtime_counts(iph[0], mc->dt_counts, mc->dt_slope);
    int16_t dt1 = mc_deadtime_counts(iph[1], mc->dt_counts, mc->dt_slope);
    int16_t dt2 = mc_deadtime_counts(iph[2], mc->dt_counts, mc->dt_slope);
    int16_t d0 = (int16_t)sv.duty[0];
    int16_t d1 = (int16_t)sv.duty[1];
    int16_t d2 = (int16_t)sv.duty[2];
#if MC_DEADTIME_COMP
    d0 = (int16_t)(d0 + dt0);
    d1 = (int16_t)(d1 + dt1);
    d2 = (int16_t)(d2 + dt2);
#endif
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
static void mc_prepare(mc_t *mc)
{
    angle_q15_t th;
    sincos_q15_t sc;
    if (mc->state == MC_STATE_CLOSED_LOOP) {
        int16_t off = mc->theta_offset;
        if (off > MC_BLEED_STEP) {
            off = (int16_t)(off - MC_BLEED_STEP);
        } else if (off < -MC_BLEED_STEP) {
            off = (int16_t)(off + MC_BLEED_STEP);
        } else {
            off = 0;
        }
        mc->theta_offset = off;
        th = angle_add(angle_add(smc_theta(&mc->smc), off), mc->pred);
        sc = sincos_compute(th);
        mc->scv_next = mc_advance(sc, mc->adv_sc);
    } else if (mc->state == MC_STATE_OPEN_LOOP) {
        th = mc_forced_angle(mc, MC_RAMP_STEP_INC, &sc);
#if MC_IDENTIFY
    } else if (mc->state == MC_STATE_IDENTIFY) {
        th = mc_forced_angle(mc, mc->ol_inc, &sc);
#endif
    } else { /* LOCK */
        th = 0;
        sc = sincos_compute(th);
        mc->scv_next = sc;
    }
    mc->theta_next = th;
    mc->sc_next = sc;
#if defined(ENVOLTRIPPLE)
    mc->ripple_gain = ripple_gain(mc->vbus, MC_VBUS_NOMINAL_Q15);
#endif
}

/* ---- identification (mc_id.h) ----------------------------------------------------------- */

#if MC_IDENTIFY

/* The sequence's command (mc_id_cmd_t) into the interrupt's loops: at
 * IDENTIFY's entry and MC_SLOW_APPLY_PERIODS after each window end. An open
 * loop sets the PIs' integrals to the voltage (and the injection's present
 * half); the first closed-loop command keeps them (a bumpless hand-over). */
static void mc_id_apply(mc_t *mc, const mc_id_cmd_t *c)
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
        q15_t inj = (c->inj != 0 && mc->id_sign < 0) ? (q15_t)(-c->inj) : c->inj;
        mc->pi_d.sum = (q31_t)(c->v_d + ((c->inj_q == 0U) ? inj : 0)) * 65536L;
        mc->pi_q.sum = (q31_t)(c->v_q + ((c->inj_q != 0U) ? inj : 0)) * 65536L;
    } else if (mc->id_open) {
        mc->pi_d.sum = (q31_t)c->v_d * 65536L;
        mc->pi_q.sum = 0;
    }
    mc->id_open = c->open_loop;
    if (c->inj_q != mc->id_inj_q || c->inj_half != mc->id_half) {
        mc->id_cnt = 0U;
    }
    mc->id_inj = c->inj;
    mc->id_inj_q = c->inj_q;
    mc->id_half = c->inj_half;
    mc->i_ref = c->i_ref;
    mc->ol_inc = (uint32_t)c->accel;
    if (c->dt_counts != mc->dt_counts) {
        mc->dt_counts = c->dt_counts;
        mc->dt_slope = mc_deadtime_slope(c->dt_counts);
    }
}

/* IDENTIFY, after CALIBRATE: the rotor's expected axis (d) on beta, the
 * dead time uncompensated while it is measured (mc_id.c note 4). */
static void mc_enter_identify(mc_t *mc)
{
    mc_id_cmd_t cmd;
    mc->id_pending = false;
    pi_reset(&mc->pi_d);
    pi_reset(&mc->pi_q);
    mc->epoch = (uint8_t)(mc->epoch + 1U);
    mc->ol_angle = 0x40000000UL; /* 90 degrees */
    mc->ol_damp = 0;
    mc->ol_step = 0U;
    mc->theta_offset = 0;
    mc->id_sign = 1;
    mc->id_z = 1;
    mc->id_z2 = 1;
    mc->id_i_prev = 0;
    mc->id_u_prev = 0;
    mc->id_open = true;
    memset(&mc->id_win, 0, sizeof mc->id_win);
    mc->lock_va = 0;
    mc->lock_vb = 0;
    mc_id_begin(&mc->id, &mc_id_params, &cmd);
    mc_id_apply(mc, &cmd);
    mc_enter(mc, MC_STATE_IDENTIFY);
    mc_prepare(mc); /* the outputs turn on with the next period */
}

/* An identification ended, or was ended (error: MC_ID_ERROR_*, NONE when
 * the sequence finished): the status for mc_identify_result, the loops
 * back to the build's gains and dead time. Any state may call it; only a
 * run that is going changes. */
static void mc_id_stop(mc_t *mc, uint16_t error)
{
    if (mc->state != MC_STATE_IDENTIFY && !mc->id_pending) {
        return;
    }
    mc->id_pending = false;
    mc->id_error = error;
    mc->id_status = (error == MC_ID_ERROR_NONE) ? MC_ID_DONE : MC_ID_FAILED;
    mc_apply_gains(mc);
    mc->pi_d.p.kp_shift = MC_CUR_KP_SHIFT;
    mc->pi_q.p.kp_shift = MC_CUR_KP_SHIFT;
    mc->dt_counts = MC_DT_COUNTS;
    mc->dt_slope = MC_DT_SLOPE;
}

/* IDENTIFY's work in each period after the duties (mc_step_finish, after
 * mc_estimate): the window's sums and the injected square wave (mc_id.c
 * note 2). v_hist[1] is the command of the period before, id_u_prev the
 * one before that: over the interval that ends at this sample they acted
 * for MC_SAMPLE_AT and 1 - MC_SAMPLE_AT of a period (mc.h note 2). The
 * injected axis in the stationary frame: d is beta and q -alpha (an axis's
 * sign drops out of its ratio). The two commands are summed apart: how
 * much each moves the current depends on L / R (mc_identify_result). */
Q15_INLINE void mc_id_period(mc_t *mc)
{
    mc_id_win_t *w = &mc->id_win;
    w->i_d += mc->i_dq.d;
    w->i_q += mc->i_dq.q;
    w->u_d += mc->pi_d.out;
    w->u_q += mc->pi_q.out;
    if (mc->id_inj != 0) {
        bool q = mc->id_inj_q != 0U;
        q15_t un = q ? mc->v_hist[1].alpha : mc->v_hist[1].beta;
        q15_t uo = mc->id_u_prev;
        q15_t i = q ? mc->i_ab.alpha : mc->i_ab.beta;
        q15_t ip = mc->id_i_prev;
        /* z: the injected square wave as it acts over this interval, the
         * same weights (Q15): +-1, or +-(W_NEW - W_OLD) across a reversal;
         * w: its sign a quarter cycle earlier, in phase with the current */
        q15_t z = (mc->id_z == mc->id_z2) ? (q15_t)(mc->id_z * 32767)
                                          : (q15_t)(mc->id_z * (MC_VEST_W_NEW - MC_VEST_W_OLD));
        mc->id_u_prev = un;
        mc->id_i_prev = i;
        w->c[0] += q15_dsp_mulss(z, i) >> 15;
        w->c[1] += q15_dsp_mulss(z, ip) >> 15;
        w->c[2] += q15_dsp_mulss(z, un) >> 15;
        w->c[3] += q15_dsp_mulss(z, uo) >> 15;
        if (((mc->id_zh >> (mc->id_half / 2U)) & 1U) != 0U) {
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
        mc->id_zh = (mc->id_zh << 1) | (uint32_t)(mc->id_z > 0);
        mc->id_z2 = mc->id_z;
        mc->id_z = mc->id_sign; /* the sign this period's command carries */
        if (++mc->id_cnt >= mc->id_half) {
            pi_t *pi = q ? &mc->pi_q : &mc->pi_d;
            q31_t step = (q31_t)mc->id_inj * 131072L; /* 2 x inj, Q31 */
            mc->id_cnt = 0U;
            mc->id_sign = (int8_t)-mc->id_sign;
            pi->sum = q31_add_sat(pi->sum, (mc->id_sign > 0) ? step : -step);
        }
    }
}
#else
/* No identification in this build: nothing ever runs to stop. */
static void mc_id_stop(mc_t *mc, uint16_t error)
{
    (void)mc;
    (void)error;
}
#endif /* MC_IDENTIFY */

/* CALIBRATE: after calib_wait periods of coasting, sum the two current
 * readings over MC_CALIB_PERIODS (mc_calibrate, before the duties); the
 * period that took the last one ends it after the duties
 * (mc_calibrate_end, from mc_step_finish), so its divisions and the lock's
 * preparation never delay a duty write. */
static void mc_calibrate(mc_t *mc, const mc_adc_frame_t *in)
{
    if (mc->timer >= mc->calib_wait && mc->timer - mc->calib_wait < (uint32_t)MC_CALIB_PERIODS) {
        mc->offset_acc_a += in->ia;
        mc->offset_acc_b += in->ib;
    }
}

/* The offsets, then LOCK from the next period, or FAULT OFFSET. Called
 * once, with mc->timer already counting the period that took the last
 * sample. */
static void mc_calibrate_end(mc_t *mc)
{
    /* Two divisions per start, not per period: the mean of
     * MC_CALIB_PERIODS <= 32767 int16 samples fits div.sd. */
    mc->offset_a = q15_dsp_divsd(mc->offset_acc_a, (int16_t)MC_CALIB_PERIODS);
    mc->offset_b = q15_dsp_divsd(mc->offset_acc_b, (int16_t)MC_CALIB_PERIODS);
    if (q15_abs_sat(mc->offset_a) > MC_OFFSET_MAX_Q15 ||
        q15_abs_sat(mc->offset_b) > MC_OFFSET_MAX_Q15) {
        mc->offset_a = 0;
        mc->offset_b = 0;
        mc_fault(mc, MC_FAULT_OFFSET);
        return;
    }
#if MC_IDENTIFY
    if (mc->id_pending) {
        mc_enter_identify(mc);
        return;
    }
#endif
    mc_enter_lock(mc);
}

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

/* The phase balance (note 5), CLOSED_LOOP, once per window: true when the
 * two measured phases' mean squares differ by more than 8:1 while the larger
 * is above MC_SENSOR_BAL_FLOOR (a quarter of the error floor, squared). A
 * turning rotor's healthy phases carry the same RMS current; a stuck, open
 * or dead sensor's reading stops following its phase. */
static bool mc_sensor_unbalanced(mc_t *mc, const mc_slow_in_t *si)
{
    /* halves of ia = alpha and ib = sqrt3/2 beta - alpha/2 (Q15, |.| < 2^15) */
    q15_t ah = (q15_t)(si->i_ab.alpha / 2);
    q15_t bh = q15_sub_sat(q15_mul(si->i_ab.beta, MC_SQRT3_2 / 2), (q15_t)(si->i_ab.alpha / 4));
    q15_t r = (q15_t)(q15_abs_sat(si->speed_est) % MC_SENSOR_BAL_SYNC16);
    int32_t big, small;
    /* squares of the halves, Q15: <= 2^13; the filters stay below 2^(13 + MC_SENSOR_BAL_SHIFT) */
    mc->sens_sa += (int32_t)q15_mul(ah, ah) - (mc->sens_sa >> MC_SENSOR_BAL_SHIFT);
    mc->sens_sb += (int32_t)q15_mul(bh, bh) - (mc->sens_sb >> MC_SENSOR_BAL_SHIFT);
    if (r < MC_SENSOR_BAL_BAND16 || r > MC_SENSOR_BAL_UPPER16) {
        return false; /* one sample per window cannot tell the phases apart here */
    }
    if (mc->sens_bal_n < 2U << MC_SENSOR_BAL_SHIFT) {
        mc->sens_bal_n++; /* the filters fill from 0 in CLOSED_LOOP's first windows */
        return false;
    }
    big = (mc->sens_sa > mc->sens_sb) ? mc->sens_sa : mc->sens_sb;
    small = (mc->sens_sa > mc->sens_sb) ? mc->sens_sb : mc->sens_sa;
    return big >> MC_SENSOR_BAL_SHIFT > MC_SENSOR_BAL_FLOOR && small < big / 8;
}

/* Current-sensor plausibility, once per window (note 5): did the measured
 * current follow the current loops? */
static void mc_slow_sensor(mc_t *mc, const mc_slow_in_t *si, mc_slow_out_t *so)
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
        mc->sens_sa = 0;
        mc->sens_sb = 0;
        mc->sens_bal_n = 0U;
        mc->sens_emf_low = 0U;
    }
    if (!mc_driving(si->state) || si->state == MC_STATE_IDENTIFY) {
        mc->sens_cnt = 0U;
        so->sensor_fault = false;
        return;
    }
    if (si->state != MC_STATE_CLOSED_LOOP) {
        /* at the start, over MC_SENSOR_START_WINDOWS windows too */
        mc->sens_fd += (ed - mc->sens_fd) / MC_SENSOR_START_WINDOWS;
        mc->sens_fq += (eq - mc->sens_fq) / MC_SENSOR_START_WINDOWS;
        ed = mc->sens_fd;
        eq = mc->sens_fq;
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
        unbalanced = mc_sensor_unbalanced(mc, si);
    }
    /* A rotor stopped in CLOSED_LOOP (locked, stalled) leaves the
     * estimate spinning with no back-EMF behind it: the frame turns under
     * the current loops and their errors look like a failed sensor's. The
     * stall check owns that case; while the back-EMF has read below
     * MC_STALL_BEMF_LO_Q12 of the speed's for MC_SENSOR_DEFER_WINDOWS
     * windows running, a failing window is held, neither counted nor
     * forgiven. A failed sensor on a turning rotor leaves its back-EMF
     * behind (the ratio swings, it does not stay low). */
    if (si->state == MC_STATE_CLOSED_LOOP && si->emf_ratio < MC_STALL_BEMF_LO_Q12) {
        if (mc->sens_emf_low < MC_SENSOR_DEFER_WINDOWS) {
            mc->sens_emf_low++;
        }
    } else {
        mc->sens_emf_low = 0U;
    }
    if (unbalanced) {
        bad = true; /* a stopped rotor's healthy phases stay balanced: no deferring */
    } else if (bad && mc->sens_emf_low >= MC_SENSOR_DEFER_WINDOWS) {
        bad = false;
        hold = true;
    }
    if (bad && MC_SENSOR_CHECK) {
        if (mc->sens_cnt < MC_SENSOR_TRIP) {
            mc->sens_cnt = (uint8_t)(mc->sens_cnt + 2U);
        }
    } else if (mc->sens_cnt > 0U && !hold) {
        mc->sens_cnt--;
    }
    so->sensor_fault = mc->sens_cnt >= MC_SENSOR_TRIP;
}

/* The dead-time measurement's phases (note 4). */
enum {
    MC_DTM_ALIGN, /* the lock proper, MC_LOCK_PERIODS */
    MC_DTM_WAIT1, /* at the lock current, until the swing reverses */
    MC_DTM_ACC1,  /* averaging, to a reversal at least MC_DTM_N periods on */
    MC_DTM_SETTLE2,
    MC_DTM_WAIT2, /* at 3/4 of it */
    MC_DTM_ACC2,
    MC_DTM_DONE /* OPEN_LOOP next */
};

#if MC_DTM_ON
/* LOCK, once per window in the slow step (note 4). The rotor's swing
 * reverses where the estimator's alpha voltage (its back-EMF), summed over
 * the window (a 1 ms mean, which also smooths the chatter an inverter with
 * a sharp dead-time edge puts on phase A, whose current sits at zero),
 * crosses its mean over MC_DTM_MEAN windows (the offset phase A's loss
 * leaves in it). Each level's average runs between two reversals, or gives
 * up waiting after MC_DTM_WAIT windows. so->lock_iq is the lock's current
 * reference; so->lock_done, with the dead time, ends the lock. */
static void mc_slow_deadtime(mc_t *mc, const mc_slow_in_t *si, mc_slow_out_t *so)
{
    int32_t a = si->lock_va; /* |.| <= MC_SLOW_STEP_PERIODS x 2^15 */
    mc->dtm_mean += a - mc->dtm_mean / MC_DTM_MEAN;
    bool pos = a >= mc->dtm_mean / MC_DTM_MEAN;
    bool rev = pos != mc->dtm_pos;
    mc->dtm_pos = pos;
    mc->dtm_cnt++;
    switch (mc->dtm_phase) {
        case MC_DTM_ALIGN:
            /* the first window may start within the lock's last MC_DTM_WAIT windows */
            if (si->timer + (uint32_t)MC_DTM_WAIT * MC_SLOW_STEP_PERIODS >=
                (uint32_t)MC_LOCK_PERIODS) {
                mc->dtm_phase = MC_DTM_WAIT1;
                mc->dtm_cnt = 0U;
            }
            break;
        case MC_DTM_WAIT1:
        case MC_DTM_WAIT2:
            if (rev || mc->dtm_cnt >= MC_DTM_WAIT) {
                mc->dtm_slow |= !rev;
                mc->dtm_phase++;
                mc->dtm_cnt = 0U;
                mc->dtm_sum = 0;
                mc->dtm_hi = a; /* each level's own range: its alpha level differs */
                mc->dtm_lo = a;
            }
            break;
        case MC_DTM_SETTLE2:
            if (mc->dtm_cnt >= MC_DTM_SETTLE) {
                mc->dtm_phase = MC_DTM_WAIT2;
                mc->dtm_cnt = 0U;
            }
            break;
        case MC_DTM_ACC1:
        case MC_DTM_ACC2:
            mc->dtm_sum += si->lock_vb;
            mc->dtm_hi = (a > mc->dtm_hi) ? a : mc->dtm_hi;
            mc->dtm_lo = (a < mc->dtm_lo) ? a : mc->dtm_lo;
            /* at least MC_DTM_N windows, and not before the lock's end */
            if (mc->dtm_cnt >= MC_DTM_N && si->timer >= (uint32_t)MC_LOCK_PERIODS &&
                (rev || mc->dtm_cnt >= MC_DTM_N + 2U * MC_DTM_WAIT)) {
                mc->dtm_slow |= !rev;
                /* the mean of <= 32767 Q15 samples (mc_derived.h) fits div.sd */
                q15_t u = q15_dsp_divsd(mc->dtm_sum, (int16_t)(mc->dtm_cnt * MC_SLOW_STEP_PERIODS));
                mc->dtm_cnt = 0U;
                if (mc->dtm_phase == MC_DTM_ACC1) {
                    mc->dtm_u1 = u;
                    mc->dtm_range1 = mc->dtm_hi - mc->dtm_lo;
                    so->lock_iq = MC_DTM_CURRENT_Q15;
                    mc->dtm_phase = MC_DTM_SETTLE2;
                } else {
                    /* The model's dead-time voltage on beta: phase B
                     * carries +sqrt(3)/2 of the lock current, C -sqrt(3)/2,
                     * both outside the band (mc_derived.h). */
                    int16_t dv[3];
                    dv[0] = 0;
                    dv[1] = si->dt_counts;
                    dv[2] = (int16_t)(-si->dt_counts);
                    q15_t d = mc_duty_to_voltage(dv, si->vbus).beta;
                    int32_t avg = 4 * (int32_t)u - 3 * (int32_t)mc->dtm_u1;
                    /* A swing too slow to reverse within the windows
                     * leaves its back-EMF in them: unless the rotor was
                     * nearly still (at each level, the alpha voltage's
                     * range within 1/16 of the dead-time voltage, i.e.
                     * the sums' within MC_SLOW_STEP_PERIODS / 16 of it:
                     * its swing then moves the result by well under 1 %),
                     * the dead time in use is kept. */
                    int32_t range = mc->dtm_hi - mc->dtm_lo;
                    range = (range > mc->dtm_range1) ? range : mc->dtm_range1;
                    bool still = range * 16 < (int32_t)d * (int32_t)MC_SLOW_STEP_PERIODS;
                    int16_t dt = (mc->dtm_slow && !still)
                                     ? si->dt_counts
                                     : mc_deadtime_from_lock(si->dt_counts, avg, d);
                    so->dt_counts = dt;
                    so->dt_slope = mc_deadtime_slope(dt); /* dt < MC_DT_BAND_Q15 */
                    so->lock_done = true;
                    mc->dtm_phase = MC_DTM_DONE;
                }
            }
            break;
        default:
            break;
    }
}
#define MC_LOCK_DONE(mc) ((mc)->lock_done)
#else
#define MC_LOCK_DONE(mc) ((mc)->timer >= MC_LOCK_PERIODS)
#endif

/* OPEN_LOOP at the end speed: hold it until the estimate is valid, for at
 * most MC_HANDOFF_WAIT_PERIODS (note 1), then retry or fault. */
static void mc_ramp_end(mc_t *mc)
{
    mc->ol_step = MC_RAMP_STEP_END;
    /* the estimated speed within the tolerance of the forced one, counts per period */
    int32_t step = (int32_t)(uint16_t)(MC_RAMP_STEP_END >> 16);
    int32_t diff = (int32_t)mc->pred - step;
    bool agrees = smc_valid(&mc->smc) && diff * 256 <= step * MC_HANDOFF_TOL_Q8 &&
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

/* ---- the seam ------------------------------------------------------------------------------ */

void mc_init(mc_t *mc)
{
    memset(mc, 0, sizeof(*mc));
    pi_init(&mc->pi_d, &mc_pi_cur_params);
    pi_init(&mc->pi_q, &mc_pi_cur_params);
    pi_init(&mc->pi_w, &mc_pi_spd_params);
    fieldweak_init(&mc->fw, &mc_fw_params);
    smc_init(&mc->smc, &mc_smc_params);
    mc->gain_posted[MC_GAIN_CUR_KP] = MC_CUR_KP;
    mc->gain_posted[MC_GAIN_CUR_KI] = MC_CUR_KI;
    mc->gain_posted[MC_GAIN_SPD_KP] = MC_SPD_KP;
    mc->gain_posted[MC_GAIN_SPD_KI] = MC_SPD_KI;
    mc->spd_kp_base = MC_SPD_KP;
    mc->spd_ki_base = MC_SPD_KI;
    mc->speed_ref = MC_SPEED_REF_MIN_Q15;
    mc->speed_target = MC_SPEED_REF_MIN_Q15;
    mc->spd_ref = MC_SPEED_REF_MIN_Q15;
    mc->ripple_gain = RIPPLE_ONE;
    mc->dt_counts = MC_DT_COUNTS;
    mc->dt_slope = MC_DT_SLOPE;
    mc_outputs_off(mc);
    mc->slow_epoch = mc->epoch;
    mc->fault = MC_FAULT_NONE;
    mc_enter(mc, MC_STATE_STOPPED);
}

/* OPEN_LOOP, with the estimator's speed fresh (mc_slow_apply): the forced
 * angle moved back by MOTOR_OL_DAMP_S times the rotor's swing speed while
 * the estimate is valid (note 1), the previous shift taken out. The swing
 * speed is forced minus estimated speed less its slow mean (a high-pass,
 * seeded at the first valid window): a steady difference, the estimate's
 * bias under a model mismatch, is no swing, and damping it takes torque
 * the load needs. */
static void mc_ol_damp(mc_t *mc)
{
    int32_t shift = 0;
    if (smc_valid(&mc->smc)) {
        /* forced minus estimated speed, angle counts per period (< 2^17) */
        int32_t d = (int32_t)(uint16_t)(mc->ol_step >> 16) - (int32_t)mc->pred;
        int32_t d16 = d * 16; /* Q4, < 2^21 */
        if (!mc->ol_dlive) {
            mc->ol_dmean = d16;
            mc->ol_dlive = true;
        }
        mc->ol_dmean += (d16 - mc->ol_dmean) / MC_OL_DAMP_MEAN_N;
        d = (d16 - mc->ol_dmean) / 16; /* |d| < 2^18: held to 2^17 so d K fits */
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
        mc->ol_dlive = false;
    }
    mc->ol_angle += (uint32_t)(shift - (int32_t)mc->ol_damp) << 16;
    mc->ol_damp = (int16_t)shift;
}

/* Current-sensor plausibility (note 5), every period with the outputs
 * on: the window's sums of the current error and of the periods with the
 * q PI at its voltage limit, for the slow step (mc_slow_sensor). */
Q15_INLINE void mc_sensor_sum(mc_t *mc)
{
    mc->sens_d += (int32_t)mc->i_ref_frame.d - (int32_t)mc->i_dq.d;
    mc->sens_q += (int32_t)mc->i_ref_frame.q - (int32_t)mc->i_dq.q;
    if (pi_at_limit(&mc->pi_q)) {
        mc->sens_qsat++;
    }
}

/* MC_SLOW_APPLY_PERIODS after a window end (mc.h note 4): the slow step's
 * results in. */
static void mc_slow_apply(mc_t *mc)
{
    const mc_slow_out_t *so = &mc->slow_out;
    if (mc->slow_busy) {
        mc_fault(mc, MC_FAULT_OVERRUN); /* the slow step has not finished in time */
        return;
    }
    if (!mc->slow_posted) {
        return; /* no window posted since mc_init */
    }
    smc_apply(&mc->smc);
    mc_set_advance(mc);
    if (mc->state == MC_STATE_OPEN_LOOP) {
        mc_ol_damp(mc);
        mc->ol_iq = so->ol_iq;
    }
    mc->speed_target = so->speed_target;
    mc->torque_target = so->torque_target;
#if MC_DTM_ON
    if (mc->state == MC_STATE_LOCK && so->epoch == mc->epoch) {
        mc->i_ref.q = so->lock_iq;
        if (so->lock_done) {
            mc->dt_counts = so->dt_counts;
            mc->dt_slope = so->dt_slope;
            mc->lock_done = true; /* OPEN_LOOP from the next period */
        }
    }
#endif
#if MC_IDENTIFY
    if (mc->state == MC_STATE_IDENTIFY && so->epoch == mc->epoch) {
        mc_id_apply(mc, &mc->id.cmd);
        if (mc->id.cmd.end) {
            mc_id_stop(mc, mc->id.error);
            mc_outputs_off(mc);
            mc_enter(mc, MC_STATE_STOPPED);
            return;
        }
    }
#endif
    if (so->sensor_fault && so->epoch == mc->epoch && mc->outputs_on) {
        mc_fault(mc, MC_FAULT_CURRENT_SENSOR);
        return;
    }
    if (so->loop && so->epoch == mc->epoch && mc->state == MC_STATE_CLOSED_LOOP) {
        mc->i_ref = so->i_ref;
        mc->speed_ref = so->speed_ref;
        if (so->fault != MC_FAULT_NONE) {
            mc_fault(mc, so->fault);
        }
    }
}

/* The window end (mc.h note 4): this window's inputs out to the slow step. */
static void mc_window_end(mc_t *mc)
{
    mc_slow_in_t *si = &mc->slow_in;
    if (mc->slow_busy) {
        mc_fault(mc, MC_FAULT_OVERRUN); /* the slow step of the last window never finished */
        return;
    }
    smc_window_end(&mc->smc);
    si->epoch = mc->epoch;
    si->state = mc->state;
    si->pot = mc->pot;
    si->ref_remote = mc->ref_remote;
    si->ref_from_remote = mc->ref_from_remote;
    si->spd_kp = mc->spd_kp_base;
    si->spd_ki = mc->spd_ki_base;
    si->preset = mc->preset_pending;
    si->preset_iq = mc->preset_iq;
    si->preset_speed_ref = mc->preset_speed_ref;
    si->i_ab = mc->i_ab;
    si->theta_est = smc_theta(&mc->smc);
    si->sens_d = mc->sens_d;
    si->sens_q = mc->sens_q;
    si->sens_qsat = mc->sens_qsat;
    si->sens_ref = mc->i_ref_frame;
    si->est_valid = smc_valid(&mc->smc);
    si->emf_ratio = smc_emf_ratio(&mc->smc);
    si->speed_est = smc_omega(&mc->smc);
    mc->sens_d = 0;
    mc->sens_q = 0;
    mc->sens_qsat = 0U;
#if MC_IDENTIFY
    if (mc->state == MC_STATE_IDENTIFY) {
        /* the applied voltage on the standing frame's axes: d is beta, q -alpha */
        mc->id_win.v_d = mc->lock_vb;
        mc->id_win.v_q = -mc->lock_va;
        mc->id_win.step = mc->ol_step;
        si->id = mc->id_win;
        si->vbus = mc->vbus;
        memset(&mc->id_win, 0, sizeof mc->id_win);
        mc->lock_va = 0;
        mc->lock_vb = 0;
    }
#endif
#if MC_DTM_ON
    si->lock_va = mc->lock_va;
    si->lock_vb = mc->lock_vb;
    si->timer = mc->timer;
    si->dt_counts = mc->dt_counts;
    si->vbus = mc->vbus;
    mc->lock_va = 0;
    mc->lock_vb = 0;
#endif
    mc->preset_pending = false;
    mc->slow_posted = true;
    MC_BARRIER(); /* every field above is written before the flag hands it over */
    mc->slow_busy = true;
}

void mc_slow_step(mc_t *mc)
{
    const mc_slow_in_t *si = &mc->slow_in;
    mc_slow_out_t *so = &mc->slow_out;
    if (!mc->slow_busy) {
        return;
    }
    smc_slow_step(&mc->smc);
#if defined(TORQUEMODE)
    so->speed_target = MC_SPEED_REF_MIN_Q15;
    so->torque_target = si->ref_from_remote
                            ? q15_clamp(si->ref_remote, (q15_t)(-MC_IQ_MAX_Q15), MC_IQ_MAX_Q15)
                            : mc_pot_to_torque(si->pot);
#else
    so->torque_target = 0;
    so->speed_target = si->ref_from_remote
                           ? q15_clamp(si->ref_remote, MC_SPEED_REF_MIN_Q15, MC_SPEED_REF_MAX_Q15)
                           : mc_pot_to_speed(si->pot);
#endif
    if (si->epoch != mc->slow_epoch) {
        mc->slow_epoch = si->epoch;
        /* a new run, or the hand-off: the dead-time measurement starts over */
        mc->dtm_phase = MC_DTM_ALIGN;
        mc->dtm_cnt = 0U;
        mc->dtm_sum = 0;
        mc->dtm_mean = 0;
        mc->dtm_slow = false;
        mc->sens_fd = 0;
        mc->sens_fq = 0;
        mc->sens_cnt = 0U;
        so->lock_iq = MC_LOCK_CURRENT_Q15;
        so->lock_done = false;
        if (si->preset) {
            /* Closed loop entered in this window: the speed loop starts from
             * the hand-off (mc_enter_closed_loop). */
            pi_preset(&mc->pi_w, si->preset_iq);
            mc->spd_ref = si->preset_speed_ref;
            mc->stall_cnt[0] = 0U;
            mc->stall_cnt[1] = 0U;
            mc->stall_cnt[2] = 0U;
        }
    }
    so->loop = false;
    so->fault = MC_FAULT_NONE;
    mc_slow_sensor(mc, si, so);
    /* OPEN_LOOP: the load's share of the ramp current, the measured current
     * on the estimated q axis low-passed over 32 windows (the hand-off's
     * preset, mc_enter_closed_loop). */
    if (si->state == MC_STATE_OPEN_LOOP) {
        q15_t iq = park_forward(si->i_ab, sincos_compute(si->theta_est)).q;
        mc->ol_iq_acc += (int32_t)iq - mc->ol_iq_acc / 32; /* |acc| <= 32 * 32768 */
    } else {
        mc->ol_iq_acc = 0;
    }
    so->ol_iq = (q15_t)(mc->ol_iq_acc / 32);
#if MC_DTM_ON
    if (si->state == MC_STATE_LOCK) {
        mc_slow_deadtime(mc, si, so);
    }
#endif
    if (si->state == MC_STATE_CLOSED_LOOP) {
        mc_slow_speed_loop(mc, &mc->smc.res, so);
    }
#if MC_IDENTIFY
    else if (si->state == MC_STATE_IDENTIFY) {
        mc_id_window(&mc->id, &si->id, si->vbus, &mc->id.cmd);
    }
#endif
    so->epoch = si->epoch;
    MC_BARRIER(); /* the results are written before the flag hands them back */
    mc->slow_busy = false;
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
    uint8_t rseq = mc->req_seq;
    if (rseq != mc->req_seen) { /* something was posted (mc.h note 1) */
        mc->req_seen = rseq;
        ev->toggle = mc_take(mc, MC_REQUEST_START_STOP);
        ev->hw_fault = mc_take(mc, MC_REQUEST_HW_FAULT);
        ev->start = mc_take(mc, MC_REQUEST_START);
        ev->stop = mc_take(mc, MC_REQUEST_STOP);
        ev->identify = mc_take(mc, MC_REQUEST_IDENTIFY);
#if MC_IDENTIFY
        if (ev->identify && mc->state != MC_STATE_STOPPED) {
            ev->identify = false;
            if (mc->state != MC_STATE_IDENTIFY && !mc->id_pending) {
                mc->id_status = MC_ID_FAILED; /* refused: nothing else changes */
                mc->id_error = MC_ID_ERROR_NOT_STOPPED;
            }
        }
#else
        if (ev->identify) {
            ev->identify = false;
            mc->id_status = MC_ID_FAILED; /* not in this build: nothing else changes */
            mc->id_error = MC_ID_ERROR_UNAVAILABLE;
        }
#endif
        uint8_t gseq = mc->gain_seq;
        if (gseq != mc->gain_seen) {
            mc->gain_seen = gseq;
            mc_apply_gains(mc);
        }
        uint8_t seq = mc->ref_remote_seq;
        if (seq != mc->ref_remote_seen) {
            mc->ref_remote_seen = seq;
            mc->ref_from_remote = !mc->ref_to_pot;
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
 * its window enters FAULT again with that cause. */
static void mc_start(mc_t *mc, const mc_adc_frame_t *in)
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

static bool mc_on_stopped(mc_t *mc, const mc_events_t *ev, const mc_adc_frame_t *in)
{
    if (ev->toggle || ev->start) {
        mc_start(mc, in);
    }
#if MC_IDENTIFY
    else if (ev->identify) {
        mc->id_status = MC_ID_RUNNING;
        mc->id_error = MC_ID_ERROR_NONE;
        mc_start(mc, in);
        mc->id_pending = mc->state == MC_STATE_CALIBRATE;
        if (!mc->id_pending) {
            mc->id_status = MC_ID_FAILED; /* the bus is out of its window: FAULT */
            mc->id_error = MC_ID_ERROR_FAULT;
        }
    }
#endif
    return false;
}

static bool mc_on_fault(mc_t *mc, const mc_events_t *ev, const mc_adc_frame_t *in)
{
    /* timer > 0: not the fault raised by this very frame. */
    if ((ev->toggle || ev->start) && mc->timer > 0U) {
        mc_start(mc, in);
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
    if (MC_LOCK_DONE(mc)) {
        mc->i_ref.q = MC_RAMP_CURRENT_Q15;
        mc_enter(mc, MC_STATE_OPEN_LOOP);
    }
    return true;
}

/* OPEN_LOOP, CLOSED_LOOP and IDENTIFY: their changes of state come from
 * the finishing part and the slow step. */
static bool mc_on_running(mc_t *mc, const mc_events_t *ev)
{
    if (ev->toggle || ev->stop) {
        mc_stop(mc);
        return false;
    }
    return true;
}

static bool mc_dispatch(mc_t *mc, const mc_events_t *ev, const mc_adc_frame_t *in)
{
    switch (mc->state) {
        case MC_STATE_STOPPED:
            return mc_on_stopped(mc, ev, in);
        case MC_STATE_FAULT:
            return mc_on_fault(mc, ev, in);
        case MC_STATE_CALIBRATE:
            return mc_on_calibrate(mc, ev, in);
        case MC_STATE_LOCK:
            return mc_on_lock(mc, ev);
        default: /* OPEN_LOOP, CLOSED_LOOP */
            return mc_on_running(mc, ev);
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
        mc_sensor_sum(mc);
        if (mc->state == MC_STATE_OPEN_LOOP && mc->ol_step >= MC_RAMP_STEP_END) {
            mc_ramp_end(mc);
        }
        if (mc->sums_on) { /* the dead-time measurement's (note 4), the identification's */
            mc->lock_va += mc->v_hist[0].alpha;
            mc->lock_vb += mc->v_hist[0].beta;
#if MC_IDENTIFY
            if (mc->state == MC_STATE_IDENTIFY) {
                mc_id_period(mc);
            }
#endif
        }
    }
    mc->timer += (uint32_t)(mc->timer != MC_TIMER_MAX); /* saturates */

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
    if (mc->outputs_on) {
        mc_prepare(mc);
    } else {
        /* Off, or a fault raised here (a failed start, a stall, an
         * overrun) has just turned the outputs off: so does *out, at once.
         * CALIBRATE ends here once it has its samples (the lock's first
         * period turns the outputs on). */
        if (mc->state == MC_STATE_CALIBRATE &&
            mc->timer == (uint32_t)mc->calib_wait + (uint32_t)MC_CALIB_PERIODS) {
            mc_calibrate_end(mc);
        }
        turned_off = out->outputs_on;
        mc_output(mc, out);
    }
    return turned_off;
}

void mc_step(mc_t *mc, const mc_adc_frame_t *in, mc_pwm_out_t *out)
{
    mc_step_control(mc, in, out);
    (void)mc_step_finish(mc, out);
}

void mc_status(const mc_t *mc, mc_status_t *st)
{
    st->state = mc->state;
    st->fault = mc->fault;
    st->theta_est = mc->theta;
    st->speed_est = smc_omega(&mc->smc);
    st->speed_ref = mc->speed_ref;
    st->id = mc->i_dq.d;
    st->iq = mc->i_dq.q;
    st->vd = mc->v_dq.d;
    st->vq = mc->v_dq.q;
    st->vbus = mc->vbus;
    st->start_retries = mc->retries;
    st->estimator_valid = smc_valid(&mc->smc);
    st->id_ref = mc->i_ref.d;
    st->iq_ref = mc->i_ref.q;
    st->speed_target = mc->speed_target;
    /* In OPEN_LOOP ol_angle is already the next period's (mc_prepare). */
    st->theta_forced =
        (mc->state == MC_STATE_OPEN_LOOP) ? mc->theta : (int16_t)(uint16_t)(mc->ol_angle >> 16);
    st->bemf = smc_emf_amplitude(&mc->smc);
    st->ia = mc->ia;
    st->ib = mc->ib;
    st->duty[0] = mc->duty[0];
    st->duty[1] = mc->duty[1];
    st->duty[2] = mc->duty[2];
    st->outputs_on = mc->outputs_on;
    st->deadtime = mc->dt_counts;
    /* a choice posted but not yet taken counts: the writer reading its
     * own write back must find it, whether or not a period fell between */
    uint8_t seq = mc->ref_remote_seq;
    st->ref_remote = (seq != mc->ref_remote_seen) ? !mc->ref_to_pot : mc->ref_from_remote;
    st->ref_seq = seq;
}

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
 *    stalls (docs/tuning.md, "Behind the defaults"). Once the estimate is valid, each window moves
 *    the forced angle back by MOTOR_OL_DAMP_S times the rotor's excess
 *    speed (mc_ol_damp): the torque then falls as the rotor runs ahead and
 *    rises as it falls behind, a viscous damping of the swing. The excess
 *    is taken less its mean over MC_OL_DAMP_MEAN_WINDOWS: under a model
 *    mismatch the estimate reads steadily high or low, and damping that
 *    bias held the forced angle back by a steady amount, the torque a
 *    loaded start needed.
 *
 * 2. Stall detection runs at the speed-loop rate in CLOSED_LOOP; each
 *    condition must hold for consecutive runs: estimated |speed| below
 *    MC_STALL_SPEED_MIN_RPM (MC_STALL_TIME_S); the estimator's back-EMF
 *    ratio (|e| over what Ke predicts at the estimated speed) above
 *    MC_STALL_BEMF_HIGH_FRACTION or, outside field weakening (where the
 *    weakened flux lowers it legitimately), below MC_STALL_BEMF_LOW_FRACTION
 *    (MC_STALL_TIME_S); the speed error above MC_STALL_SPEED_ERROR_RPM with
 *    the speed PI at its limit (MC_STALL_TRACK_TIME_S).
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
 *    while the back-EMF ratio has read below the stall check's low
 *    fraction for MC_SENSOR_DEFER_WINDOWS windows, failing windows are
 *    held and the stall check decides, unless the phases are out of
 *    balance (a stopped rotor's healthy phases are not; a sensor failed at
 *    low speed, whose estimate also loses its back-EMF, is). Failing
 *    windows count 2, passing ones -1: MC_SENSOR_TIME_S of failure net sets
 *    slow_out.sensor_fault, applied as MC_FAULT_CURRENT_SENSOR. A phase-A
 *    sensor failed during LOCK reads what the phase carries there (the
 *    lock's current is on beta: none in phase A), so it shows, and trips,
 *    once the ramp turns the current. Not covered: a gain error or a
 *    slowly drifting offset (the loop then regulates the wrong current,
 *    consistently).
 */
