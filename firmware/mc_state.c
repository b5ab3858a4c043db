/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* mc_state.c - the core's changes of state: once per transition, from the step that makes it. */
#include "mc_parts.h"

void mc_apply_gains(mc_t *mc)
{
    q15_t kp = mc->mbox.gain_posted[MC_GAIN_CUR_KP];
    q15_t ki = mc->mbox.gain_posted[MC_GAIN_CUR_KI];
    mc->pi_d.p.kp = kp;
    mc->pi_q.p.kp = kp;
    mc->pi_d.p.ki = ki;
    mc->pi_q.p.ki = ki;
    mc->pi_d.p.kc = ki;
    mc->pi_q.p.kc = ki;
    mc->spd_kp_base = mc->mbox.gain_posted[MC_GAIN_SPD_KP]; /* to the slow step at the window end */
    mc->spd_ki_base = mc->mbox.gain_posted[MC_GAIN_SPD_KI];
}

void mc_enter(mc_t *mc, mc_state_t s)
{
    mc->state = s;
    mc->timer = 0U;
    /* the window's voltage sums: the dead-time measurement's, the identification's */
    mc->sums_on = s == MC_STATE_IDENTIFY || (MC_DTM_ON && s == MC_STATE_LOCK);
}

void mc_outputs_off(mc_t *mc)
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
    /* With the outputs off the estimator sees no current and the core
     * applies no voltage: it cannot follow a coasting rotor, and its last
     * speed would stand frozen while the rotor slows (2,003 rpm shown as
     * the Hurst coasted from 937 to 103). It reads unknown instead: speed
     * 0, not valid, until the next start measures again. */
    mc_est_reset(mc);
    mc->stopping = false;
    mc->epoch = (uint8_t)(mc->epoch + 1U); /* the slow step's results of this run are void */
    mc->preset_pending = false;
#if MC_IDENTIFY
    mc->id_isr.inj = 0; /* no injection, no spin */
    mc->id_isr.inc = 0U;
#endif
}

void mc_enter_fault(mc_t *mc, uint16_t code)
{
    mc->fault = code;
    if (MC_IDENTIFY) {
        mc_id_stop(mc, MC_ID_ERROR_FAULT);
    }
    mc_outputs_off(mc);
    mc_enter(mc, MC_STATE_FAULT);
}

void mc_fault(mc_t *mc, uint16_t code)
{
    if (mc->state != MC_STATE_FAULT) {
        mc_enter_fault(mc, code);
    }
}

void mc_begin_calibration(mc_t *mc, uint16_t wait)
{
    mc_outputs_off(mc);
    mc->calib_wait = wait;
    mc->offset_acc_a = 0;
    mc->offset_acc_b = 0;
    mc_enter(mc, MC_STATE_CALIBRATE);
}

void mc_stop(mc_t *mc)
{
    if (MC_IDENTIFY) {
        mc_id_stop(mc, MC_ID_ERROR_ABORTED);
    }
    mc_outputs_off(mc);
    mc_enter(mc, MC_STATE_STOPPED);
}

/* LOCK, after CALIBRATE; the caller prepares its first period's angle. */
static void mc_enter_lock(mc_t *mc)
{
    pi_reset(&mc->pi_d);
    pi_reset(&mc->pi_q);
    mc_est_reset(mc);
    mc_set_advance(mc);
    mc->epoch = (uint8_t)(mc->epoch + 1U);
    mc->ol_angle = 0U;
    mc->ol_damp = 0;
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
}

void mc_enter_closed_loop(mc_t *mc)
{
    angle_q15_t est = mc_est_theta(mc);
    /* The forced angle stays the reference; the difference is bled off. */
    mc->theta_offset = angle_sub(mc->theta, est);
    /* The rotor turns at the forced speed on average; the estimator's
     * window speed is noisier than that, so both start from it. */
    mc_est_preset(mc, MC_RAMP_END_Q15);
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

/* Called once, with mc->timer already counting the period that took the
 * last sample. */
void mc_calibrate_end(mc_t *mc)
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
    if (MC_IDENTIFY && mc_id_pending(mc)) {
        mc_enter_identify(mc);
        return;
    }
    if (MC_DRIVE) {
        mc_enter_lock(mc);
    } else {
        mc_stop(mc); /* the commissioning image has nothing else to run */
    }
}
