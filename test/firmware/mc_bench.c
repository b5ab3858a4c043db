/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* mc_bench.c - the firmware tests' settings of the one bench (mc_bench.h). */
#include "mc_bench.h"

#include <stdlib.h>

void mc_bench_cfg_default(mc_bench_cfg_t *c)
{
    simcore_cfg_default(c);
    c->theta0_rad = 0.3;
    c->substeps = 2;
    c->seed = 12345u;
}

void mc_bench_init(mc_bench_t *b, const mc_bench_cfg_t *c)
{
    if (simcore_init(b, c) != 0) {
        abort(); /* simcore_init said why on stderr */
    }
}

void mc_bench_step(mc_bench_t *b)
{
    simcore_step(b);
}

long mc_bench_run_until(mc_bench_t *b, mc_state_t s, long n)
{
    for (long k = 0; k < n; k++) {
        mc_bench_step(b);
        if (b->st.state == s) {
            return k + 1;
        }
    }
    return -1;
}

double mc_bench_rpm(const mc_bench_t *b)
{
    return sim_plant_rpm(&b->rig.plant);
}

double mc_bench_angle_err_deg(const mc_bench_t *b)
{
    return b->now.theta_err_deg;
}

double mc_rpm_of_q15(int16_t q)
{
    return (double)q * (double)MC_SPEED_FULLSCALE_RPM / 32768.0;
}
