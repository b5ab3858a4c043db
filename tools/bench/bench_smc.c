/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* bench_smc.c - instruction count of smc_update over a rotating back-EMF (sliding-mode estimator).
 */
/* bench-requires: smc_estimator/smc.c */
/* bench-symbols: smc_init */
#include "bench.h"

#include "sincos.h"
#include "smc_params.h"

/* The Hurst DMB0224C10002's data, read from its profile whatever MOTOR the
 * host build is for, so the row is the same on every build. */
#include "motors/motor_hurst.h"

/*
 * Parameters of the Hurst on the MCLV at 20 kHz: its R and L, the speed
 * full scale and the lowest speed in electrical Hz, its back-EMF constant in
 * V per electrical Hz; the voltage full scale 24 V / sqrt(3) and the current
 * full scale 4.4 A of the MCLV.
 * Inputs: currents and voltages rotating at 0.3 of full speed with a little
 * noise. smc_update is the per-period step, inline in smc_update.h, so it is
 * measured through a wrapper that is never inlined (its call and return
 * included); the speed window runs in smc_slow_step, counted in the
 * mc_slow_step rows.
 */
void bench_smc_update(smc_t *s, ab_q15_t i, ab_q15_t v);
__attribute__((noinline)) void bench_smc_update(smc_t *s, ab_q15_t i, ab_q15_t v)
{
    smc_update(s, i, v);
}

/* The speed full scale and the lowest speed in electrical Hz; the back-EMF
 * constant in peak phase volts per electrical Hz. */
#define WFS_HZ  (MOTOR_SPEED_FULLSCALE_RPM * MOTOR_POLE_PAIRS / 60.0)
#define FMIN_HZ (MOTOR_SPEED_MIN_RPM * MOTOR_POLE_PAIRS / 60.0)
#define KE_HZ   (MOTOR_KE_VPK_LL_PER_KRPM / 1.7320508075688772 / (1000.0 * MOTOR_POLE_PAIRS / 60.0))
static const smc_params_t params = SMC_PARAMS_INIT(MOTOR_RS_OHM, MOTOR_LS_H, 50e-6, 13.856, 4.4,
                                                   0.85, 0.1, WFS_HZ, FMIN_HZ, 20, 10.0, KE_HZ);

static void run_smc(uint32_t n)
{
    static smc_t s;
    uint32_t k;
    angle_q15_t theta = 0;
    smc_init(&s, &params);
    for (k = 0U; k < n; k++) {
        sincos_q15_t sc;
        ab_q15_t i;
        ab_q15_t v;
        theta = angle_add(theta, 655);
        sc = sincos_compute(theta);
        i.alpha = q15_add_sat(q15_mul(sc.cos, Q15(0.2)), bench_rand_between(-40, 40));
        i.beta = q15_add_sat(q15_mul(sc.sin, Q15(0.2)), bench_rand_between(-40, 40));
        v.alpha = q15_mul(sc.sin, Q15(-0.3));
        v.beta = q15_mul(sc.cos, Q15(0.3));
        bench_smc_update(&s, i, v);
        bench_sink += smc_theta(&s);
    }
}

void bench_smc(void)
{
    bench_add("smc_update", "bench_smc_update", 4000U, run_smc);
}
