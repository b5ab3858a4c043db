/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_support.h - helpers shared by the host tests: error statistics, conversions, PRNG. */
#ifndef TEST_SUPPORT_H
#define TEST_SUPPORT_H

/* cmocka needs these before it is included. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "q15.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* assert_cmp(a, op, b) with op one of < <= > >=: the comparison on the
 * values as doubles (exact for every integer a test compares), and on a
 * failure both expressions with their values (cmocka's assert_true prints
 * only the expression's text). */
#define assert_cmp(a, op, b)                                                                       \
    do {                                                                                           \
        const double assert_a_ = (double)(a);                                                      \
        const double assert_b_ = (double)(b);                                                      \
        if (!(assert_a_ op assert_b_)) {                                                           \
            fail_msg("%s " #op " %s: %.9g " #op " %.9g is false", #a, #b, assert_a_, assert_b_);   \
        }                                                                                          \
    } while (0)

/* Worst and mean absolute error of a sweep, with the input that gave the worst. */
typedef struct {
    double max_abs;
    double sum_abs;
    double sum;
    long n;
    double worst_at;
} err_stats_t;

void err_stats_init(err_stats_t *s);
void err_stats_add(err_stats_t *s, double err, double at);
double err_stats_mean_abs(const err_stats_t *s);
double err_stats_mean(const err_stats_t *s);
/* Prints "measured: <name>: max |err| = .. <unit> (at ..), mean |err| = .., n = .."
 * so the figures of every sweep are in the test log. */
void err_stats_print(const char *name, const err_stats_t *s, const char *unit);

double q15_to_double(q15_t x);
double q31_to_double(q31_t x);
/* Binary angle -> radians in [-pi, pi). */
double angle_to_rad(angle_q15_t a);
/* Radians -> degrees of the shortest difference a - b, in [-180, 180). */
double angle_diff_deg(double a_rad, double b_rad);

/* Exact integer references: clamp, the int16 and int32 saturations, and
 * floor(n / d) for d > 0 and any sign of n (no >> of a negative value). */
int64_t test_clamp64(int64_t v, int64_t lo, int64_t hi);
int64_t test_sat16(int64_t v);
int64_t test_sat32(int64_t v);
int64_t test_floor_div(int64_t n, int64_t d);

/* Deterministic xorshift32; state must be non-zero. */
uint32_t test_rand_u32(uint32_t *state);
/* Uniform int16 over the whole range. */
int16_t test_rand_i16(uint32_t *state);
/* Uniform double in [lo, hi). */
double test_rand_range(uint32_t *state, double lo, double hi);

#endif /* TEST_SUPPORT_H */
