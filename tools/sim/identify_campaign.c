/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* identify_campaign.c - self-commissioning against random motors: the identification's
 * accuracy over a population the profile knows nothing of (docs/identify.md). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sim_core.h"
#include "sim_opt.h"
#include "sim_parse.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define COUNT_MAX 100000L

/*
 * One motor per seed, drawn around the build's profile: R, L and Ke each
 * log-uniform over SPAN:1 (20:1) centred on the profile's; or, for the
 * share --small-motors gives of the seeds (default none), a small motor: R and L together a
 * SMALL_LO to 1 / sqrt(SPAN) share of the profile's (the small 24 V
 * motors whose R and L are a tenth to a fifth of the Hurst's), each
 * within SMALL_SPREAD of that and Ke as above; the inertia 0.5 to 3 times, the dead time 0.5 to 3
 * us, ADC noise 0.5 to 3 codes and amplifier offsets up to 30 codes, the rotor at any angle, the
 * inverter averaged (its dead-time shape linear, hard or ripple) or switching (ideal devices: a
 * switch's resistance and a diode's drop are part of what the drive sees, R and the dead time, not
 * of the motor). The same seed gives the same motor on every machine (xorshift64*,
 * sim_rand_uniform).
 *
 * The identification is requested at T_REQUEST and must end in STOPPED
 * with its result within T_LIMIT. A motor passes when the result is within
 * the envelope below of the plant's parameters and the phase currents
 * stayed under I_PEAK_FRAC times MC_ID_CURRENT_A.
 */
#define SPAN         20.0
#define SMALL_LO     0.1
#define SMALL_SPREAD 1.5
#define T_REQUEST    0.05
#define T_LIMIT      40.0
#define ENV_R        5.0 /* per cent */
#define ENV_L        5.0 /* Ld, Lq and their mean */
#define ENV_KE       3.0
#define ENV_J        20.0
#define ENV_DT       15.0
#define I_PEAK_FRAC  1.6 /* mc_derived.h: the trip sits above 1.6 x MC_ID_CURRENT_A */

typedef struct {
    uint32_t seed;
    simcore_cfg_t cfg;
} draw_t;

typedef struct {
    mc_id_result_t r;
    simcore_id_err_t e;
    double t_s;         /* from the request to STOPPED */
    double i_peak;      /* largest phase current, A */
    int state;          /* the core's mc_state_t at the end */
    const char *result; /* PASS or FAIL */
    char why[96];
} outcome_t;

static double uni(uint64_t *r, double lo, double hi)
{
    return lo + (hi - lo) * sim_rand_uniform(r);
}

static double log_uni(uint64_t *r, double lo, double hi)
{
    return exp(uni(r, log(lo), log(hi)));
}

static void draw(uint32_t seed, const char *motor, const char *board, double small, draw_t *d)
{
    uint64_t r = 0x9E3779B97F4A7C15ULL ^ ((uint64_t)seed * 0x2545F4914F6CDD1DULL);
    double h = sqrt(SPAN);
    int k;
    memset(d, 0, sizeof(*d));
    d->seed = seed;
    for (k = 0; k < 4; k++) {
        (void)sim_rand_uniform(&r); /* stir the seed in */
    }
    simcore_cfg_default(&d->cfg);
    d->cfg.motor = motor;
    d->cfg.board = board;
    d->cfg.progress = false;
    if (small > 0.0 && sim_rand_uniform(&r) < small) {
        double s = log_uni(&r, SMALL_LO, 1.0 / h);
        d->cfg.rs_scale = s * log_uni(&r, 1.0 / SMALL_SPREAD, SMALL_SPREAD);
        d->cfg.l_scale = s * log_uni(&r, 1.0 / SMALL_SPREAD, SMALL_SPREAD);
    } else {
        d->cfg.rs_scale = log_uni(&r, 1.0 / h, h);
        d->cfg.l_scale = log_uni(&r, 1.0 / h, h);
    }
    d->cfg.ke_scale = log_uni(&r, 1.0 / h, h);
    d->cfg.j_scale = uni(&r, 0.5, 3.0);
    d->cfg.theta0_rad = uni(&r, 0.0, 2.0 * M_PI);
    d->cfg.deadtime_s = uni(&r, 0.5e-6, 3.0e-6);
    d->cfg.noise_codes = uni(&r, 0.5, 3.0);
    d->cfg.offsets_set = true;
    d->cfg.offset_a_codes = uni(&r, -30.0, 30.0);
    d->cfg.offset_b_codes = uni(&r, -30.0, 30.0);
    d->cfg.seed = seed | 1u;
    if (sim_rand_uniform(&r) < 0.75) {
        d->cfg.inv.model = SIM_INV_AVERAGED;
        d->cfg.inv.dt_shape = (int)(sim_rand_uniform(&r) * 3.0); /* linear, hard, ripple */
    } else {
        d->cfg.inv.model = SIM_INV_SWITCHING;
    }
}

static bool outside(double e, double lim)
{
    return !(fabs(e) <= lim); /* NaN is outside */
}

/* Runs one motor; 0, or 2 when the bench refuses the draw. */
static int run_one(const draw_t *d, outcome_t *o, bool verbose)
{
    static simcore_t s;
    double t_req;
    if (simcore_init(&s, &d->cfg) != 0) {
        return 2;
    }
    memset(o, 0, sizeof(*o));
    while (s.rig.t < T_REQUEST) {
        simcore_step(&s);
    }
    t_req = s.rig.t;
    simcore_request(&s, MC_REQUEST_IDENTIFY);
    do {
        simcore_step(&s);
    } while (s.rig.t < t_req + T_LIMIT && !s.diverged &&
             !((s.now.state == MC_STATE_STOPPED || s.now.state == MC_STATE_FAULT) &&
               (s.mc.id_status == MC_ID_DONE || s.mc.id_status == MC_ID_FAILED)));
    mc_identify_result(&s.mc, &o->r);
    simcore_identify_errors(&s, &o->r, &o->e);
    o->t_s = s.rig.t - t_req;
    o->i_peak = s.log.i_peak_a;
    o->state = s.now.state;
    o->result = "FAIL";
    if (o->r.status != MC_ID_DONE) {
        snprintf(o->why, sizeof(o->why), "%s %s",
                 (o->r.status == MC_ID_FAILED) ? "failed," : "no result,",
                 (o->r.status == MC_ID_FAILED) ? mc_id_error_name(o->r.error) : "timeout");
    } else if (o->state != MC_STATE_STOPPED) {
        snprintf(o->why, sizeof(o->why), "ended in %s", mc_state_name(o->state));
    } else if (outside(o->e.rs, ENV_R)) {
        snprintf(o->why, sizeof(o->why), "R %+.2f %%", o->e.rs);
    } else if (outside(o->e.ld, ENV_L) || outside(o->e.lq, ENV_L) || outside(o->e.ls, ENV_L)) {
        snprintf(o->why, sizeof(o->why), "L %+.2f %% (Ld %+.2f, Lq %+.2f)", o->e.ls, o->e.ld,
                 o->e.lq);
    } else if (outside(o->e.ke, ENV_KE)) {
        snprintf(o->why, sizeof(o->why), "Ke %+.2f %%", o->e.ke);
    } else if (outside(o->e.j, ENV_J)) {
        snprintf(o->why, sizeof(o->why), "J %+.2f %%", o->e.j);
    } else if (outside(o->e.deadtime, ENV_DT)) {
        snprintf(o->why, sizeof(o->why), "dead time %+.2f %%", o->e.deadtime);
    } else if (o->i_peak > I_PEAK_FRAC * (double)MC_ID_CURRENT_A) {
        snprintf(o->why, sizeof(o->why), "peak current %.2f A", o->i_peak);
    } else {
        o->result = "PASS";
    }
    if (verbose) {
        simcore_print_identify(&s, stdout);
        printf("   time %.2f s, peak phase current %.2f A (MC_ID_CURRENT_A %.2f A)\n", o->t_s,
               o->i_peak, (double)MC_ID_CURRENT_A);
    }
    return 0;
}

static void print_header(void)
{
    printf("seed,rs_scale,l_scale,ke_scale,j_scale,deadtime_us,inverter,status,error,e_rs_pct,e_ld_"
           "pct,"
           "e_lq_pct,e_ls_pct,e_ke_pct,e_j_pct,e_dt_pct,t_s,i_peak_a,result,why\n");
}

static void print_row(const draw_t *d, const outcome_t *o)
{
    static const char *const SHAPES[] = {"linear", "hard", "ripple"};
    printf("%lu,%.4f,%.4f,%.4f,%.4f,%.3f,%s,%s,%s,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%s,%"
           "s\n",
           (unsigned long)d->seed, d->cfg.rs_scale, d->cfg.l_scale, d->cfg.ke_scale, d->cfg.j_scale,
           d->cfg.deadtime_s * 1e6,
           (d->cfg.inv.model == SIM_INV_SWITCHING) ? "switching" : SHAPES[d->cfg.inv.dt_shape % 3],
           (o->r.status == MC_ID_DONE)     ? "done"
           : (o->r.status == MC_ID_FAILED) ? "failed"
                                           : "none",
           mc_id_error_name(o->r.error), o->e.rs, o->e.ld, o->e.lq, o->e.ls, o->e.ke, o->e.j,
           o->e.deadtime, o->t_s, o->i_peak, o->result, o->why);
}

/* The distribution of one error over the motors that finished: max |e|,
 * 95th percentile of |e|, median of e, and how many lie outside lim. */
static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void summary_line(const char *name, double *v, int n, double lim)
{
    double *a = (double *)malloc((size_t)(n > 0 ? n : 1) * sizeof(double));
    int k, out = 0;
    if (a == NULL || n == 0) {
        free(a);
        return;
    }
    for (k = 0; k < n; k++) {
        a[k] = fabs(v[k]);
        out += outside(v[k], lim);
    }
    qsort(a, (size_t)n, sizeof(double), cmp_double);
    qsort(v, (size_t)n, sizeof(double), cmp_double);
    fprintf(stderr,
            "identify_campaign:   %-9s |e| max %6.2f %%, p95 %6.2f %%, median e %+6.2f %%; outside "
            "+-%g %%: %d\n",
            name, a[n - 1], a[(int)ceil(0.95 * n) - 1], v[n / 2], lim, out);
    free(a);
}

enum { OPT_HELP, OPT_MOTOR, OPT_BOARD, OPT_SEED, OPT_FROM, OPT_COUNT, OPT_PASS_MIN, OPT_SMALL };

/* clang-format off */
static const sim_opt_t OPTS[] = {
    {.id = OPT_HELP, .name = "--help", .type = SIM_OPT_FLAG, .help = "this list"},
    {.id = OPT_MOTOR, .name = "--motor", .type = SIM_OPT_NAME, .value = "NAME",
     .help = "simulated motor the draws centre on (default hurst)"},
    {.id = OPT_BOARD, .name = "--board", .type = SIM_OPT_NAME, .value = "NAME",
     .help = "simulated board (default mclv)"},
    {.id = OPT_SEED, .name = "--seed", .type = SIM_OPT_NUMBER, .value = "N",
     .range = SIM_OPT_SEED_RANGE, .help = "identify this one motor and print its result"},
    {.id = OPT_FROM, .name = "--from", .type = SIM_OPT_NUMBER, .value = "N",
     .range = SIM_OPT_SEED_RANGE, .help = "a campaign: the first seed"},
    {.id = OPT_COUNT, .name = "--count", .type = SIM_OPT_NUMBER, .value = "N",
     .range = {"count", "motors", 1.0, (double)COUNT_MAX, SIM_RANGE_INTEGER},
     .help = "with --from: how many seeds"},
    {.id = OPT_PASS_MIN, .name = "--pass-min", .type = SIM_OPT_NUMBER, .value = "PCT",
     .range = {"pass-min", "%", 0.0, 100.0, 0u},
     .help = "with --from: exit 1 only below this share of motors inside the envelope (default "
             "100), or when one was not identified"},
    {.id = OPT_SMALL, .name = "--small-motors", .type = SIM_OPT_NUMBER, .value = "PCT",
     .range = {"small-motors", "%", 0.0, 100.0, 0u},
     .help = "this share of the draws small motors, R and L together 0.1 to 0.22 of the "
             "profile's (default 0)"},
};
/* clang-format on */

#define N_OPTS (sizeof(OPTS) / sizeof(OPTS[0]))
#define PROG   "identify_campaign"

static void usage(FILE *f)
{
    fprintf(
        f, "usage: identify_campaign [--motor NAME] [--board NAME] (--seed N | --from N --count N\n"
           "                         [--pass-min PCT] [--small-motors PCT])\n"
           "  one CSV row per motor on stdout, the distribution on stderr (docs/identify.md);\n"
           "  exit status 1 if a motor failed (--pass-min: if fewer passed, or one was not\n"
           "  identified)\n");
    sim_opt_usage(f, OPTS, N_OPTS);
}

int main(int argc, char **argv)
{
    const char *motor = "hurst", *board = "mclv";
    long long from = -1, count = 0, one = -1;
    double pass_min = 100.0, small = 0.0;
    double *e[7];
    int i, k, failed = 0, done = 0;
    for (i = 1; i < argc; i++) {
        const char *v;
        const sim_opt_t *o;
        double x;
        if (strcmp(argv[i], "-h") == 0) {
            usage(stdout);
            return 0;
        }
        o = sim_opt_read(PROG, OPTS, N_OPTS, argc, argv, &i, &v, &x);
        if (o == NULL) {
            return 2;
        }
        switch (o->id) {
            case OPT_HELP:
                usage(stdout);
                return 0;
            case OPT_MOTOR:
                motor = v;
                break;
            case OPT_BOARD:
                board = v;
                break;
            case OPT_SEED:
                one = (long long)x;
                break;
            case OPT_FROM:
                from = (long long)x;
                break;
            case OPT_SMALL:
                small = x / 100.0;
                break;
            case OPT_COUNT:
                count = (long long)x;
                break;
            default:
                pass_min = x;
                break;
        }
    }
    if (one >= 0 && from >= 0) {
        return sim_refuse(PROG, "--seed", "identifies one motor: not with --from");
    }
    if (one < 0 && from < 0) {
        return sim_refuse(PROG, "--seed", "give --seed N, or --from N --count N");
    }
    if (from < 0 && count > 0) {
        return sim_refuse(PROG, "--count", "only with --from");
    }
    if (from >= 0 && count == 0) {
        return sim_refuse(PROG, "--count", "--from needs it");
    }
    if (from >= 0 && (double)from + (double)count - 1.0 > SIM_OPT_SEED_MAX) {
        return sim_refuse(PROG, "--count", "the seeds would pass the last one");
    }
    if (one >= 0) {
        draw_t d;
        outcome_t o;
        draw((uint32_t)one, motor, board, small, &d);
        if (run_one(&d, &o, true) != 0) {
            return 2;
        }
        print_header();
        print_row(&d, &o);
        return (strcmp(o.result, "PASS") == 0) ? 0 : 1;
    }
    for (k = 0; k < 7; k++) {
        e[k] = (double *)malloc((size_t)count * sizeof(double));
        if (e[k] == NULL) {
            fputs("identify_campaign: out of memory\n", stderr);
            return 2;
        }
    }
    print_header();
    for (i = 0; i < (int)count; i++) {
        draw_t d;
        outcome_t o;
        draw((uint32_t)(from + i), motor, board, small, &d);
        if (run_one(&d, &o, false) != 0) {
            return 2;
        }
        print_row(&d, &o);
        fflush(stdout);
        failed += (strcmp(o.result, "PASS") != 0);
        if (o.r.status == MC_ID_DONE) {
            e[0][done] = o.e.rs;
            e[1][done] = o.e.ls;
            e[2][done] = o.e.ld;
            e[3][done] = o.e.lq;
            e[4][done] = o.e.ke;
            e[5][done] = o.e.j;
            e[6][done] = o.e.deadtime;
            done++;
        }
    }
    fprintf(stderr,
            "identify_campaign: %lld motors, %d identified, %d passed, %d failed (envelope: R, L "
            "%g %%, "
            "Ke %g %%, J %g %%, dead time %g %%)\n",
            count, done, (int)count - failed, failed, ENV_R, ENV_KE, ENV_J, ENV_DT);
    summary_line("R", e[0], done, ENV_R);
    summary_line("L", e[1], done, ENV_L);
    summary_line("Ld", e[2], done, ENV_L);
    summary_line("Lq", e[3], done, ENV_L);
    summary_line("Ke", e[4], done, ENV_KE);
    summary_line("J", e[5], done, ENV_J);
    summary_line("dead time", e[6], done, ENV_DT);
    for (k = 0; k < 7; k++) {
        free(e[k]);
    }
    if (pass_min < 100.0) {
        double pct = 100.0 * (double)(count - failed) / (double)count;
        fprintf(stderr, "identify_campaign: %.1f %% inside the envelope (--pass-min %g %%)%s\n",
                pct, pass_min, (done < (int)count) ? "; a motor was not identified" : "");
        return (pct < pass_min || done < (int)count) ? 1 : 0;
    }
    return (failed > 0) ? 1 : 0;
}
