/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_support.c - helpers shared by the host tests. */
#include "test_support.h"

#include <math.h>
#include <stdio.h>

void err_stats_init(err_stats_t *s)
{
    s->max_abs = 0.0;
    s->sum_abs = 0.0;
    s->sum = 0.0;
    s->n = 0;
    s->worst_at = 0.0;
}

void err_stats_add(err_stats_t *s, double err, double at)
{
    double a = fabs(err);
    if (a > s->max_abs || s->n == 0) {
        s->max_abs = a;
        s->worst_at = at;
    }
    s->sum_abs += a;
    s->sum += err;
    s->n++;
}

double err_stats_mean_abs(const err_stats_t *s)
{
    return (s->n > 0) ? s->sum_abs / (double)s->n : 0.0;
}

double err_stats_mean(const err_stats_t *s)
{
    return (s->n > 0) ? s->sum / (double)s->n : 0.0;
}

void err_stats_print(const char *name, const err_stats_t *s, const char *unit)
{
    printf("measured: %s: max |err| = %.4f %s (at %.6g), mean |err| = %.4f %s, n = %ld\n", name,
           s->max_abs, unit, s->worst_at, err_stats_mean_abs(s), unit, s->n);
}

double q15_to_double(q15_t x)
{
    return (double)x / 32768.0;
}

double q31_to_double(q31_t x)
{
    return (double)x / 2147483648.0;
}

double angle_to_rad(angle_q15_t a)
{
    return (double)a * M_PI / 32768.0;
}

double angle_diff_deg(double a_rad, double b_rad)
{
    double d = fmod((a_rad - b_rad) * 180.0 / M_PI, 360.0);
    if (d >= 180.0) {
        d -= 360.0;
    } else if (d < -180.0) {
        d += 360.0;
    }
    return d;
}

int64_t test_clamp64(int64_t v, int64_t lo, int64_t hi)
{
    return (v < lo) ? lo : ((v > hi) ? hi : v);
}

int64_t test_sat16(int64_t v)
{
    return test_clamp64(v, -32768, 32767);
}

int64_t test_sat32(int64_t v)
{
    return test_clamp64(v, -2147483647LL - 1LL, 2147483647LL);
}

int64_t test_floor_div(int64_t n, int64_t d)
{
    int64_t q = n / d;
    if ((n % d) != 0 && n < 0) {
        q -= 1;
    }
    return q;
}

uint32_t test_rand_u32(uint32_t *state)
{
    uint32_t x = *state;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    *state = x;
    return x;
}

int16_t test_rand_i16(uint32_t *state)
{
    return (int16_t)(uint16_t)(test_rand_u32(state) >> 16);
}

double test_rand_range(uint32_t *state, double lo, double hi)
{
    return lo + (hi - lo) * ((double)test_rand_u32(state) / 4294967296.0);
}
