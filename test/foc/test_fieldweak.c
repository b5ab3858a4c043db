/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_fieldweak.c - fieldweak_id_ref against double linear interpolation of the table. */
#include "test_support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "fieldweak.h"

/* The reference, in LSB: 0 below nominal, the last entry at and above max,
 * linear interpolation between 16 equally spaced points otherwise. */
static double ref_id(const fieldweak_params_t *p, q15_t speed)
{
    double s = fabs((double)speed);
    if (s > 32767.0) {
        s = 32767.0;
    }
    double nom = (double)p->speed_nominal;
    double max = (double)p->speed_max;
    if (p->speed_nominal < 0 || max <= nom || s < nom) {
        return 0.0;
    }
    if (s >= max) {
        return (double)p->id_table[15];
    }
    double pos = 15.0 * (s - nom) / (max - nom);
    int i = (int)floor(pos);
    double f = pos - (double)i;
    return (double)p->id_table[i] + f * ((double)p->id_table[i + 1] - (double)p->id_table[i]);
}

/* fieldweak.h: |error| <= 0.5 + |step| / 131072 LSB, step = the difference
 * of the two bracketing entries. */
static double bound_at(const fieldweak_params_t *p, q15_t speed)
{
    double s = fabs((double)speed);
    if (s > 32767.0) {
        s = 32767.0;
    }
    double nom = (double)p->speed_nominal;
    double max = (double)p->speed_max;
    if (max <= nom || s < nom || s >= max) {
        return 0.0; /* table end or zero: exact */
    }
    int i = (int)floor(15.0 * (s - nom) / (max - nom));
    return 0.5 + fabs((double)p->id_table[i + 1] - (double)p->id_table[i]) / 131072.0 + 1e-9;
}

/* A falling Id table like AN1078's dqKfw0..15 (0 down to -0.7 of full scale,
 * steeper at first). */
static void table_an1078_like(q15_t t[16])
{
    for (int i = 0; i < 16; i++) {
        t[i] = (q15_t)lround(-0.7 * 32768.0 * sqrt((double)i / 15.0));
    }
}

/* Sweep every speed -32768..32767 and check the bound point by point. */
static void sweep(const fieldweak_params_t *p, err_stats_t *e, double *worst_excess)
{
    fieldweak_t fw;
    fieldweak_init(&fw, p);
    for (int32_t sp = -32768; sp <= 32767; sp++) {
        q15_t id = fieldweak_id_ref(&fw, (q15_t)sp);
        double err = (double)id - ref_id(p, (q15_t)sp);
        double b = bound_at(p, (q15_t)sp);
        if (b == 0.0) {
            assert_cmp(err, ==, 0.0); /* zero or the last entry: exact */
        } else if (fabs(err) - b > *worst_excess) {
            *worst_excess = fabs(err) - b;
        }
        err_stats_add(e, err, (double)sp);
    }
}

/* {nominal, max}: a typical 1 : 1.8 range, the widest span, one where
 * AN1078's Q15(a - b + 1) would overflow (16384..32767), spans of 1, 2 and
 * around 15 counts, a multiple of 15, and 0..14429, where the reciprocal's
 * first guess of the segment overshoots (speed 13467: the i-- path). */
static const q15_t spans[][2] = {
    {Q15(0.5), Q15(0.9)}, {0, 32767},   {16384, 32767}, {1000, 1001}, {1000, 1002},   {1000, 1015},
    {1000, 1016},         {1000, 1017}, {20000, 20255}, {5, 32766},   {12345, 23456}, {0, 14429},
};

static void test_fieldweak_id_ref_should_match_linear_interpolation_over_every_speed(void **state)
{
    (void)state;
    err_stats_t e;
    err_stats_init(&e);
    double worst_excess = -10.0;
    fieldweak_params_t p;
    table_an1078_like(p.id_table);
    for (unsigned k = 0; k < sizeof spans / sizeof spans[0]; k++) {
        p.speed_nominal = spans[k][0];
        p.speed_max = spans[k][1];
        sweep(&p, &e, &worst_excess);
    }
    err_stats_print("fieldweak AN1078-like table, 12 spans x all 65536 speeds", &e, "LSB");
    printf("measured: fieldweak AN1078-like: largest |err| minus its bound: %.4f LSB\n",
           worst_excess);
    assert_cmp(worst_excess, <=, 0.0);
    assert_cmp(e.max_abs, <=, 0.5 + 23000.0 / 131072.0);
}

static void test_fieldweak_id_ref_should_stay_in_bound_for_random_and_extreme_tables(void **state)
{
    (void)state;
    uint32_t rng = 0xF1E1DU;
    err_stats_t e;
    err_stats_init(&e);
    double worst_excess = -10.0;
    for (int trial = 0; trial < 40; trial++) {
        fieldweak_params_t p;
        for (int i = 0; i < 16; i++) {
            if (trial % 4 == 0) {
                p.id_table[i] = (i % 2 == 0) ? 32767 : -32768; /* step 65535 */
            } else {
                p.id_table[i] = test_rand_i16(&rng);
            }
        }
        q15_t a = (q15_t)(test_rand_u32(&rng) % 32768U);
        q15_t b = (q15_t)(test_rand_u32(&rng) % 32768U);
        p.speed_nominal = (a < b) ? a : b;
        p.speed_max = (a < b) ? b : a;
        if (p.speed_max == p.speed_nominal) {
            p.speed_max = (q15_t)(p.speed_max + 1);
        }
        sweep(&p, &e, &worst_excess);
    }
    err_stats_print("fieldweak random/alternating +-full-scale tables, 40 x 65536 speeds", &e,
                    "LSB");
    printf("measured: fieldweak: largest |err| minus its bound 0.5 + |step|/131072: %.4f LSB\n",
           worst_excess);
    assert_cmp(worst_excess, <=, 0.0);
    assert_cmp(e.max_abs, <=, 0.5 + 65535.0 / 131072.0);
}

/* Speeds at the table points (15 (s - nominal) a multiple of the span)
 * give the entry exactly. */
static void test_fieldweak_id_ref_should_hit_the_table_points_exactly(void **state)
{
    (void)state;
    uint32_t rng = 7U;
    long hits = 0;
    for (unsigned k = 0; k < sizeof spans / sizeof spans[0]; k++) {
        fieldweak_params_t p;
        for (int i = 0; i < 16; i++) {
            p.id_table[i] = test_rand_i16(&rng);
        }
        p.speed_nominal = spans[k][0];
        p.speed_max = spans[k][1];
        fieldweak_t fw;
        fieldweak_init(&fw, &p);
        int32_t span = (int32_t)p.speed_max - (int32_t)p.speed_nominal;
        for (int32_t s = p.speed_nominal; s <= p.speed_max; s++) {
            int32_t num = 15 * (s - (int32_t)p.speed_nominal);
            if (num % span == 0) {
                assert_int_equal(fieldweak_id_ref(&fw, (q15_t)s), p.id_table[num / span]);
                hits++;
            }
        }
        assert_int_equal(fieldweak_id_ref(&fw, p.speed_nominal), p.id_table[0]);
        assert_int_equal(fieldweak_id_ref(&fw, p.speed_max), p.id_table[15]);
    }
    printf("measured: fieldweak: %ld table-point speeds, all exact\n", hits);
    assert_cmp(hits, >=, 16L * 2);
}

static void test_fieldweak_id_ref_should_be_monotone_for_a_monotone_table(void **state)
{
    (void)state;
    fieldweak_params_t p;
    table_an1078_like(p.id_table);
    for (unsigned k = 0; k < sizeof spans / sizeof spans[0]; k++) {
        p.speed_nominal = spans[k][0];
        p.speed_max = spans[k][1];
        fieldweak_t fw;
        fieldweak_init(&fw, &p);
        q15_t prev = fieldweak_id_ref(&fw, p.speed_nominal);
        for (int32_t s = p.speed_nominal; s <= 32767; s++) {
            q15_t id = fieldweak_id_ref(&fw, (q15_t)s);
            assert_cmp(id, <=, prev); /* falling table -> falling Id */
            prev = id;
        }
    }
    /* A rising table as well. */
    for (int i = 0; i < 16; i++) {
        p.id_table[i] = (q15_t)(i * i * 100 - 20000);
    }
    p.speed_nominal = 3000;
    p.speed_max = 31000;
    fieldweak_t fw;
    fieldweak_init(&fw, &p);
    q15_t prev = fieldweak_id_ref(&fw, 3000);
    for (int32_t s = 3000; s <= 32767; s++) {
        q15_t id = fieldweak_id_ref(&fw, (q15_t)s);
        assert_cmp(id, >=, prev);
        prev = id;
    }
}

static void
test_fieldweak_id_ref_should_use_the_speed_magnitude_and_zero_below_nominal(void **state)
{
    (void)state;
    fieldweak_params_t p;
    table_an1078_like(p.id_table);
    p.id_table[0] = -123; /* nonzero, to see the step at nominal */
    p.speed_nominal = Q15(0.5);
    p.speed_max = Q15(0.9);
    fieldweak_t fw;
    fieldweak_init(&fw, &p);
    for (int32_t s = 1; s <= 32767; s++) {
        assert_int_equal(fieldweak_id_ref(&fw, (q15_t)-s), fieldweak_id_ref(&fw, (q15_t)s));
    }
    assert_int_equal(fieldweak_id_ref(&fw, -32768), fieldweak_id_ref(&fw, 32767));
    assert_int_equal(fieldweak_id_ref(&fw, -32768), p.id_table[15]);
    assert_int_equal(fieldweak_id_ref(&fw, 0), 0);
    assert_int_equal(fieldweak_id_ref(&fw, (q15_t)(Q15(0.5) - 1)), 0);
    assert_int_equal(fieldweak_id_ref(&fw, Q15(0.5)), -123);
    assert_int_equal(fieldweak_id_ref(&fw, (q15_t)-Q15(0.5)), -123);
}

static void test_fieldweak_id_ref_should_be_zero_when_disabled(void **state)
{
    (void)state;
    fieldweak_params_t p;
    for (int i = 0; i < 16; i++) {
        p.id_table[i] = -5000;
    }
    const q15_t cfg[][2] = {{Q15(0.5), Q15(0.5)}, {Q15(0.6), Q15(0.5)}, {-100, 2000}, {0, 0}};
    for (unsigned k = 0; k < sizeof cfg / sizeof cfg[0]; k++) {
        p.speed_nominal = cfg[k][0];
        p.speed_max = cfg[k][1];
        fieldweak_t fw;
        fieldweak_init(&fw, &p);
        assert_int_equal(fw.span, 0);
        for (int32_t s = -32768; s <= 32767; s += 17) {
            assert_int_equal(fieldweak_id_ref(&fw, (q15_t)s), 0);
        }
        assert_int_equal(fieldweak_id_ref(&fw, 32767), 0);
        assert_int_equal(fieldweak_id_ref(&fw, -32768), 0);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fieldweak_id_ref_should_match_linear_interpolation_over_every_speed),
        cmocka_unit_test(test_fieldweak_id_ref_should_stay_in_bound_for_random_and_extreme_tables),
        cmocka_unit_test(test_fieldweak_id_ref_should_hit_the_table_points_exactly),
        cmocka_unit_test(test_fieldweak_id_ref_should_be_monotone_for_a_monotone_table),
        cmocka_unit_test(
            test_fieldweak_id_ref_should_use_the_speed_magnitude_and_zero_below_nominal),
        cmocka_unit_test(test_fieldweak_id_ref_should_be_zero_when_disabled),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
