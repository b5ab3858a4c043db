/* cl_helpers.h - shared steps of the closed-loop tests: run the core against the plant. */
#ifndef CL_HELPERS_H
#define CL_HELPERS_H

#include "test_support.h"

#include <math.h>
#include <stdio.h>

#include "sim_core.h"

#define CL_PERIOD_S (1.0 / (double)PWM_FREQUENCY_HZ)

/* Steady-state figures over a window, closed loop only. */
typedef struct {
    long n, n_all;
    double spd_sum, ref_sum, est_sum;
    double ang_sum, ang_sum2, ang_max;
    double spd_min, spd_max;
    bool left_closed_loop;
} cl_window_t;

static inline void cl_window_init(cl_window_t *w)
{
    w->n = 0;
    w->n_all = 0;
    w->spd_sum = w->ref_sum = w->est_sum = 0.0;
    w->ang_sum = w->ang_sum2 = w->ang_max = 0.0;
    w->spd_min = 1e9;
    w->spd_max = -1e9;
    w->left_closed_loop = false;
}

static inline void cl_window_add(cl_window_t *w, const simcore_sample_t *n)
{
    w->n_all++;
    if (n->state != MC_STATE_CLOSED_LOOP) {
        w->left_closed_loop = true;
        return;
    }
    w->n++;
    w->spd_sum += n->speed_rpm;
    w->ref_sum += n->speed_ref_rpm;
    w->est_sum += n->speed_est_rpm;
    w->ang_sum += n->theta_err_deg;
    w->ang_sum2 += n->theta_err_deg * n->theta_err_deg;
    w->ang_max = fmax(w->ang_max, fabs(n->theta_err_deg));
    w->spd_min = fmin(w->spd_min, n->speed_rpm);
    w->spd_max = fmax(w->spd_max, n->speed_rpm);
}

static inline double cl_speed(const cl_window_t *w)
{
    return (w->n > 0) ? w->spd_sum / (double)w->n : 0.0;
}
static inline double cl_ref(const cl_window_t *w)
{
    return (w->n > 0) ? w->ref_sum / (double)w->n : 0.0;
}
static inline double cl_est(const cl_window_t *w)
{
    return (w->n > 0) ? w->est_sum / (double)w->n : 0.0;
}
static inline double cl_speed_err_pct(const cl_window_t *w)
{
    double r = cl_ref(w);
    return (r != 0.0) ? 100.0 * (cl_speed(w) - r) / r : 100.0;
}
static inline double cl_ang_mean(const cl_window_t *w)
{
    return (w->n > 0) ? w->ang_sum / (double)w->n : 180.0;
}
static inline double cl_ang_rms(const cl_window_t *w)
{
    return (w->n > 0) ? sqrt(w->ang_sum2 / (double)w->n) : 180.0;
}

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

/* Steady window of `seconds`. */
static inline void cl_measure(simcore_t *s, double seconds, cl_window_t *w)
{
    long n = (long)(seconds / CL_PERIOD_S + 0.5);
    cl_window_init(w);
    while (n-- > 0) {
        simcore_step(s);
        cl_window_add(w, &s->now);
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
