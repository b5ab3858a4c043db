/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* mc_api.c - the main loop's side of the seam: mc_init, the mailbox, the status. */
#include <string.h>

#include "mc_contract.h"
#include "mc_parts.h"
#include "ripple.h"

/* ---- constant parameters (compile-time, mc_derived.h) --------------------- */

#if MC_DRIVE
static const smc_params_t mc_smc_params = MC_SMC_PARAMS_INIT;
#endif

static const pi_params_t mc_pi_cur_params = {
    MC_CUR_KP, MC_CUR_KP_SHIFT, MC_CUR_KI, MC_PI_KC, (q15_t)(-MC_VMAX_Q15), MC_VMAX_Q15,
};

bool mc_reference_held(const mc_status_t *st, uint8_t seq)
{
    return st->ref_remote && st->ref_seq == seq;
}

/* ---- the mailbox (mc.h note 1): the main loop's calls write its part alone ---------- */

void mc_request(mc_t *mc, mc_request_t r)
{
    mc_mailbox_t *b = &mc->mbox;
    MC_REQUIRE((unsigned)r < (unsigned)MC_REQUEST_COUNT); /* the chip ignores another */
    if (r == MC_REQUEST_REF_POT) {
        /* a choice of reference like mc_set_reference, on the same
         * sequence: of the two, the later one wins even within a period */
        b->ref_to_pot = true;
        b->ref_seq = (uint8_t)(b->ref_seq + 1U);
        b->req_seq = (uint8_t)(b->req_seq + 1U); /* last: mc.h note 1 */
    } else if ((unsigned)r < (unsigned)MC_REQUEST_COUNT) {
        b->req_posted[r] = (uint8_t)(b->req_posted[r] + 1U);
        b->req_seq = (uint8_t)(b->req_seq + 1U); /* after the request: mc.h note 1 */
    }
}

uint8_t mc_set_reference(mc_t *mc, int16_t ref)
{
    mc_mailbox_t *b = &mc->mbox;
    uint8_t seq = (uint8_t)(b->ref_seq + 1U);
    b->ref_remote = ref;
    b->ref_to_pot = false;
    b->ref_seq = seq;
    b->req_seq = (uint8_t)(b->req_seq + 1U); /* last: mc.h note 1 */
    return seq;
}

/* The region a loop's posted pair must stay in (mc.h note 3), as factors of
 * the built-in gains: 8ths for Kp and Ki each, the PI zero's bound whole. */
static const uint8_t mc_gain_min8[MC_GAIN_COUNT] = {MC_GAIN_CUR_KP_MIN8, MC_GAIN_CUR_KI_MIN8,
                                                    MC_GAIN_SPD_KP_MIN8, MC_GAIN_SPD_KI_MIN8};
static const int16_t mc_gain_base[MC_GAIN_COUNT] = {MC_CUR_KP, MC_CUR_KI, MC_SPD_KP, MC_SPD_KI};
Q15_STATIC_ASSERT(MC_GAIN_CUR_KP == 0 && MC_GAIN_CUR_KI == 1 && MC_GAIN_SPD_KP == 2 &&
                      MC_GAIN_SPD_KI == 3 && MC_GAIN_COUNT == 4,
                  "mc_gain_allowed takes the gains as Kp, Ki pairs, Kp at the even index");

bool mc_gain_allowed(const mc_t *mc, mc_gain_t g, int16_t value)
{
    if ((unsigned)g >= (unsigned)MC_GAIN_COUNT || value < 1) {
        return false;
    }
    int16_t base = mc_gain_base[g];
    /* min8 / 8 base <= value <= 8 base, as 16 x 16 products (the dsPIC's mul.ss) */
    if (q15_dsp_mulss(value, 8) < q15_dsp_mulss((int16_t)mc_gain_min8[g], base) ||
        q15_dsp_mulss(base, 8) < (int32_t)value) {
        return false;
    }
    /* the loop's pair, this value in place: Ki / Kp <= Z Ki0 / Kp0, as Ki Kp0 <= Z Ki0 Kp,
     * each product below 2^30, as ceil(left / Z) <= right (Z a power of two) */
    unsigned kp_i = (unsigned)g & ~1U; /* the gains are Kp, Ki pairs (mc.h mc_gain_t) */
    bool is_kp = g == (mc_gain_t)kp_i;
    int16_t kp = is_kp ? value : mc->mbox.gain_posted[kp_i];
    int16_t ki = is_kp ? mc->mbox.gain_posted[kp_i + 1U] : value;
    int32_t left = q15_dsp_mulss(ki, mc_gain_base[kp_i]);
    int32_t right = q15_dsp_mulss(mc_gain_base[kp_i + 1U], kp);
    return (left + ((int32_t)MC_GAIN_ZERO_MAX - 1)) / (int32_t)MC_GAIN_ZERO_MAX <= right;
}

bool mc_set_gain(mc_t *mc, mc_gain_t g, int16_t value)
{
    mc_mailbox_t *b = &mc->mbox;
    if (!mc_gain_allowed(mc, g, value)) {
        return false;
    }
    b->gain_posted[g] = value;
    b->gain_seq = (uint8_t)(b->gain_seq + 1U);
    b->req_seq = (uint8_t)(b->req_seq + 1U); /* last: mc.h note 1 */
    return true;
}

int16_t mc_get_gain(const mc_t *mc, mc_gain_t g)
{
    return ((unsigned)g < (unsigned)MC_GAIN_COUNT) ? mc->mbox.gain_posted[g] : 0;
}

/* ---- the seam ---------------------------------------------------------------------- */

void mc_init(mc_t *mc)
{
    memset(mc, 0, sizeof(*mc));
    pi_init(&mc->pi_d, &mc_pi_cur_params);
    pi_init(&mc->pi_q, &mc_pi_cur_params);
#if MC_DRIVE
    mc_slow_init(&mc->slow);
    smc_init(&mc->smc, &mc_smc_params);
#endif
    mc->mbox.gain_posted[MC_GAIN_CUR_KP] = MC_CUR_KP;
    mc->mbox.gain_posted[MC_GAIN_CUR_KI] = MC_CUR_KI;
    mc->mbox.gain_posted[MC_GAIN_SPD_KP] = MC_SPD_KP;
    mc->mbox.gain_posted[MC_GAIN_SPD_KI] = MC_SPD_KI;
    mc->spd_kp_base = MC_SPD_KP;
    mc->spd_ki_base = MC_SPD_KI;
    mc->speed_ref = MC_SPEED_REF_MIN_Q15;
    mc->speed_target = MC_SPEED_REF_MIN_Q15;
    mc->ripple_gain = RIPPLE_ONE;
    mc->dt_counts = MC_DT_COUNTS;
    mc->dt_slope = MC_DT_SLOPE;
#if MC_IDENTIFY
    mc->id_isr.dt_band = MC_DT_BAND_Q15;
#endif
    mc_outputs_off(mc);
#if MC_DRIVE
    mc->slow.epoch = mc->epoch;
#endif
    mc->fault = MC_FAULT_NONE;
    mc_enter(mc, MC_STATE_STOPPED);
}

void mc_status(const mc_t *mc, mc_status_t *st)
{
    st->state = mc->state;
    st->fault = mc->fault;
    st->theta_est = mc->theta;
    st->speed_est = mc_est_omega(mc);
    st->speed_ref = mc->speed_ref;
    st->id = mc->i_dq.d;
    st->iq = mc->i_dq.q;
    st->vd = mc->v_dq.d;
    st->vq = mc->v_dq.q;
    st->vbus = mc->vbus;
    st->start_retries = mc->retries;
    st->estimator_valid = mc_est_valid(mc);
    st->id_ref = mc->i_ref.d;
    st->iq_ref = mc->i_ref.q;
    st->speed_target = mc->speed_target;
    /* In OPEN_LOOP ol_angle is already the next period's (mc_prepare). */
    st->theta_forced =
        (mc->state == MC_STATE_OPEN_LOOP) ? mc->theta : (int16_t)(uint16_t)(mc->ol_angle >> 16);
    st->bemf = mc_est_emf_amplitude(mc);
    st->ia = mc->ia;
    st->ib = mc->ib;
    st->duty[0] = mc->duty[0];
    st->duty[1] = mc->duty[1];
    st->duty[2] = mc->duty[2];
    st->outputs_on = mc->outputs_on;
    st->stopping = mc->stopping;
    st->deadtime = mc->dt_counts;
    /* a choice posted but not yet taken counts: the writer reading its
     * own write back must find it, whether or not a period fell between */
    uint8_t seq = mc->mbox.ref_seq;
    st->ref_remote = (seq != mc->ref_seen) ? !mc->mbox.ref_to_pot : mc->ref_from_remote;
    st->ref_seq = seq;
}
