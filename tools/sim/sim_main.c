/* sim_main.c - runs a scenario file against the firmware core and the simulated motor. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "sim_core.h"
#include "sim_parse.h"
#ifdef SIM_HAVE_PTY
#include "sim_pty.h"
#endif

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/*
 * The numeric options and their ranges (docs/sim.md). Every value is parsed
 * strictly (sim_parse.h) and refused in one line on stderr, exit status 2,
 * when it is not a plain decimal number inside its range. The ranges are
 * physical or sane, and they bound the work: substeps and the pty's pace
 * are capped so that no value makes a run take unbounded time (a scenario's
 * length is bounded by its own parser, 3,600 s).
 */
typedef struct {
    const char *opt;
    const char *unit;
    double lo, hi;
    unsigned flags; /* SIM_RANGE_INTEGER, SIM_RANGE_LO_OPEN */
} num_opt_t;

static const num_opt_t NUM_OPTS[] = {
    {"--decim", "periods", 1.0, 1e6, SIM_RANGE_INTEGER},  /* one CSV row per N periods */
    {"--substeps", "", 1.0, 64.0, SIM_RANGE_INTEGER},     /* RK4 steps per 50 us period */
    {"--theta0", "deg", -360.0, 360.0, 0u},               /* electrical angle */
    {"--rpm0", "rpm", -100000.0, 100000.0, 0u},           /* mechanical, either direction */
    {"--deadtime", "us", 0.0, 20.0, 0u},                  /* 40 % of a 50 us period */
    {"--noise", "codes", 0.0, 100.0, 0u},                 /* sigma, a tenth of the 10-bit range */
    {"--vbus", "V", 0.0, 1000.0, 0u},                     /* three times the MCHV's 320 V */
    {"--seed", "", 0.0, 4294967295.0, SIM_RANGE_INTEGER}, /* uint32_t */
    {"--rs-scale", "", 0.0, 100.0, SIM_RANGE_LO_OPEN},
    {"--l-scale", "", 0.0, 100.0, SIM_RANGE_LO_OPEN},
    {"--ke-scale", "", 0.0, 100.0, SIM_RANGE_LO_OPEN},
    {"--j-scale", "", 0.0, 100.0, SIM_RANGE_LO_OPEN},
    {"--b-scale", "", 0.0, 100.0, 0u},     /* 0: no viscous friction */
    {"--j-extra", "kg m^2", 0.0, 1.0, 0u}, /* 10^5 x the Hurst's rotor */
    {"--coulomb", "N m", 0.0, 10.0, 0u},   /* as the scenario's loads */
    {"--dt-band", "A", 0.0, 10.0, 0u},     /* 0: automatic, Vbus/(12 L fpwm) */
    {"--r-on", "ohm", 0.0, 10.0, 0u},
    {"--v-diode", "V", 0.0, 10.0, 0u},
#ifdef SIM_HAVE_PTY
    {"--realtime", "x real time", 0.0, 1000.0, 0u}, /* 0: free-running; else >= 0.01 (below) */
    {"--baud", "Bd", 1200.0, 1000000.0, SIM_RANGE_INTEGER},
    {"--duration", "s", 0.0, 3600.0, 0u}, /* 0: until SIGINT/SIGTERM */
#endif
};

#define N_NUM_OPTS (sizeof(NUM_OPTS) / sizeof(NUM_OPTS[0]))

/* The slowest pace --realtime takes other than 0: at 0.01 x real time one
 * simulated second is 100 s of wall time. */
#define REALTIME_MIN 0.01
/* An ADC offset of half the 10-bit range puts the amplifier on a rail. */
#define OFFSET_MAX_CODES 512.0

static void usage(FILE *f)
{
    fprintf(
        f,
        "usage: sim [options] <scenario.txt>\n"
        "       sim --pty [options]   the live data monitor on a pseudo-terminal "
        "(docs/monitor.md)\n"
        "  --motor NAME      simulated motor (default hurst; %s)\n"
        "  --board NAME      simulated board (default mclv)\n"
        "  --csv FILE        write the trace (default: none)\n"
        "  --decim N         one CSV row every N PWM periods (default 10; 1..1000000)\n"
        "  --substeps N      RK4 steps per PWM period (default 4; 1..64)\n"
        "  --theta0 DEG      initial electrical rotor angle (default 0; -360..360)\n"
        "  --rpm0 RPM        initial rotor speed (default 0: at rest; -100000..100000)\n"
        "  --deadtime US     inverter dead time (default: the board's, 2 us; 0..20)\n"
        "  --noise LSB       ADC noise sigma in codes (default: the board's, 1; 0..100)\n"
        "  --vbus V          DC bus (default: the board's; 0..1000)\n"
        "  --seed N          noise seed (0..4294967295)\n"
        "  --rs-scale X --l-scale X --ke-scale X --j-scale X --b-scale X\n"
        "                    plant parameters times X (mismatch with UserParms.h; 0 < X <= 100,\n"
        "                    --b-scale 0..100)\n"
        "  --j-extra KGM2    load inertia added to the rotor's (0..1)\n"
        "  --coulomb NM      plant dry friction (default: the profile's; 0..10)\n"
        "  --offsets A,B     current amplifier offsets, ADC codes (default: the board's; "
        "-512..512)\n"
        "  --inverter M      averaged (default) or switching (docs/sim.md)\n"
        "  --deadtime-shape S  averaged model: linear (default), hard or ripple\n"
        "  --dt-band A       averaged model: dead-time band, A (default 0: automatic; 0..10)\n"
        "  --r-on OHM        switching model: switch on-resistance (default 0; 0..10)\n"
        "  --v-diode V       switching model: diode forward drop (default 0; 0..10)\n"
        "  --no-progress     no progress line on stderr\n"
        "  --pty             no scenario: serve the monitor protocol on a pty\n"
        "  --realtime X      with --pty: X times real time (default 1; 0 = free-running, "
        "else 0.01..1000)\n"
        "  --baud N          with --pty: emulated UART rate (default 38400; 1200..1000000)\n"
        "  --duration S      with --pty: stop after S simulated seconds (0..3600; 0 = until "
        "killed)\n"
        "  --truth FILE      with --pty: true speed at every recorded sample (CSV)\n",
        sim_profiles_list());
}

/* One line on stderr, as every refusal: "sim: <field>: <why>". */
static int refuse(const char *field, const char *why)
{
    fprintf(stderr, "sim: %s: %s\n", field, why);
    return 2;
}

static const num_opt_t *num_opt(const char *a)
{
    size_t k;
    for (k = 0; k < N_NUM_OPTS; k++) {
        if (strcmp(NUM_OPTS[k].opt, a) == 0) {
            return &NUM_OPTS[k];
        }
    }
    return NULL;
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
        return refuse("--offsets", why);
    }
    memcpy(buf, v, n);
    buf[n] = '\0';
    if (sim_parse_number(buf, &ra, a, why, sizeof(why)) != 0 ||
        sim_parse_number(comma + 1, &ra, b, why, sizeof(why)) != 0) {
        return refuse("--offsets", why);
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
            return refuse("--rs-scale/--l-scale/--ke-scale/--j-scale/--b-scale/--substeps", why);
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
    const char *scen_path = NULL, *csv_path = NULL;
    const char *pty_only = NULL; /* a --pty option given, for the check below */
    char err[512], name[128], q[48], why[320], pq[256]; /* pq: a path, quoted */
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
        const char *v = (i + 1 < argc) ? argv[i + 1] : NULL;
        const num_opt_t *no;
        double x = 0.0;
        if (strcmp(a, "--no-progress") == 0) {
            cfg.progress = false;
            continue;
        }
#ifdef SIM_HAVE_PTY
        if (strcmp(a, "--pty") == 0) {
            use_pty = 1;
            continue;
        }
#endif
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            usage(stdout);
            return 0;
        }
        if (a[0] != '-') {
            if (scen_path != NULL) {
                sim_parse_msg(why, sizeof(why), "a second one, '%s' (only one runs)",
                              sim_parse_quote(a, pq, sizeof(pq)));
                return refuse("scenario", why);
            }
            scen_path = a;
            continue;
        }
        if (strncmp(a, "--", 2) != 0 ||
            (num_opt(a) == NULL && strcmp(a, "--motor") != 0 && strcmp(a, "--board") != 0 &&
             strcmp(a, "--csv") != 0 && strcmp(a, "--offsets") != 0 &&
             strcmp(a, "--inverter") != 0 && strcmp(a, "--deadtime-shape") != 0
#ifdef SIM_HAVE_PTY
             && strcmp(a, "--truth") != 0
#endif
             )) {
            return refuse(sim_parse_quote(a, q, sizeof(q)),
                          "unknown option (sim --help lists them)");
        }
        if (v == NULL) {
            return refuse(a, "needs a value");
        }
        i++;
        no = num_opt(a);
        if (no != NULL) {
            sim_range_t r;
            r.name = no->opt;
            r.unit = no->unit;
            r.lo = no->lo;
            r.hi = no->hi;
            r.flags = no->flags;
            if (sim_parse_number(v, &r, &x, why, sizeof(why)) != 0) {
                return refuse(a, why);
            }
        }
        if (strcmp(a, "--motor") == 0 || strcmp(a, "--board") == 0) {
            if (sim_parse_name(v, why, sizeof(why)) != 0) {
                return refuse(a, why);
            }
            if (a[2] == 'm') {
                cfg.motor = v;
            } else {
                cfg.board = v;
            }
        } else if (strcmp(a, "--csv") == 0) {
            csv_path = v;
        } else if (strcmp(a, "--decim") == 0) {
            cfg.csv_decim = (int)x;
        } else if (strcmp(a, "--substeps") == 0) {
            cfg.substeps = (int)x;
        } else if (strcmp(a, "--theta0") == 0) {
            cfg.theta0_rad = x * M_PI / 180.0;
        } else if (strcmp(a, "--rpm0") == 0) {
            cfg.rpm0 = x;
        } else if (strcmp(a, "--deadtime") == 0) {
            cfg.deadtime_s = x * 1e-6;
        } else if (strcmp(a, "--noise") == 0) {
            cfg.noise_codes = x;
        } else if (strcmp(a, "--vbus") == 0) {
            cfg.vbus_v = x;
        } else if (strcmp(a, "--seed") == 0) {
            cfg.seed = (uint32_t)x;
        } else if (strcmp(a, "--rs-scale") == 0) {
            cfg.rs_scale = x;
        } else if (strcmp(a, "--l-scale") == 0) {
            cfg.l_scale = x;
        } else if (strcmp(a, "--ke-scale") == 0) {
            cfg.ke_scale = x;
        } else if (strcmp(a, "--j-scale") == 0) {
            cfg.j_scale = x;
        } else if (strcmp(a, "--b-scale") == 0) {
            cfg.b_scale = x;
        } else if (strcmp(a, "--j-extra") == 0) {
            cfg.j_extra_kgm2 = x;
        } else if (strcmp(a, "--coulomb") == 0) {
            cfg.coulomb_nm = x;
        } else if (strcmp(a, "--offsets") == 0) {
            if (parse_offsets(v, &cfg.offset_a_codes, &cfg.offset_b_codes) != 0) {
                return 2;
            }
            cfg.offsets_set = true;
        } else if (strcmp(a, "--inverter") == 0) {
            if (sim_inverter_model_parse(v, &cfg.inv.model) != 0) {
                sim_parse_msg(why, sizeof(why), "'%s' is not averaged or switching",
                              sim_parse_quote(v, q, sizeof(q)));
                return refuse(a, why);
            }
        } else if (strcmp(a, "--deadtime-shape") == 0) {
            if (sim_inverter_shape_parse(v, &cfg.inv.dt_shape) != 0) {
                sim_parse_msg(why, sizeof(why), "'%s' is not linear, hard or ripple",
                              sim_parse_quote(v, q, sizeof(q)));
                return refuse(a, why);
            }
        } else if (strcmp(a, "--dt-band") == 0) {
            cfg.inv.i_band_a = x;
        } else if (strcmp(a, "--r-on") == 0) {
            cfg.inv.r_on_ohm = x;
        } else if (strcmp(a, "--v-diode") == 0) {
            cfg.inv.v_diode_v = x;
#ifdef SIM_HAVE_PTY
        } else if (strcmp(a, "--realtime") == 0) {
            if (x > 0.0 && x < REALTIME_MIN) {
                sim_parse_msg(why, sizeof(why),
                              "'%s' is outside 0.01..1000 x real time (or 0: free-running)",
                              sim_parse_quote(v, q, sizeof(q)));
                return refuse(a, why);
            }
            pty.speed = x;
            pty_only = a;
        } else if (strcmp(a, "--baud") == 0) {
            pty.baud = (long)x;
            pty_only = a;
        } else if (strcmp(a, "--duration") == 0) {
            pty.duration_s = x;
            pty_only = a;
        } else if (strcmp(a, "--truth") == 0) {
            pty.truth_path = v;
            pty_only = a;
#endif
        }
    }
#ifdef SIM_HAVE_PTY
    if (use_pty) {
        cfg.progress = false;
        if (scen_path != NULL) {
            return refuse("--pty", "runs no scenario: drop the scenario file or --pty");
        }
        if (csv_path != NULL) {
            return refuse("--csv", "only with a scenario (with --pty, --truth writes the trace)");
        }
        if (simcore_init(&s, &cfg) != 0 || check_stiffness(&s) != 0) {
            return 2;
        }
        return sim_pty_run(&s, &pty);
    }
#endif
    if (pty_only != NULL) {
        return refuse(pty_only, "only with --pty");
    }
    if (scen_path == NULL) {
        return refuse("scenario", "no scenario file given (sim --help)");
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
    if (csv_path != NULL) {
        struct stat a, b;
        if (stat(csv_path, &a) == 0 && stat(scen_path, &b) == 0 && a.st_dev == b.st_dev &&
            a.st_ino == b.st_ino) {
            sim_parse_msg(why, sizeof(why), "'%s' is the scenario file",
                          sim_parse_quote(csv_path, pq, sizeof(pq)));
            return refuse("--csv", why);
        }
        s.cfg.csv = fopen(csv_path, "w");
        if (s.cfg.csv == NULL) {
            sim_parse_msg(why, sizeof(why), "cannot write '%s'",
                          sim_parse_quote(csv_path, pq, sizeof(pq)));
            return refuse("--csv", why);
        }
        simcore_csv_header(s.cfg.csv);
    }
    c0 = clock();
    rc = simcore_run_scenario(&s, &sc, name);
    wall = (double)(clock() - c0) / CLOCKS_PER_SEC;
    if (s.cfg.csv != NULL && fclose(s.cfg.csv) != 0) {
        return refuse("--csv", "write failed (disk full?)");
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
