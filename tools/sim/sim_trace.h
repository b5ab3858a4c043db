/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_trace.h - the CSV trace of a run: one row per sample (docs/sim.md "Outputs"). */
#ifndef SIM_TRACE_H
#define SIM_TRACE_H

#include <stdbool.h>
#include <stdio.h>

#include "sim_sample.h"

/* The column names, one line. */
void sim_trace_header(FILE *f);

/* One row; zoom: the row falls in a full-rate window (the plot's close-ups). */
void sim_trace_row(FILE *f, const sim_sample_t *s, bool zoom);

#endif /* SIM_TRACE_H */
