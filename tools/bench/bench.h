/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* bench.h - registration API of the instruction-count bench (tools/bench/run, make bench). */
#ifndef BENCH_H
#define BENCH_H

#include <stdint.h>

/*
 * A bench module (tools/bench/bench_<module>.c) defines
 *     void bench_<module>(void);
 * which registers its cases with bench_add(). tools/bench/run runs every
 * case once under valgrind's callgrind with --toggle-collect=<symbol>
 * --dump-after=<symbol>: each call of <symbol> is measured on its own
 * (inclusive of what it calls), so the table shows min, mean and max
 * instructions per call. Setting up the inputs costs nothing: only
 * instructions executed inside <symbol> are counted.
 *
 *   name    the table row, [A-Za-z0-9_/.-] only (no spaces)
 *   symbol  the function measured; it must be an out-of-line call from
 *           run() (a block of the core libraries always is)
 *   calls   how many times run() calls symbol; at most BENCH_MAX_CALLS
 *           (every call leaves one small dump file while it is measured)
 *   run     does the calls, with varied inputs
 */
#define BENCH_MAX_CALLS 20000UL

typedef void (*bench_run_fn)(uint32_t calls);
void bench_add(const char *name, const char *symbol, uint32_t calls, bench_run_fn run);

/* Results go here so no call can be optimised away. */
extern volatile int32_t bench_sink;

/* Deterministic inputs (xorshift32). */
uint32_t bench_rand_u32(void);
int16_t bench_rand_i16(void);
/* Uniform in [lo, hi]. */
int16_t bench_rand_between(int16_t lo, int16_t hi);

#endif /* BENCH_H */
