/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* bench_mc.c - instruction count of mc_step in the states reachable without a motor model. */
/* bench-requires: firmware/mc.c */
/* bench-symbols: mc_init mc_step mc_request */
#include "bench.h"

#include "mc.h"

/*
 * Without a plant the core sees currents that do not answer its voltages,
 * so these rows show the cost of the stopped state and of the start-up
 * (offset calibration, alignment, open-loop ramp) only. The closed-loop
 * max and mean of mc_step, on the simulated motor, are the row
 * "mc_step/closed_loop_sim" of bench_mc_closedloop.c.
 */
static void frame(mc_adc_frame_t *in)
{
    /* Currents near zero (amplifier offset 0, a few LSB of noise), the
     * nominal bus, the pot at half travel. */
    in->ia = bench_rand_between(-8, 8);
    in->ib = bench_rand_between(-8, 8);
    in->vbus = Q15_SCALED(BOARD_VBUS_NOMINAL_V, BOARD_VBUS_FULLSCALE_V);
    in->pot = 16384;
}

/* n steps of a fresh core, started first when start is true. */
static void run_steps(uint32_t n, bool start)
{
    static mc_t mc;
    uint32_t k;
    mc_init(&mc);
    if (start) {
        mc_request(&mc, MC_REQUEST_START);
    }
    for (k = 0U; k < n; k++) {
        mc_adc_frame_t in;
        mc_pwm_out_t out;
        frame(&in);
        mc_step(&mc, &in, &out);
        mc_slow_step(&mc);
        bench_sink += out.duty[0];
    }
}

static void run_stopped(uint32_t n)
{
    run_steps(n, false);
}

static void run_startup(uint32_t n)
{
    run_steps(n, true);
}

void bench_mc(void)
{
    bench_add("mc_step/stopped", "mc_step", 2000U, run_stopped);
    bench_add("mc_step/startup_no_plant", "mc_step", 20000U, run_startup);
}
