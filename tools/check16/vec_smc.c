/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* vec_smc.c - 16-bit check vectors for the sliding-mode estimator (smc_estimator/). */
/* check16-requires: smc_estimator/smc.c foc/lpf.c foc/atan2.c foc/sincos.c */
#include "emit.h"

#include "sincos.h"
#include "smc_params.h"

/*
 * Sections:
 *   smc_params       every field of two SMC_PARAMS_INIT sets (Hurst, dead-beat
 *                    band; Hurst with AN1078's relay gains): the compile-time
 *                    arithmetic must give the same integers with a 32-bit
 *                    double (avr-gcc) as with a 64-bit one.
 *   smc_phase_lead   smc_phase_lead over a sweep of x and four K per x.
 *   smc_speed        smc_speed_from_steps over edges and random sums.
 *   smc_update       6000 periods of a synthetic drive (a rotating current
 *                    and voltage whose frequency ramps from +0.6 to -0.3 of
 *                    full scale, with noise and a few full-scale spikes),
 *                    per period: inputs | theta, theta_raw, omega, valid,
 *                    z, e; for both parameter sets.
 */

/* The Hurst's R and L, read from its profile whatever MOTOR the check is
 * built for. */
#include "motors/motor_hurst.h"

#define VFS (24.0 / 1.7320508075688772)
static const smc_params_t set_linear =
    SMC_PARAMS_INIT(MOTOR_RS_OHM, MOTOR_LS_H, 50e-6, VFS, 4.4, 1.8,
                    SMC_MAXERR_DEADBEAT(MOTOR_RS_OHM, MOTOR_LS_H, 50e-6, VFS, 4.4, 1.8), 666.6667,
                    33.3333, 20, 100.0, 0.0584);
static const smc_params_t set_relay = SMC_PARAMS_INIT(
    MOTOR_RS_OHM, MOTOR_LS_H, 50e-6, VFS, 4.4, 1.7, 0.005, 666.6667, 33.3333, 20, 100.0, 0.0584);

static void emit_params(const smc_params_t *p)
{
    emit_i16(p->f);
    emit_i16(p->g);
    emit_u8(p->g_shift);
    emit_i16(p->kslide);
    emit_i16(p->max_err);
    emit_i16(p->kz);
    emit_u8(p->kz_shift);
    emit_i16(p->k_per_omega);
    emit_i16(p->k_min);
    emit_i16(p->omega_min);
    emit_i16(p->kspeed);
    emit_u8(p->kspeed_shift);
    emit_u16(p->irp_percalc);
    emit_i16(p->k_speed_lpf);
    emit_i16(p->emf_gain);
    emit_u8(p->emf_shift);
    emit_i16(p->tf_mdc);
    emit_i16(p->tf_b10);
    emit_i16(p->tf_b1k);
    emit_i16(p->tf_b2);
    emit_i16(p->tf_xadv);
    emit_end();
}

static void vec_smc_params(void)
{
    emit_section("smc_params");
    emit_params(&set_linear);
    emit_params(&set_relay);
}

static void vec_smc_phase_lead(void)
{
    int16_t x;
    emit_section("smc_phase_lead");
    for (x = 0; x < 12000; x = (int16_t)(x + 37)) {
        q15_t k0 = (x > set_linear.k_min) ? x : set_linear.k_min;
        q15_t ks[4];
        uint8_t m;
        ks[0] = k0;
        ks[1] = set_linear.k_min;
        ks[2] = (q15_t)((k0 < 16000) ? 2 * k0 : 32000);
        ks[3] = (q15_t)((k0 / 2 > 0) ? k0 / 2 : 1);
        for (m = 0U; m < 4U; m++) {
            emit_i16(x);
            emit_i16(ks[m]);
            emit_sep();
            emit_i16(smc_phase_lead(&set_linear, ks[m], x));
            emit_i16(smc_phase_lead(&set_relay, ks[m], x));
            emit_end();
        }
    }
}

static void vec_smc_speed(void)
{
    static const int32_t edges[] = {0L,        1L,       -1L,      16383L,  -16384L,
                                    32767L,    -32768L,  65535L,   -65536L, 4194303L,
                                    -4194304L, 8388607L, -8388608L};
    uint32_t k;
    emit_section("smc_speed");
    vec_seed(0x5A11U);
    for (k = 0U; k < 1013U; k++) {
        int32_t sum;
        if (k < sizeof edges / sizeof edges[0]) {
            sum = edges[k];
        } else {
            sum = (int32_t)(vec_rand_u32() & 0x00FFFFFFUL) - (int32_t)0x00800000L;
        }
        emit_i32(sum);
        emit_sep();
        emit_i16(smc_speed_from_steps(&set_linear, sum));
        emit_end();
    }
}

static void run_drive(const smc_params_t *p, uint32_t seed)
{
    smc_t s;
    angle_q15_t th = 0;
    int32_t step = 1311L * 256L; /* angle step per period, 1/256 counts */
    uint32_t frac = 0UL;
    uint16_t n;
    smc_init(&s, p);
    vec_seed(seed);
    for (n = 0U; n < 6000U; n++) {
        sincos_q15_t sc;
        sincos_q15_t sv;
        ab_q15_t i;
        ab_q15_t v;
        /* Ramp the frequency down through zero into reverse. */
        step -= 64L;
        frac += (uint32_t)step;
        th = angle_add(th, (angle_q15_t)(int16_t)(uint16_t)(frac >> 8));
        frac &= 0xFFUL;
        sc = sincos_compute(th);
        sv = sincos_compute(angle_add(th, 15000));
        i.alpha = q15_add_sat(q15_mul(sc.cos, Q15(0.1)), vec_rand_between(-20, 20));
        i.beta = q15_add_sat(q15_mul(sc.sin, Q15(0.1)), vec_rand_between(-20, 20));
        v.alpha = q15_mul(sv.cos, Q15(0.5));
        v.beta = q15_mul(sv.sin, Q15(0.5));
        if ((n % 997U) == 500U) {
            i.alpha = Q15_MIN; /* a full-scale spike */
            v.beta = Q15_MAX;
        }
        if (n == 3000U) {
            smc_preset_speed(&s, -12000);
        }
        smc_update(&s, i, v);
        if (s.count >= p->irp_percalc) { /* the window end and its slow step */
            smc_window_end(&s);
            smc_slow_step(&s);
            smc_apply(&s);
        }
        emit_i16(i.alpha);
        emit_i16(i.beta);
        emit_i16(v.alpha);
        emit_i16(v.beta);
        emit_sep();
        emit_i16(smc_theta(&s));
        emit_i16(smc_theta_raw(&s));
        emit_i16(smc_omega(&s));
        emit_bool(smc_valid(&s));
        emit_i16(s.z.alpha);
        emit_i16(s.e.beta);
        emit_i16(smc_emf_ratio(&s));
        emit_end();
    }
}

static void vec_smc_update(void)
{
    emit_section("smc_update_linear");
    run_drive(&set_linear, 0xA1U);
    emit_section("smc_update_relay");
    run_drive(&set_relay, 0xB2U);
}

void vec_smc(void)
{
    vec_smc_params();
    vec_smc_phase_lead();
    vec_smc_speed();
    vec_smc_update();
}
