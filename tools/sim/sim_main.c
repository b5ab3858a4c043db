/* sim_main.c - runs a scenario file against the firmware core and the simulated motor. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "sim_core.h"
#ifdef SIM_HAVE_PTY
#include "sim_pty.h"
#endif

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static void usage(void)
{
    fprintf(stderr,
            "usage: sim [options] <scenario.txt>\n"
            "       sim --pty [options]   the live data monitor on a pseudo-terminal "
            "(docs/monitor.md)\n"
            "  --motor NAME      simulated motor (default hurst; %s)\n"
            "  --board NAME      simulated board (default mclv)\n"
            "  --csv FILE        write the trace (default: none)\n"
            "  --decim N         one CSV row every N PWM periods (default 10)\n"
            "  --substeps N      RK4 steps per PWM period (default 4)\n"
            "  --theta0 DEG      initial electrical rotor angle (default 0)\n"
            "  --rpm0 RPM        initial rotor speed (default 0: at rest)\n"
            "  --deadtime US     inverter dead time (default: the board's, 2 us)\n"
            "  --noise LSB       ADC noise sigma in codes (default: the board's, 1)\n"
            "  --vbus V          DC bus (default: the board's)\n"
            "  --seed N          noise seed\n"
            "  --rs-scale X --l-scale X --ke-scale X --j-scale X --b-scale X\n"
            "                    plant parameters times X (mismatch with UserParms.h)\n"
            "  --j-extra KGM2    load inertia added to the rotor's\n"
            "  --coulomb NM      plant dry friction (default: the profile's)\n"
            "  --offsets A,B     current amplifier offsets, ADC codes (default: the board's)\n"
            "  --inverter M      averaged (default) or switching (docs/sim.md)\n"
            "  --deadtime-shape S  averaged model: linear (default), hard or ripple\n"
            "  --dt-band A       averaged model: dead-time band, A (default: automatic)\n"
            "  --r-on OHM        switching model: switch on-resistance (default 0)\n"
            "  --v-diode V       switching model: diode forward drop (default 0)\n"
            "  --no-progress     no progress line on stderr\n"
            "  --pty             no scenario: serve the monitor protocol on a pty\n"
            "  --realtime X      with --pty: X times real time (default 1; 0 = free-running)\n"
            "  --baud N          with --pty: emulated UART rate (default 38400)\n"
            "  --duration S      with --pty: stop after S simulated seconds\n"
            "  --truth FILE      with --pty: true speed at every recorded sample (CSV)\n",
            sim_profiles_list());
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
    char err[200], name[128];
    int i;
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
            usage();
            return 0;
        }
        if (a[0] != '-') {
            scen_path = a;
            continue;
        }
        if (v == NULL) {
            usage();
            return 2;
        }
        i++;
        if (strcmp(a, "--motor") == 0) {
            cfg.motor = v;
        } else if (strcmp(a, "--board") == 0) {
            cfg.board = v;
        } else if (strcmp(a, "--csv") == 0) {
            csv_path = v;
        } else if (strcmp(a, "--decim") == 0) {
            cfg.csv_decim = atoi(v);
        } else if (strcmp(a, "--substeps") == 0) {
            cfg.substeps = atoi(v);
        } else if (strcmp(a, "--theta0") == 0) {
            cfg.theta0_rad = atof(v) * M_PI / 180.0;
        } else if (strcmp(a, "--rpm0") == 0) {
            cfg.rpm0 = atof(v);
        } else if (strcmp(a, "--deadtime") == 0) {
            cfg.deadtime_s = atof(v) * 1e-6;
        } else if (strcmp(a, "--noise") == 0) {
            cfg.noise_codes = atof(v);
        } else if (strcmp(a, "--vbus") == 0) {
            cfg.vbus_v = atof(v);
        } else if (strcmp(a, "--seed") == 0) {
            cfg.seed = (uint32_t)strtoul(v, NULL, 0);
        } else if (strcmp(a, "--rs-scale") == 0) {
            cfg.rs_scale = atof(v);
        } else if (strcmp(a, "--l-scale") == 0) {
            cfg.l_scale = atof(v);
        } else if (strcmp(a, "--ke-scale") == 0) {
            cfg.ke_scale = atof(v);
        } else if (strcmp(a, "--j-scale") == 0) {
            cfg.j_scale = atof(v);
        } else if (strcmp(a, "--b-scale") == 0) {
            cfg.b_scale = atof(v);
        } else if (strcmp(a, "--j-extra") == 0) {
            cfg.j_extra_kgm2 = atof(v);
        } else if (strcmp(a, "--coulomb") == 0) {
            cfg.coulomb_nm = atof(v);
        } else if (strcmp(a, "--offsets") == 0) {
            if (sscanf(v, "%lf,%lf", &cfg.offset_a_codes, &cfg.offset_b_codes) != 2) {
                fprintf(stderr, "sim: --offsets wants A,B in ADC codes, got '%s'\n", v);
                return 2;
            }
            cfg.offsets_set = true;
        } else if (strcmp(a, "--inverter") == 0) {
            if (sim_inverter_model_parse(v, &cfg.inv.model) != 0) {
                fprintf(stderr, "sim: --inverter is averaged or switching, got '%s'\n", v);
                return 2;
            }
        } else if (strcmp(a, "--deadtime-shape") == 0) {
            if (sim_inverter_shape_parse(v, &cfg.inv.dt_shape) != 0) {
                fprintf(stderr, "sim: --deadtime-shape is linear, hard or ripple, got '%s'\n", v);
                return 2;
            }
        } else if (strcmp(a, "--dt-band") == 0) {
            cfg.inv.i_band_a = atof(v);
        } else if (strcmp(a, "--r-on") == 0) {
            cfg.inv.r_on_ohm = atof(v);
        } else if (strcmp(a, "--v-diode") == 0) {
            cfg.inv.v_diode_v = atof(v);
#ifdef SIM_HAVE_PTY
        } else if (strcmp(a, "--realtime") == 0) {
            pty.speed = atof(v);
        } else if (strcmp(a, "--baud") == 0) {
            pty.baud = atol(v);
        } else if (strcmp(a, "--duration") == 0) {
            pty.duration_s = atof(v);
        } else if (strcmp(a, "--truth") == 0) {
            pty.truth_path = v;
#endif
        } else {
            usage();
            return 2;
        }
    }
#ifdef SIM_HAVE_PTY
    if (use_pty) {
        cfg.progress = false;
        if (pty.baud <= 0L) {
            usage();
            return 2;
        }
        if (simcore_init(&s, &cfg) != 0) {
            return 2;
        }
        return sim_pty_run(&s, &pty);
    }
#endif
    if (scen_path == NULL) {
        usage();
        return 2;
    }
    if (sim_scenario_load(scen_path, &sc, err, sizeof(err)) != 0) {
        fprintf(stderr, "sim: %s: %s\n", scen_path, err);
        return 2;
    }
    basename_noext(scen_path, name, sizeof(name));
    if (csv_path != NULL) {
        cfg.csv = fopen(csv_path, "w");
        if (cfg.csv == NULL) {
            fprintf(stderr, "sim: cannot write %s\n", csv_path);
            return 2;
        }
        simcore_csv_header(cfg.csv);
    }
    if (simcore_init(&s, &cfg) != 0) {
        return 2;
    }
    c0 = clock();
    simcore_run_scenario(&s, &sc, name);
    wall = (double)(clock() - c0) / CLOCKS_PER_SEC;
    if (cfg.csv != NULL) {
        fclose(cfg.csv);
    }
    simcore_print_summary(&s, stdout, name);
    printf("   run: %.2f s simulated in %.2f s CPU (%.0f x real time)%s%s\n", s.rig.t, wall,
           (wall > 0.0) ? s.rig.t / wall : 0.0, (csv_path != NULL) ? ", trace " : "",
           (csv_path != NULL) ? csv_path : "");
    return 0;
}
