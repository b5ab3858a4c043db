/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_window.h - sums of a steady-state window: speeds, speed error, angle error, current. */
#ifndef SIM_WINDOW_H
#define SIM_WINDOW_H

#include "sim_sample.h"

/*
 * The one copy of the window sums the simulator's summary (a segment's
 * second half), the closed-loop tests and the randomized campaign measure
 * with. A sample is counted (summed) or skipped (the caller's condition:
 * not in closed loop, not settled yet); both are counted in n + n_skipped.
 */
typedef struct {
    long n;         /* samples summed */
    long n_skipped; /* samples seen but not summed */
    double spd_sum, ref_sum, est_sum,
        iq_sum;                        /* true, reference, estimated speed (rpm); true iq (A) */
    double err_sum, err_sum2;          /* true speed - reference (rpm), and its square */
    double ang_sum, ang_sum2, ang_max; /* angle error (est - true, deg): sum, square, max |.| */
    double spd_min, spd_max;           /* true speed's extremes over the summed samples, rpm */
} sim_window_t;

void sim_window_init(sim_window_t *w);

/* One sample: summed when counted, else only counted as skipped. */
void sim_window_add(sim_window_t *w, const sim_sample_t *s, bool counted);

/* Means over the summed samples; 0 (speeds, current) or 180 (angles) when
 * none was summed, a value no bound accepts. */
double sim_window_speed(const sim_window_t *w); /* true speed, rpm */
double sim_window_ref(const sim_window_t *w);   /* the core's ramped reference, rpm */
double sim_window_est(const sim_window_t *w);   /* the core's estimate, rpm */
double sim_window_iq(const sim_window_t *w);    /* true iq, A */
double sim_window_ang_mean(const sim_window_t *w);
double sim_window_ang_rms(const sim_window_t *w);

/* Mean true speed versus mean reference, % of the reference (100 without one). */
double sim_window_speed_err_pct(const sim_window_t *w);

/* Mean estimate versus mean true speed, % of the true speed (100 without one). */
double sim_window_est_err_pct(const sim_window_t *w);

/* The speed error's RMS about its mean, % of the mean reference: a loop that
 * rings or limit-cycles shows here, not in the mean error (0 when empty). */
double sim_window_ripple_pct(const sim_window_t *w);

#endif /* SIM_WINDOW_H */
