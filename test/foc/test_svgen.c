/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_svgen.c - svgen_update: line-to-line voltages rebuilt from the duties vs the request. */
#include "test_support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "svgen.h"

/*
 * On svgen.h's scale (|v| = 1.0 = the inscribed circle) the requested
 * line-to-line voltages in units of Vbus are
 *   v_ab = (sqrt3 alpha - beta) / 2,  v_bc = beta,  v_ca = (-sqrt3 alpha - beta) / 2
 * and the duties give (d_a - d_b) / period etc. T1 and T1 + T2 are each
 * rounded to 0.5 count and T2 is their difference, and the Q15 sqrt(3)/2
 * adds 2.5e-6 period (0.08 count at period 32767; svgen.c note 1): the
 * bound is 1 + 2.5e-6 period counts.
 */
static double line_bound_counts(uint16_t p)
{
    return 1.0 + 2.5e-6 * (double)p;
}

static const uint16_t periods[] = {2000, 1000, 32767};

typedef struct {
    double ab, bc, ca; /* line-to-line, units of Vbus */
} line_t;

static line_t requested(ab_q15_t v)
{
    double a = q15_to_double(v.alpha);
    double b = q15_to_double(v.beta);
    line_t l;
    l.ab = (sqrt(3.0) * a - b) / 2.0;
    l.bc = b;
    l.ca = (-sqrt(3.0) * a - b) / 2.0;
    return l;
}

/* The largest line-to-line voltage: <= 1 inside the hexagon. */
static double line_max(line_t l)
{
    double m = fabs(l.ab);
    if (fabs(l.bc) > m) {
        m = fabs(l.bc);
    }
    if (fabs(l.ca) > m) {
        m = fabs(l.ca);
    }
    return m;
}

/* Angle (degrees, [0, 360)) of the alpha/beta vector behind line voltages. */
static double angle_of_lines(double ab, double bc)
{
    double beta = bc;
    double alpha = (2.0 * ab + bc) / sqrt(3.0);
    double deg = atan2(beta, alpha) * 180.0 / M_PI;
    return (deg < 0.0) ? deg + 360.0 : deg;
}

static void check_range_and_centre(const svgen_out_t *o, uint16_t p, bool linear)
{
    uint16_t mx = o->duty[0];
    uint16_t mn = o->duty[0];
    for (int k = 0; k < 3; k++) {
        assert_cmp(o->duty[k], <=, p);
        if (o->duty[k] > mx) {
            mx = o->duty[k];
        }
        if (o->duty[k] < mn) {
            mn = o->duty[k];
        }
    }
    assert_cmp(o->sector, >=, 1);
    assert_cmp(o->sector, <=, 6);
    if (linear) {
        /* Centred: (max + min) / 2 = period / 2 within half a count. */
        int s = (int)mx + (int)mn;
        assert_true(s == (int)p || s == (int)p - 1);
    } else {
        assert_int_equal(mx - mn, p); /* on the hexagon exactly */
    }
}

/* Errors of the three rebuilt line-to-line voltages, in counts. */
static void add_line_errors(err_stats_t *e, const svgen_out_t *o, ab_q15_t v, uint16_t p)
{
    line_t l = requested(v);
    double pp = (double)p;
    double at = angle_of_lines(l.ab, l.bc);
    err_stats_add(e, ((double)o->duty[0] - (double)o->duty[1]) - l.ab * pp, at);
    err_stats_add(e, ((double)o->duty[1] - (double)o->duty[2]) - l.bc * pp, at);
    err_stats_add(e, ((double)o->duty[2] - (double)o->duty[0]) - l.ca * pp, at);
}

static void test_svgen_update_should_reproduce_line_voltages_in_the_linear_region(void **state)
{
    (void)state;
    for (unsigned ip = 0; ip < sizeof periods / sizeof periods[0]; ip++) {
        uint16_t p = periods[ip];
        uint32_t rng = 0xC0FFEEU + ip;
        err_stats_t e;
        err_stats_init(&e);
        long per_sector[7] = {0};
        long n = 0;
        long fewest = 0;
        while (fewest < 100000) { /* >= 10^5 vectors in every sector */
            ab_q15_t v;
            v.alpha = test_rand_i16(&rng);
            v.beta = test_rand_i16(&rng);
            line_t l = requested(v);
            if (line_max(l) > 1.0 - 1e-4) {
                continue; /* outside (or on) the hexagon: tested below */
            }
            svgen_out_t o;
            svgen_update(v, p, &o);
            assert_false(o.clamped);
            check_range_and_centre(&o, p, true);
            add_line_errors(&e, &o, v, p);
            double deg = angle_of_lines(l.ab, l.bc);
            double in_sector = fmod(deg, 60.0);
            if (in_sector > 1e-3 && in_sector < 60.0 - 1e-3) {
                assert_int_equal(o.sector, (int)(deg / 60.0) + 1);
            }
            per_sector[o.sector]++;
            n++;
            if ((n & 1023) == 0) {
                fewest = per_sector[1];
                for (int sct = 2; sct <= 6; sct++) {
                    fewest = (per_sector[sct] < fewest) ? per_sector[sct] : fewest;
                }
            }
        }
        char name[96];
        snprintf(name, sizeof name, "svgen line-to-line, period %u, random in the hexagon", p);
        err_stats_print(name, &e, "counts");
        printf("measured: svgen period %u: vectors per sector 1..6: %ld %ld %ld %ld %ld %ld\n", p,
               per_sector[1], per_sector[2], per_sector[3], per_sector[4], per_sector[5],
               per_sector[6]);
        for (int s = 1; s <= 6; s++) {
            assert_cmp(per_sector[s], >=, 100000);
        }
        assert_cmp(e.max_abs, <=, line_bound_counts(p));
    }
}

/* Inside the inscribed circle (|v| <= 1), by angle and radius, so the
 * sweep also covers the small vectors. */
static void test_svgen_update_should_reproduce_line_voltages_inside_the_circle(void **state)
{
    (void)state;
    for (unsigned ip = 0; ip < sizeof periods / sizeof periods[0]; ip++) {
        uint16_t p = periods[ip];
        uint32_t rng = 0xBADC0DEU + ip;
        err_stats_t e;
        err_stats_init(&e);
        for (long n = 0; n < 100000; n++) {
            double th = test_rand_range(&rng, 0.0, 2.0 * M_PI);
            double r = test_rand_range(&rng, 0.0, 32767.0);
            ab_q15_t v;
            v.alpha = (q15_t)lround(r * cos(th));
            v.beta = (q15_t)lround(r * sin(th));
            svgen_out_t o;
            svgen_update(v, p, &o);
            assert_false(o.clamped);
            check_range_and_centre(&o, p, true);
            add_line_errors(&e, &o, v, p);
        }
        char name[96];
        snprintf(name, sizeof name, "svgen line-to-line, period %u, random in |v| <= 1", p);
        err_stats_print(name, &e, "counts");
        assert_cmp(e.max_abs, <=, line_bound_counts(p));
    }
}

static void test_svgen_update_should_give_half_period_duties_for_the_zero_vector(void **state)
{
    (void)state;
    const uint16_t ps[] = {2000, 1000, 32767, 1, 2};
    for (unsigned i = 0; i < sizeof ps / sizeof ps[0]; i++) {
        ab_q15_t v = {0, 0};
        svgen_out_t o;
        svgen_update(v, ps[i], &o);
        for (int k = 0; k < 3; k++) {
            assert_int_equal(o.duty[k], ps[i] / 2U); /* floor for an odd period */
        }
        assert_int_equal(o.sector, 1);
        assert_false(o.clamped);
    }
    ab_q15_t v = {Q15(0.5), Q15(-0.3)};
    svgen_out_t o;
    svgen_update(v, 0, &o);
    assert_int_equal(o.duty[0] + o.duty[1] + o.duty[2], 0);
    svgen_update(v, 65535, &o); /* treated as 32767 */
    svgen_out_t o2;
    svgen_update(v, 32767, &o2);
    assert_memory_equal(o.duty, o2.duty, sizeof o.duty);
}

/* Vectors on the sector boundaries (0, 60, ..., 300 degrees, quantised to
 * Q15) and their +-1 LSB neighbours: consistent sectors, the bound holds,
 * and the duties are continuous across the boundary. */
static void test_svgen_update_should_be_continuous_across_sector_boundaries(void **state)
{
    (void)state;
    const double mags[] = {1.0, 100.0, 5000.0, 16384.0, 30000.0, 32767.0};
    err_stats_t e;
    err_stats_init(&e);
    int max_jump = 0;
    for (int b = 0; b < 6; b++) {
        double th = (double)b * M_PI / 3.0;
        for (unsigned im = 0; im < sizeof mags / sizeof mags[0]; im++) {
            ab_q15_t c;
            c.alpha = (q15_t)lround(mags[im] * cos(th));
            c.beta = (q15_t)lround(mags[im] * sin(th));
            svgen_out_t oc;
            svgen_update(c, 2000, &oc);
            check_range_and_centre(&oc, 2000, true);
            add_line_errors(&e, &oc, c, 2000);
            for (int da = -1; da <= 1; da++) {
                for (int db = -1; db <= 1; db++) {
                    ab_q15_t v;
                    v.alpha = q15_sat((int32_t)c.alpha + da);
                    v.beta = q15_sat((int32_t)c.beta + db);
                    svgen_out_t o;
                    svgen_update(v, 2000, &o);
                    check_range_and_centre(&o, 2000, true);
                    add_line_errors(&e, &o, v, 2000);
                    for (int k = 0; k < 3; k++) {
                        int j = abs((int)o.duty[k] - (int)oc.duty[k]);
                        if (j > max_jump) {
                            max_jump = j;
                        }
                    }
                }
            }
        }
    }
    err_stats_print("svgen line-to-line at sector boundaries +-1 LSB, period 2000", &e, "counts");
    printf("measured: svgen largest duty change for a 1 LSB step across a boundary: %d counts\n",
           max_jump);
    assert_cmp(e.max_abs, <=, line_bound_counts(2000));
    assert_cmp(max_jump, <=, 1);

    /* Exactly on the alpha axis (0 and 180 degrees): phases b and c equal;
     * on the beta axis (90, 270): phase a midway. */
    const q15_t ms[] = {1, 12345, 32767, -32768};
    for (unsigned i = 0; i < sizeof ms / sizeof ms[0]; i++) {
        ab_q15_t v = {ms[i], 0};
        svgen_out_t o;
        svgen_update(v, 2000, &o);
        assert_int_equal(o.duty[1], o.duty[2]);
        assert_int_equal(o.sector, (ms[i] > 0) ? 1 : 4);
        ab_q15_t w = {0, ms[i]};
        svgen_update(w, 2000, &o);
        /* T1 and T1 + T2 are rounded separately: equal halves within 1 count. */
        assert_cmp(abs(((int)o.duty[1] - (int)o.duty[0]) - ((int)o.duty[0] - (int)o.duty[2])), <=,
                   1);
        assert_int_equal(o.sector, (ms[i] > 0) ? 2 : 5);
    }
}

/* Outside the hexagon: clamped onto it, angle kept, never wrapped. */
static void test_svgen_update_should_clamp_overmodulation_onto_the_hexagon(void **state)
{
    (void)state;
    for (unsigned ip = 0; ip < sizeof periods / sizeof periods[0]; ip++) {
        uint16_t p = periods[ip];
        uint32_t rng = 0x5EED5U + ip;
        err_stats_t e;
        err_stats_init(&e);
        long n = 0;
        ab_q15_t corners[] = {{-32768, -32768}, {-32768, 32767}, {32767, -32768}, {32767, 32767},
                              {-32768, 0},      {0, -32768},     {32767, 0},      {0, 32767}};
        for (long i = 0; n < 100000; i++) {
            ab_q15_t v;
            if (i < (long)(sizeof corners / sizeof corners[0])) {
                v = corners[i];
            } else {
                v.alpha = test_rand_i16(&rng);
                v.beta = test_rand_i16(&rng);
            }
            line_t l = requested(v);
            if (line_max(l) < 1.0 + 1e-4) {
                continue;
            }
            svgen_out_t o;
            svgen_update(v, p, &o);
            assert_true(o.clamped);
            check_range_and_centre(&o, p, false);
            double want = angle_of_lines(l.ab, l.bc);
            double got = angle_of_lines(((double)o.duty[0] - (double)o.duty[1]) / (double)p,
                                        ((double)o.duty[1] - (double)o.duty[2]) / (double)p);
            err_stats_add(&e, angle_diff_deg(got * M_PI / 180.0, want * M_PI / 180.0), want);
            n++;
        }
        /* Bound (svgen.c note 3): T1 / period is x16 / s16 with s16 >=
         * 16384, both rounded, so it is off by <= 1 / 16384, plus 0.5 count
         * for the quotient's rounding; one count moves the vector by
         * 1.155 / period along a hexagon edge (edge = active vector =
         * 2 / sqrt3), at distance >= 1 from the origin. */
        double dt_counts = 0.5 + (double)p / 16384.0;
        double bound_deg = 1.155 * dt_counts / (double)p * 180.0 / M_PI;
        char name[96];
        snprintf(name, sizeof name, "svgen clamped angle error, period %u (bound %.4f deg)", p,
                 bound_deg);
        err_stats_print(name, &e, "deg");
        assert_cmp(e.max_abs, <=, bound_deg);
    }
}

/* Along rays from 0 to beyond the square's corner: T1 + T2 (= max - min
 * duty) never decreases, saturates at the period, and the clamped duties
 * stay put. */
static void test_svgen_update_should_be_monotone_along_rays(void **state)
{
    (void)state;
    int clamped_spread = 0;
    int rays_clamped = 0;
    int rays = 0;
    for (int ia = 0; ia < 360; ia += 7) {
        double th = (double)ia * M_PI / 180.0 + 0.01;
        int prev_span = -1;
        svgen_out_t first_clamped;
        bool have_clamped = false;
        for (double r = 0.0; r < 46341.0; r += 64.0) {
            ab_q15_t v;
            v.alpha = q15_sat((int32_t)lround(r * cos(th)));
            v.beta = q15_sat((int32_t)lround(r * sin(th)));
            if (v.alpha == -32768 || v.alpha == 32767 || v.beta == -32768 || v.beta == 32767) {
                break; /* the square's edge bends the ray */
            }
            svgen_out_t o;
            svgen_update(v, 2000, &o);
            int mx = o.duty[0];
            int mn = o.duty[0];
            for (int k = 1; k < 3; k++) {
                mx = (o.duty[k] > mx) ? o.duty[k] : mx;
                mn = (o.duty[k] < mn) ? o.duty[k] : mn;
            }
            assert_cmp(mx - mn, >=, prev_span);
            assert_cmp(mx - mn, <=, 2000);
            prev_span = mx - mn;
            if (o.clamped) {
                if (!have_clamped) {
                    first_clamped = o;
                    have_clamped = true;
                }
                for (int k = 0; k < 3; k++) {
                    int d = abs((int)o.duty[k] - (int)first_clamped.duty[k]);
                    clamped_spread = (d > clamped_spread) ? d : clamped_spread;
                }
            }
        }
        /* The hexagon's radius at this angle vs the Q15 square's: where the
         * hexagon ends first (by a margin of a few ray steps), the ray
         * must have been clamped; near the hexagon's corners the square
         * ends first. */
        double deg = (double)ia + 0.01 * 180.0 / M_PI;
        double hex_r = 32768.0 / cos((fmod(deg, 60.0) - 30.0) * M_PI / 180.0);
        double sq_r = 32767.0 / fmax(fabs(cos(th)), fabs(sin(th)));
        rays++;
        if (hex_r + 200.0 < sq_r) {
            assert_true(have_clamped);
        }
        if (have_clamped) {
            rays_clamped++;
            assert_int_equal(prev_span, 2000);
        }
    }
    printf("measured: svgen rays (period 2000): largest duty change beyond the hexagon: %d "
           "counts\n",
           clamped_spread);
    printf("measured: svgen rays: %d of %d left the hexagon inside the Q15 square\n", rays_clamped,
           rays);
    assert_cmp(clamped_spread, <=, 2);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_svgen_update_should_reproduce_line_voltages_in_the_linear_region),
        cmocka_unit_test(test_svgen_update_should_reproduce_line_voltages_inside_the_circle),
        cmocka_unit_test(test_svgen_update_should_give_half_period_duties_for_the_zero_vector),
        cmocka_unit_test(test_svgen_update_should_be_continuous_across_sector_boundaries),
        cmocka_unit_test(test_svgen_update_should_clamp_overmodulation_onto_the_hexagon),
        cmocka_unit_test(test_svgen_update_should_be_monotone_along_rays),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
