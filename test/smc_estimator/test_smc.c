/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_smc.c - the sliding-mode estimator against double-precision references and an ideal PMSM. */
#include "test_support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pmsm_ideal.h"
#include "smc_params.h" /* SMC_PARAMS_INIT; includes smc.h */

/*
 * Profiles (stated in docs/estimator.md):
 *  hurst    Hurst DMB0224C10002 on the MCLV: 5 pole pairs, 2.67 ohm, 1.92 mH
 *           per phase, 7.3 V peak line-to-line per 1000 rpm; 24 V bus,
 *           V_FS = 24/sqrt(3) V, I_FS = 4.4 A; 20 kHz; speed full scale
 *           8000 rpm (firmware/motors/motor_hurst.h); minimum speed 400 rpm;
 *           Kslide 1.8 V_FS, dead-beat linear band; speed filter 100 Hz.
 *  hispeed  the 2-pole-pair high-speed motor of firmware/motors/motor_hispeed.h
 *           (ASSUMED data): 1.2 ohm, 4 mH, 10 V peak line-to-line per
 *           1000 rpm, on the MCHV (320 V bus, I_FS = 8 A); full scale
 *           24,000 rpm, minimum 1600 rpm, Kslide 1.0 V_FS.
 * The drive: a 0.5 A (hurst) / 1 A (hispeed) torque current, field
 * weakening that keeps |v| <= 0.9 V_FS.
 */
#define TS 50e-6

/*
 * The two motors' data (R, L, Ke, pole pairs, speed full scale) are read
 * from their firmware profiles. Both profiles define the same macro names:
 * the high-speed motor's are read first, into its parameter set and the
 * constants of its drive (hs), and undefined, then the Hurst's profile is
 * read; HURST_ below are its macros. Only the names undefined here are read.
 */
#include "../../firmware/motors/motor_hispeed.h"

#define HS_VFS  (320.0 / 1.7320508075688772)
#define HS_IFS  8.0
#define HS_WFS  (MOTOR_SPEED_FULLSCALE_RPM * MOTOR_POLE_PAIRS / 60.0)
#define HS_FMIN (1600.0 * MOTOR_POLE_PAIRS / 60.0)
#define HS_KEHZ (MOTOR_KE_VPK_LL_PER_KRPM / 1.7320508075688772 / (1000.0 * MOTOR_POLE_PAIRS / 60.0))
static const smc_params_t hispeed =
    SMC_PARAMS_INIT(MOTOR_RS_OHM, MOTOR_LS_H, TS, HS_VFS, HS_IFS, 1.0,
                    SMC_MAXERR_DEADBEAT(MOTOR_RS_OHM, MOTOR_LS_H, TS, HS_VFS, HS_IFS, 1.0), HS_WFS,
                    HS_FMIN, 20, 100.0, HS_KEHZ);
static const struct {
    double r, l, ke; /* ohm, H, V peak line-line per 1000 rpm */
    int pp;
    double wfs_hz; /* speed full scale, electrical Hz */
} hs = {MOTOR_RS_OHM, MOTOR_LS_H, MOTOR_KE_VPK_LL_PER_KRPM, MOTOR_POLE_PAIRS, HS_WFS};
#undef HS_WFS
#undef HS_FMIN
#undef HS_KEHZ
#undef MOTOR_NAME
#undef MOTOR_POLE_PAIRS
#undef MOTOR_RS_OHM
#undef MOTOR_LS_H
#undef MOTOR_KE_VPK_LL_PER_KRPM
#undef MOTOR_SPEED_FULLSCALE_RPM

#include "../../firmware/motors/motor_hurst.h"

#define HURST_VFS      (24.0 / 1.7320508075688772)
#define HURST_IFS      4.4
#define HURST_R        MOTOR_RS_OHM
#define HURST_L        MOTOR_LS_H
#define HURST_PP       MOTOR_POLE_PAIRS
#define HURST_KE       MOTOR_KE_VPK_LL_PER_KRPM /* V peak line-line per 1000 rpm */
#define HURST_WFS      (MOTOR_SPEED_FULLSCALE_RPM * HURST_PP / 60.0)
#define HURST_FMIN     (400.0 * HURST_PP / 60.0)
#define HURST_KEHZ     (HURST_KE / 1.7320508075688772 / (1000.0 * HURST_PP / 60.0))
#define HURST_KS       1.8
#define HURST_ME(r, l) SMC_MAXERR_DEADBEAT(r, l, TS, HURST_VFS, HURST_IFS, HURST_KS)
#define HURST_PARAMS(r, l)                                                                         \
    SMC_PARAMS_INIT(r, l, TS, HURST_VFS, HURST_IFS, HURST_KS, HURST_ME(HURST_R, HURST_L),          \
                    HURST_WFS, HURST_FMIN, 20, 100.0, HURST_KEHZ)

static const smc_params_t hurst = HURST_PARAMS(HURST_R, HURST_L);
/* R and L of the model off by +-30 % (the motor keeps its true values). */
static const smc_params_t hurst_r07 = HURST_PARAMS(0.7 * HURST_R, HURST_L);
static const smc_params_t hurst_r13 = HURST_PARAMS(1.3 * HURST_R, HURST_L);
static const smc_params_t hurst_l07 = HURST_PARAMS(HURST_R, 0.7 * HURST_L);
static const smc_params_t hurst_l13 = HURST_PARAMS(HURST_R, 1.3 * HURST_L);
static const smc_params_t hurst_r07l07 = HURST_PARAMS(0.7 * HURST_R, 0.7 * HURST_L);
static const smc_params_t hurst_r13l13 = HURST_PARAMS(1.3 * HURST_R, 1.3 * HURST_L);
static const smc_params_t hurst_r07l13 = HURST_PARAMS(0.7 * HURST_R, 1.3 * HURST_L);
static const smc_params_t hurst_r13l07 = HURST_PARAMS(1.3 * HURST_R, 0.7 * HURST_L);
/* No Ke given: validity from the speed alone. */
static const smc_params_t hurst_noke =
    SMC_PARAMS_INIT(HURST_R, HURST_L, TS, HURST_VFS, HURST_IFS, HURST_KS,
                    HURST_ME(HURST_R, HURST_L), HURST_WFS, HURST_FMIN, 20, 100.0, 0.0);
/* AN1078's published gains (Kslide 0.85, band 0.005 of full scale): the
 * relay (chattering) mode. */
static const smc_params_t hurst_relay =
    SMC_PARAMS_INIT(HURST_R, HURST_L, TS, HURST_VFS, HURST_IFS, 1.7, 0.005, HURST_WFS, HURST_FMIN,
                    20, 100.0, HURST_KEHZ);

typedef struct {
    pmsm_motor_t motor;
    pmsm_drive_t drive;
    double wfs_hz;
} bench_t;

/* A drive with a torque current, field weakening at 0.9 V_FS, Q15 rounding,
 * no noise and no dead time (the tests add what they vary). */
static bench_t bench_make(pmsm_motor_t motor, double v_fs, double i_fs, double iq, double vbus,
                          uint32_t seed, double wfs_hz)
{
    bench_t b;
    memset(&b, 0, sizeof b);
    b.motor = motor;
    b.drive.ts_s = TS;
    b.drive.v_fs_v = v_fs;
    b.drive.i_fs_a = i_fs;
    b.drive.iq_a = iq;
    b.drive.v_limit_frac = 0.9;
    b.drive.adc_lsb = 1;
    b.drive.vbus_v = vbus;
    b.drive.seed = seed;
    b.wfs_hz = wfs_hz;
    return b;
}

static bench_t bench_hurst(void)
{
    return bench_make(pmsm_motor_from_ke(HURST_R, HURST_L, HURST_KE, HURST_PP), HURST_VFS,
                      HURST_IFS, 0.5, 24.0, 0x1234567U, HURST_WFS);
}

static bench_t bench_hispeed(void)
{
    return bench_make(pmsm_motor_from_ke(hs.r, hs.l, hs.ke, hs.pp), HS_VFS, HS_IFS, 1.0, 320.0,
                      0x7654321U, hs.wfs_hz);
}

/* One period, the estimator driven with its results taken straight after
 * the slow step (the core takes them a few periods later): smc_update, and
 * every irp_percalc periods the window end, the slow step and the apply
 * (docs/estimator.md note 10). */
static void smc_period(smc_t *s, ab_q15_t i, ab_q15_t v)
{
    smc_update(s, i, v);
    if (s->count >= s->p->irp_percalc) {
        smc_window_end(s);
        smc_slow_step(s);
        smc_apply(s);
    }
}

/* n periods of motor and estimator, nothing checked on the way. */
static void run_periods(smc_t *s, pmsm_ideal_t *m, long n)
{
    long k;
    for (k = 0; k < n; k++) {
        ab_q15_t i;
        ab_q15_t v;
        pmsm_ideal_step(m, &i, &v);
        smc_period(s, i, v);
    }
}

/* Estimated minus true electrical angle, degrees in [-180, 180). */
static double angle_err_deg(const smc_t *s, const pmsm_ideal_t *m)
{
    return angle_diff_deg(angle_to_rad(smc_theta(s)), pmsm_ideal_theta(m));
}

static double omega_rpm(const smc_t *s, const bench_t *b)
{
    return (double)smc_omega(s) / 32768.0 * b->wfs_hz * 60.0 / (double)b->motor.pole_pairs;
}

/* ---- steady state ------------------------------------------------------ */

typedef struct {
    double err_max;   /* max |angle error| over one mechanical turn, deg */
    double err_mean;  /* mean angle error, deg */
    double speed_max; /* max |speed error| / speed, % */
    double conv_ms;   /* last instant |error| > 2 deg, from the start, ms */
    long invalid;     /* periods of the measurement with valid == false */
    double ratio_min; /* smallest and largest emf_ratio seen (1 = as Ke predicts) */
    double ratio_max;
} steady_t;

/* Run at rpm from a reset estimator: settle_ms, then measure over one
 * mechanical turn (at least measure_min_ms). */
static steady_t run_steady(const smc_params_t *p, const bench_t *b, double rpm, double settle_ms)
{
    pmsm_ideal_t m;
    smc_t s;
    steady_t r;
    long n;
    long n_settle = (long)(settle_ms / 1000.0 / TS);
    double turn_s = 60.0 / fabs(rpm);
    long n_meas = (long)(turn_s / TS) + 1;
    double sum = 0.0;
    memset(&r, 0, sizeof r);
    r.ratio_min = 1e9;
    pmsm_ideal_init(&m, &b->motor, &b->drive, rpm, 0.4);
    smc_init(&s, p);
    for (n = 0; n < n_settle + n_meas; n++) {
        ab_q15_t i;
        ab_q15_t v;
        double e;
        pmsm_ideal_step(&m, &i, &v);
        smc_period(&s, i, v);
        e = angle_err_deg(&s, &m);
        if (fabs(e) > 2.0) {
            r.conv_ms = (double)(n + 1) * TS * 1000.0;
        }
        if (n >= n_settle) {
            double se = fabs(omega_rpm(&s, b) - rpm) / fabs(rpm) * 100.0;
            double ratio = (double)smc_emf_ratio(&s) / 4096.0;
            r.invalid += smc_valid(&s) ? 0 : 1;
            r.ratio_min = (ratio < r.ratio_min) ? ratio : r.ratio_min;
            r.ratio_max = (ratio > r.ratio_max) ? ratio : r.ratio_max;
            sum += e;
            if (fabs(e) > r.err_max) {
                r.err_max = fabs(e);
            }
            if (se > r.speed_max) {
                r.speed_max = se;
            }
        }
    }
    r.err_mean = sum / (double)n_meas;
    return r;
}

/* The table of the steady-state tests, one row per speed. */
static void steady_print_header(void)
{
    printf("measured:   rpm   max|angle err| deg   mean deg   max|speed err| %%   conv ms   "
           "emf ratio\n");
}

static void steady_print_row(double rpm, const steady_t *r)
{
    printf("measured: %5.0f   %8.3f            %7.3f    %8.4f            %5.1f     %.2f..%.2f\n",
           rpm, r->err_max, r->err_mean, r->speed_max, r->conv_ms, r->ratio_min, r->ratio_max);
}

static void
test_smc_should_hold_the_angle_within_2_degrees_and_the_speed_within_1_percent_from_500_to_5300_rpm(
    void **state)
{
    static const double rpms[] = {500,  750,  1000, 1500, 2000, 2500,
                                  3000, 3500, 4000, 4500, 5000, 5300};
    bench_t b = bench_hurst();
    err_stats_t ang;
    err_stats_t spd;
    size_t k;
    (void)state;
    err_stats_init(&ang);
    err_stats_init(&spd);
    printf("measured: hurst steady state (settle 150 ms, then one mechanical turn)\n");
    steady_print_header();
    for (k = 0; k < sizeof rpms / sizeof rpms[0]; k++) {
        steady_t r = run_steady(&hurst, &b, rpms[k], 150.0);
        steady_print_row(rpms[k], &r);
        err_stats_add(&ang, r.err_max, rpms[k]);
        err_stats_add(&spd, r.speed_max, rpms[k]);
        assert_cmp(r.err_max, <=, 2.0);
        assert_cmp(r.speed_max, <=, 1.0);
        assert_int_equal(r.invalid, 0);
    }
    err_stats_print("hurst angle error over 500..5300 rpm", &ang, "deg");
    err_stats_print("hurst speed error over 500..5300 rpm", &spd, "%");
}

static void
test_smc_should_hold_the_angle_within_2_degrees_on_a_2_pole_pair_motor_up_to_17000_rpm(void **state)
{
    static const double rpms[] = {2000, 4000, 6000, 8000, 10000, 12000, 14000, 16000, 17000};
    bench_t b = bench_hispeed();
    err_stats_t ang;
    size_t k;
    (void)state;
    err_stats_init(&ang);
    printf("measured: hispeed (2 pp, 1.2 ohm, 4 mH, 10 V/krpm, 320 V) steady state\n");
    steady_print_header();
    for (k = 0; k < sizeof rpms / sizeof rpms[0]; k++) {
        steady_t r = run_steady(&hispeed, &b, rpms[k], 60.0);
        steady_print_row(rpms[k], &r);
        err_stats_add(&ang, r.err_max, rpms[k]);
        assert_cmp(r.err_max, <=, 2.0);
        assert_cmp(r.speed_max, <=, 1.0);
        assert_int_equal(r.invalid, 0);
    }
    err_stats_print("hispeed angle error over 2000..17000 rpm", &ang, "deg");
}

static void test_smc_should_track_reverse_rotation_with_the_same_accuracy(void **state)
{
    static const double rpms[] = {-1000, -3000};
    bench_t b = bench_hurst();
    size_t k;
    (void)state;
    for (k = 0; k < sizeof rpms / sizeof rpms[0]; k++) {
        steady_t r = run_steady(&hurst, &b, rpms[k], 150.0);
        printf("measured: reverse %5.0f rpm: max|angle err| %.3f deg, max|speed err| %.4f %%\n",
               rpms[k], r.err_max, r.speed_max);
        assert_cmp(r.err_max, <=, 2.0);
        assert_cmp(r.speed_max, <=, 1.0);
    }
}

/* ---- convergence from any initial state --------------------------------- */

static int16_t rand_between(uint32_t *st, int lo, int hi)
{
    return (int16_t)(lo + (int)(test_rand_u32(st) % (uint32_t)(hi - lo + 1)));
}

/* Kinds of initial state: 0 reset, 1 preset to +full scale, 2 preset to
 * -full scale, 3 the state converged at another speed in the other
 * direction, >= 4 random (model current, correction, both stages, speed,
 * angle; back-EMF states up to +-0.9 E_FS). */
static void make_initial_state(smc_t *s, const smc_params_t *p, const bench_t *b, int kind,
                               uint32_t *st)
{
    smc_init(s, p);
    if (kind == 1) {
        smc_preset_speed(s, Q15_MAX);
    } else if (kind == 2) {
        smc_preset_speed(s, Q15_MIN);
    } else if (kind == 3) {
        pmsm_ideal_t m;
        pmsm_ideal_init(&m, &b->motor, &b->drive, -4000.0, 1.0);
        run_periods(s, &m, 2000);
    } else if (kind >= 4) {
        s->i_est.alpha = rand_between(st, -30000, 30000);
        s->i_est.beta = rand_between(st, -30000, 30000);
        s->z.alpha = rand_between(st, -p->kslide, p->kslide);
        s->z.beta = rand_between(st, -p->kslide, p->kslide);
        s->e.alpha = rand_between(st, -29500, 29500);
        s->e.beta = rand_between(st, -29500, 29500);
        lpf_reset(&s->e_alpha, s->e.alpha);
        lpf_reset(&s->e_beta, s->e.beta);
        lpf_reset(&s->ef_alpha, rand_between(st, -29500, 29500));
        lpf_reset(&s->ef_beta, rand_between(st, -29500, 29500));
        s->theta_raw = rand_between(st, -32768, 32767);
        smc_preset_speed(s, rand_between(st, -32768, 32767));
    }
}

/* Time (ms) after which |angle error| stays <= 2 deg, within a 150 ms run. */
static double convergence_ms(const smc_params_t *p, const bench_t *b, double rpm, int kind,
                             uint32_t *st)
{
    pmsm_ideal_t m;
    smc_t s;
    long n;
    long last = 0;
    make_initial_state(&s, p, b, kind, st);
    pmsm_ideal_init(&m, &b->motor, &b->drive, rpm, 0.1 * (double)kind);
    for (n = 0; n < (long)(0.150 / TS); n++) {
        ab_q15_t i;
        ab_q15_t v;
        pmsm_ideal_step(&m, &i, &v);
        smc_period(&s, i, v);
        if (fabs(angle_err_deg(&s, &m)) > 2.0) {
            last = n + 1;
        }
    }
    return (double)last * TS * 1000.0;
}

static void test_smc_should_converge_from_any_initial_state(void **state)
{
    static const double rpms[] = {500, 700, 1000, 2000, 3500, 5300};
    bench_t b = bench_hurst();
    uint32_t st = 0xC0FFEEU;
    size_t k;
    (void)state;
    printf("measured: convergence to |angle error| <= 2 deg (worst of reset, +-full-scale "
           "preset, reversed stale state, 20 random states)\n");
    for (k = 0; k < sizeof rpms / sizeof rpms[0]; k++) {
        double worst = 0.0;
        double reset_ms = 0.0;
        int kind;
        for (kind = 0; kind < 24; kind++) {
            double t = convergence_ms(&hurst, &b, rpms[k], kind, &st);
            if (kind == 0) {
                reset_ms = t;
            }
            if (t > worst) {
                worst = t;
            }
        }
        printf("measured: %5.0f rpm: from reset %.1f ms, worst %.1f ms\n", rpms[k], reset_ms,
               worst);
        assert_cmp(worst, <=, 30.0);
    }
}

/* ---- ramps ----------------------------------------------------------------- */

static void run_ramp(const smc_params_t *p, const bench_t *b, double rpm0, double rpm1,
                     double rpm_per_s, err_stats_t *ang, err_stats_t *spd)
{
    pmsm_ideal_t m;
    smc_t s;
    long n;
    long n_settle = (long)(0.100 / TS);
    long n_ramp = (long)(fabs(rpm1 - rpm0) / rpm_per_s / TS);
    pmsm_ideal_init(&m, &b->motor, &b->drive, rpm0, 0.0);
    smc_init(&s, p);
    for (n = 0; n < n_settle + n_ramp; n++) {
        ab_q15_t i;
        ab_q15_t v;
        if (n == n_settle) {
            pmsm_ideal_set_speed(&m, rpm1, rpm_per_s);
        }
        pmsm_ideal_step(&m, &i, &v);
        smc_period(&s, i, v);
        if (n >= n_settle) {
            double rpm = pmsm_ideal_rpm(&m);
            err_stats_add(ang, angle_err_deg(&s, &m), rpm);
            err_stats_add(spd, omega_rpm(&s, b) - rpm, rpm);
        }
    }
}

static void
test_smc_should_hold_the_angle_within_5_degrees_during_a_2000_rpm_per_s_ramp(void **state)
{
    bench_t b = bench_hurst();
    err_stats_t ang_up;
    err_stats_t spd_up;
    err_stats_t ang_dn;
    err_stats_t spd_dn;
    (void)state;
    err_stats_init(&ang_up);
    err_stats_init(&spd_up);
    err_stats_init(&ang_dn);
    err_stats_init(&spd_dn);
    run_ramp(&hurst, &b, 500.0, 5300.0, 2000.0, &ang_up, &spd_up);
    run_ramp(&hurst, &b, 5300.0, 500.0, 2000.0, &ang_dn, &spd_dn);
    err_stats_print("ramp 500 -> 5300 rpm at 2000 rpm/s: angle error", &ang_up, "deg");
    err_stats_print("ramp 500 -> 5300 rpm at 2000 rpm/s: speed error", &spd_up, "rpm");
    err_stats_print("ramp 5300 -> 500 rpm at 2000 rpm/s: angle error", &ang_dn, "deg");
    err_stats_print("ramp 5300 -> 500 rpm at 2000 rpm/s: speed error", &spd_dn, "rpm");
    assert_cmp(ang_up.max_abs, <=, 5.0);
    assert_cmp(ang_dn.max_abs, <=, 5.0);
}

/* ---- parameter mismatch, noise, dead time -------------------------------------------- */

static void test_smc_should_stay_bounded_with_r_and_l_off_by_30_percent(void **state)
{
    static const struct {
        const char *name;
        const smc_params_t *p;
    } cases[] = {
        {"R -30%", &hurst_r07},           {"R +30%", &hurst_r13},
        {"L -30%", &hurst_l07},           {"L +30%", &hurst_l13},
        {"R,L -30%", &hurst_r07l07},      {"R,L +30%", &hurst_r13l13},
        {"R -30% L +30%", &hurst_r07l13}, {"R +30% L -30%", &hurst_r13l07},
    };
    static const double rpms[] = {500, 1000, 2500, 5300};
    bench_t b = bench_hurst();
    size_t c;
    size_t k;
    double worst = 0.0;
    (void)state;
    printf("measured: model R/L mismatch: mean / max|angle error| (deg), max|speed err| (%%)\n");
    for (c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        printf("measured: %-14s", cases[c].name);
        for (k = 0; k < sizeof rpms / sizeof rpms[0]; k++) {
            steady_t r = run_steady(cases[c].p, &b, rpms[k], 150.0);
            printf("  %4.0f rpm: %6.2f / %5.2f / %5.2f", rpms[k], r.err_mean, r.err_max,
                   r.speed_max);
            if (r.err_max > worst) {
                worst = r.err_max;
            }
            /* Bounded: the estimate neither diverges nor loses the speed. */
            assert_cmp(r.err_max, <=, 15.0);
            assert_cmp(r.speed_max, <=, 2.0);
        }
        printf("\n");
    }
    printf("measured: worst |angle error| with +-30 %% R/L: %.2f deg\n", worst);
}

static void
test_smc_should_hold_the_angle_within_3_degrees_with_adc_noise_above_1000_rpm(void **state)
{
    static const double rpms[] = {1000, 2000, 3500, 5300};
    /* Two noise models: 3 LSB rms on the Q15 grid, and a 10-bit ADC (64-count
     * steps) with 1 ADC LSB (64 counts) rms on top. */
    static const struct {
        const char *name;
        double noise;
        int step;
    } models[] = {{"3 Q15 LSB rms", 3.0, 1}, {"10-bit ADC + 1 LSB rms", 64.0, 64}};
    size_t j;
    size_t k;
    (void)state;
    for (j = 0; j < sizeof models / sizeof models[0]; j++) {
        bench_t b = bench_hurst();
        b.drive.noise_lsb = models[j].noise;
        b.drive.adc_lsb = models[j].step;
        printf("measured: noise %s:", models[j].name);
        for (k = 0; k < sizeof rpms / sizeof rpms[0]; k++) {
            steady_t r = run_steady(&hurst, &b, rpms[k], 150.0);
            printf("  %4.0f rpm max %.2f deg (speed %.2f %%)", rpms[k], r.err_max, r.speed_max);
            assert_cmp(r.err_max, <=, 3.0);
        }
        printf("\n");
    }
}

static void test_smc_should_show_the_dead_time_bias_unless_fed_the_applied_voltage(void **state)
{
    static const double rpms[] = {500, 1000, 2000, 4000};
    size_t k;
    (void)state;
    printf("measured: 2 us dead time at 20 kHz (4 %% of a 24 V bus per phase), estimator fed "
           "the command / the applied voltage: mean (max) angle error, deg\n");
    for (k = 0; k < sizeof rpms / sizeof rpms[0]; k++) {
        bench_t b = bench_hurst();
        steady_t cmd;
        steady_t app;
        b.drive.deadtime_frac = 0.04;
        cmd = run_steady(&hurst, &b, rpms[k], 150.0);
        b.drive.feed_applied = 1;
        app = run_steady(&hurst, &b, rpms[k], 150.0);
        printf("measured: %5.0f rpm: command %7.2f (%6.2f)   applied %6.3f (%5.3f)\n", rpms[k],
               cmd.err_mean, cmd.err_max, app.err_mean, app.err_max);
        /* Fed the voltage really applied, the estimator is as exact as
         * without dead time; fed the command, it keeps a bounded bias. */
        assert_cmp(app.err_max, <=, 2.0);
        assert_cmp(cmd.err_max, <=, 30.0);
    }
}

/* ---- below the minimum speed, overspeed, validity -------------------------- */

static void test_smc_should_report_not_valid_below_the_minimum_speed_without_overflow(void **state)
{
    static const double rpms[] = {0.0, 50.0, 150.0, 300.0, -300.0};
    bench_t b = bench_hurst();
    size_t k;
    (void)state;
    for (k = 0; k < sizeof rpms / sizeof rpms[0]; k++) {
        pmsm_ideal_t m;
        smc_t s;
        long n;
        long valid_count = 0;
        err_stats_t ang;
        err_stats_init(&ang);
        pmsm_ideal_init(&m, &b.motor, &b.drive, rpms[k], 0.2);
        smc_init(&s, &hurst);
        for (n = 0; n < 4000; n++) {
            ab_q15_t i;
            ab_q15_t v;
            pmsm_ideal_step(&m, &i, &v);
            smc_period(&s, i, v);
            if (n > 2000) {
                valid_count += smc_valid(&s) ? 1 : 0;
                err_stats_add(&ang, angle_err_deg(&s, &m), (double)n);
                /* Defined ranges: K at its floor or above, the ratio
                 * saturating rather than wrapping negative. */
                assert_cmp(s.k, >=, hurst.k_min);
                assert_cmp(s.emf_ratio, >=, 0);
            }
        }
        printf("measured: %5.0f rpm (minimum 400): valid in %ld of 1999 periods, speed %.0f rpm, "
               "angle error mean %.1f max %.1f deg\n",
               rpms[k], valid_count, omega_rpm(&s, &b), err_stats_mean(&ang), ang.max_abs);
        assert_int_equal(valid_count, 0);
    }
}

static void
test_smc_should_become_valid_above_the_minimum_speed_and_saturate_past_full_scale(void **state)
{
    bench_t b = bench_hurst();
    pmsm_ideal_t m;
    smc_t s;
    long n;
    (void)state;
    pmsm_ideal_init(&m, &b.motor, &b.drive, 600.0, 0.0);
    smc_init(&s, &hurst);
    run_periods(&s, &m, 3000);
    assert_true(smc_valid(&s));
    printf("measured: 600 rpm: emf ratio %.3f (1 = as expected from Ke), amplitude %d\n",
           (double)smc_emf_ratio(&s) / 4096.0, smc_emf_amplitude(&s));
    assert_in_range(smc_emf_ratio(&s), SMC_EMF_RATIO_LO, SMC_EMF_RATIO_HI);
    /* 9000 rpm on an 8000 rpm full scale: the speed saturates, no wrap. */
    pmsm_ideal_init(&m, &b.motor, &b.drive, 9000.0, 0.0);
    for (n = 0; n < 3000; n++) {
        ab_q15_t i;
        ab_q15_t v;
        pmsm_ideal_step(&m, &i, &v);
        smc_period(&s, i, v);
        if (n > 1500) {
            assert_cmp(smc_omega(&s), >, 30000);
        }
    }
    printf("measured: 9000 rpm on an 8000 rpm scale: omega %d (saturated)\n", smc_omega(&s));
}

static void test_smc_should_judge_validity_by_speed_alone_without_ke(void **state)
{
    bench_t b = bench_hurst();
    pmsm_ideal_t m;
    smc_t s;
    (void)state;
    assert_int_equal(hurst_noke.emf_gain, 0);
    pmsm_ideal_init(&m, &b.motor, &b.drive, 1000.0, 0.0);
    smc_init(&s, &hurst_noke);
    run_periods(&s, &m, 3000);
    assert_true(smc_valid(&s));
    assert_int_equal(smc_emf_ratio(&s), SMC_EMF_RATIO_ONE);
    assert_cmp(fabs(angle_err_deg(&s, &m)), <=, 2.0);
}

static void test_smc_should_flag_a_stalled_rotor_through_the_emf_ratio(void **state)
{
    /* The estimator is preset to 2000 rpm but the motor stands still with
     * current flowing: the speed collapses and the flag drops. */
    bench_t b = bench_hurst();
    pmsm_ideal_t m;
    smc_t s;
    long n;
    long valid_late = 0;
    (void)state;
    pmsm_ideal_init(&m, &b.motor, &b.drive, 0.0, 0.0);
    smc_init(&s, &hurst);
    smc_preset_speed(&s, (q15_t)(2000.0 / 8000.0 * 32768.0));
    for (n = 0; n < 2000; n++) {
        ab_q15_t i;
        ab_q15_t v;
        pmsm_ideal_step(&m, &i, &v);
        smc_period(&s, i, v);
        if (n > 400) {
            valid_late += smc_valid(&s) ? 1 : 0;
        }
    }
    printf("measured: stall after a 2000 rpm preset: valid in %ld of the last 1599 periods, "
           "omega %d\n",
           valid_late, smc_omega(&s));
    assert_int_equal(valid_late, 0);
}

static void test_smc_should_stay_within_20_degrees_with_the_published_relay_gains(void **state)
{
    static const double rpms[] = {1000, 3000};
    bench_t b = bench_hurst();
    size_t k;
    (void)state;
    for (k = 0; k < sizeof rpms / sizeof rpms[0]; k++) {
        steady_t r = run_steady(&hurst_relay, &b, rpms[k], 200.0);
        printf("measured: relay mode (band 0.005 FS, AN1078's): %4.0f rpm mean %.2f max %.2f deg, "
               "speed %.2f %%\n",
               rpms[k], r.err_mean, r.err_max, r.speed_max);
        /* Characterisation, not a recommendation: the relay chatter and the
         * unmodelled switching lag cost accuracy (docs/estimator.md). */
        assert_cmp(r.err_max, <=, 20.0);
    }
}

/* ---- blocks against double precision ------------------------------------------- */

static void test_smc_params_should_match_their_double_precision_definitions(void **state)
{
    const smc_params_t *p = &hurst;
    double y = TS * HURST_R / HURST_L;
    double f = exp(-y);
    double g = (1.0 - f) / HURST_R * 2.0 * HURST_VFS / HURST_IFS;
    double me = 1.8 * (1.0 - f) / HURST_R * HURST_VFS / HURST_IFS / f;
    double kz = 0.9 / me;
    double c = g * kz;
    (void)state;
    printf("measured: hurst F %d G %d<<%d Kslide %d band %d Kz %d<<%d c %.4f\n", p->f, p->g,
           p->g_shift, p->kslide, p->max_err, p->kz, p->kz_shift, c);
    assert_cmp(fabs(p->f - f * 32768.0), <=, 0.5);
    assert_cmp(fabs(ldexp(p->g, p->g_shift) - g * 32768.0), <=, ldexp(0.5, p->g_shift));
    assert_cmp(fabs(p->kslide - 0.9 * 32768.0), <=, 0.5);
    assert_cmp(fabs(p->max_err - me * 32768.0), <=, 0.5);
    assert_cmp(fabs(ldexp(p->kz, p->kz_shift) - kz * 32768.0), <=, ldexp(0.5, p->kz_shift));
    assert_cmp(fabs(p->k_per_omega - 2.0 * M_PI * HURST_WFS * TS * 32768.0), <=, 0.5);
    assert_cmp(fabs(p->k_min - 2.0 * M_PI * HURST_FMIN * TS * 32768.0), <=, 0.5);
    assert_cmp(fabs(ldexp(p->kspeed, p->kspeed_shift) - 32768.0 / (2.0 * 20 * TS * HURST_WFS)), <=,
               ldexp(0.5, p->kspeed_shift));
    /* Transfer-function constants (notes 3-4): c = F (dead-beat), p = 0. */
    assert_cmp(fabs(p->tf_mdc - (1.0 + 2.0 * c - f) * 4096.0), <=, 0.5);
    assert_cmp(fabs(p->tf_b10 - (1.0 - (f - c)) * 4096.0), <=, 0.5);
    assert_cmp(fabs(p->tf_b1k + (1.0 + 3.0 * c - 2.0 * f) * 4096.0), <=, 0.5);
    assert_cmp(fabs(p->tf_b2 - (f - c) * 32768.0), <=, 0.5);
    assert_cmp(fabs(p->tf_xadv - 0.5 / M_PI * 32768.0), <=, 0.5);
    /* The relay set switches to the ideal sliding-mode form. */
    assert_int_equal(hurst_relay.tf_mdc, 8192);
    assert_int_equal(hurst_relay.tf_b10, 4096);
    assert_int_equal(hurst_relay.tf_b1k, -4096);
    assert_int_equal(hurst_relay.tf_b2, 0);
    assert_int_equal(hurst_relay.tf_xadv, 0);
}

/* The lead in double: arg D1 + arg D2 + xadv x, with the constants as
 * stored (note 3). */
static double lead_ref_deg(const smc_params_t *p, double k, double x)
{
    double ur = 1.0 - cos(x);
    double ui = sin(x);
    double mdc = p->tf_mdc / 4096.0;
    double b1 = p->tf_b10 / 4096.0 + k * p->tf_b1k / 4096.0;
    double b2 = p->tf_b2 / 32768.0 * (1.0 - k);
    double u2r = ur * ur - ui * ui;
    double u2i = 2.0 * ur * ui;
    double d1r = k * mdc + b1 * ur + b2 * u2r;
    double d1i = b1 * ui + b2 * u2i;
    double d2r = k + (1.0 - k) * ur;
    double d2i = (1.0 - k) * ui;
    double xadv = p->tf_xadv / 32768.0 * M_PI;
    return (atan2(d1i, d1r) + atan2(d2i, d2r) + xadv * x) * 180.0 / M_PI;
}

static void test_smc_phase_lead_should_match_the_transfer_function_in_double(void **state)
{
    static const smc_params_t *const sets[] = {&hurst, &hispeed, &hurst_relay, &hurst_r07l13};
    err_stats_t es;
    size_t j;
    (void)state;
    err_stats_init(&es);
    for (j = 0; j < sizeof sets / sizeof sets[0]; j++) {
        int xi;
        for (xi = 0; xi <= 9000; xi += 7) {
            /* K equal to x (above the floor), at the floor, and off by 2x. */
            q15_t x = (q15_t)xi;
            q15_t ks[4];
            int m;
            ks[0] = (x > sets[j]->k_min) ? x : sets[j]->k_min;
            ks[1] = sets[j]->k_min;
            ks[2] = (q15_t)((ks[0] < 16000) ? 2 * ks[0] : 32000);
            ks[3] = (q15_t)((ks[0] / 2 > 0) ? ks[0] / 2 : 1);
            for (m = 0; m < 4; m++) {
                double ref = lead_ref_deg(sets[j], ks[m] / 32768.0, xi / 32768.0);
                double got = angle_to_rad(smc_phase_lead(sets[j], ks[m], x)) * 180.0 / M_PI;
                err_stats_add(&es, angle_diff_deg(got * M_PI / 180.0, ref * M_PI / 180.0), xi);
            }
        }
    }
    err_stats_print("smc_phase_lead vs double transfer function", &es, "deg");
    assert_cmp(es.max_abs, <=, 0.03);
}

static void
test_smc_phase_lead_should_be_the_observer_lag_in_a_double_precision_simulation(void **state)
{
    /* The derivation itself: a double-precision copy of the observer (same
     * order of operations, no internal quantisation, fed the Q15 samples of
     * the exact ZOH plant) lags the rotor by the formula's value (note 3). */
    static const double rpms[] = {500, 1500, 3000, 5300};
    const smc_params_t *p = &hurst;
    bench_t b = bench_hurst();
    double f = exp(-TS * HURST_R / HURST_L);
    double g = (1.0 - f) / HURST_R * HURST_VFS / HURST_IFS; /* per V_FS */
    double kz = f / g;                                      /* dead-beat: c = G Kz = F */
    err_stats_t es;
    size_t k;
    (void)state;
    err_stats_init(&es);
    for (k = 0; k < sizeof rpms / sizeof rpms[0]; k++) {
        pmsm_ideal_t m;
        double x = 2.0 * M_PI * rpms[k] * HURST_PP / 60.0 * TS;
        double ie[2] = {0, 0}, z[2] = {0, 0}, e[2] = {0, 0}, ef[2] = {0, 0};
        double sum = 0.0;
        long n;
        long cnt = 0;
        pmsm_ideal_init(&m, &b.motor, &b.drive, rpms[k], 0.0);
        for (n = 0; n < 8000; n++) {
            ab_q15_t iq;
            ab_q15_t vq;
            int a;
            pmsm_ideal_step(&m, &iq, &vq);
            for (a = 0; a < 2; a++) {
                double im = ((a == 0) ? iq.alpha : iq.beta) / 32768.0;
                double vv = ((a == 0) ? vq.alpha : vq.beta) / 32768.0;
                double err;
                ie[a] = f * ie[a] + g * (vv - e[a] - z[a]);
                err = ie[a] - im;
                z[a] = kz * err; /* linear band: never left at steady state */
                e[a] += x * (z[a] - e[a]);
                ef[a] += x * (e[a] - ef[a]);
            }
            if (n >= 6000) {
                double th = atan2(-ef[0], ef[1]);
                sum += angle_diff_deg(th, pmsm_ideal_theta(&m));
                cnt++;
            }
        }
        {
            double lag = -sum / (double)cnt;
            double model = lead_ref_deg(p, x, x);
            printf("measured: %4.0f rpm: double observer lags %.3f deg, formula %.3f deg\n",
                   rpms[k], lag, model);
            err_stats_add(&es, lag - model, rpms[k]);
        }
    }
    err_stats_print("formula vs double-precision observer lag", &es, "deg");
    assert_cmp(es.max_abs, <=, 0.1);
}

static void test_smc_speed_from_steps_should_match_the_scaled_sum(void **state)
{
    static const smc_params_t *const sets[] = {&hurst, &hispeed};
    err_stats_t es;
    size_t j;
    uint32_t st = 0x5EEDU;
    (void)state;
    err_stats_init(&es);
    for (j = 0; j < sizeof sets / sizeof sets[0]; j++) {
        const smc_params_t *p = sets[j];
        double scale = ldexp(p->kspeed, p->kspeed_shift) / 32768.0;
        long k;
        for (k = 0; k < 40000; k++) {
            int32_t sum;
            double ref;
            q15_t got;
            if (k < 20000) {
                sum = (int32_t)(k - 10000) * 7; /* dense around 0 */
            } else {
                sum = (int32_t)(test_rand_u32(&st) % (256UL * 65536UL)) - (int32_t)(128L * 65536L);
            }
            ref = floor((double)sum * scale + 0.5);
            if (sum < 0) {
                ref = -floor(-(double)sum * scale + 0.5);
            }
            ref = (ref > 32767.0) ? 32767.0 : (ref < -32767.0) ? -32767.0 : ref;
            got = smc_speed_from_steps(p, sum);
            err_stats_add(&es, (double)got - ref, (double)sum);
        }
        /* Edges: the largest window sums saturate symmetrically. */
        assert_int_equal(smc_speed_from_steps(p, 256L * 32768L), 32767);
        assert_int_equal(smc_speed_from_steps(p, -256L * 32768L), -32767);
        assert_int_equal(smc_speed_from_steps(p, 0), 0);
    }
    err_stats_print("smc_speed_from_steps vs rounded double", &es, "LSB");
    assert_cmp(es.max_abs, <=, 0.0);
}

/* A window end, its slow step and the apply: what a preset or a reset has
 * become once the slow side's results are in (docs/estimator.md note 10). */
static void smc_round_trip(smc_t *s)
{
    smc_window_end(s);
    smc_slow_step(s);
    smc_apply(s);
}

static void test_smc_reset_and_preset_should_define_every_output(void **state)
{
    smc_t s;
    (void)state;
    smc_init(&s, &hurst);
    assert_int_equal(smc_theta(&s), 0);
    assert_int_equal(smc_theta_raw(&s), 0);
    assert_int_equal(smc_omega(&s), 0);
    assert_false(smc_valid(&s));
    assert_int_equal(s.k, hurst.k_min);
    assert_int_equal(s.comp, smc_phase_lead(&hurst, hurst.k_min, 0));
    assert_int_equal(smc_e_final(&s).alpha, 0);
    /* A preset takes the speed at once, K and the compensation with the
     * slow side's next results. */
    smc_preset_speed(&s, 8192);
    assert_int_equal(smc_omega(&s), 8192);
    assert_int_equal(s.k, hurst.k_min);
    smc_round_trip(&s);
    assert_int_equal(smc_omega(&s), 8192); /* a window cut short measures no speed */
    assert_cmp(s.k, >, hurst.k_min);
    assert_int_equal(s.comp, smc_phase_lead(&hurst, s.k, q15_mul(8192, hurst.k_per_omega)));
    smc_preset_speed(&s, -8192);
    assert_int_equal(smc_omega(&s), -8192);
    smc_round_trip(&s);
    assert_int_equal(smc_omega(&s), -8192);
    /* Reverse: the lead is negated and pi added. */
    assert_int_equal(
        s.comp,
        angle_add(angle_sub(0, smc_phase_lead(&hurst, s.k, q15_mul(8192, hurst.k_per_omega))),
                  Q15_MIN));
    /* A reset returns to rest at once, and a result computed before it is
     * dropped. */
    smc_window_end(&s);
    smc_slow_step(&s);
    smc_reset(&s);
    smc_apply(&s);
    assert_int_equal(smc_omega(&s), 0);
    assert_int_equal(s.k, hurst.k_min);
    assert_false(smc_valid(&s));
}

static void test_smc_update_should_saturate_at_the_input_extremes(void **state)
{
    /* Full-scale garbage in: every state stays in range (UBSan guards the
     * arithmetic), and the correction never exceeds Kslide. */
    static const q15_t edges[] = {-32768, -32767, -1, 0, 1, 32767};
    smc_t s;
    size_t a;
    size_t b2;
    uint32_t st = 77U;
    long n;
    (void)state;
    smc_init(&s, &hurst);
    for (a = 0; a < 6; a++) {
        for (b2 = 0; b2 < 6; b2++) {
            ab_q15_t i = {edges[a], edges[b2]};
            ab_q15_t v = {edges[b2], edges[a]};
            smc_period(&s, i, v);
            assert_cmp(abs(s.z.alpha), <=, hurst.kslide);
            assert_cmp(abs(s.z.beta), <=, hurst.kslide);
        }
    }
    for (n = 0; n < 20000; n++) {
        ab_q15_t i = {test_rand_i16(&st), test_rand_i16(&st)};
        ab_q15_t v = {test_rand_i16(&st), test_rand_i16(&st)};
        smc_period(&s, i, v);
        assert_cmp(abs(s.z.alpha), <=, hurst.kslide);
        assert_cmp(abs(s.z.beta), <=, hurst.kslide);
    }
}

static void
test_pmsm_ideal_should_track_its_current_reference_with_the_steady_state_voltage(void **state)
{
    /* The harness itself: at 2000 rpm (no field weakening) the sampled
     * current is iq j exp(j theta) to within the Q15 rounding, and the fed
     * voltage matches the phasor (R + j w L) I + j w psi exp(j theta) taken at
     * mid-period (the ZOH average) within 0.1 % of its amplitude. */
    bench_t b = bench_hurst();
    pmsm_ideal_t m;
    err_stats_t ei;
    err_stats_t ev;
    long n;
    double w = 2000.0 / 60.0 * 2.0 * M_PI * HURST_PP;
    double prev_theta = 0.0;
    (void)state;
    err_stats_init(&ei);
    err_stats_init(&ev);
    pmsm_ideal_init(&m, &b.motor, &b.drive, 2000.0, 0.3);
    for (n = 0; n < 2000; n++) {
        ab_q15_t i;
        ab_q15_t v;
        double th;
        pmsm_ideal_step(&m, &i, &v);
        th = pmsm_ideal_theta(&m);
        {
            double ia = -0.5 * sin(th) / HURST_IFS * 32768.0;
            double ib = 0.5 * cos(th) / HURST_IFS * 32768.0;
            err_stats_add(&ei, hypot(i.alpha - ia, i.beta - ib), th);
        }
        if (n > 0) {
            /* v_fed(n) was applied over [t_(n-1), t_n]: phasor at mid-period. */
            double thm = prev_theta + 0.5 * w * TS;
            double sn = sin(thm);
            double cs = cos(thm);
            double iq = 0.5;
            /* I = iq j e^(j thm); V = (R + j w L) I + j w psi e^(j thm). */
            double ire = -iq * sn;
            double iim = iq * cs;
            double vre = HURST_R * ire - w * HURST_L * iim - w * b.motor.psi_vs * sn;
            double vim = HURST_R * iim + w * HURST_L * ire + w * b.motor.psi_vs * cs;
            double amp = hypot(vre, vim);
            double got_re = v.alpha / 32768.0 * HURST_VFS;
            double got_im = v.beta / 32768.0 * HURST_VFS;
            err_stats_add(&ev, hypot(got_re - vre, got_im - vim) / amp * 100.0, thm);
        }
        prev_theta = th;
    }
    err_stats_print("pmsm_ideal current vs reference", &ei, "LSB");
    err_stats_print("pmsm_ideal voltage vs steady-state phasor", &ev, "%");
    assert_cmp(ei.max_abs, <=, 1.0);
    assert_cmp(ev.max_abs, <=, 0.1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(
            test_pmsm_ideal_should_track_its_current_reference_with_the_steady_state_voltage),
        cmocka_unit_test(test_smc_params_should_match_their_double_precision_definitions),
        cmocka_unit_test(test_smc_phase_lead_should_match_the_transfer_function_in_double),
        cmocka_unit_test(
            test_smc_phase_lead_should_be_the_observer_lag_in_a_double_precision_simulation),
        cmocka_unit_test(test_smc_speed_from_steps_should_match_the_scaled_sum),
        cmocka_unit_test(test_smc_reset_and_preset_should_define_every_output),
        cmocka_unit_test(test_smc_update_should_saturate_at_the_input_extremes),
        cmocka_unit_test(
            test_smc_should_hold_the_angle_within_2_degrees_and_the_speed_within_1_percent_from_500_to_5300_rpm),
        cmocka_unit_test(
            test_smc_should_hold_the_angle_within_2_degrees_on_a_2_pole_pair_motor_up_to_17000_rpm),
        cmocka_unit_test(test_smc_should_track_reverse_rotation_with_the_same_accuracy),
        cmocka_unit_test(test_smc_should_converge_from_any_initial_state),
        cmocka_unit_test(
            test_smc_should_hold_the_angle_within_5_degrees_during_a_2000_rpm_per_s_ramp),
        cmocka_unit_test(test_smc_should_stay_bounded_with_r_and_l_off_by_30_percent),
        cmocka_unit_test(
            test_smc_should_hold_the_angle_within_3_degrees_with_adc_noise_above_1000_rpm),
        cmocka_unit_test(test_smc_should_show_the_dead_time_bias_unless_fed_the_applied_voltage),
        cmocka_unit_test(test_smc_should_report_not_valid_below_the_minimum_speed_without_overflow),
        cmocka_unit_test(
            test_smc_should_become_valid_above_the_minimum_speed_and_saturate_past_full_scale),
        cmocka_unit_test(test_smc_should_judge_validity_by_speed_alone_without_ke),
        cmocka_unit_test(test_smc_should_flag_a_stalled_rotor_through_the_emf_ratio),
        cmocka_unit_test(test_smc_should_stay_within_20_degrees_with_the_published_relay_gains),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
