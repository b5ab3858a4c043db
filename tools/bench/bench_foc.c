/* bench_foc.c - instruction-count cases for every foc/ block that is present. */
/* bench-requires: foc/q15.h */
#include "bench.h"

#include "q15.h"

/*
 * tools/bench/run defines BENCH_HAVE_<BLOCK> for every foc/<block>.c, so a
 * block's row appears once its implementation exists. Inputs cover the
 * working range and the saturating corners in proportion to how the core
 * meets them (mostly inside the range), so the mean is a running cost and
 * the max the worst path.
 */
#define CALLS 2000U

#if defined(BENCH_HAVE_SINCOS)
#include "sincos.h"
static void run_sincos(uint32_t n)
{
    uint32_t k;
    for (k = 0U; k < n; k++) {
        sincos_q15_t sc = sincos_compute(bench_rand_i16());
        bench_sink += sc.sin + sc.cos;
    }
}
#endif

#if defined(BENCH_HAVE_CLARKE)
#include "clarke.h"
static void run_clarke(uint32_t n)
{
    uint32_t k;
    for (k = 0U; k < n; k++) {
        ab_q15_t ab =
            clarke_forward(bench_rand_between(-16384, 16383), bench_rand_between(-16384, 16383));
        bench_sink += ab.alpha + ab.beta;
    }
}
#endif

#if defined(BENCH_HAVE_PARK)
#include "park.h"
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
        dq = park_forward(ab, any_sc());
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
        ab = park_inverse(dq, any_sc());
        bench_sink += ab.alpha + ab.beta;
    }
}
#endif

#if defined(BENCH_HAVE_PI)
#include "pi.h"
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
        bench_sink += pi_update(&pi, 1000, meas);
    }
}
#endif

#if defined(BENCH_HAVE_SVGEN)
#include "svgen.h"
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
        svgen_update(v, 1000U, &out);
        bench_sink += out.duty[0] + out.duty[1] + out.duty[2];
    }
}
#endif

#if defined(BENCH_HAVE_LPF)
#include "lpf.h"
static void run_lpf(uint32_t n)
{
    lpf_t f;
    uint32_t k;
    lpf_reset(&f, 0);
    for (k = 0U; k < n; k++) {
        bench_sink += lpf_update(&f, bench_rand_i16(), Q15(0.05));
    }
}
#endif

#if defined(BENCH_HAVE_ATAN2)
#include "atan2.h"
static void run_atan2(uint32_t n)
{
    uint32_t k;
    for (k = 0U; k < n; k++) {
        bench_sink += atan2_q15(bench_rand_i16(), bench_rand_i16());
    }
}
#endif

#if defined(BENCH_HAVE_Q15_SQRT)
#include "q15_sqrt.h"
static void run_sqrt(uint32_t n)
{
    uint32_t k;
    for (k = 0U; k < n; k++) {
        bench_sink += q15_sqrt(bench_rand_between(0, 32767));
    }
}
#endif

#if defined(BENCH_HAVE_FIELDWEAK)
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
#endif

#if defined(BENCH_HAVE_RIPPLE)
#include "ripple.h"
static void run_ripple(uint32_t n)
{
    uint32_t k;
    for (k = 0U; k < n; k++) {
        dq_q15_t v;
        dq_q15_t r;
        v.d = bench_rand_between(-8000, 8000);
        v.q = bench_rand_between(-25000, 25000);
        r = ripple_compensate_dq(v, bench_rand_between(18000, 26000), 22000);
        bench_sink += r.d + r.q;
    }
}
#endif

#if defined(BENCH_HAVE_VLIMIT)
#include "vlimit.h"
static void run_vlimit(uint32_t n)
{
    uint32_t k;
    for (k = 0U; k < n; k++) {
        bench_sink += vlimit_vq_max(bench_rand_between(-31000, 31000), Q15(0.95));
    }
}
#endif

void bench_foc(void)
{
#if defined(BENCH_HAVE_SINCOS)
    bench_add("sincos_compute", "sincos_compute", CALLS, run_sincos);
#endif
#if defined(BENCH_HAVE_CLARKE)
    bench_add("clarke_forward", "clarke_forward", CALLS, run_clarke);
#endif
#if defined(BENCH_HAVE_PARK)
    bench_add("park_forward", "park_forward", CALLS, run_park_forward);
    bench_add("park_inverse", "park_inverse", CALLS, run_park_inverse);
#endif
#if defined(BENCH_HAVE_PI)
    bench_add("pi_update", "pi_update", CALLS, run_pi);
#endif
#if defined(BENCH_HAVE_SVGEN)
    bench_add("svgen_update", "svgen_update", CALLS, run_svgen);
#endif
#if defined(BENCH_HAVE_LPF)
    bench_add("lpf_update", "lpf_update", CALLS, run_lpf);
#endif
#if defined(BENCH_HAVE_ATAN2)
    bench_add("atan2_q15", "atan2_q15", CALLS, run_atan2);
#endif
#if defined(BENCH_HAVE_Q15_SQRT)
    bench_add("q15_sqrt", "q15_sqrt", CALLS, run_sqrt);
#endif
#if defined(BENCH_HAVE_FIELDWEAK)
    bench_add("fieldweak_id_ref", "fieldweak_id_ref", CALLS, run_fieldweak);
#endif
#if defined(BENCH_HAVE_RIPPLE)
    bench_add("ripple_compensate_dq", "ripple_compensate_dq", CALLS, run_ripple);
#endif
#if defined(BENCH_HAVE_VLIMIT)
    bench_add("vlimit_vq_max", "vlimit_vq_max", CALLS, run_vlimit);
#endif
}
