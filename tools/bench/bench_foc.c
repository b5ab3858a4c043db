/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* bench_foc.c - instruction-count cases for every foc/ block that is present. */
/* bench-requires: foc/q15.h */
#include "bench.h"

#include "q15.h"

/*
 * Inputs cover the
 * working range and the saturating corners in proportion to how the core
 * meets them (mostly inside the range), so the mean is a running cost and
 * the max the worst path.
 */
#define CALLS 2000U

/* The blocks of the 50 us path are inline in their headers (Q15_INLINE), so
 * they have no symbol of their own: each is measured through a wrapper that
 * is never inlined, bench_<function>, which adds its call and return (a
 * handful of instructions) to the figure. */
#define BENCH_NOINLINE __attribute__((noinline))

#include "sincos.h"
sincos_q15_t bench_sincos_compute(angle_q15_t theta);
BENCH_NOINLINE sincos_q15_t bench_sincos_compute(angle_q15_t theta)
{
    return sincos_compute(theta);
}
static void run_sincos(uint32_t n)
{
    uint32_t k;
    for (k = 0U; k < n; k++) {
        sincos_q15_t sc = bench_sincos_compute(bench_rand_i16());
        bench_sink += sc.sin + sc.cos;
    }
}

#include "clarke.h"
ab_q15_t bench_clarke_forward(q15_t ia, q15_t ib);
BENCH_NOINLINE ab_q15_t bench_clarke_forward(q15_t ia, q15_t ib)
{
    return clarke_forward(ia, ib);
}
static void run_clarke(uint32_t n)
{
    uint32_t k;
    for (k = 0U; k < n; k++) {
        ab_q15_t ab = bench_clarke_forward(bench_rand_between(-16384, 16383),
                                           bench_rand_between(-16384, 16383));
        bench_sink += ab.alpha + ab.beta;
    }
}

#include "park.h"
dq_q15_t bench_park_forward(ab_q15_t ab, sincos_q15_t sc);
BENCH_NOINLINE dq_q15_t bench_park_forward(ab_q15_t ab, sincos_q15_t sc)
{
    return park_forward(ab, sc);
}
ab_q15_t bench_park_inverse(dq_q15_t dq, sincos_q15_t sc);
BENCH_NOINLINE ab_q15_t bench_park_inverse(dq_q15_t dq, sincos_q15_t sc)
{
    return park_inverse(dq, sc);
}
static sincos_q15_t any_sc(void)
{
    /* A unit vector without calling sincos (which would be counted only
     * if it ran inside park; it does not, but keep the inputs simple). */
    sincos_q15_t sc;
    sc.sin = bench_rand_between(-23170, 23170);
    sc.cos = (int16_t)(((bench_rand_u32() & 1U) != 0U) ? 23170 : -23170);
    return sc;
}
static void run_park_forward(uint32_t n)
{
    uint32_t k;
    for (k = 0U; k < n; k++) {
        ab_q15_t ab;
        dq_q15_t dq;
        ab.alpha = bench_rand_between(-20000, 20000);
        ab.beta = bench_rand_between(-20000, 20000);
        dq = bench_park_forward(ab, any_sc());
        bench_sink += dq.d + dq.q;
    }
}
static void run_park_inverse(uint32_t n)
{
    uint32_t k;
    for (k = 0U; k < n; k++) {
        dq_q15_t dq;
        ab_q15_t ab;
        dq.d = bench_rand_between(-20000, 20000);
        dq.q = bench_rand_between(-20000, 20000);
        ab = bench_park_inverse(dq, any_sc());
        bench_sink += ab.alpha + ab.beta;
    }
}

#include "pi.h"
q15_t bench_pi_update(pi_t *pi, q15_t ref, q15_t meas);
BENCH_NOINLINE q15_t bench_pi_update(pi_t *pi, q15_t ref, q15_t meas)
{
    return pi_update(pi, ref, meas);
}
static void run_pi(uint32_t n)
{
    pi_params_t p;
    pi_t pi;
    uint32_t k;
    p.kp = Q15(0.6);
    p.kp_shift = 1U;
    p.ki = Q15(0.01);
    p.kc = Q15(0.01);
    p.out_min = Q15(-0.95);
    p.out_max = Q15(0.95);
    pi_init(&pi, &p);
    for (k = 0U; k < n; k++) {
        /* Small errors mostly; every 8th a large one that saturates. */
        int16_t meas = ((k & 7U) == 0U) ? bench_rand_i16() : bench_rand_between(-3000, 3000);
        bench_sink += bench_pi_update(&pi, 1000, meas);
    }
}

#include "svgen.h"
void bench_svgen_update(ab_q15_t v, uint16_t period, svgen_out_t *out);
BENCH_NOINLINE void bench_svgen_update(ab_q15_t v, uint16_t period, svgen_out_t *out)
{
    svgen_update(v, period, out);
}
static void run_svgen(uint32_t n)
{
    uint32_t k;
    for (k = 0U; k < n; k++) {
        ab_q15_t v;
        svgen_out_t out;
        /* Inside the linear circle mostly; every 8th over-modulated. */
        int16_t lim = ((k & 7U) == 0U) ? 32767 : 23000;
        v.alpha = bench_rand_between((int16_t)-lim, lim);
        v.beta = bench_rand_between((int16_t)-lim, lim);
        bench_svgen_update(v, 1000U, &out);
        bench_sink += out.duty[0] + out.duty[1] + out.duty[2];
    }
}

#include "lpf.h"
q15_t bench_lpf_update(lpf_t *f, q15_t x, q15_t k);
BENCH_NOINLINE q15_t bench_lpf_update(lpf_t *f, q15_t x, q15_t k)
{
    return lpf_update(f, x, k);
}
static void run_lpf(uint32_t n)
{
    lpf_t f;
    uint32_t k;
    lpf_reset(&f, 0);
    for (k = 0U; k < n; k++) {
        bench_sink += bench_lpf_update(&f, bench_rand_i16(), Q15(0.05));
    }
}

#include "atan2.h"
angle_q15_t bench_atan2_q15(int16_t y, int16_t x);
BENCH_NOINLINE angle_q15_t bench_atan2_q15(int16_t y, int16_t x)
{
    return atan2_q15(y, x);
}
static void run_atan2(uint32_t n)
{
    uint32_t k;
    for (k = 0U; k < n; k++) {
        bench_sink += bench_atan2_q15(bench_rand_i16(), bench_rand_i16());
    }
}

#include "q15_sqrt.h"
static void run_sqrt(uint32_t n)
{
    uint32_t k;
    for (k = 0U; k < n; k++) {
        bench_sink += q15_sqrt(bench_rand_between(0, 32767));
    }
}

#include "fieldweak.h"
static void run_fieldweak(uint32_t n)
{
    fieldweak_params_t p;
    fieldweak_t fw;
    uint32_t k;
    int16_t i;
    p.speed_nominal = Q15(0.5);
    p.speed_max = Q15(0.9);
    for (i = 0; i < FIELDWEAK_TABLE_SIZE; i++) {
        p.id_table[i] = (int16_t)(-i * 1000);
    }
    fieldweak_init(&fw, &p);
    for (k = 0U; k < n; k++) {
        bench_sink += fieldweak_id_ref(&fw, bench_rand_i16());
    }
}

#include "ripple.h"
dq_q15_t bench_ripple_compensate_dq(dq_q15_t v_pi, q15_t vbus, q15_t vbus_target);
BENCH_NOINLINE dq_q15_t bench_ripple_compensate_dq(dq_q15_t v_pi, q15_t vbus, q15_t vbus_target)
{
    return ripple_compensate_dq(v_pi, vbus, vbus_target);
}
static void run_ripple(uint32_t n)
{
    uint32_t k;
    for (k = 0U; k < n; k++) {
        dq_q15_t v;
        dq_q15_t r;
        v.d = bench_rand_between(-8000, 8000);
        v.q = bench_rand_between(-25000, 25000);
        r = bench_ripple_compensate_dq(v, bench_rand_between(18000, 26000), 22000);
        bench_sink += r.d + r.q;
    }
}

#include "vlimit.h"
q15_t bench_vlimit_vq_max(q15_t vd, q15_t vmax);
BENCH_NOINLINE q15_t bench_vlimit_vq_max(q15_t vd, q15_t vmax)
{
    return vlimit_vq_max(vd, vmax);
}
static void run_vlimit(uint32_t n)
{
    uint32_t k;
    for (k = 0U; k < n; k++) {
        bench_sink += bench_vlimit_vq_max(bench_rand_between(-31000, 31000), Q15(0.95));
    }
}

void bench_foc(void)
{
    bench_add("sincos_compute", "bench_sincos_compute", CALLS, run_sincos);
    bench_add("clarke_forward", "bench_clarke_forward", CALLS, run_clarke);
    bench_add("park_forward", "bench_park_forward", CALLS, run_park_forward);
    bench_add("park_inverse", "bench_park_inverse", CALLS, run_park_inverse);
    bench_add("pi_update", "bench_pi_update", CALLS, run_pi);
    bench_add("svgen_update", "bench_svgen_update", CALLS, run_svgen);
    bench_add("lpf_update", "bench_lpf_update", CALLS, run_lpf);
    bench_add("atan2_q15", "bench_atan2_q15", CALLS, run_atan2);
    bench_add("q15_sqrt", "q15_sqrt", CALLS, run_sqrt);
    bench_add("fieldweak_id_ref", "fieldweak_id_ref", CALLS, run_fieldweak);
    bench_add("ripple_compensate_dq", "bench_ripple_compensate_dq", CALLS, run_ripple);
    bench_add("vlimit_vq_max", "bench_vlimit_vq_max", CALLS, run_vlimit);
}
