/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_clarke_park.c - Clarke, Park and inverse Park against double references. */
#include "test_support.h"

#include <math.h>
#include <stdio.h>

#include "clarke.h"
#include "park.h"
#include "sincos.h"

/* Bounds stated in clarke.h / park.h (LSB of Q15). */
#define CLARKE_BETA_MAX_ERR_LSB 0.7  /* 0.5 rounding + 0.2 for the Q16 1/sqrt(3) */
#define PARK_ARITH_MAX_ERR_LSB  0.5  /* one rounding, given the sin/cos values */
#define SINCOS_MAX_ERR_LSB      1.5  /* sincos.h */
#define SINCOS_NORM_MAX_LSB     4.25 /* sincos.h: 32768 |sin^2 + cos^2 - 1| */

static double clamp_q15(double v)
{
    if (v > 32767.0) {
        return 32767.0;
    }
    if (v < -32768.0) {
        return -32768.0;
    }
    return v;
}

/* The saturated Q15 value nearest to v (ties up, as the code rounds). */
static double round_sat_q15(double v)
{
    return clamp_q15(floor(v + 0.5));
}

/* ---- Clarke -------------------------------------------------------------- */

static void check_clarke(q15_t ia, q15_t ib, err_stats_t *e, long *n_sat)
{
    ab_q15_t ab = clarke_forward(ia, ib);
    double exact = ((double)ia + 2.0 * (double)ib) / sqrt(3.0);

    assert_int_equal(ab.alpha, ia);
    if (exact >= 32767.5 || exact < -32768.5) {
        /* Outside full scale: saturated to the right side, never wrapped. */
        assert_cmp((double)ab.beta, ==, clamp_q15(exact));
        (*n_sat)++;
    } else {
        err_stats_add(e, (double)ab.beta - exact, (double)ia * 65536.0 + (double)ib);
    }
}

static void test_clarke_forward_should_stay_within_bound_over_a_dense_grid(void **state)
{
    err_stats_t e;
    long n_sat = 0;
    int32_t ia;
    int32_t ib;
    (void)state;

    err_stats_init(&e);
    /* every 3rd ia x every 37th ib (3.9e7 pairs), both grids through the ends */
    for (ia = -32768; ia <= 32767; ia += 3) {
        for (ib = -32768; ib <= 32767; ib += 37) {
            check_clarke((q15_t)ia, (q15_t)ib, &e, &n_sat);
        }
        check_clarke((q15_t)ia, 32767, &e, &n_sat);
    }
    for (ib = -32768; ib <= 32767; ib++) { /* the edges of ia against every ib */
        check_clarke(-32768, (q15_t)ib, &e, &n_sat);
        check_clarke(32767, (q15_t)ib, &e, &n_sat);
        check_clarke(0, (q15_t)ib, &e, &n_sat);
        check_clarke(-1, (q15_t)ib, &e, &n_sat);
    }
    err_stats_print("clarke beta, dense grid (unsaturated part)", &e, "LSB");
    printf("measured: clarke beta saturated (and checked exact) in %ld cases\n", n_sat);
    assert_cmp(e.n, >, 20000000L);
    assert_cmp(n_sat, >, 1000000L);
    assert_cmp(e.max_abs, <=, CLARKE_BETA_MAX_ERR_LSB);
}

static void test_clarke_forward_should_be_amplitude_invariant_on_a_balanced_set(void **state)
{
    /* ia = A cos(th), ib = A cos(th - 120 deg) -> alpha = A cos th, beta = A sin th.
     * The inputs are rounded to integers, which adds up to 1.5 / sqrt(3) LSB. */
    static const double amps[] = {32767.0, 20000.0, 1000.0, 10.0};
    const double bound = CLARKE_BETA_MAX_ERR_LSB + 1.5 / sqrt(3.0);
    size_t m;
    (void)state;

    for (m = 0U; m < sizeof amps / sizeof amps[0]; m++) {
        err_stats_t ea;
        err_stats_t eb;
        char name[96];
        int k;
        err_stats_init(&ea);
        err_stats_init(&eb);
        for (k = 0; k < 65536; k++) {
            double th = (double)k * 2.0 * M_PI / 65536.0;
            q15_t ia = (q15_t)lround(amps[m] * cos(th));
            q15_t ib = (q15_t)lround(amps[m] * cos(th - 2.0 * M_PI / 3.0));
            ab_q15_t ab = clarke_forward(ia, ib);
            err_stats_add(&ea, (double)ab.alpha - amps[m] * cos(th), (double)k);
            err_stats_add(&eb, (double)ab.beta - amps[m] * sin(th), (double)k);
        }
        (void)snprintf(name, sizeof name, "clarke balanced set, amplitude %.0f, alpha", amps[m]);
        err_stats_print(name, &ea, "LSB");
        (void)snprintf(name, sizeof name, "clarke balanced set, amplitude %.0f, beta", amps[m]);
        err_stats_print(name, &eb, "LSB");
        assert_cmp(ea.max_abs, <=, 0.5);
        assert_cmp(eb.max_abs, <=, bound);
    }
}

static void test_clarke_forward_should_saturate_monotonically_at_the_edges(void **state)
{
    static const q15_t ias[] = {-32768, -1, 0, 32767};
    size_t j;
    ab_q15_t ab;
    (void)state;

    for (j = 0U; j < sizeof ias / sizeof ias[0]; j++) {
        q15_t prev = -32768;
        int32_t ib;
        for (ib = -32768; ib <= 32767; ib++) {
            ab = clarke_forward(ias[j], (q15_t)ib);
            assert_cmp(ab.beta, >=, prev); /* no wrap anywhere along ib */
            prev = ab.beta;
        }
    }
    ab = clarke_forward(0, 0);
    assert_int_equal(ab.alpha, 0);
    assert_int_equal(ab.beta, 0);
    ab = clarke_forward(-32768, -32768);
    assert_int_equal(ab.alpha, -32768);
    assert_int_equal(ab.beta, -32768);
    ab = clarke_forward(32767, 32767);
    assert_int_equal(ab.beta, 32767);
    ab = clarke_forward(-32768, 32767); /* u = 32766: 18917.2 */
    assert_int_equal(ab.beta, 18917);
    ab = clarke_forward(32767, -32768); /* u = -32769: -18919.3 */
    assert_int_equal(ab.beta, -18919);
    ab = clarke_forward(1, 0);
    assert_int_equal(ab.beta, 1); /* 0.577 rounds to 1 */
    /* The clamp points: u = 56755 -> 32767, u = 56756 -> 32767 (saturated),
     * u = -56756 -> -32768, u = -56757 -> -32768 (saturated). */
    assert_int_equal(clarke_forward(-8779, 32767).beta, 32767);
    assert_int_equal(clarke_forward(-8778, 32767).beta, 32767);
    assert_int_equal(clarke_forward(8780, -32768).beta, -32768);
    assert_int_equal(clarke_forward(8779, -32768).beta, -32768);
    assert_int_equal(clarke_forward(-8781, 32767).beta, 32766); /* u = 56753: 32766.4 */
}

/* ---- Park / inverse Park ------------------------------------------------- */

typedef struct {
    err_stats_t arith; /* against double using the same sin/cos values */
    err_stats_t angle; /* against double sin/cos of the true angle (inside the unit circle) */
    long n_sat;
} park_errs_t;

static void park_errs_init(park_errs_t *e)
{
    err_stats_init(&e->arith);
    err_stats_init(&e->angle);
    e->n_sat = 0;
}

/* Record the error of one computed output against its exact value (and,
 * when given, against the true-angle value). */
static void park_record(park_errs_t *e, q15_t got, double exact, double exact_angle, int inside,
                        double at)
{
    if (exact >= 32767.5 || exact < -32768.5) {
        assert_cmp((double)got, ==, round_sat_q15(exact)); /* saturated, correct side */
        e->n_sat++;
    } else {
        err_stats_add(&e->arith, (double)got - exact, at);
    }
    if (inside) {
        err_stats_add(&e->angle, (double)got - exact_angle, at);
    }
}

static void park_check_one(park_errs_t *ef, park_errs_t *ei, uint16_t a, q15_t u, q15_t v)
{
    sincos_q15_t sc = sincos_compute((angle_q15_t)(int16_t)a);
    double s = q15_to_double(sc.sin);
    double c = q15_to_double(sc.cos);
    double th = (double)a * 2.0 * M_PI / 65536.0;
    double st = sin(th);
    double ct = cos(th);
    int inside = ((double)u * u + (double)v * v) <= 32767.0 * 32767.0;
    ab_q15_t ab;
    dq_q15_t dq;
    ab_q15_t back;

    /* forward: (alpha, beta) = (u, v) */
    ab.alpha = u;
    ab.beta = v;
    dq = park_forward(ab, sc);
    park_record(ef, dq.d, u * c + v * s, u * ct + v * st, inside, (double)a);
    park_record(ef, dq.q, -u * s + v * c, -u * st + v * ct, inside, (double)a);

    /* inverse: (d, q) = (u, v) */
    dq.d = u;
    dq.q = v;
    back = park_inverse(dq, sc);
    park_record(ei, back.alpha, u * c - v * s, u * ct - v * st, inside, (double)a);
    park_record(ei, back.beta, u * s + v * c, u * st + v * ct, inside, (double)a);
}

static void test_park_should_stay_within_bound_over_angles_and_vectors(void **state)
{
    park_errs_t ef;
    park_errs_t ei;
    uint32_t seed = 0x600DCAFEU;
    uint32_t a;
    int i;
    /* inside the unit circle: 0.5 LSB + (|u| + |v|) sincos error <= 0.5 + sqrt(2) 1.5 */
    const double angle_bound = PARK_ARITH_MAX_ERR_LSB + sqrt(2.0) * SINCOS_MAX_ERR_LSB;
    (void)state;

    park_errs_init(&ef);
    park_errs_init(&ei);
    for (a = 0U; a < 65536U; a++) {
        /* every angle with the edge vectors, then 64 random full-range vectors */
        park_check_one(&ef, &ei, (uint16_t)a, 32767, 0);
        park_check_one(&ef, &ei, (uint16_t)a, -32768, 0);
        park_check_one(&ef, &ei, (uint16_t)a, 0, -32768);
        park_check_one(&ef, &ei, (uint16_t)a, 23170, 23170);
        park_check_one(&ef, &ei, (uint16_t)a, -32768, -32768);
        park_check_one(&ef, &ei, (uint16_t)a, 32767, 32767);
        for (i = 0; i < 64; i++) {
            park_check_one(&ef, &ei, (uint16_t)a, test_rand_i16(&seed), test_rand_i16(&seed));
        }
    }
    err_stats_print("park_forward vs double with the same sin/cos", &ef.arith, "LSB");
    err_stats_print("park_forward vs double with the true angle (|v| <= 1)", &ef.angle, "LSB");
    err_stats_print("park_inverse vs double with the same sin/cos", &ei.arith, "LSB");
    err_stats_print("park_inverse vs double with the true angle (|v| <= 1)", &ei.angle, "LSB");
    printf("measured: park saturated outputs checked exact: forward %ld, inverse %ld\n", ef.n_sat,
           ei.n_sat);
    assert_cmp(ef.arith.n, >, 8000000L);
    assert_cmp(ef.n_sat, >, 100000L);
    assert_cmp(ei.n_sat, >, 100000L);
    assert_cmp(ef.arith.max_abs, <=, PARK_ARITH_MAX_ERR_LSB);
    assert_cmp(ei.arith.max_abs, <=, PARK_ARITH_MAX_ERR_LSB);
    assert_cmp(ef.angle.max_abs, <=, angle_bound);
    assert_cmp(ei.angle.max_abs, <=, angle_bound);
}

static void test_park_inverse_should_undo_park_forward_within_a_few_lsb(void **state)
{
    /* inverse(forward(v)) = (sin^2 + cos^2) v + rotated roundings, so each
     * component is within |comp| 4.25 / 32768 + 0.5 (|sin| + |cos|) + 0.5
     * <= |comp| 4.25 / 32768 + 1.21 LSB. */
    err_stats_t e;
    uint32_t seed = 0xA5A5F00DU;
    uint32_t a;
    int i;
    (void)state;

    err_stats_init(&e);
    for (a = 0U; a < 65536U; a++) {
        sincos_q15_t sc = sincos_compute((angle_q15_t)(int16_t)(uint16_t)a);
        for (i = 0; i < 32; i++) {
            ab_q15_t ab;
            ab_q15_t back;
            double r;
            double ea;
            double eb;
            /* inside the unit circle, so the forward step does not saturate */
            do {
                ab.alpha = test_rand_i16(&seed);
                ab.beta = test_rand_i16(&seed);
                r = (double)ab.alpha * ab.alpha + (double)ab.beta * ab.beta;
            } while (r > 32767.0 * 32767.0);
            back = park_inverse(park_forward(ab, sc), sc);
            ea = (double)back.alpha - (double)ab.alpha;
            eb = (double)back.beta - (double)ab.beta;
            err_stats_add(&e, ea, (double)a);
            err_stats_add(&e, eb, (double)a);
            assert_cmp(fabs(ea), <=, fabs((double)ab.alpha) * SINCOS_NORM_MAX_LSB / 32768.0 + 1.21);
            assert_cmp(fabs(eb), <=, fabs((double)ab.beta) * SINCOS_NORM_MAX_LSB / 32768.0 + 1.21);
        }
    }
    err_stats_print("park round trip inverse(forward(v)) - v", &e, "LSB");
    assert_cmp(e.max_abs, <=, SINCOS_NORM_MAX_LSB + 1.21);
}

static void test_park_should_saturate_cleanly_outside_the_unit_circle(void **state)
{
    sincos_q15_t sc;
    ab_q15_t ab;
    dq_q15_t dq;
    (void)state;

    /* (1, 1) at 45 degrees: d = sqrt(2) -> 32767, q = 0 */
    sc = sincos_compute(ANGLE_Q15_DEG(45));
    ab.alpha = 32767;
    ab.beta = 32767;
    dq = park_forward(ab, sc);
    assert_int_equal(dq.d, 32767);
    assert_cmp(dq.q, >=, -1);
    assert_cmp(dq.q, <=, 1);
    ab.alpha = -32768;
    ab.beta = -32768;
    dq = park_forward(ab, sc);
    assert_int_equal(dq.d, -32768);
    /* inverse: d = q = -1 at 45 degrees: alpha = 0, beta = -sqrt(2) -> -32768 */
    dq.d = -32768;
    dq.q = -32768;
    ab = park_inverse(dq, sc);
    assert_cmp(ab.alpha, >=, -1);
    assert_cmp(ab.alpha, <=, 1);
    assert_int_equal(ab.beta, -32768);
    /* -32768 in sin/cos (not from sincos_compute, but a caller may pass it):
     * the -1 x -1 products saturate in the accumulator, no wrap. */
    sc.sin = -32768;
    sc.cos = -32768;
    ab.alpha = -32768;
    ab.beta = -32768;
    dq = park_forward(ab, sc);
    assert_int_equal(dq.d, 32767); /* 1 + 1 */
    assert_int_equal(dq.q, 0);     /* -1 + 1 */
    dq.d = -32768;
    dq.q = 32767;
    ab = park_inverse(dq, sc);
    assert_int_equal(ab.alpha, 32767); /* 1 + 32767/32768 */
    assert_int_equal(ab.beta, 1);      /* 1 - 32767/32768 = 1 LSB (less 2^-31) */
}

static void test_park_should_scale_by_cos_zero_at_zero_angle(void **state)
{
    sincos_q15_t sc = sincos_compute(0); /* sin 0, cos 32767 */
    static const q15_t vals[] = {-32768, -32767, -16384, -1, 0, 1, 16383, 16384, 32767};
    size_t i;
    size_t j;
    (void)state;

    for (i = 0U; i < sizeof vals / sizeof vals[0]; i++) {
        for (j = 0U; j < sizeof vals / sizeof vals[0]; j++) {
            ab_q15_t ab;
            dq_q15_t dq;
            ab.alpha = vals[i];
            ab.beta = vals[j];
            dq = park_forward(ab, sc);
            /* cos 0 is 32767/32768: v (1 - 2^-15), rounded once (ties up),
             * which leaves |v| < 16384 unchanged and moves the ends by 1 */
            assert_int_equal(dq.d, (q15_t)floor((double)vals[i] * 32767.0 / 32768.0 + 0.5));
            assert_int_equal(dq.q, (q15_t)floor((double)vals[j] * 32767.0 / 32768.0 + 0.5));
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_clarke_forward_should_stay_within_bound_over_a_dense_grid),
        cmocka_unit_test(test_clarke_forward_should_be_amplitude_invariant_on_a_balanced_set),
        cmocka_unit_test(test_clarke_forward_should_saturate_monotonically_at_the_edges),
        cmocka_unit_test(test_park_should_stay_within_bound_over_angles_and_vectors),
        cmocka_unit_test(test_park_inverse_should_undo_park_forward_within_a_few_lsb),
        cmocka_unit_test(test_park_should_saturate_cleanly_outside_the_unit_circle),
        cmocka_unit_test(test_park_should_scale_by_cos_zero_at_zero_angle),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
