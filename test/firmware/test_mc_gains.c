/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_mc_gains.c - gains a client may post (mc_set_gain) keep the simulated Hurst stable. */
#include "test_support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "mc_bench.h"

static mc_bench_t b;

#define PERIODS(s) ((long)((s) * (double)PWM_FREQUENCY_HZ))

static double pot_for_rpm(double rpm)
{
    return (rpm - SPEED_REF_MIN_RPM) / (SPEED_REF_MAX_RPM - SPEED_REF_MIN_RPM);
}

/* A gain's value at factor f of its built-in one, rounded up (so a factor
 * at a lower bound is inside it), within 1..32767. */
static int16_t at(mc_gain_t g, double f)
{
    static const double base[MC_GAIN_COUNT] = {MC_CUR_KP, MC_CUR_KI, MC_SPD_KP, MC_SPD_KI};
    double v = ceil(f * base[g] - 1e-9);
    return (int16_t)(v > 32767.0 ? 32767.0 : (v < 1.0 ? 1.0 : v));
}

typedef struct {
    mc_state_t state; /* at the end */
    unsigned fault;
    double i_peak;  /* A, the largest phase current after the gains */
    double err_rms; /* rpm, speed error RMS over the last half */
} outcome_t;

/* The four gains at factors f[] of the built-in ones (mc_set_gain), posted in
 * CLOSED_LOOP at rpm or before START; then 1 s (4 s from START) with a load
 * step of 0.03 N m 0.6 s before the end. */
static outcome_t run_with(double rpm, const double f[4], bool *accepted, bool before_start)
{
    mc_bench_cfg_t c;
    outcome_t o = {MC_STATE_STOPPED, 0U, 0.0, 0.0};
    mc_bench_cfg_default(&c);
    c.pot = pot_for_rpm(rpm);
    mc_bench_init(&b, &c);
    *accepted = true;
    if (!before_start) {
        mc_request(&b.mc, MC_REQUEST_START);
        long n = mc_bench_run_until(&b, MC_STATE_CLOSED_LOOP, PERIODS(4.0));
        assert_cmp(n, >, 0);
    }
    /* Kp first where it grows, Ki first where Kp shrinks: each write judged against the
     * other gain as posted */
    for (int l = 0; l < 4; l += 2) {
        mc_gain_t kp = (mc_gain_t)l, ki = (mc_gain_t)(l + 1);
        bool kp_first = f[l] >= 1.0;
        if (!mc_set_gain(&b.mc, kp_first ? kp : ki,
                         at(kp_first ? kp : ki, f[kp_first ? l : l + 1])) ||
            !mc_set_gain(&b.mc, kp_first ? ki : kp,
                         at(kp_first ? ki : kp, f[kp_first ? l + 1 : l]))) {
            *accepted = false;
        }
    }
    double e2 = 0.0;
    long ne = 0;
    long len = PERIODS(1.0);
    if (before_start) {
        mc_request(&b.mc, MC_REQUEST_START);
        len = PERIODS(4.0);
    }
    for (long k = 0; k < len; k++) {
        if (k == len - PERIODS(0.6)) {
            b.rig.plant.load.active_nm = 0.03;
        }
        mc_bench_step(&b);
        double ia = fabs(b.now.ia_a), ib = fabs(b.now.ib_a), ic = fabs(b.now.ic_a);
        double i = ia > ib ? ia : ib;
        i = i > ic ? i : ic;
        o.i_peak = i > o.i_peak ? i : o.i_peak;
        if (k >= len - PERIODS(0.5)) {
            double e = b.now.speed_rpm - b.now.speed_ref_rpm;
            e2 += e * e;
            ne++;
        }
        if (b.st.state == MC_STATE_FAULT) {
            break;
        }
    }
    o.state = b.st.state;
    o.fault = (unsigned)b.st.fault;
    o.err_rms = ne > 0 ? sqrt(e2 / (double)ne) : -1.0;
    return o;
}

/* Every corner of the region mc_set_gain lets a client into (mc.h note 3),
 * posted while running and before START, near the lowest closed-loop speed,
 * a middle one and the top, with a load step: CLOSED_LOOP at the end, no
 * fault, the phase currents under the trip, the speed within 60 rpm RMS of
 * its reference over the last half second. */
static void test_every_corner_of_the_allowed_region_should_hold_the_speed(void **state)
{
    (void)state;
    const double z = (double)MC_GAIN_ZERO_MAX;
    const double cur_lo = (double)MC_GAIN_CUR_KP_MIN8 / 8.0,
                 cur_ki_lo = (double)MC_GAIN_CUR_KI_MIN8 / 8.0;
    const double spd_lo = (double)MC_GAIN_SPD_KP_MIN8 / 8.0,
                 spd_ki_lo = (double)MC_GAIN_SPD_KI_MIN8 / 8.0;
    /* {cur kp, cur ki, spd kp, spd ki} factors; the zero's corner where Ki / Kp = Z */
    const double corners[][4] = {
        {cur_lo, cur_ki_lo, 1.0, 1.0}, {cur_lo, z * cur_lo, 1.0, 1.0}, {8.0, 8.0, 1.0, 1.0},
        {8.0, cur_ki_lo, 1.0, 1.0},    {1.0, 1.0, spd_lo, spd_ki_lo},  {1.0, 1.0, spd_lo, 8.0},
        {1.0, 1.0, 8.0, 8.0},          {1.0, 1.0, 8.0, spd_ki_lo},
    };
    /* 600 rpm, not the lowest 500: there the load step stalls the built-in gains too */
    static const double rpms[] = {600.0, 2000.0, SPEED_REF_MAX_RPM};
    double worst_err = 0.0, worst_i = 0.0;
    unsigned runs = 0;
    for (unsigned c = 0; c < sizeof corners / sizeof corners[0]; c++) {
        for (unsigned r = 0; r < 3U; r++) {
            for (int before = 0; before < 2; before++) {
                bool acc;
                outcome_t o = run_with(rpms[r], corners[c], &acc, before != 0);
                if (!acc || o.state != MC_STATE_CLOSED_LOOP || o.fault != 0U ||
                    o.i_peak >= MC_OVERCURRENT_A || o.err_rms > 60.0) {
                    fail_msg("gains x{%g %g %g %g} at %.0f rpm (%s): %s, state %d fault %u, peak "
                             "%.2f A, "
                             "error %.1f rpm RMS",
                             corners[c][0], corners[c][1], corners[c][2], corners[c][3], rpms[r],
                             before ? "before START" : "running", acc ? "accepted" : "REFUSED",
                             (int)o.state, o.fault, o.i_peak, o.err_rms);
                }
                worst_err = o.err_rms > worst_err ? o.err_rms : worst_err;
                worst_i = o.i_peak > worst_i ? o.i_peak : worst_i;
                runs++;
            }
        }
    }
    printf("measured: %u runs at the region's corners: worst speed error %.1f rpm RMS, peak %.2f A "
           "(trip "
           "%.2f A)\n",
           runs, worst_err, worst_i, (double)MC_OVERCURRENT_A);
}

/* Pairs the simulated drive does not survive are refused, with nothing
 * changed: a speed Kp below its built-in (a load step at the lowest speed
 * stalls it), Ki above Z Kp (the limit cycle at the full Iq limit, no
 * fault), the current loops' zero likewise. The refused side of each bound
 * by one count. */
static void test_pairs_outside_the_region_should_be_refused(void **state)
{
    (void)state;
    mc_init(&b.mc);
    assert_false(mc_set_gain(&b.mc, MC_GAIN_SPD_KP, at(MC_GAIN_SPD_KP, 0.125)));
    assert_false(mc_set_gain(&b.mc, MC_GAIN_SPD_KP, (int16_t)(MC_SPD_KP - 1)));
    assert_true(mc_set_gain(&b.mc, MC_GAIN_SPD_KP, MC_SPD_KP));
    assert_false(mc_set_gain(&b.mc, MC_GAIN_SPD_KI, at(MC_GAIN_SPD_KI, 0.25)));
    /* the current loops: Kp / 8 holds with Ki up to Z / 8 of its own, not Ki x 8 */
    assert_true(mc_set_gain(&b.mc, MC_GAIN_CUR_KI, at(MC_GAIN_CUR_KI, 8.0)));
    assert_false(mc_set_gain(&b.mc, MC_GAIN_CUR_KP, at(MC_GAIN_CUR_KP, 0.125)));
    assert_int_equal(mc_get_gain(&b.mc, MC_GAIN_CUR_KP), MC_CUR_KP); /* nothing changed */
    assert_true(mc_set_gain(&b.mc, MC_GAIN_CUR_KI, MC_CUR_KI));
    assert_true(mc_set_gain(&b.mc, MC_GAIN_CUR_KP, at(MC_GAIN_CUR_KP, 0.125)));
    assert_false(mc_set_gain(&b.mc, MC_GAIN_CUR_KI, at(MC_GAIN_CUR_KI, 8.0)));
    /* beyond x 8, below 1, negative, an unknown gain */
    assert_false(mc_set_gain(&b.mc, MC_GAIN_CUR_KI, 0));
    assert_false(mc_set_gain(&b.mc, MC_GAIN_CUR_KI, -5));
    assert_false(mc_set_gain(&b.mc, MC_GAIN_COUNT, MC_CUR_KI));
    if (8L * MC_SPD_KI < 32767L) {
        assert_false(mc_set_gain(&b.mc, MC_GAIN_SPD_KI, (int16_t)(8 * MC_SPD_KI + 1)));
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_corner_of_the_allowed_region_should_hold_the_speed),
        cmocka_unit_test(test_pairs_outside_the_region_should_be_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
