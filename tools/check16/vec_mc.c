/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* vec_mc.c - 16-bit check vectors for the motor-control core: mc_step over a recorded start. */
/* check16-requires: firmware/mc.c firmware/mc_state.c firmware/mc_slow.c firmware/mc_sensor.c
 * firmware/mc_dtm.c firmware/mc_api.c firmware/mc_contract.c firmware/mc_id_isr.c
 * firmware/mc_id_units.c firmware/mc_id.c smc_estimator/smc.c */
/* check16-cflags: -DMOTOR_LOCK_TIME_S=0.02 -DMOTOR_RAMP_TIME_S=0.15 -DMC_HANDOFF_WAIT_S=0.05 */
/* check16-cflags: -DMC_HANDOFF_AGREE_S=0.005 */
#include "emit.h"

#include "mc.h"
#include "mc_frames.h"
#include "mc_internal.h"
#include "vec_mc_frames.h"

/*
 * Sections:
 *   mc_constants  every derived constant mc_step uses, as each compiler
 *                 folded it (a 32-bit double on the AVR): a difference here
 *                 names the constant before any step does;
 *   mc_helpers    the pure helpers (dead-time counts at any dead time a
 *                 lock may measure, the lock's result, duty -> voltage, pot
 *                 maps) over edges and random inputs;
 *   mc_step       the recorded frames of a simulated Hurst start
 *                 (tools/check16/mc_frames.h, gen_mc_frames.c): START at
 *                 frame 10, calibration, lock, ramp, hand-off, closed loop,
 *                 the pot to full travel at frame 7000; duties, state and
 *                 the main internal values after every step;
 *   mc_protect    synthetic frames through each protection and request.
 * The start-up is shortened by the check16-cflags above (the same flags
 * recorded the frames) so the closed loop fits in 6000 frames of flash.
 */

static mc_t mc; /* static: off the AVR stack */

static void emit_out(const mc_pwm_out_t *out)
{
    mc_status_t st;
    mc_status(&mc, &st);
    emit_u16(out->duty[0]);
    emit_u16(out->duty[1]);
    emit_u16(out->duty[2]);
    emit_bool(out->outputs_on);
    emit_u8((uint8_t)st.state);
    emit_u16(st.fault);
    emit_i16(st.theta_est);
    emit_i16(st.speed_est);
    emit_i16(st.speed_ref);
    emit_i16(st.id);
    emit_i16(st.iq);
    emit_i16(st.vd);
    emit_i16(st.vq);
    emit_i16(st.id_ref);
    emit_i16(st.iq_ref);
    emit_end();
}

static void constants(void)
{
    static const smc_params_t sp = MC_SMC_PARAMS_INIT;
    static const q15_t fw[16] = MC_FW_TABLE_Q15;
    uint8_t k;
    emit_section("mc_constants");
    emit_u16(PWM_DUTY_MAX);
    emit_u16(IRP_PERCALC);
    emit_i16(MC_IQ_MAX_Q15);
    emit_i16(MC_OVERCURRENT_Q15);
    emit_i16(MC_LOCK_CURRENT_Q15);
    emit_i16(MC_RAMP_CURRENT_Q15);
    emit_i16(MC_OFFSET_MAX_Q15);
    emit_end();
    emit_i16(MC_VBUS_UV_Q15);
    emit_i16(MC_VBUS_OV_Q15);
    emit_i16(MC_VBUS_NOMINAL_Q15);
    emit_i16(MC_VMAX_Q15);
    emit_i16(MC_SPEED_REF_MIN_Q15);
    emit_i16(MC_SPEED_REF_MAX_Q15);
    emit_i16(MC_SPEED_RAMP_STEP);
    emit_end();
    emit_i16(MC_CUR_KP);
    emit_u8(MC_CUR_KP_SHIFT);
    emit_i16(MC_CUR_KI);
    emit_i16(MC_SPD_KP);
    emit_u8(MC_SPD_KP_SHIFT);
    emit_i16(MC_SPD_KI);
    emit_end();
    emit_u16(MC_LOCK_PERIODS);
    emit_i16(MC_DT_COUNTS_MIN);
    emit_i16(MC_DT_COUNTS_MAX);
    emit_i16(MC_DTM_CURRENT_Q15);
    emit_u16(MC_CALIB_PERIODS);
    emit_u16(MC_COAST_PERIODS);
    emit_u32(MC_RAMP_STEP_INC);
    emit_u32(MC_RAMP_STEP_END);
    emit_u32(MC_RAMP_PERIODS);
    emit_u32(MC_HANDOFF_WAIT_PERIODS);
    emit_i16(MC_RAMP_END_Q15);
    emit_i16(MC_BLEED_STEP);
    emit_end();
    emit_i16(MC_DT_COUNTS);
    emit_i16(MC_DT_BAND_Q15);
    emit_i16(MC_DT_SLOPE);
    emit_i32(MC_VAPP_K);
    emit_i32(MC_VAPP_KB);
    emit_u16(MC_STALL_TICKS);
    emit_u16(MC_STALL_TRACK_TICKS);
    emit_i16(MC_STALL_SPEED_Q15);
    emit_i16(MC_STALL_SPEED_ERR_Q15);
    emit_i16(MC_STALL_BEMF_LO_Q12);
    emit_i16(MC_STALL_BEMF_HI_Q12);
    emit_end();
    emit_i16(sp.f);
    emit_i16(sp.g);
    emit_u8(sp.g_shift);
    emit_i16(sp.kslide);
    emit_i16(sp.max_err);
    emit_i16(sp.kz);
    emit_u8(sp.kz_shift);
    emit_i16(sp.k_per_omega);
    emit_i16(sp.k_min);
    emit_i16(sp.omega_min);
    emit_end();
    for (k = 0U; k < 16U; k++) {
        emit_i16(fw[k]);
    }
    emit_end();
}

static void helpers(void)
{
    uint32_t n;
    emit_section("mc_helpers");
    vec_seed(0x3C0DEU);
    for (n = 0U; n < 2000U; n++) {
        int16_t i = vec_edge_or_rand(n);
        int16_t d[3];
        int16_t vb;
        int16_t dt;
        q15_t slope;
        ab_q15_t v;
        d[0] = vec_rand_between(-(int16_t)(PWM_DUTY_MAX / 2U), (int16_t)(3U * PWM_DUTY_MAX / 2U));
        d[1] = vec_rand_between(-(int16_t)(PWM_DUTY_MAX / 2U), (int16_t)(3U * PWM_DUTY_MAX / 2U));
        d[2] = vec_rand_between(-(int16_t)(PWM_DUTY_MAX / 2U), (int16_t)(3U * PWM_DUTY_MAX / 2U));
        vb = (n < VEC_N_EDGES) ? vec_edges[n] : vec_rand_between(0, 32767);
        v = mc_duty_to_voltage(d, vb);
        /* a dead time a lock may measure, and its slope as mc.c forms it */
        dt = (n == 0U) ? MC_DT_COUNTS : vec_rand_between(MC_DT_COUNTS_MIN, MC_DT_COUNTS_MAX);
        slope = q15_dsp_divsd(((int32_t)dt << 15) + MC_DT_BAND_Q15 / 2, MC_DT_BAND_Q15);
        emit_i16(i);
        emit_i16(d[0]);
        emit_i16(d[1]);
        emit_i16(d[2]);
        emit_i16(vb);
        emit_i16(dt);
        emit_sep();
        emit_i16(mc_deadtime_counts(i, dt, slope, MC_DT_BAND_Q15));
        emit_i16(mc_deadtime_from_lock(dt, 3 * (int32_t)i, vb));
        emit_i16(v.alpha);
        emit_i16(v.beta);
        emit_i16(mc_pot_to_speed(i));
        emit_i16(mc_pot_to_torque(i));
        emit_end();
    }
}

static void replay(void)
{
    uint32_t n;
    emit_section("mc_step");
    mc_init(&mc);
    for (n = 0U; n < MC_FRAMES_N && n < MC_FRAMES_RECORDED_N; n++) {
        mc_adc_frame_t in;
        mc_pwm_out_t out;
        mc_frames_input(&mc, n, &in);
        mc_step(&mc, &in, &out);
        mc_slow_step(&mc);
        emit_i16(in.ia);
        emit_i16(in.ib);
        emit_i16(in.vbus);
        emit_sep();
        emit_out(&out);
    }
}

static void step_frame(int16_t ia, int16_t ib, int16_t vbus, int16_t pot)
{
    mc_adc_frame_t in;
    mc_pwm_out_t out;
    in.ia = ia;
    in.ib = ib;
    in.vbus = vbus;
    in.pot = pot;
    mc_step(&mc, &in, &out);
    mc_slow_step(&mc);
    emit_i16(ia);
    emit_i16(ib);
    emit_i16(vbus);
    emit_i16(pot);
    emit_sep();
    emit_out(&out);
}

static void protections(void)
{
    uint32_t n;
    int16_t nom = MC_VBUS_NOMINAL_Q15;
    emit_section("mc_protect");
    vec_seed(0x9807EU);
    mc_init(&mc);
    /* Random frames while stopped, then a start into the lock. */
    for (n = 0U; n < 300U; n++) {
        /* Four draws, sequenced (emit.h): as arguments their order would be unspecified. */
        int16_t ia = vec_rand_i16();
        int16_t ib = vec_rand_i16();
        int16_t vbus = vec_rand_between(0, 19000);
        step_frame(ia, ib, vbus, vec_rand_i16());
    }
    mc_request(&mc, MC_REQUEST_START_STOP);
    for (n = 0U; n < 700U; n++) {
        step_frame(vec_rand_between(-40, 40), vec_rand_between(-40, 40), nom, 16384);
    }
    /* Overcurrent at the threshold, then restart, under-voltage, restart,
     * overvoltage, hardware fault, stop. */
    step_frame(MC_OVERCURRENT_Q15, (int16_t)(-MC_OVERCURRENT_Q15 / 2), nom, 0);
    mc_request(&mc, MC_REQUEST_START);
    step_frame(0, 0, nom, 0);
    for (n = 0U; n < 600U; n++) {
        step_frame(vec_rand_between(-40, 40), vec_rand_between(-40, 40), nom, 0);
    }
    step_frame(0, 0, MC_VBUS_UV_Q15, 0);
    mc_request(&mc, MC_REQUEST_START);
    step_frame(0, 0, nom, 0);
    step_frame(0, 0, MC_VBUS_OV_Q15, 0);
    mc_request(&mc, MC_REQUEST_START);
    step_frame(0, 0, nom, 0);
    mc_set_reference(&mc, 12000);
    for (n = 0U; n < 300U; n++) {
        step_frame(vec_rand_between(-40, 40), vec_rand_between(-40, 40), nom, 0);
    }
    mc_request(&mc, MC_REQUEST_HW_FAULT);
    step_frame(0, 0, nom, 0);
    mc_request(&mc, MC_REQUEST_STOP);
    step_frame(0, 0, nom, 0);
    mc_request(&mc, MC_REQUEST_REF_POT);
    mc_request(&mc, MC_REQUEST_START_STOP);
    step_frame(0, 0, nom, 0);
    mc_request(&mc, MC_REQUEST_STOP);
    step_frame(0, 0, nom, 0);
}

void vec_mc(void)
{
    constants();
    helpers();
    replay();
    protections();
}
