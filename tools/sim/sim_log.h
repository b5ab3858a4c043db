/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_log.h - the record of a run: state changes, peak current, the segments' windows. */
#ifndef SIM_LOG_H
#define SIM_LOG_H

#include <stdio.h>

#include "sim_sample.h"
#include "sim_scenario.h"
#include "sim_window.h"

/* What the record knows of the core (sim_core.c hands in mc.h's): its state
 * codes and the names of its states and faults. */
typedef struct {
    const char *(*state_name)(int state);
    const char *(*fault_name)(unsigned fault);
    int closed_loop; /* the state code of closed loop */
    int fault;       /* ... and of FAULT */
} sim_log_core_t;

#define SIM_LOG_MAX_CHANGES  64
#define SIM_LOG_MAX_SEGMENTS 96

/* Angle-error window: skip this long after entering closed loop, s (the
 * hand-off bleeds the forced-angle offset away). */
#define SIM_LOG_SETTLE_S 0.1

/* A state change, at the sample that first shows it. */
typedef struct {
    double t_s;
    int from, to;
    unsigned fault;
} sim_log_change_t;

/* The span between two scenario events (events at the same time share one);
 * its window is the second half, closed loop only, settled. */
typedef struct {
    double t0_s, t1_s, win_s; /* segment and the start of its window, s */
    char label[40];           /* the event(s) that opened it */
    sim_window_t w;
    int state_end; /* state at the last sample in the window */
} sim_log_segment_t;

typedef struct {
    const sim_log_core_t *core;
    double t_start_s;        /* first start request, s; < 0 none */
    double t_closed_s;       /* first CLOSED_LOOP, s; < 0 never */
    double t_enter_closed_s; /* latest entry into CLOSED_LOOP, s */
    double i_peak_a, t_i_peak_s;
    int n_change;
    sim_log_change_t change[SIM_LOG_MAX_CHANGES]; /* the first ones */
    int n_seg;
    sim_log_segment_t seg[SIM_LOG_MAX_SEGMENTS];
    int prev_state;
} sim_log_t;

void sim_log_init(sim_log_t *l, const sim_log_core_t *core, int state0);

/* A start request at t_s (the first one counts). */
void sim_log_start(sim_log_t *l, double t_s);

/* One segment between each two operating-point events of the scenario. */
void sim_log_segments(sim_log_t *l, const sim_scenario_t *sc);

/* One period's sample; ts_s, the PWM period, sets half a period of slack at
 * the windows' edges (times are sums of periods, events exact). */
void sim_log_add(sim_log_t *l, const sim_sample_t *s, double ts_s);

/* The summary's lines of the whole run: time to closed loop, angle error. */
void sim_log_print_run(const sim_log_t *l, FILE *f);

/* ... and its faults, state changes and segment table. */
void sim_log_print_states(const sim_log_t *l, FILE *f);

#endif /* SIM_LOG_H */
