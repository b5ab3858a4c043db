/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* vec_id.c - 16-bit check vectors for self-commissioning: the sequence, its math, its results. */
/* check16-requires: firmware/mc.c firmware/mc_state.c firmware/mc_slow.c firmware/mc_sensor.c
 * firmware/mc_dtm.c firmware/mc_api.c firmware/mc_contract.c firmware/mc_id_isr.c
 * firmware/mc_id_units.c firmware/mc_id.c smc_estimator/smc.c */
#include "emit.h"

#include <string.h>

#include "mc.h"
#include "mc_id.h"

/*
 * Sections:
 *   id_constants  the sequence's parameters as each compiler folded them (a
 *               32-bit double on the AVR);
 *   id_math     mc_id_neg_ln_q24 and mc_id_exp_neg_q30 over their whole
 *               input ranges (edges, a log sweep, random inputs);
 *   id_stages   each stage of the sequence entered with a drawn state and fed
 *               drawn windows (sums of the sizes the interrupt gives): after
 *               every window the command, the stage, the error and the
 *               stage's sums, until it ends or 120 windows pass;
 *   id_result   mc_identify_result over drawn finished sequences (its 64-bit
 *               conversions, the exact L solve, the fallbacks): every field;
 *   id_band     the spin's dead-time band (mc_id_dt_band) as each compiler
 *               folded its constants, and over the bus, the inductance and
 *               the dead time: edges, sweeps, drawn inputs.
 * Bit-identical on the PC, the AVR and the dsPIC, so int's width and the
 * compilers' 64-bit helpers change nothing.
 */

#if MC_IDENTIFY

static mc_t mc; /* static: off the AVR stack */

/* The parameters the build gives the sequence (mc.c mc_id_params). */
static const mc_id_params_t params = MC_ID_PARAMS_INIT;

static int32_t draw_i32(int32_t lo, int32_t hi)
{
    uint32_t span = (uint32_t)(hi - lo) + 1U;
    return lo + (int32_t)(vec_rand_u32() % span);
}

static void vec_math(void)
{
    uint32_t k, x;
    emit_section("id_math");
    for (k = 0; k < 400U; k++) {
        if (k < 32U) {
            x = (uint32_t)1 << k; /* every power of two, 1 .. 2^31 */
        } else if (k < 40U) {
            static const uint32_t edges[8] = {0UL,          1UL,         0xFFFFFFUL,
                                              0x1000000UL,  0x1000001UL, 0x7FFFFFFFUL,
                                              0xFFFFFFFEUL, 0xFFFFFFFFUL};
            x = edges[k - 32U];
        } else {
            x = vec_rand_u32() >> (vec_rand_u16() % 24U);
        }
        emit_u32(x);
        emit_sep();
        emit_u32(mc_id_neg_ln_q24(x));
        emit_u32(mc_id_exp_neg_q30(x));
        emit_end();
    }
}

/* One stage entered with drawn state, fed drawn windows. */
static void vec_stage(mc_id_t *id, uint8_t stage, uint16_t n)
{
    uint16_t k;
    mc_id_cmd_t cmd;
    mc_id_begin(id, &params, &cmd);
    id->stage = stage;
    id->sub = (uint8_t)(vec_rand_u16() % 8U);
    id->i_dc = (q15_t)vec_rand_between(params.i_min, params.i_target);
    id->r_q16 = draw_i32(1000, 16L * 65536L);
    id->l_q12 = draw_i32(100, 4000000L);
    id->v0 = draw_i32(-2000000L, 20000000L);
    id->goal = (int32_t)params.accel;
    id->cmd.i_ref.d = (q15_t)(id->i_dc / 3);
    id->cmd.v_d = (q15_t)vec_rand_between(64, params.v_max);
    id->cmd.inj = (q15_t)vec_rand_between(0, params.inj_max);
    id->cmd.inj_half = (uint8_t)(4U << (vec_rand_u16() % 4U));
    id->x1 = (uint32_t)draw_i32(100000L, (int32_t)(params.step_max / 2U));
    id->m1 = draw_i32(0, 300000L);
    for (k = 0; k < n && id->stage != MC_ID_STAGE_DONE && id->stage != MC_ID_STAGE_FAILED; k++) {
        mc_id_win_t w;
        int32_t nn = (int32_t)params.n;
        uint8_t c;
        memset(&w, 0, sizeof w);
        w.i_d = draw_i32(-1000, params.i_target + params.i_target / 4) * nn;
        w.i_q = draw_i32(-params.i_target / 2, params.i_target / 2) * nn;
        w.u_d = draw_i32(-3000, 30000) * nn;
        w.u_q = draw_i32(-30000, 30000) * nn;
        w.v_d = w.u_d;
        w.v_q = w.u_q;
        for (c = 0; c < 8U; c++) {
            w.c[c] = draw_i32(-200000L, 200000L);
        }
        w.step = (uint32_t)draw_i32(0, (int32_t)params.step_max);
        mc_id_window(id, &w, (q15_t)vec_rand_between(20000, 32767), &cmd);
        emit_u16(k);
        emit_sep();
        emit_u8(id->stage);
        emit_u8(id->sub);
        emit_u8(id->error);
        emit_i16(cmd.i_ref.d);
        emit_i16(cmd.kp);
        emit_u8(cmd.kp_shift);
        emit_i16(cmd.ki);
        emit_i16(cmd.v_d);
        emit_i16(cmd.v_q);
        emit_i16(cmd.inj);
        emit_u8(cmd.inj_half);
        emit_i32(cmd.accel);
        emit_i16(cmd.dt_counts);
        emit_bool(cmd.end);
        emit_end();
        emit_u16(k);
        emit_sep();
        emit_i32(id->acc[0]);
        emit_i32(id->acc[1]);
        emit_i32(id->acc[2]);
        emit_i32(id->r_q16);
        emit_i32(id->l_q12);
        emit_i32(id->damp);
        emit_i32(id->j_ia);
        emit_end();
    }
}

static void vec_stages(void)
{
    static mc_id_t id; /* static: off the AVR stack */
    uint8_t st, rep;
    emit_section("id_stages");
    for (st = MC_ID_STAGE_RAMP; st <= MC_ID_STAGE_SPIN4; st++) {
        for (rep = 0; rep < 6U; rep++) {
            vec_stage(&id, st, 120U);
        }
    }
}

static void vec_result(void)
{
    uint16_t k;
    uint8_t c;
    mc_id_result_t r;
    emit_section("id_result");
    mc_init(&mc);
    for (k = 0; k < 600U; k++) {
        mc_id_t *id = &mc.id;
        mc.id_status = (k % 8U == 7U) ? MC_ID_FAILED : MC_ID_DONE;
        mc.id_error = (uint16_t)(k % 13U);
        id->dv = draw_i32(1, 200000000L);
        id->di = draw_i32(1, 200000000L);
        id->v0 = draw_i32(-20000000L, 20000000L);
        id->nwin = 100;
        id->vbus = (q15_t)vec_rand_between(0, 32767);
        for (c = 0; c < 8U; c++) {
            /* a decaying response: the first two correlations near each other */
            id->l_c[0][c] = draw_i32(-50000000L, 50000000L);
            id->l_c[1][c] = draw_i32(-50000000L, 50000000L);
        }
        if (k % 3U == 0U) { /* alpha in (0, 1): c0 = a c1 + b u1 */
            id->l_c[0][1] = draw_i32(1000000L, 40000000L);
            id->l_c[0][0] = id->l_c[0][1] - draw_i32(1, 900000L);
            id->l_c[1][1] = draw_i32(1000000L, 40000000L);
            id->l_c[1][0] = id->l_c[1][1] - draw_i32(1, 900000L);
        }
        id->l_dq[0] = draw_i32(0, 4000000L);
        id->l_dq[1] = draw_i32(0, 4000000L);
        id->lq_i[0] = draw_i32(-40000000L, 40000000L);
        id->lq_i[1] = draw_i32(-10000000L, 10000000L);
        id->lq_half = (uint8_t)(4U << (vec_rand_u16() % 4U));
        id->x1 = (uint32_t)draw_i32(1000, 100000000L);
        id->x2 = (k % 5U == 0U) ? id->x1 : id->x1 * 2U;
        id->m1 = draw_i32(0, 500000L);
        id->m2 = draw_i32(0, 1000000L);
        id->j_n = draw_i32(0, 400);
        id->j_a = draw_i32(-4000, 4000);
        id->j_aa = draw_i32(0, 400000L);
        id->j_i = draw_i32(-4000000L, 4000000L);
        id->j_ia = draw_i32(-40000000L, 40000000L);
        id->p = &params; /* mc_identify_result reads the spin's acceleration there */
        mc_identify_result(&mc, &r);
        emit_u16(k);
        emit_sep();
        emit_u8((uint8_t)r.status);
        emit_u16(r.error);
        emit_u32(r.rs_uohm);
        emit_u32(r.ls_nh);
        emit_u32(r.ld_nh);
        emit_u32(r.lq_nh);
        emit_u32(r.ke_uv_per_rpm);
        emit_u32(r.j_ng_m2);
        emit_u16(r.deadtime_ns);
        emit_u8(r.pole_pairs);
        emit_end();
    }
}

static void vec_constants(void)
{
    emit_section("id_constants");
    emit_i16(params.i_target);
    emit_i16(params.i_min);
    emit_i16(params.v_max);
    emit_i16(params.inj_max);
    emit_i16(params.wc_ts);
    emit_u16(params.n);
    emit_i16(params.w_new);
    emit_u32(params.accel);
    emit_u32(params.step_max);
    emit_u32(params.damp);
    emit_end();
}

static void vec_band(void)
{
    static const int16_t dts[6] = {-3, 0, 1, MC_DT_COUNTS, MC_DT_COUNTS_MAX, 8191};
    uint32_t k;
    emit_section("id_band");
    emit_i16(params.dt_band);
    emit_u16(params.band_k);
    emit_end();
    for (k = 0; k < 1200U; k++) {
        int16_t dt = dts[k % 6U];
        q15_t vb;
        int32_t l;
        if (k < 600U) { /* the bus in steps, L a power of two (k / 6 % 31) */
            vb = (q15_t)((k / 6U % 9U) * 4095U);
            l = (int32_t)1 << (k / 6U % 31U);
        } else {
            vb = (q15_t)vec_rand_between(0, 32767);
            l = (int32_t)(vec_rand_u32() >> (1U + vec_rand_u16() % 30U));
            l = (l < 1) ? 1 : l;
        }
        emit_i16(dt);
        emit_i16(vb);
        emit_i32(l);
        emit_sep();
        emit_i16(mc_id_dt_band(dt, vb, l, params.band_k));
        emit_end();
    }
}

void vec_id(void)
{
    vec_constants();
    vec_seed(0x1D5EED01UL);
    vec_math();
    vec_seed(0x1D5EED02UL);
    vec_stages();
    vec_seed(0x1D5EED03UL);
    vec_result();
    vec_seed(0x1D5EED04UL);
    vec_band();
}

#else
void vec_id(void)
{
    emit_section("id_absent");
    emit_u8(0);
    emit_end();
}
#endif /* MC_IDENTIFY */
