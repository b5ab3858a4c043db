/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* cl_helpers.h - shared steps of the closed-loop tests: run the core against the plant. */
#ifndef CL_HELPERS_H
#define CL_HELPERS_H

#include "test_support.h"

#include <math.h>
#include <stdio.h>

#include "sim_core.h"
#include "sim_window.h"

#define CL_PERIOD_S (1.0 / (double)PWM_FREQUENCY_HZ)

/* Core + bench for the given motor and board profiles, noise and dead time of
 * the board; cfg has been set by simcore_cfg_default() (and then adjusted). */
static inline void cl_setup(simcore_t *s, simcore_cfg_t *cfg, const char *motor, const char *board)
{
    cfg->motor = motor;
    cfg->board = board;
    assert_int_equal(simcore_init(s, cfg), 0);
}

static inline void cl_run(simcore_t *s, double seconds)
{
    long n = (long)(seconds / CL_PERIOD_S + 0.5);
    while (n-- > 0) {
        simcore_step(s);
    }
}

/* Runs until closed loop with the true speed within tol_pct of target_rpm for
 * hold_s; returns the time that happened, or -1 after max_s. */
static inline double cl_run_until_at_speed(simcore_t *s, double target_rpm, double tol_pct,
                                           double hold_s, double max_s)
{
    double t_end = s->rig.t + max_s, t_in = -1.0;
    while (s->rig.t < t_end) {
        simcore_step(s);
        if (s->now.state == MC_STATE_CLOSED_LOOP &&
            fabs(s->now.speed_rpm - target_rpm) <= tol_pct / 100.0 * target_rpm) {
            if (t_in < 0.0) {
                t_in = s->now.t_s;
            }
            if (s->now.t_s - t_in >= hold_s) {
                return s->now.t_s;
            }
        } else {
            t_in = -1.0;
        }
    }
    return -1.0;
}

/* Pot at rpm and START, then cl_run_until_at_speed (2 %, held 0.2 s) within
 * max_s; the test fails, saying where the core is, if that does not happen. */
static inline void cl_start_and_reach(simcore_t *s, double rpm, double max_s)
{
    simcore_set_speed(s, rpm);
    simcore_request(s, MC_REQUEST_START);
    if (cl_run_until_at_speed(s, rpm, 2.0, 0.2, max_s) < 0.0) {
        fail_msg("%.0f rpm not reached within %.1f s: state %s, fault %s, true %.0f rpm", rpm,
                 max_s, mc_state_name(s->now.state), mc_fault_name(s->now.fault), s->now.speed_rpm);
    }
}

/* Runs until closed loop with the speed reference (ramped by the core) at
 * 99.9 % of ref_rpm or more, a FAULT, or max_s, whichever comes first. The
 * caller's window then tells which (a FAULT leaves closed loop). */
static inline void cl_run_until_ref(simcore_t *s, double ref_rpm, double max_s)
{
    double t_end = s->rig.t + max_s;
    while (s->rig.t < t_end &&
           !(s->now.state == MC_STATE_CLOSED_LOOP && s->now.speed_ref_rpm >= 0.999 * ref_rpm)) {
        simcore_step(s);
        if (s->now.state == MC_STATE_FAULT) {
            break;
        }
    }
}

/* A steady window of `seconds` (sim_window.h), closed loop only: a sample
 * outside closed loop is skipped, and w->n_skipped > 0 says the loop was left. */
static inline void cl_measure(simcore_t *s, double seconds, sim_window_t *w)
{
    long n = (long)(seconds / CL_PERIOD_S + 0.5);
    sim_window_init(w);
    while (n-- > 0) {
        simcore_step(s);
        sim_window_add(w, &s->now, s->now.state == MC_STATE_CLOSED_LOOP);
    }
}

static inline void cl_event(simcore_t *s, sim_event_kind_t kind, double v1, double v2)
{
    sim_event_t ev;
    ev.t_s = s->rig.t;
    ev.kind = kind;
    ev.v1 = v1;
    ev.v2 = v2;
    simcore_event(s, &ev);
}

#endif /* CL_HELPERS_H */
