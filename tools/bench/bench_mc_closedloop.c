/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* bench_mc_closedloop.c - instructions per mc_step in closed loop, the core on the simulated Hurst.
 */
/* bench-requires: firmware/mc.c smc_estimator/smc.c tools/sim/sim_core.c */
/* bench-symbols: mc_init mc_step simcore_init simcore_sample simcore_finish */
#include "bench.h"

#include "mc.h"
#include "sim_core.h"

/*
 * The core is started on the simulator's bench (tools/sim/sim_core.h: the
 * Hurst on the MCLV, its 24 V bus, dead time and ADC noise) and run into
 * CLOSED_LOOP with whole simcore_step() periods, which callgrind does not
 * count; then every period of the measured run is the bench's two halves
 * around mc_bench_cl_step(), the counted symbol: one mc_step() plus a
 * call's overhead. A quarter into the run the pot goes from 0.2 to full
 * travel, so the reference ramps into field weakening and every path of
 * the closed loop (speed loop every IRP_PERCALC periods, field weakening,
 * voltage limit) is in the max and the mean.
 */

static simcore_t bench;

/* The counted symbols: the step, and the slow step after each window end. */
__attribute__((noinline)) void mc_bench_cl_step(const mc_adc_frame_t *in, mc_pwm_out_t *out);
__attribute__((noinline)) void mc_bench_cl_step(const mc_adc_frame_t *in, mc_pwm_out_t *out)
{
    mc_step(&bench.mc, in, out);
}
__attribute__((noinline)) void mc_bench_cl_slow(void);
__attribute__((noinline)) void mc_bench_cl_slow(void)
{
    mc_slow_step(&bench.mc);
}

static void run_periods(uint32_t n)
{
    uint32_t k;
    mc_adc_frame_t in;
    simcore_cfg_t cfg;
    simcore_cfg_default(&cfg);
    cfg.theta0_rad = 0.3;
    cfg.substeps = 2;
    cfg.seed = 4242U;
    cfg.pot = 0.2; /* about 1460 rpm */
    if (simcore_init(&bench, &cfg) != 0) {
        return;
    }
    mc_request(&bench.mc, MC_REQUEST_START);
    for (k = 0U; k < 200000UL && bench.mc.state != MC_STATE_CLOSED_LOOP; k++) {
        simcore_step(&bench);
    }
    for (k = 0U; k < n; k++) {
        /* Pot to full travel after a quarter of the run: the reference
         * ramps into field weakening at MC_SPEED_RAMP_RPM_PER_S. */
        bench.rig.pot = (k < n / 4U) ? 0.2 : 1.0;
        simcore_sample(&bench, &in);
        mc_bench_cl_step(&in, &bench.out);
        if (bench.mc.ho.busy) {
            mc_bench_cl_slow();
        } else {
            mc_slow_step(&bench.mc); /* the same no-op, uncounted */
        }
        simcore_finish(&bench);
        bench_sink += (int32_t)bench.out.duty[0] + (int32_t)bench.mc.state;
    }
}

/* n periods: n calls of mc_bench_cl_step. */
static void run_closed_loop(uint32_t n)
{
    run_periods(n);
}

/* n calls of mc_bench_cl_slow: one per window. */
static void run_closed_loop_slow(uint32_t n)
{
    run_periods(n * MC_SLOW_STEP_PERIODS);
}

void bench_mc_closedloop(void)
{
    bench_add("mc_step/closed_loop_sim", "mc_bench_cl_step", 20000U, run_closed_loop);
    bench_add("mc_slow_step/closed_loop_sim", "mc_bench_cl_slow", 20000U / MC_SLOW_STEP_PERIODS,
              run_closed_loop_slow);
}
