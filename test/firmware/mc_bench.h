/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* mc_bench.h - the firmware tests' settings of the one bench (tools/sim/sim_core.h). */
#ifndef MC_BENCH_H
#define MC_BENCH_H

#include <stdint.h>

#include "sim_core.h"

/* The bench is the simulator's (sim_core.h): the core driven exactly like
 * the ISR (sample, mc_step, the duties latched for the next period), the
 * plant in physical units. b.rig, b.mc, b.st, b.out, b.frame and
 * b.rpm_sample are the tests' view of it. */
typedef simcore_t mc_bench_t;
typedef simcore_cfg_t mc_bench_cfg_t;

/* The simulator's defaults with the firmware tests' own: the rotor at
 * 0.3 rad, 2 RK4 steps a period, noise seed 12345. */
void mc_bench_cfg_default(mc_bench_cfg_t *c);

/* Builds the bench; the test fails when the profiles are not this build's. */
void mc_bench_init(mc_bench_t *b, const mc_bench_cfg_t *c);

/* One PWM period (simcore_step). */
void mc_bench_step(mc_bench_t *b);

/* Steps until the state is s or n periods have passed; returns periods used
 * or -1. */
long mc_bench_run_until(mc_bench_t *b, mc_state_t s, long n);

/* True speed now, rpm. */
double mc_bench_rpm(const mc_bench_t *b);

/* Angle the core used for this period's sample minus the true angle at the
 * sample instant, degrees in [-180, 180). */
double mc_bench_angle_err_deg(const mc_bench_t *b);

/* A Q15 speed of the core in rpm. */
double mc_rpm_of_q15(int16_t q);

#endif /* MC_BENCH_H */
