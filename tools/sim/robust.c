/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* robust.c - the randomized campaign: the core against motors, loads and inverters drawn
 * around its profile (docs/robustness.md). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "sim_core.h"
#include "sim_opt.h"
#include "sim_parse.h"
#include "sim_trace.h"
#include "sim_window.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define COUNT_MAX 100000L /* runs per --count: a campaign chunk, a few hours of CPU at most */

/*
 * One run, from one seed: the plant (R, L, Ke, inertia, friction), the
 * inverter (model, dead time and its shape, device drops), the ADC (offsets,
 * noise), the rotor's angle and the load are drawn from the seed; the run
 * starts, reaches a speed, holds it, takes a step (load or speed), and
 * stops. Every draw and every threshold is in this file, and the same seed
 * gives the same run on every machine (the generator is xorshift64*, the
 * plant double precision without library randomness).
 *
 * Timeline (s): 0.1 START; t_hold..t_step the hold window; t_step the
 * step; t_meas..t_stop the second window; t_stop STOP; t_end the end.
 */

#define T_START         0.10
#define T_STEP_AFTER_CL 1.40 /* the hold window ends this long after CLOSED_LOOP */
#define T_HOLD_LEN      0.50 /* ... and is this long */
#define T_SETTLE        0.80 /* after the step's end, the second window starts */
#define T_MEAS_LEN      0.40
#define T_LOAD_RAMP     0.50 /* a load ramp's length */
#define T_STOPPED       0.30 /* STOP to the end of the run */
/* No CLOSED_LOOP by then: a failed start. Every attempt (calibration,
 * lock, ramp, the longest wait at its end, the coast before a retry) and
 * one second more. */
#define T_CL_LIMIT                                                                                 \
    (T_START + 1.0 +                                                                               \
     ((double)MC_START_RETRIES + 1.0) *                                                            \
         (0.05 + (double)MOTOR_LOCK_TIME_S + (double)MOTOR_RAMP_TIME_S +                           \
          (double)MC_HANDOFF_WAIT_S + (double)MC_RETRY_COAST_S))

#define SPEED_TOL                                                                                  \
    0.03 /* |mean true speed - reference| / reference in both windows; the RMS about it in the     \
            second */

/* What the profile claims, the envelope the draws stay inside (docs/robustness.md). */
#define ENV_SPEED_HI_FRAC 0.8 /* speeds up to this fraction of the nominal speed */
#define ENV_TORQUE_FRAC   0.6 /* steady load up to this fraction of Kt * MOTOR_CURRENT_MAX_A */
/* The start the profile claims: its start load (MOTOR_START_LOAD_NM, which
 * tools/tune sizes the ramp current for at 60 % of Kt I_ramp; 60 % when a
 * profile does not say) plus ENV_ACCEL_SHARE of Kt I_ramp to accelerate the
 * inertia it was sized for (tools/tune's ramp rule), at the profile's Kt.
 * A start that needs more, at the end of the ramp (load, friction, J
 * alpha), is outside the claim: it may fail, safely. */
#define ENV_ACCEL_SHARE 0.2
/* ... and the inertia it was sized for: tools/tune makes the lock eight
 * periods of the rotor's swing at the stated inertia (five settle a start
 * from any angle; four failed one from 160 deg), so up to (8/5)^2 times it,
 * and no more than the ramp's acceleration budget allows. */
#define ENV_J_LOCK_MAX 2.56
#if defined(MOTOR_START_LOAD_NM)
#define ENV_START_LOAD_NM ((double)MOTOR_START_LOAD_NM)
#else
#define ENV_START_LOAD_NM (0.6 * ENV_KT_NOM * (double)MOTOR_RAMP_CURRENT_A)
#endif
#define ENV_KT_NOM                                                                                 \
    (1.5 * (double)MOTOR_POLE_PAIRS *                                                              \
     sim_psi_from_ke((double)MOTOR_KE_VPK_LL_PER_KRPM, (int)MOTOR_POLE_PAIRS))
/* A load step the rotor cannot ride through sensorless: uncorrected, it
 * would take more than ENV_STEP_DROP of the speed within ENV_STEP_REACT_S
 * (about ten speed-loop periods, the time the speed loop needs to answer),
 * so the rotor stops before the loop has the current. */
#define ENV_STEP_REACT_S 0.010
#define ENV_STEP_DROP    0.5

typedef enum { LOAD_NONE, LOAD_COULOMB, LOAD_VISCOUS, LOAD_FAN, LOAD_KINDS } load_kind_t;
typedef enum { STEP_LOAD_UP, STEP_LOAD_DOWN, STEP_LOAD_RAMP, STEP_SPEED, STEP_KINDS } step_kind_t;

static const char *const LOAD_NAMES[] = {"none", "coulomb", "viscous", "fan"};
static const char *const STEP_NAMES[] = {"load_up", "load_down", "load_ramp", "speed"};

typedef struct {
    uint32_t seed;
    simcore_cfg_t cfg;
    load_kind_t load;
    double load_nm; /* coulomb: the brake's torque; viscous/fan: torque at the rated speed */
    step_kind_t step;
    double step_nm; /* load steps: the brake's torque after the step */
    double rpm1, rpm2;
    double start_need_nm, start_have_nm; /* torque the ramp needs vs the profile claims */
    double j_claim;                      /* the inertia scale the profile claims, at most */
    bool physics_limited;                /* the start is outside the claim */
    bool step_limited; /* the step is beyond what a sensorless drive can ride through */
} run_draw_t;

typedef struct {
    const char *result; /* PASS, SAFE (a physics-limited start that faulted safely), FAIL */
    char why[96];
    double t_cl; /* time to CLOSED_LOOP from START, s; < 0 never */
    int retries;
    unsigned fault;
    double ang_mean, ang_rms, ang_max; /* hold window, deg */
    double spd_err, est_err;           /* hold window: true vs reference, estimate vs true, % */
    double spd_err2, ang_rms2;         /* second window */
    double spd_rip, spd_rip2;          /* speed error's RMS about its mean, % of the reference */
    double dt_comp_us;                 /* the dead time the core compensates at the end, us */
    double vbus_peak_v;                /* the bus's highest (--bus-model; else the supply's), V */
    double i_peak;
} run_result_t;

static double uni(uint64_t *r, double lo, double hi)
{
    return lo + (hi - lo) * sim_rand_uniform(r);
}

static double rated_rpm_w(const simcore_t *s)
{
    return s->mp->rated_rpm * 2.0 * M_PI / 60.0;
}

/* Everything a seed decides; bus_model: the bus as its capacitor (sim --bus-model). */
static void draw(uint32_t seed, const char *motor, const char *board, bool bus_model, run_draw_t *d)
{
    uint64_t r = 0x9E3779B97F4A7C15ULL ^ ((uint64_t)seed * 0x2545F4914F6CDD1DULL);
    const sim_motor_profile_t *mp;
    double lo_rpm, hi_rpm, psi_nom, kt_nom, kt_plant, cap_nm, w_end, j;
    int k;
    memset(d, 0, sizeof(*d));
    d->seed = seed;
    for (k = 0; k < 4; k++) {
        (void)sim_rand_uniform(&r); /* stir the seed in */
    }
    simcore_cfg_default(&d->cfg);
    d->cfg.motor = motor;
    d->cfg.board = board;
    d->cfg.rs_scale = uni(&r, 0.7, 1.3);
    d->cfg.l_scale = uni(&r, 0.7, 1.3);
    d->cfg.ke_scale = uni(&r, 0.85, 1.15);
    d->cfg.j_scale = exp(uni(&r, log(0.5), log(20.0)));
    d->cfg.b_scale = uni(&r, 0.0, 3.0);
    d->cfg.theta0_rad = uni(&r, 0.0, 2.0 * M_PI);
    d->cfg.deadtime_s = uni(&r, 1.0e-6, 3.0e-6);
    d->cfg.offsets_set = true;
    d->cfg.offset_a_codes = uni(&r, -30.0, 30.0);
    d->cfg.offset_b_codes = uni(&r, -30.0, 30.0);
    d->cfg.noise_codes = uni(&r, 0.5, 3.0);
    d->cfg.seed = seed | 1u;
    d->cfg.bus_model = bus_model;
    if (sim_rand_uniform(&r) < 0.5) {
        d->cfg.inv.model = SIM_INV_AVERAGED;
        d->cfg.inv.dt_shape = (int)(sim_rand_uniform(&r) * 3.0); /* linear, hard, ripple */
    } else {
        d->cfg.inv.model = SIM_INV_SWITCHING;
        d->cfg.inv.r_on_ohm = uni(&r, 0.0, 0.1);
        d->cfg.inv.v_diode_v = uni(&r, 0.0, 1.0);
    }

    mp = sim_motor_profile(motor);
    psi_nom = sim_psi_from_ke((double)MOTOR_KE_VPK_LL_PER_KRPM, (int)MOTOR_POLE_PAIRS);
    kt_nom = 1.5 * (double)MOTOR_POLE_PAIRS * psi_nom;
    kt_plant = kt_nom * d->cfg.ke_scale;
    cap_nm = ENV_TORQUE_FRAC * kt_plant * (double)MOTOR_CURRENT_MAX_A;
    d->cfg.coulomb_nm = uni(&r, 0.0, 0.02) * kt_nom * (double)MOTOR_RAMP_CURRENT_A;

    lo_rpm = (double)SPEED_REF_MIN_RPM;
    hi_rpm = ENV_SPEED_HI_FRAC * (double)MOTOR_SPEED_NOMINAL_RPM;
    d->rpm1 = uni(&r, lo_rpm, hi_rpm);
    d->rpm2 = uni(&r, lo_rpm, hi_rpm);

    /* The load: Coulomb up to 100 % of the profile's start torque
     * (Kt * MOTOR_RAMP_CURRENT_A); viscous and fan loads given by their
     * torque at the rated speed; all inside the steady-torque envelope. */
    d->load = (load_kind_t)(int)(sim_rand_uniform(&r) * (double)LOAD_KINDS);
    d->load_nm = 0.0;
    if (d->load == LOAD_COULOMB) {
        d->load_nm = uni(&r, 0.0, 1.0) * ENV_START_LOAD_NM;
    } else if (d->load != LOAD_NONE) {
        d->load_nm = uni(&r, 0.0, 1.0) * cap_nm;
    }
    if (d->load_nm > cap_nm) {
        d->load_nm = cap_nm;
    }
    d->step = (step_kind_t)(int)(sim_rand_uniform(&r) * (double)STEP_KINDS);
    d->step_nm = uni(&r, 0.0, 1.0) * cap_nm; /* load_up / load_ramp: the brake after */
    if (d->step == STEP_LOAD_DOWN) {
        d->step_nm = 0.0;
    }

    /* What the ramp needs at its end: the load, friction, and J times the
     * ramp's acceleration; what the plant gives: Kt_plant * I_ramp. */
    j = (mp != NULL) ? mp->j_kgm2 * d->cfg.j_scale : 0.0;
    w_end = (double)MOTOR_RAMP_END_RPM * 2.0 * M_PI / 60.0;
    d->start_need_nm = d->cfg.coulomb_nm +
                       ((mp != NULL) ? mp->b_nms * d->cfg.b_scale * w_end : 0.0) +
                       j * w_end / (double)MOTOR_RAMP_TIME_S;
    if (d->load == LOAD_COULOMB) {
        d->start_need_nm += d->load_nm;
    }
    d->start_have_nm = ENV_START_LOAD_NM + ENV_ACCEL_SHARE * kt_nom * (double)MOTOR_RAMP_CURRENT_A;
    /* viscous and fan loads at the ramp end are added once the plant is known (apply_load) */
    d->j_claim = ENV_J_LOCK_MAX;
    if (mp != NULL) {
        double j_acc = ENV_ACCEL_SHARE * kt_nom * (double)MOTOR_RAMP_CURRENT_A /
                       (mp->j_kgm2 * w_end / (double)MOTOR_RAMP_TIME_S);
        d->j_claim = (j_acc < d->j_claim) ? j_acc : d->j_claim;
    }
    d->physics_limited = d->start_need_nm > d->start_have_nm || d->cfg.j_scale > d->j_claim;
}

/* Applies the drawn load to a fresh plant. */
static void apply_load(simcore_t *s, run_draw_t *d)
{
    sim_event_t ev = {0.0, SIM_EV_LOAD, 0.0, 0.0};
    double w = rated_rpm_w(s), w_end = (double)MOTOR_RAMP_END_RPM * 2.0 * M_PI / 60.0;
    if (d->load == LOAD_COULOMB) {
        ev.v1 = d->load_nm;
        simcore_event(s, &ev);
    } else if (d->load == LOAD_VISCOUS) {
        s->rig.plant.m.b_nms += d->load_nm / w;
        d->start_need_nm += d->load_nm * w_end / w;
    } else if (d->load == LOAD_FAN) {
        ev.kind = SIM_EV_LOAD_FAN;
        ev.v1 = d->load_nm;
        simcore_event(s, &ev);
        d->start_need_nm += d->load_nm * (w_end / w) * (w_end / w);
    }
    d->physics_limited = d->start_need_nm > d->start_have_nm || d->cfg.j_scale > d->j_claim;
    if (d->step == STEP_LOAD_UP) {
        double j = s->rig.plant.m.j_kgm2;
        double before = (d->load == LOAD_COULOMB) ? d->load_nm : 0.0;
        double w_hold = d->rpm1 * 2.0 * M_PI / 60.0;
        d->step_limited = (d->step_nm - before) * ENV_STEP_REACT_S / j > ENV_STEP_DROP * w_hold;
    }
}

/* Runs one draw; apply_load completes its start need and step class. */
static int run_one(run_draw_t *dp, run_result_t *res, FILE *csv, bool verbose)
{
    static simcore_t s;
    run_draw_t d = *dp;
    sim_window_t w1, w2; /* the hold window and the one after the step: every sample */
    double t_cl = -1.0, t_step = 1e9, t_meas = 1e9, t_stop = 1e9, t_end = T_CL_LIMIT + 1.0;
    double ramp_t0 = 0.0, ramp_nm0 = 0.0;
    bool started = false, stepped = false, stopped = false, saw_fault = false;
    sim_event_t ev;
    memset(res, 0, sizeof(*res));
    sim_window_init(&w1);
    sim_window_init(&w2);
    d.cfg.csv = csv;
    d.cfg.csv_decim = 10;
    if (simcore_init(&s, &d.cfg) != 0) {
        return -1;
    }
    apply_load(&s, &d);
    *dp = d;
    simcore_set_speed(&s, d.rpm1);
    res->t_cl = -1.0;
    while (s.rig.t < t_end) {
        double t = s.rig.t;
        if (!started && t >= T_START) {
            simcore_request(&s, MC_REQUEST_START);
            started = true;
        }
        if (!stepped && t >= t_step) {
            stepped = true;
            if (d.step == STEP_SPEED) {
                simcore_set_speed(&s, d.rpm2);
            } else if (d.step == STEP_LOAD_RAMP) {
                ramp_t0 = t;
                ramp_nm0 = (d.load == LOAD_COULOMB) ? d.load_nm : 0.0;
            } else {
                ev.t_s = t;
                ev.kind = SIM_EV_LOAD;
                ev.v1 = d.step_nm;
                ev.v2 = 0.0;
                simcore_event(&s, &ev);
            }
        }
        if (stepped && d.step == STEP_LOAD_RAMP && t - ramp_t0 <= T_LOAD_RAMP + 1e-9) {
            double f = (t - ramp_t0) / T_LOAD_RAMP;
            ev.t_s = t;
            ev.kind = SIM_EV_LOAD;
            ev.v1 = ramp_nm0 + (d.step_nm - ramp_nm0) * ((f > 1.0) ? 1.0 : f);
            ev.v2 = 0.0;
            simcore_event(&s, &ev);
        }
        if (!stopped && t >= t_stop) {
            stopped = true;
            simcore_request(&s, MC_REQUEST_STOP);
        }
        simcore_step(&s);
        if (s.diverged) {
            snprintf(res->why, sizeof(res->why), "the plant diverged at %.3f s (%.0f rpm)",
                     s.diverged_t_s, s.diverged_rpm);
            break;
        }
        if (s.st.fault != MC_FAULT_NONE && !saw_fault) {
            saw_fault = true;
            res->fault = s.st.fault;
            res->retries = (int)s.st.start_retries;
            break;
        }
        if (t_cl < 0.0 && s.st.state == MC_STATE_CLOSED_LOOP) {
            t_cl = s.rig.t;
            res->t_cl = t_cl - T_START;
            t_step = t_cl + T_STEP_AFTER_CL;
            /* the settling counts from the step's end: a load ramp's, or
             * a speed step's reference slewed at MC_SPEED_RAMP_RPM_PER_S */
            t_meas = t_step + T_SETTLE;
            if (d.step == STEP_SPEED) {
                t_meas += fabs(d.rpm2 - d.rpm1) / (double)MC_SPEED_RAMP_RPM_PER_S;
            } else if (d.step == STEP_LOAD_RAMP) {
                t_meas += T_LOAD_RAMP;
            }
            t_stop = t_meas + T_MEAS_LEN;
            t_end = t_stop + T_STOPPED;
        }
        if (t_cl >= 0.0 && s.rig.t >= t_step - T_HOLD_LEN && s.rig.t < t_step) {
            sim_window_add(&w1, &s.now, true);
        }
        if (t_cl >= 0.0 && s.rig.t >= t_meas && s.rig.t < t_stop) {
            sim_window_add(&w2, &s.now, true);
        }
        if (t_cl >= 0.0 && !stopped && s.st.state != MC_STATE_CLOSED_LOOP) {
            snprintf(res->why, sizeof(res->why), "left CLOSED_LOOP (%s) at %.3f s",
                     mc_state_name((int)s.st.state), s.rig.t);
            break;
        }
        if (t_cl < 0.0 && s.rig.t > T_CL_LIMIT) {
            snprintf(res->why, sizeof(res->why), "no CLOSED_LOOP by %.1f s (state %s)", T_CL_LIMIT,
                     mc_state_name((int)s.st.state));
            break;
        }
    }
    res->i_peak = s.log.i_peak_a;
    res->dt_comp_us = (double)s.st.deadtime / (double)BOARD_FCY_HZ * 1e6;
    res->vbus_peak_v = s.rig.vbus_peak_v;
    if (w1.n > 0) {
        res->ang_mean = sim_window_ang_mean(&w1);
        res->ang_rms = sim_window_ang_rms(&w1);
        res->ang_max = w1.ang_max;
        res->spd_err = sim_window_speed_err_pct(&w1);
        res->est_err = sim_window_est_err_pct(&w1);
        res->spd_rip = sim_window_ripple_pct(&w1);
    }
    if (w2.n > 0) {
        res->spd_err2 = sim_window_speed_err_pct(&w2);
        res->ang_rms2 = sim_window_ang_rms(&w2);
        res->spd_rip2 = sim_window_ripple_pct(&w2);
    }
    if (saw_fault) {
        snprintf(res->why, sizeof(res->why), "fault %s at %.3f s", mc_fault_name(res->fault),
                 s.rig.t);
        /* A physics-limited start may end in a start or stall fault, a step
         * beyond the drive's reach in a stall fault after the step; always
         * with the outputs off. */
        bool stall = res->fault == MC_FAULT_STALL_SPEED || res->fault == MC_FAULT_STALL_BEMF ||
                     res->fault == MC_FAULT_STALL_TRACK;
        /* A step the drive cannot ride through can stop the rotor within a
         * few ms, before the stall checks' time; the estimator's angle is
         * then lost, and the current the trip was set for is the one
         * protection that answers. */
        bool step_trip = stall || res->fault == MC_FAULT_OVERCURRENT;
        bool safe = !s.st.outputs_on &&
                    ((d.physics_limited && (res->fault == MC_FAULT_START_FAILED || stall)) ||
                     (d.step_limited && stepped && step_trip));
        res->result = safe ? "SAFE" : "FAIL";
    } else if (res->why[0] != '\0') {
        res->result = "FAIL";
    } else if (w1.n == 0 || w2.n == 0) {
        res->result = "FAIL";
        snprintf(res->why, sizeof(res->why), "a measuring window is empty");
    } else if (fabs(res->spd_err) > 100.0 * SPEED_TOL || fabs(res->spd_err2) > 100.0 * SPEED_TOL) {
        res->result = "FAIL";
        snprintf(res->why, sizeof(res->why), "speed error %.2f %% / %.2f %% (bound %.0f %%)",
                 res->spd_err, res->spd_err2, 100.0 * SPEED_TOL);
    } else if (res->spd_rip2 > 100.0 * SPEED_TOL) {
        /* A loop that rings or limit-cycles keeps its mean: by the second
         * window every rotor has settled, so what is left is sustained. */
        res->result = "FAIL";
        snprintf(res->why, sizeof(res->why),
                 "speed ripple %.2f %% rms after the step (bound %.0f %%)", res->spd_rip2,
                 100.0 * SPEED_TOL);
    } else if (s.st.state != MC_STATE_STOPPED || s.st.outputs_on) {
        res->result = "FAIL";
        snprintf(res->why, sizeof(res->why), "not STOPPED %.1f s after STOP (%s)", T_STOPPED,
                 mc_state_name((int)s.st.state));
    } else {
        res->result = "PASS";
        snprintf(res->why, sizeof(res->why), "-");
    }
    if (verbose) {
        simcore_print_summary(&s, stdout, "robust");
    }
    return 0;
}

static void print_header(void)
{
    printf("seed,motor,result,why,rs_scale,l_scale,ke_scale,j_scale,b_scale,coulomb_nm,deadtime_us,"
           "inverter,dt_shape,r_on,v_diode,off_a,off_b,noise,theta0_deg,load,load_nm,step,step_nm,"
           "rpm1,rpm2,start_need_nm,start_have_nm,physics_limited,step_limited,t_cl_s,retries,"
           "fault,ang_mean,"
           "ang_rms,ang_max,spd_err_pct,est_err_pct,spd_err2_pct,ang_rms2,i_peak,spd_rip_pct,"
           "spd_rip2_pct,dt_comp_us,vbus_peak_v\n");
}

static void print_row(const char *motor, const run_draw_t *d, const run_result_t *r)
{
    const simcore_cfg_t *c = &d->cfg;
    printf(
        "%u,%s,%s,\"%s\",%.4f,%.4f,%.4f,%.4f,%.4f,%.5f,%.3f,%s,%d,%.4f,%.3f,%.2f,%.2f,%.2f,%.1f,"
        "%s,%.5f,%s,%.5f,%.1f,%.1f,%.5f,%.5f,%d,%d,%.4f,%d,%s,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,"
        "%.3f,%.3f,%.3f,%.3f,%.2f\n",
        d->seed, motor, r->result, r->why, c->rs_scale, c->l_scale, c->ke_scale, c->j_scale,
        c->b_scale, c->coulomb_nm, c->deadtime_s * 1e6,
        (c->inv.model == SIM_INV_SWITCHING) ? "switching" : "averaged", c->inv.dt_shape,
        c->inv.r_on_ohm, c->inv.v_diode_v, c->offset_a_codes, c->offset_b_codes, c->noise_codes,
        c->theta0_rad * 180.0 / M_PI, LOAD_NAMES[d->load], d->load_nm, STEP_NAMES[d->step],
        d->step_nm, d->rpm1, d->rpm2, d->start_need_nm, d->start_have_nm,
        d->physics_limited ? 1 : 0, d->step_limited ? 1 : 0, r->t_cl, r->retries,
        mc_fault_name(r->fault), r->ang_mean, r->ang_rms, r->ang_max, r->spd_err, r->est_err,
        r->spd_err2, r->ang_rms2, r->i_peak, r->spd_rip, r->spd_rip2, r->dt_comp_us,
        r->vbus_peak_v);
    fflush(stdout);
}

/* Every option, once (sim_opt.h). A campaign chunk is bounded so that no
 * option value asks for unbounded work: COUNT_MAX runs of a few seconds of
 * simulated time each. */
enum {
    OPT_HELP,
    OPT_MOTOR,
    OPT_BOARD,
    OPT_CSV,
    OPT_SEED,
    OPT_FROM,
    OPT_COUNT,
    OPT_KNOWN_FAIL,
    OPT_BUS_MODEL
};

#define KNOWN_MAX 8 /* --known-fail seeds a campaign takes */

/* clang-format off */
static const sim_opt_t OPTS[] = {
    {.id = OPT_HELP, .name = "--help", .type = SIM_OPT_FLAG, .help = "this list"},
    {.id = OPT_MOTOR, .name = "--motor", .type = SIM_OPT_NAME, .value = "NAME",
     .help = "simulated motor (default hurst)"},
    {.id = OPT_BOARD, .name = "--board", .type = SIM_OPT_NAME, .value = "NAME",
     .help = "simulated board (default mclv)"},
    {.id = OPT_CSV, .name = "--csv", .type = SIM_OPT_TEXT, .value = "FILE",
     .help = "with --seed: that run's trace"},
    {.id = OPT_SEED, .name = "--seed", .type = SIM_OPT_NUMBER, .value = "N",
     .range = SIM_OPT_SEED_RANGE,
     .help = "run this one seed and print its summary (a failure's reproduction)"},
    {.id = OPT_FROM, .name = "--from", .type = SIM_OPT_NUMBER, .value = "N",
     .range = SIM_OPT_SEED_RANGE, .help = "a campaign: the first seed"},
    {.id = OPT_COUNT, .name = "--count", .type = SIM_OPT_NUMBER, .value = "N",
     .range = {"count", "runs", 1.0, (double)COUNT_MAX, SIM_RANGE_INTEGER},
     .help = "with --from: how many seeds, from --from on"},
    {.id = OPT_KNOWN_FAIL, .name = "--known-fail", .type = SIM_OPT_NUMBER, .value = "N",
     .range = SIM_OPT_SEED_RANGE,
     .help = "with --from: a seed whose failure goes to stderr, not the exit status"},
    {.id = OPT_BUS_MODEL, .name = "--bus-model", .type = SIM_OPT_FLAG,
     .help = "the bus as its capacitor and a supply that only sources (sim --bus-model)"},
};
/* clang-format on */

#define N_OPTS (sizeof(OPTS) / sizeof(OPTS[0]))

/* The program's name in its refusals (sim_refuse). */
#define PROG "robust"

static void usage(FILE *f)
{
    fprintf(f, "usage: robust [--motor NAME] [--board NAME] (--seed N [--csv FILE] | --from N "
               "--count N\n"
               "              [--known-fail N]...)\n"
               "  one CSV row per run on stdout (docs/robustness.md)\n");
    sim_opt_usage(f, OPTS, N_OPTS);
}

int main(int argc, char **argv)
{
    const char *motor = "hurst", *board = "mclv", *csv_path = NULL;
    bool bus_model = false;
    long long from = -1, count = 0, one = -1; /* seeds up to 2^32 - 1 even where long is 32 bits */
    long long known[KNOWN_MAX];
    int n_known = 0;
    int i, k, failed = 0;
    char why[320];
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
            case OPT_CSV:
                csv_path = v;
                break;
            case OPT_BUS_MODEL:
                bus_model = true;
                break;
            case OPT_SEED:
                one = (long long)x;
                break;
            case OPT_FROM:
                from = (long long)x;
                break;
            case OPT_COUNT:
                count = (long long)x;
                break;
            case OPT_KNOWN_FAIL:
                if (n_known == KNOWN_MAX) {
                    sim_parse_msg(why, sizeof(why), "at most %d of them", KNOWN_MAX);
                    return sim_refuse(PROG, o->name, why);
                }
                known[n_known++] = (long long)x;
                break;
            default:
                break;
        }
    }
    if (one >= 0 && from >= 0) {
        return sim_refuse(PROG, "--seed", "runs one seed: not with --from");
    }
    if (from < 0 && count > 0) {
        return sim_refuse(PROG, "--count", "only with --from");
    }
    if (one < 0 && from < 0) {
        return sim_refuse(PROG, "--seed", "give --seed N, or --from N --count N");
    }
    if (from >= 0 && count == 0) {
        sim_parse_msg(why, sizeof(why), "--from needs it (1..%ld runs)", (long)COUNT_MAX);
        return sim_refuse(PROG, "--count", why);
    }
    if (from >= 0 && (double)from + (double)count - 1.0 > SIM_OPT_SEED_MAX) {
        sim_parse_msg(why, sizeof(why), "seeds %lld..%.0f pass the last seed, %.0f", from,
                      (double)from + (double)count - 1.0, SIM_OPT_SEED_MAX);
        return sim_refuse(PROG, "--count", why);
    }
    if (one >= 0 && n_known > 0) {
        return sim_refuse(PROG, "--known-fail", "only with --from (a campaign)");
    }
    if (from >= 0 && csv_path != NULL) {
        return sim_refuse(PROG, "--csv", "only with --seed (one run's trace)");
    }
    {
        /* the motor and board exist for this build, before any output */
        static simcore_t probe;
        simcore_cfg_t cfg;
        simcore_cfg_default(&cfg);
        cfg.motor = motor;
        cfg.board = board;
        cfg.progress = false;
        if (simcore_init(&probe, &cfg) != 0) {
            return 2;
        }
    }
    if (one >= 0) {
        run_draw_t d;
        run_result_t r;
        FILE *csv = NULL;
        char part[4096]; /* the trace is written here and renamed over --csv once complete,
                            so a refused or failed run leaves an earlier trace as it was */
        char pq[256];    /* the path, quoted */
        draw((uint32_t)one, motor, board, bus_model, &d);
        if (csv_path != NULL) {
            struct stat st;
            if (stat(csv_path, &st) == 0 && !S_ISREG(st.st_mode)) {
                snprintf(part, sizeof(part), "%s", csv_path); /* a device: written in place */
            } else if (snprintf(part, sizeof(part), "%s.part", csv_path) >= (int)sizeof(part)) {
                return sim_refuse(PROG, "--csv", "path too long");
            }
            csv = fopen(part, "w");
            if (csv == NULL) {
                sim_parse_msg(why, sizeof(why), "cannot write '%s'",
                              sim_parse_quote(part, pq, sizeof(pq)));
                return sim_refuse(PROG, "--csv", why);
            }
            sim_trace_header(csv);
        }
        if (run_one(&d, &r, csv, true) != 0) {
            if (csv != NULL) {
                fclose(csv);
                if (strcmp(part, csv_path) != 0) {
                    remove(part);
                }
            }
            return 2;
        }
        if (csv != NULL) {
            bool ok = (ferror(csv) == 0);
            ok = (fclose(csv) == 0) && ok;
            if (!ok || (strcmp(part, csv_path) != 0 && rename(part, csv_path) != 0)) {
                if (strcmp(part, csv_path) != 0) {
                    remove(part);
                }
                sim_parse_msg(why, sizeof(why), "writing '%s' failed (disk full?)",
                              sim_parse_quote(csv_path, pq, sizeof(pq)));
                return sim_refuse(PROG, "--csv", why);
            }
        }
        print_header();
        print_row(motor, &d, &r);
        return (strcmp(r.result, "FAIL") == 0) ? 1 : 0;
    }
    print_header();
    for (i = 0; i < (int)count; i++) {
        run_draw_t d;
        run_result_t r;
        draw((uint32_t)(from + i), motor, board, bus_model, &d);
        if (run_one(&d, &r, NULL, false) != 0) {
            return 2;
        }
        print_row(motor, &d, &r);
        if (strcmp(r.result, "FAIL") == 0) {
            bool is_known = false;
            for (k = 0; k < n_known; k++) {
                is_known = is_known || known[k] == from + i;
            }
            if (is_known) {
                fprintf(stderr, "robust: seed %lld failed, a known failure (docs/robustness.md)\n",
                        from + i);
            } else {
                failed++;
            }
        }
    }
    return (failed > 0) ? 1 : 0; /* the rows say which */
}
