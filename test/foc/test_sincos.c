/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_sincos.c - sincos_compute against double sin/cos over every binary angle. */
#include "test_support.h"

#include <math.h>
#include <stdio.h>

#include "sincos.h"

/* The bound stated in sincos.h: table rounding 0.5 + chord error 0.62 +
 * interpolation rounding 0.5 LSB, measured 1.44 LSB. */
#define SINCOS_MAX_ERR_LSB 1.5

static double ref_sin_lsb(uint16_t a)
{
    return 32768.0 * sin((double)a * 2.0 * M_PI / 65536.0);
}

static double ref_cos_lsb(uint16_t a)
{
    return 32768.0 * cos((double)a * 2.0 * M_PI / 65536.0);
}

static void test_sincos_compute_should_stay_within_bound_for_all_65536_angles(void **state)
{
    err_stats_t es;
    err_stats_t ec;
    uint32_t a;
    (void)state;

    err_stats_init(&es);
    err_stats_init(&ec);
    for (a = 0U; a < 65536U; a++) {
        sincos_q15_t sc = sincos_compute((angle_q15_t)(int16_t)(uint16_t)a);
        err_stats_add(&es, (double)sc.sin - ref_sin_lsb((uint16_t)a), (double)a);
        err_stats_add(&ec, (double)sc.cos - ref_cos_lsb((uint16_t)a), (double)a);
    }
    err_stats_print("sincos sin, all 65536 angles", &es, "LSB");
    err_stats_print("sincos cos, all 65536 angles", &ec, "LSB");
    printf("measured: sincos max |err| as a share of full scale: sin %.5f %%, cos %.5f %%\n",
           100.0 * es.max_abs / 32768.0, 100.0 * ec.max_abs / 32768.0);
    assert_cmp(es.n, ==, 65536L);
    assert_cmp(ec.n, ==, 65536L);
    assert_cmp(es.max_abs, <=, SINCOS_MAX_ERR_LSB);
    assert_cmp(ec.max_abs, <=, SINCOS_MAX_ERR_LSB);
    /* No bias: the mean error is a small fraction of an LSB. */
    assert_cmp(fabs(err_stats_mean(&es)), <, 0.05);
    assert_cmp(fabs(err_stats_mean(&ec)), <, 0.05);
}

static void test_sincos_compute_should_never_exceed_plus_minus_32767(void **state)
{
    uint32_t a;
    int min_sin = 0;
    int max_sin = 0;
    int min_cos = 0;
    int max_cos = 0;
    (void)state;

    for (a = 0U; a < 65536U; a++) {
        sincos_q15_t sc = sincos_compute((angle_q15_t)(int16_t)(uint16_t)a);
        min_sin = (sc.sin < min_sin) ? sc.sin : min_sin;
        max_sin = (sc.sin > max_sin) ? sc.sin : max_sin;
        min_cos = (sc.cos < min_cos) ? sc.cos : min_cos;
        max_cos = (sc.cos > max_cos) ? sc.cos : max_cos;
    }
    printf("measured: sincos output range sin [%d, %d], cos [%d, %d]\n", min_sin, max_sin, min_cos,
           max_cos);
    assert_int_equal(min_sin, -32767);
    assert_int_equal(max_sin, 32767);
    assert_int_equal(min_cos, -32767);
    assert_int_equal(max_cos, 32767);
}

static void test_sincos_compute_should_be_exact_at_the_four_axes(void **state)
{
    sincos_q15_t sc;
    (void)state;

    sc = sincos_compute(ANGLE_Q15_DEG(0));
    assert_int_equal(sc.sin, 0);
    assert_int_equal(sc.cos, 32767);
    sc = sincos_compute(ANGLE_Q15_DEG(90));
    assert_int_equal(sc.sin, 32767);
    assert_int_equal(sc.cos, 0);
    sc = sincos_compute(ANGLE_Q15_DEG(180)); /* -32768 */
    assert_int_equal(sc.sin, 0);
    assert_int_equal(sc.cos, -32767);
    sc = sincos_compute(ANGLE_Q15_DEG(-90));
    assert_int_equal(sc.sin, -32767);
    assert_int_equal(sc.cos, 0);
    sc = sincos_compute(ANGLE_Q15_DEG(270)); /* wraps to -90 */
    assert_int_equal(sc.sin, -32767);
    assert_int_equal(sc.cos, 0);
    sc = sincos_compute((angle_q15_t)Q15_MIN);
    assert_int_equal(sc.sin, 0);
    assert_int_equal(sc.cos, -32767);
    sc = sincos_compute((angle_q15_t)Q15_MAX); /* one LSB below +pi */
    assert_cmp(sc.sin, >, 0);
    assert_cmp(sc.sin, <=, 4);
    assert_int_equal(sc.cos, -32767);
}

static void test_sincos_compute_should_match_the_table_nodes_to_half_an_lsb(void **state)
{
    /* Every multiple of 128 counts is a table node: only the table's own
     * rounding (and the 32768 -> 32767 saturation at 90 deg) remains. */
    err_stats_t e;
    uint32_t a;
    (void)state;

    err_stats_init(&e);
    for (a = 0U; a < 65536U; a += 128U) {
        sincos_q15_t sc = sincos_compute((angle_q15_t)(int16_t)(uint16_t)a);
        double r = ref_sin_lsb((uint16_t)a);
        double expect = (r > 32767.0) ? 32767.0 : ((r < -32767.0) ? -32767.0 : r);
        err_stats_add(&e, (double)sc.sin - expect, (double)a);
    }
    err_stats_print("sincos sin at the 512 table nodes", &e, "LSB");
    assert_cmp(e.max_abs, <=, 0.5);
}

static void test_sincos_compute_should_keep_the_symmetries_bit_exact(void **state)
{
    uint32_t a;
    (void)state;

    for (a = 0U; a < 65536U; a++) {
        uint16_t u = (uint16_t)a;
        sincos_q15_t p = sincos_compute((angle_q15_t)(int16_t)u);
        sincos_q15_t n = sincos_compute((angle_q15_t)(int16_t)(uint16_t)(0U - a));
        sincos_q15_t s = sincos_compute((angle_q15_t)(int16_t)(uint16_t)(32768U - a));
        sincos_q15_t q = sincos_compute((angle_q15_t)(int16_t)(uint16_t)(a + 16384U));
        assert_int_equal(n.sin, -p.sin); /* sin(-x) = -sin(x) */
        assert_int_equal(n.cos, p.cos);  /* cos(-x) = cos(x) */
        assert_int_equal(s.sin, p.sin);  /* sin(pi - x) = sin(x) */
        assert_int_equal(q.sin, p.cos);  /* sin(x + pi/2) = cos(x) */
    }
}

static void test_sincos_compute_should_be_monotonic_in_the_first_quadrant(void **state)
{
    uint32_t a;
    q15_t prev = -1;
    (void)state;

    for (a = 0U; a <= 16384U; a++) {
        sincos_q15_t sc = sincos_compute((angle_q15_t)(int16_t)(uint16_t)a);
        assert_cmp(sc.sin, >=, prev);
        prev = sc.sin;
    }
}

static void test_sincos_compute_should_keep_sin2_plus_cos2_close_to_one(void **state)
{
    err_stats_t e;
    uint32_t a;
    (void)state;

    err_stats_init(&e);
    for (a = 0U; a < 65536U; a++) {
        sincos_q15_t sc = sincos_compute((angle_q15_t)(int16_t)(uint16_t)a);
        double s = q15_to_double(sc.sin);
        double c = q15_to_double(sc.cos);
        err_stats_add(&e, 32768.0 * (s * s + c * c - 1.0), (double)a);
    }
    err_stats_print("sincos 32768 (sin^2 + cos^2 - 1)", &e, "LSB");
    /* From the per-output bound: 2 (|sin| + |cos|) 1.5 LSB <= 2 sqrt(2) 1.5
     * = 4.25 LSB (1.3e-4 of full scale), plus second-order terms. */
    assert_cmp(e.max_abs, <=, 4.25);
}

/* The call (sincos_call, for the cold paths) is the inline body, bit for bit. */
static void test_sincos_call_should_equal_sincos_compute_for_all_65536_angles(void **state)
{
    uint32_t a;
    uint32_t differ = 0U;
    (void)state;

    for (a = 0U; a < 65536U; a++) {
        angle_q15_t th = (angle_q15_t)(int16_t)(uint16_t)a;
        sincos_q15_t c = sincos_call(th);
        sincos_q15_t i = sincos_compute(th);
        differ += (c.sin != i.sin || c.cos != i.cos) ? 1U : 0U;
    }
    printf("measured: sincos_call differs from sincos_compute at %u of 65536 angles\n",
           (unsigned)differ);
    assert_int_equal(differ, 0U);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sincos_compute_should_stay_within_bound_for_all_65536_angles),
        cmocka_unit_test(test_sincos_compute_should_never_exceed_plus_minus_32767),
        cmocka_unit_test(test_sincos_compute_should_be_exact_at_the_four_axes),
        cmocka_unit_test(test_sincos_compute_should_match_the_table_nodes_to_half_an_lsb),
        cmocka_unit_test(test_sincos_compute_should_keep_the_symmetries_bit_exact),
        cmocka_unit_test(test_sincos_compute_should_be_monotonic_in_the_first_quadrant),
        cmocka_unit_test(test_sincos_compute_should_keep_sin2_plus_cos2_close_to_one),
        cmocka_unit_test(test_sincos_call_should_equal_sincos_compute_for_all_65536_angles),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
