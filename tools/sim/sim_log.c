/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_log.c - the record of a run and its summary lines (sim_log.h). */
#include "sim_log.h"

#include <math.h>
#include <string.h>

void sim_log_init(sim_log_t *l, const sim_log_core_t *core, int state0)
{
    memset(l, 0, sizeof(*l));
    l->core = core;
    l->t_start_s = -1.0;
    l->t_closed_s = -1.0;
    l->t_enter_closed_s = -1.0;
    l->prev_state = state0;
}

void sim_log_start(sim_log_t *l, double t_s)
{
    if (l->t_start_s < 0.0) {
        l->t_start_s = t_s;
    }
}

/* Events that change the operating point open a segment; these do not. */
static bool opens_segment(sim_event_kind_t k)
{
    return k != SIM_EV_ZOOM && k != SIM_EV_NOISE && k != SIM_EV_DEADTIME && k != SIM_EV_INVERTER &&
           k != SIM_EV_DEADTIME_SHAPE;
}

static void label_event(sim_log_segment_t *g, const sim_event_t *e)
{
    const char *name = sim_event_name(e->kind);
    snprintf(g->label, sizeof(g->label), "%s", name);
    if (e->kind == SIM_EV_SPEED || e->kind == SIM_EV_SPEED_RAMP) {
        if (e->v1 == SIM_SPEED_MAX || e->v1 == SIM_SPEED_MIN) {
            snprintf(g->label, sizeof(g->label), "%s %s", name,
                     (e->v1 == SIM_SPEED_MAX) ? "max" : "min");
        } else {
            snprintf(g->label, sizeof(g->label), "%s %.0f", name, e->v1);
        }
    } else if (e->kind == SIM_EV_LOAD || e->kind == SIM_EV_LOAD_FAN || e->kind == SIM_EV_VBUS) {
        snprintf(g->label, sizeof(g->label), "%s %.3g", name, e->v1);
    }
}

void sim_log_segments(sim_log_t *l, const sim_scenario_t *sc)
{
    int k;
    l->n_seg = 0;
    for (k = 0; k < sc->n && l->n_seg < SIM_LOG_MAX_SEGMENTS; k++) {
        const sim_event_t *e = &sc->ev[k];
        sim_log_segment_t *g;
        if (e->kind == SIM_EV_END) {
            break;
        }
        if (!opens_segment(e->kind)) {
            continue;
        }
        if (l->n_seg > 0 && l->seg[l->n_seg - 1].t0_s == e->t_s) {
            g = &l->seg[l->n_seg - 1];
            if (strlen(g->label) + strlen(sim_event_name(e->kind)) + 2 < sizeof(g->label)) {
                strcat(g->label, "+");
                strcat(g->label, sim_event_name(e->kind));
            }
            continue;
        }
        g = &l->seg[l->n_seg++];
        memset(g, 0, sizeof(*g));
        sim_window_init(&g->w);
        g->t0_s = e->t_s;
        label_event(g, e);
    }
    for (k = 0; k < l->n_seg; k++) {
        l->seg[k].t1_s = (k + 1 < l->n_seg) ? l->seg[k + 1].t0_s : sc->end_s;
        l->seg[k].win_s = l->seg[k].t0_s + 0.5 * (l->seg[k].t1_s - l->seg[k].t0_s);
    }
}

static void log_change(sim_log_t *l, const sim_sample_t *s)
{
    if (l->n_change < SIM_LOG_MAX_CHANGES) {
        sim_log_change_t *c = &l->change[l->n_change++];
        c->t_s = s->t_s;
        c->from = l->prev_state;
        c->to = s->state;
        c->fault = s->fault;
    }
}

void sim_log_add(sim_log_t *l, const sim_sample_t *s, double ts_s)
{
    double ipk = fmax(fabs(s->ia_a), fmax(fabs(s->ib_a), fabs(s->ic_a)));
    double slack = 0.5 * ts_s;
    bool settled;
    int k;
    if (ipk > l->i_peak_a) {
        l->i_peak_a = ipk;
        l->t_i_peak_s = s->t_s;
    }
    if (s->state != l->prev_state) {
        log_change(l, s);
        if (s->state == l->core->closed_loop) {
            l->t_enter_closed_s = s->t_s;
            if (l->t_closed_s < 0.0) {
                l->t_closed_s = s->t_s;
            }
        }
        l->prev_state = s->state;
    }
    settled = s->state == l->core->closed_loop && s->t_s >= l->t_enter_closed_s + SIM_LOG_SETTLE_S;
    for (k = 0; k < l->n_seg; k++) {
        sim_log_segment_t *g = &l->seg[k];
        if (s->t_s >= g->win_s - slack && s->t_s < g->t1_s - slack) {
            g->state_end = s->state;
            sim_window_add(&g->w, s, settled);
        }
    }
}

void sim_log_print_run(const sim_log_t *l, FILE *f)
{
    double ang_sum = 0.0, ang_sum2 = 0.0, ang_max = 0.0;
    long ang_n = 0;
    int k;
    for (k = 0; k < l->n_seg; k++) {
        ang_sum += l->seg[k].w.ang_sum;
        ang_sum2 += l->seg[k].w.ang_sum2;
        ang_max = fmax(ang_max, l->seg[k].w.ang_max);
        ang_n += l->seg[k].w.n;
    }
    if (l->t_closed_s >= 0.0 && l->t_start_s >= 0.0) {
        fprintf(f, "   time to closed loop       %.3f s (START at %.3f s)\n",
                l->t_closed_s - l->t_start_s, l->t_start_s);
    } else {
        fprintf(f, "   time to closed loop       never\n");
    }
    if (ang_n > 0) {
        fprintf(f,
                "   angle error (est - true)  mean %+.2f deg, rms %.2f deg, max |.| %.2f deg "
                "(settled closed loop, 2nd half of each segment)\n",
                ang_sum / (double)ang_n, sqrt(ang_sum2 / (double)ang_n), ang_max);
    }
}

void sim_log_print_states(const sim_log_t *l, FILE *f)
{
    const sim_log_core_t *c = l->core;
    int k, n_fault = 0;
    for (k = 0; k < l->n_change; k++) {
        if (l->change[k].to == c->fault) {
            n_fault++;
        }
    }
    fprintf(f, "   faults                    %d", n_fault);
    for (k = 0; k < l->n_change; k++) {
        if (l->change[k].to == c->fault) {
            fprintf(f, "  %s at %.4f s", c->fault_name(l->change[k].fault), l->change[k].t_s);
        }
    }
    fprintf(f, "\n   states                   ");
    for (k = 0; k < l->n_change && k < 24; k++) {
        fprintf(f, " %.3f:%s", l->change[k].t_s, c->state_name(l->change[k].to));
    }
    fprintf(f, "\n   %-20s %7s %7s %-11s %8s %8s %8s %7s %7s %7s %6s\n", "segment (event)",
            "from_s", "to_s", "state_end", "ref_rpm", "true_rpm", "est_rpm", "spd_err%", "ang_avg",
            "ang_max", "iq_A");
    for (k = 0; k < l->n_seg; k++) {
        const sim_log_segment_t *g = &l->seg[k];
        fprintf(f, "   %-20s %7.3f %7.3f %-11s", g->label, g->t0_s, g->t1_s,
                (g->w.n + g->w.n_skipped > 0) ? c->state_name(g->state_end) : "-");
        if (g->w.n > 0) {
            fprintf(f, " %8.1f %8.1f %8.1f %7.2f%% %+7.2f %7.2f %6.3f\n", sim_window_ref(&g->w),
                    sim_window_speed(&g->w), sim_window_est(&g->w), sim_window_speed_err_pct(&g->w),
                    sim_window_ang_mean(&g->w), g->w.ang_max, sim_window_iq(&g->w));
        } else {
            fprintf(f, " %8s %8s %8s %8s %7s %7s %6s\n", "-", "-", "-", "-", "-", "-", "-");
        }
    }
}
