/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_main.c - runs a scenario file against the firmware core and the simulated motor. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "sim_core.h"
#include "sim_record.h"
#include "sim_opt.h"
#include "sim_parse.h"
#include "sim_trace.h"
#ifdef SIM_HAVE_PTY
#include "sim_pty.h"
#endif

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/*
 * Every option, once (sim_opt.h): its value and the value's range
 * (docs/sim.md). Every number is parsed strictly (sim_parse.h) and refused
 * in one line on stderr, exit status 2, when it is not a plain decimal
 * number inside its range. The ranges are physical or sane, and they bound
 * the work: substeps and the pty's pace are capped so that no value makes a
 * run take unbounded time (a scenario's length is bounded by its own
 * parser, 3,600 s).
 */
enum {
    OPT_HELP,
    OPT_NO_PROGRESS,
    OPT_MOTOR,
    OPT_BOARD,
    OPT_CSV,
    OPT_RECORD,
    OPT_DECIM,
    OPT_SUBSTEPS,
    OPT_THETA0,
    OPT_RPM0,
    OPT_DEADTIME,
    OPT_NOISE,
    OPT_VBUS,
    OPT_BUS_MODEL,
    OPT_SEED,
    OPT_RS_SCALE,
    OPT_L_SCALE,
    OPT_KE_SCALE,
    OPT_J_SCALE,
    OPT_B_SCALE,
    OPT_J_EXTRA,
    OPT_COULOMB,
    OPT_OFFSETS,
    OPT_INVERTER,
    OPT_DT_SHAPE,
    OPT_DT_BAND,
    OPT_R_ON,
    OPT_V_DIODE,
    OPT_PTY,
    OPT_REALTIME,
    OPT_TCP,
    OPT_BAUD,
    OPT_DURATION,
    OPT_TRUTH
};

/* The slowest pace --realtime takes other than 0: at 0.01 x real time one
 * simulated second is 100 s of wall time. */
#define REALTIME_MIN 0.01
/* An ADC offset of half the 10-bit range puts the amplifier on a rail. */
#define OFFSET_MAX_CODES 512.0

/* clang-format off */
static const sim_opt_t OPTS[] = {
    {.id = OPT_HELP, .name = "--help", .type = SIM_OPT_FLAG, .help = "this list"},
    {.id = OPT_MOTOR, .name = "--motor", .type = SIM_OPT_NAME, .value = "NAME",
     .help = "simulated motor (default hurst; the profiles below)"},
    {.id = OPT_BOARD, .name = "--board", .type = SIM_OPT_NAME, .value = "NAME",
     .help = "simulated board (default mclv)"},
    {.id = OPT_CSV, .name = "--csv", .type = SIM_OPT_TEXT, .value = "FILE",
     .help = "write the trace (default: none)"},
    {.id = OPT_RECORD, .name = "--record", .type = SIM_OPT_TEXT, .value = "FILE",
     .help = "write every period's inputs and outputs (a replay's, docs/sim.md)"},
    {.id = OPT_DECIM, .name = "--decim", .type = SIM_OPT_NUMBER, .value = "N",
     .range = {"", "periods", 1.0, 1e6, SIM_RANGE_INTEGER},
     .help = "one CSV row every N PWM periods (default 10)"},
    {.id = OPT_SUBSTEPS, .name = "--substeps", .type = SIM_OPT_NUMBER, .value = "N",
     .range = {"", "", 1.0, 64.0, SIM_RANGE_INTEGER},
     .help = "RK4 steps per 50 us PWM period (default 4)"},
    {.id = OPT_THETA0, .name = "--theta0", .type = SIM_OPT_NUMBER, .value = "DEG",
     .range = {"", "deg", -360.0, 360.0, 0u}, .help = "initial electrical rotor angle (default 0)"},
    {.id = OPT_RPM0, .name = "--rpm0", .type = SIM_OPT_NUMBER, .value = "RPM",
     .range = {"", "rpm", -100000.0, 100000.0, 0u},
     .help = "initial rotor speed, either direction (default 0: at rest)"},
    {.id = OPT_DEADTIME, .name = "--deadtime", .type = SIM_OPT_NUMBER, .value = "US",
     .range = {"", "us", 0.0, 20.0, 0u}, /* 40 % of a 50 us period */
     .help = "inverter dead time (default: the board's)"},
    {.id = OPT_NOISE, .name = "--noise", .type = SIM_OPT_NUMBER, .value = "LSB",
     .range = {"", "codes", 0.0, 100.0, 0u}, /* a tenth of the 10-bit range */
     .help = "ADC noise sigma (default: the board's)"},
    {.id = OPT_VBUS, .name = "--vbus", .type = SIM_OPT_NUMBER, .value = "V",
     .range = {"", "V", 0.0, 1000.0, 0u}, /* three times the MCHV's 320 V */
     .help = "DC bus (default: the board's)"},
    {.id = OPT_BUS_MODEL, .name = "--bus-model", .type = SIM_OPT_FLAG,
     .help = "the bus as its capacitor and a supply that only sources (the board's C and R)"},
    {.id = OPT_SEED, .name = "--seed", .type = SIM_OPT_NUMBER, .value = "N",
     .range = SIM_OPT_SEED_RANGE, .help = "ADC noise seed (default 1)"},
    {.id = OPT_RS_SCALE, .name = "--rs-scale", .type = SIM_OPT_NUMBER, .value = "X",
     .range = {"", "", 0.0, 100.0, SIM_RANGE_LO_OPEN},
     .help = "plant R times X (a mismatch with the firmware's profile)"},
    {.id = OPT_L_SCALE, .name = "--l-scale", .type = SIM_OPT_NUMBER, .value = "X",
     .range = {"", "", 0.0, 100.0, SIM_RANGE_LO_OPEN}, .help = "plant L times X"},
    {.id = OPT_KE_SCALE, .name = "--ke-scale", .type = SIM_OPT_NUMBER, .value = "X",
     .range = {"", "", 0.0, 100.0, SIM_RANGE_LO_OPEN}, .help = "plant back-EMF constant times X"},
    {.id = OPT_J_SCALE, .name = "--j-scale", .type = SIM_OPT_NUMBER, .value = "X",
     .range = {"", "", 0.0, 100.0, SIM_RANGE_LO_OPEN}, .help = "plant inertia times X"},
    {.id = OPT_B_SCALE, .name = "--b-scale", .type = SIM_OPT_NUMBER, .value = "X",
     .range = {"", "", 0.0, 100.0, 0u}, .help = "plant viscous friction times X (0: none)"},
    {.id = OPT_J_EXTRA, .name = "--j-extra", .type = SIM_OPT_NUMBER, .value = "KGM2",
     .range = {"", "kg m^2", 0.0, 1.0, 0u}, /* 10^5 x the Hurst's rotor */
     .help = "load inertia added to the rotor's"},
    {.id = OPT_COULOMB, .name = "--coulomb", .type = SIM_OPT_NUMBER, .value = "NM",
     .range = {"", "N m", 0.0, 10.0, 0u}, /* as the scenarios' loads */
     .help = "plant dry friction (default: the profile's)"},
    {.id = OPT_OFFSETS, .name = "--offsets", .type = SIM_OPT_TEXT, .value = "A,B",
     .help = "current amplifiers' offsets, ADC codes (default: the board's)"},
    {.id = OPT_INVERTER, .name = "--inverter", .type = SIM_OPT_WORD, .value = "M",
     .words = sim_inverter_models, .help = "inverter model (default averaged; docs/sim.md)"},
    {.id = OPT_DT_SHAPE, .name = "--deadtime-shape", .type = SIM_OPT_WORD, .value = "S",
     .words = sim_inverter_shapes, .help = "averaged model: dead-time shape (default linear)"},
    {.id = OPT_DT_BAND, .name = "--dt-band", .type = SIM_OPT_NUMBER, .value = "A",
     .range = {"", "A", 0.0, 10.0, 0u},
     .help = "averaged model: dead-time band (default 0: automatic, Vbus/(12 L fpwm))"},
    {.id = OPT_R_ON, .name = "--r-on", .type = SIM_OPT_NUMBER, .value = "OHM",
     .range = {"", "ohm", 0.0, 10.0, 0u}, .help = "switching model: switch on-resistance"},
    {.id = OPT_V_DIODE, .name = "--v-diode", .type = SIM_OPT_NUMBER, .value = "V",
     .range = {"", "V", 0.0, 10.0, 0u}, .help = "switching model: diode forward drop"},
    {.id = OPT_NO_PROGRESS, .name = "--no-progress", .type = SIM_OPT_FLAG,
     .help = "no progress line on stderr"},
#ifdef SIM_HAVE_PTY
    {.id = OPT_PTY, .name = "--pty", .type = SIM_OPT_FLAG,
     .help = "no scenario: serve X2Cscope on a pty (docs/x2cscope.md)"},
    {.id = OPT_TCP, .name = "--tcp", .type = SIM_OPT_NUMBER, .value = "PORT",
     .range = {"", "", 1024.0, 65535.0, SIM_RANGE_INTEGER},
     .help = "with --pty: also serve X2Cscope on 127.0.0.1:PORT (X2Cscope's is 12666)"},
    {.id = OPT_REALTIME, .name = "--realtime", .type = SIM_OPT_NUMBER, .value = "X",
     .range = {"", "x real time", 0.0, 1000.0, 0u}, /* and 0 or at least REALTIME_MIN */
     .help = "with --pty: X times real time (default 1; 0: free-running)"},
    {.id = OPT_BAUD, .name = "--baud", .type = SIM_OPT_NUMBER, .value = "N",
     .range = {"", "Bd", 1200.0, 1000000.0, SIM_RANGE_INTEGER},
     .help = "with --pty: emulated UART rate (default 115200)"},
    {.id = OPT_DURATION, .name = "--duration", .type = SIM_OPT_NUMBER, .value = "S",
     .range = {"", "s", 0.0, 3600.0, 0u},
     .help = "with --pty: stop after S simulated seconds (0: until SIGINT or SIGTERM)"},
    {.id = OPT_TRUTH, .name = "--truth", .type = SIM_OPT_TEXT, .value = "FILE",
     .help = "with --pty: the true speed at every dataset the scope stores (CSV)"},
#endif
};
/* clang-format on */

#define N_OPTS (sizeof(OPTS) / sizeof(OPTS[0]))

/* Whether two paths name one existing file. */
static bool same_file(const char *x, const char *y)
{
    struct stat a, b;
    return stat(x, &a) == 0 && stat(y, &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

/* The program's name in its refusals (sim_refuse). */
#define PROG "sim"

/* An output, opened without emptying it: a refused run leaves a file as it
 * was, and removes one it created. */
typedef struct {
    const char *path;
    const char *flag;
    FILE *f;
    bool created;
} sim_output_t;

static int output_try(sim_output_t *o)
{
    struct stat st;
    o->created = stat(o->path, &st) != 0;
    o->f = fopen(o->path, "ab");
    return (o->f == NULL) ? -1 : 0;
}

static void output_drop(sim_output_t *o)
{
    if (o->f != NULL) {
        (void)fclose(o->f);
        o->f = NULL;
        if (o->created) {
            (void)remove(o->path);
        }
    }
}

/* The trace (--csv) and the record (--record), each when asked for: both
 * are opened before either is emptied, so that one that cannot be written
 * refuses the run with the other untouched; then the trace's header and
 * the record's are written. 0, or 2 after the one line. */
static int open_outputs(simcore_t *s, const char *csv_path, const char *rec_path)
{
    char why[320], pq[256]; /* pq: a path, quoted */
    sim_output_t out[2] = {{csv_path, "--csv", NULL, false}, {rec_path, "--record", NULL, false}};
    size_t k;
    for (k = 0; k < 2U; k++) {
        if (out[k].path != NULL && output_try(&out[k]) != 0) {
            sim_parse_msg(why, sizeof(why), "cannot write '%s'",
                          sim_parse_quote(out[k].path, pq, sizeof(pq)));
            output_drop(&out[0]);
            return sim_refuse(PROG, out[k].flag, why);
        }
    }
    /* both writable: emptied (freopen truncates), then their headers */
    for (k = 0; k < 2U; k++) {
        if (out[k].f != NULL) {
            out[k].f = freopen(out[k].path, (k == 0U) ? "w" : "wb", out[k].f);
        }
    }
    s->cfg.csv = out[0].f;
    s->cfg.record = out[1].f;
    if ((csv_path != NULL && s->cfg.csv == NULL) || (rec_path != NULL && s->cfg.record == NULL)) {
        return sim_refuse(PROG, (csv_path != NULL && s->cfg.csv == NULL) ? "--csv" : "--record",
                          "cannot reopen the file it just opened");
    }
    if (s->cfg.csv != NULL) {
        sim_trace_header(s->cfg.csv);
    }
    if (s->cfg.record != NULL && sim_record_header(s->cfg.record, (uint16_t)MC_SLOW_STEP_PERIODS,
                                                   (uint32_t)PWM_FREQUENCY_HZ) != 0) {
        return sim_refuse(PROG, "--record", "write failed (disk full?)");
    }
    return 0;
}

static void usage(FILE *f)
{
    fprintf(f, "usage: sim [options] <scenario.txt>\n"
               "       sim --pty [options]   the X2Cscope target on a pseudo-terminal "
               "(docs/x2cscope.md)\n");
    sim_opt_usage(f, OPTS, N_OPTS);
    fprintf(f, "profiles: %s\n", sim_profiles_list());
}

/* "A,B": two offsets in ADC codes, each strictly parsed. */
static int parse_offsets(const char *v, double *a, double *b)
{
    static const sim_range_t ra = {"A", "codes", -OFFSET_MAX_CODES, OFFSET_MAX_CODES, 0u};
    char buf[64], why[160];
    const char *comma = strchr(v, ',');
    size_t n = (comma != NULL) ? (size_t)(comma - v) : 0u;
    if (comma == NULL || n >= sizeof(buf) || strchr(comma + 1, ',') != NULL) {
        char q[48];
        sim_parse_msg(why, sizeof(why), "'%s' is not A,B (two numbers, ADC codes)",
                      sim_parse_quote(v, q, sizeof(q)));
        return sim_refuse(PROG, "--offsets", why);
    }
    memcpy(buf, v, n);
    buf[n] = '\0';
    if (sim_parse_number(buf, &ra, a, why, sizeof(why)) != 0 ||
        sim_parse_number(comma + 1, &ra, b, why, sizeof(why)) != 0) {
        return sim_refuse(PROG, "--offsets", why);
    }
    return 0;
}

/*
 * Options that are each in range can still make the plant stiffer than its
 * fixed-step RK4 can follow (R x100 with L x0.05; J x1e-6): the state then
 * grows without bound to inf and NaN within a few periods. A mode whose rate
 * lambda (1/s) times the step h stays below RK4_STABLE is followed (RK4's
 * stability limit is 2.785 on the real axis and 2.83 on the imaginary one).
 * Modes checked: electrical R/L; electromechanical sqrt(1.5 p^2 psi^2 /
 * (J L)) (the current and the speed exchanging energy through the
 * back-EMF); viscous B/J. The step is the rig's longest: with the sample
 * inside the period (sim_rig.h) the substeps are split across it, at most
 * max(sample_at, 1 - sample_at) Ts over floor(substeps / 2) steps.
 */
#define RK4_STABLE 2.5

static int check_stiffness(const simcore_t *s)
{
    const sim_motor_params_t *m = &s->rig.plant.m;
    double l = (m->ld_h < m->lq_h) ? m->ld_h : m->lq_h;
    double p = (double)m->pole_pairs;
    double part = (s->rig.sample_at > 0.0) ? fmax(s->rig.sample_at, 1.0 - s->rig.sample_at) : 1.0;
    int n = (s->rig.sample_at > 0.0) ? s->rig.substeps / 2 : s->rig.substeps;
    double h = s->rig.ts * part / (double)((n > 0) ? n : 1);
    double lam[3];
    static const char *const what[3] = {"R/L", "electromechanical sqrt(1.5 p^2 psi^2 / (J L))",
                                        "viscous B/J"};
    char why[240];
    int k;
    lam[0] = m->rs_ohm / l;
    lam[1] = sqrt(1.5 * p * p * m->psi_vs * m->psi_vs / (m->j_kgm2 * l));
    lam[2] = m->b_nms / m->j_kgm2;
    for (k = 0; k < 3; k++) {
        if (!(lam[k] * h <= RK4_STABLE)) { /* also catches a NaN */
            sim_parse_msg(why, sizeof(why),
                          "the plant's %s mode, %.3g 1/s, times the RK4 step, %.3g us, is %.3g > "
                          "%.2g: it would diverge; raise --substeps (<= 64) or bring the scales "
                          "nearer 1",
                          what[k], lam[k], h * 1e6, lam[k] * h, RK4_STABLE);
            return sim_refuse(
                PROG, "--rs-scale/--l-scale/--ke-scale/--j-scale/--b-scale/--substeps", why);
        }
    }
    return 0;
}

static const char *basename_noext(const char *path, char *buf, size_t len)
{
    const char *b = strrchr(path, '/');
    char *dot;
    snprintf(buf, len, "%s", (b != NULL) ? b + 1 : path);
    dot = strrchr(buf, '.');
    if (dot != NULL) {
        *dot = '\0';
    }
    return buf;
}

int main(int argc, char **argv)
{
    simcore_cfg_t cfg;
    static simcore_t s;
    static sim_scenario_t sc;
    const char *scen_path = NULL, *csv_path = NULL, *rec_path = NULL;
    const char *pty_only = NULL;                 /* a --pty option given, for the check below */
    char err[512], name[128], why[320], pq[256]; /* pq: a path, quoted */
    int i, rc;
    clock_t c0;
    double wall;
#ifdef SIM_HAVE_PTY
    sim_pty_cfg_t pty;
    int use_pty = 0;
    sim_pty_cfg_default(&pty);
#endif

    simcore_cfg_default(&cfg);
    cfg.progress = true;
    for (i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v;
        const sim_opt_t *o;
        double x;
        if (strcmp(a, "-h") == 0) {
            usage(stdout);
            return 0;
        }
        if (a[0] != '-') {
            if (scen_path != NULL) {
                sim_parse_msg(why, sizeof(why), "a second one, '%s' (only one runs)",
                              sim_parse_quote(a, pq, sizeof(pq)));
                return sim_refuse(PROG, "scenario", why);
            }
            scen_path = a;
            continue;
        }
        o = sim_opt_read(PROG, OPTS, N_OPTS, argc, argv, &i, &v, &x);
        if (o == NULL) {
            return 2;
        }
        switch (o->id) {
            case OPT_HELP:
                usage(stdout);
                return 0;
            case OPT_NO_PROGRESS:
                cfg.progress = false;
                break;
            case OPT_BUS_MODEL:
                cfg.bus_model = true;
                break;
            case OPT_MOTOR:
                cfg.motor = v;
                break;
            case OPT_BOARD:
                cfg.board = v;
                break;
            case OPT_CSV:
                csv_path = v;
                break;
            case OPT_RECORD:
                rec_path = v;
                break;
            case OPT_DECIM:
                cfg.csv_decim = (int)x;
                break;
            case OPT_SUBSTEPS:
                cfg.substeps = (int)x;
                break;
            case OPT_THETA0:
                cfg.theta0_rad = x * M_PI / 180.0;
                break;
            case OPT_RPM0:
                cfg.rpm0 = x;
                break;
            case OPT_DEADTIME:
                cfg.deadtime_s = x * 1e-6;
                break;
            case OPT_NOISE:
                cfg.noise_codes = x;
                break;
            case OPT_VBUS:
                cfg.vbus_v = x;
                break;
            case OPT_SEED:
                cfg.seed = (uint32_t)x;
                break;
            case OPT_RS_SCALE:
                cfg.rs_scale = x;
                break;
            case OPT_L_SCALE:
                cfg.l_scale = x;
                break;
            case OPT_KE_SCALE:
                cfg.ke_scale = x;
                break;
            case OPT_J_SCALE:
                cfg.j_scale = x;
                break;
            case OPT_B_SCALE:
                cfg.b_scale = x;
                break;
            case OPT_J_EXTRA:
                cfg.j_extra_kgm2 = x;
                break;
            case OPT_COULOMB:
                cfg.coulomb_nm = x;
                break;
            case OPT_OFFSETS:
                if (parse_offsets(v, &cfg.offset_a_codes, &cfg.offset_b_codes) != 0) {
                    return 2;
                }
                cfg.offsets_set = true;
                break;
            case OPT_INVERTER:
                cfg.inv.model = (int)x;
                break;
            case OPT_DT_SHAPE:
                cfg.inv.dt_shape = (int)x;
                break;
            case OPT_DT_BAND:
                cfg.inv.i_band_a = x;
                break;
            case OPT_R_ON:
                cfg.inv.r_on_ohm = x;
                break;
            case OPT_V_DIODE:
                cfg.inv.v_diode_v = x;
                break;
#ifdef SIM_HAVE_PTY
            case OPT_PTY:
                use_pty = 1;
                break;
            case OPT_REALTIME:
                if (x > 0.0 && x < REALTIME_MIN) {
                    char q[48];
                    sim_parse_msg(why, sizeof(why),
                                  "'%s' is outside 0.01..1000 x real time (or 0: free-running)",
                                  sim_parse_quote(v, q, sizeof(q)));
                    return sim_refuse(PROG, a, why);
                }
                pty.speed = x;
                pty_only = a;
                break;
            case OPT_TCP:
                pty.tcp_port = (int)x;
                pty_only = a;
                break;
            case OPT_BAUD:
                pty.baud = (long)x;
                pty_only = a;
                break;
            case OPT_DURATION:
                pty.duration_s = x;
                pty_only = a;
                break;
            case OPT_TRUTH:
                pty.truth_path = v;
                pty_only = a;
                break;
#endif
            default:
                break;
        }
    }
#ifdef SIM_HAVE_PTY
    if (use_pty) {
        cfg.progress = false;
        if (scen_path != NULL) {
            return sim_refuse(PROG, "--pty", "runs no scenario: drop the scenario file or --pty");
        }
        if (csv_path != NULL) {
            return sim_refuse(PROG, "--csv",
                              "only with a scenario (with --pty, --truth writes the trace)");
        }
        if (rec_path != NULL) {
            return sim_refuse(PROG, "--record", "only with a scenario");
        }
        if (simcore_init(&s, &cfg) != 0 || check_stiffness(&s) != 0) {
            return 2;
        }
        return sim_pty_run(&s, &pty);
    }
#endif
    if (pty_only != NULL) {
        return sim_refuse(PROG, pty_only, "only with --pty");
    }
    if (scen_path == NULL) {
        return sim_refuse(PROG, "scenario", "no scenario file given (sim --help)");
    }
    if (sim_scenario_load(scen_path, &sc, err, sizeof(err)) != 0) {
        fprintf(stderr, "sim: %s\n", err);
        return 2;
    }
    basename_noext(scen_path, name, sizeof(name));
    /* The trace is opened only once every input is known good, so a refused
     * run never truncates an earlier trace. */
    if (simcore_init(&s, &cfg) != 0 || check_stiffness(&s) != 0) {
        return 2;
    }
    if (csv_path != NULL && same_file(csv_path, scen_path)) {
        sim_parse_msg(why, sizeof(why), "'%s' is the scenario file",
                      sim_parse_quote(csv_path, pq, sizeof(pq)));
        return sim_refuse(PROG, "--csv", why);
    }
    if (rec_path != NULL &&
        (same_file(rec_path, scen_path) || (csv_path != NULL && same_file(rec_path, csv_path)))) {
        sim_parse_msg(why, sizeof(why), "'%s' is the scenario file or the trace",
                      sim_parse_quote(rec_path, pq, sizeof(pq)));
        return sim_refuse(PROG, "--record", why);
    }
    if (open_outputs(&s, csv_path, rec_path) != 0) {
        return 2;
    }
    c0 = clock();
    rc = simcore_run_scenario(&s, &sc, name);
    wall = (double)(clock() - c0) / CLOCKS_PER_SEC;
    if (s.cfg.csv != NULL && fclose(s.cfg.csv) != 0) {
        return sim_refuse(PROG, "--csv", "write failed (disk full?)");
    }
    if (s.cfg.record != NULL && (fclose(s.cfg.record) != 0 || s.record_failed)) {
        return sim_refuse(PROG, "--record", "write failed (disk full?)");
    }
    simcore_print_summary(&s, stdout, name);
    printf("   run: %.2f s simulated in %.2f s CPU (%.0f x real time)%s%s\n", s.rig.t, wall,
           (wall > 0.0) ? s.rig.t / wall : 0.0, (csv_path != NULL) ? ", trace " : "",
           (csv_path != NULL) ? csv_path : "");
    if (rc != 0) {
        /* the summary above covers the run up to the stop; exit 1: the run, not its input */
        simcore_diverged_msg(&s, why, sizeof(why));
        fflush(stdout);
        fprintf(stderr, "sim: %s: %s\n", name, why);
        return 1;
    }
    return 0;
}
