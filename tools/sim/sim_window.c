/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_window.c - sums of a steady-state window (sim_window.h). */
#include "sim_window.h"

#include <math.h>

void sim_window_init(sim_window_t *w)
{
    w->n = 0;
    w->n_skipped = 0;
    w->spd_sum = w->ref_sum = w->est_sum = w->iq_sum = 0.0;
    w->err_sum = w->err_sum2 = 0.0;
    w->ang_sum = w->ang_sum2 = w->ang_max = 0.0;
    w->spd_min = 1e9; /* above any speed: the first summed sample replaces it */
    w->spd_max = -1e9;
}

void sim_window_add(sim_window_t *w, const sim_sample_t *s, bool counted)
{
    double err = s->speed_rpm - s->speed_ref_rpm;
    if (!counted) {
        w->n_skipped++;
        return;
    }
    w->n++;
    w->spd_sum += s->speed_rpm;
    w->ref_sum += s->speed_ref_rpm;
    w->est_sum += s->speed_est_rpm;
    w->iq_sum += s->iq_true_a;
    w->err_sum += err;
    w->err_sum2 += err * err;
    w->ang_sum += s->theta_err_deg;
    w->ang_sum2 += s->theta_err_deg * s->theta_err_deg;
    w->ang_max = fmax(w->ang_max, fabs(s->theta_err_deg));
    w->spd_min = fmin(w->spd_min, s->speed_rpm);
    w->spd_max = fmax(w->spd_max, s->speed_rpm);
}

static double mean(const sim_window_t *w, double sum, double empty)
{
    return (w->n > 0) ? sum / (double)w->n : empty;
}

double sim_window_speed(const sim_window_t *w)
{
    return mean(w, w->spd_sum, 0.0);
}

double sim_window_ref(const sim_window_t *w)
{
    return mean(w, w->ref_sum, 0.0);
}

double sim_window_est(const sim_window_t *w)
{
    return mean(w, w->est_sum, 0.0);
}

double sim_window_iq(const sim_window_t *w)
{
    return mean(w, w->iq_sum, 0.0);
}

double sim_window_ang_mean(const sim_window_t *w)
{
    return mean(w, w->ang_sum, 180.0);
}

double sim_window_ang_rms(const sim_window_t *w)
{
    return (w->n > 0) ? sqrt(w->ang_sum2 / (double)w->n) : 180.0;
}

double sim_window_speed_err_pct(const sim_window_t *w)
{
    double r = sim_window_ref(w);
    return (r != 0.0) ? 100.0 * (sim_window_speed(w) - r) / r : 100.0;
}

double sim_window_est_err_pct(const sim_window_t *w)
{
    double v = sim_window_speed(w);
    return (v != 0.0) ? 100.0 * (sim_window_est(w) - v) / v : 100.0;
}

double sim_window_ripple_pct(const sim_window_t *w)
{
    double m, var;
    if (w->n == 0) {
        return 0.0;
    }
    m = w->err_sum / (double)w->n;
    var = w->err_sum2 / (double)w->n - m * m;
    return 100.0 * sqrt((var > 0.0) ? var : 0.0) / (w->ref_sum / (double)w->n);
}
