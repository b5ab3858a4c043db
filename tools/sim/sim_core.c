/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_core.c - the one bench: the core on the simulated plant, one PWM period a step. */
/* clock_gettime (wall time for the progress line) is POSIX, not C99. */
#define _POSIX_C_SOURCE 199309L
#include "sim_core.h"
#include "sim_record.h"

#include <math.h>
#include <string.h>
#include <time.h>

#include "sim_trace.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define Q15_TO(x, fs) ((double)(x) / 32768.0 * (double)(fs))
#define RAD_TO_DEG    (180.0 / M_PI)

void simcore_cfg_default(simcore_cfg_t *cfg)
{
    cfg->motor = "hurst";
    cfg->board = "mclv";
    cfg->rs_scale = 1.0;
    cfg->l_scale = 1.0;
    cfg->ke_scale = 1.0;
    cfg->j_scale = 1.0;
    cfg->theta0_rad = 0.0;
    cfg->rpm0 = 0.0;
    cfg->pot = 0.0;
    cfg->deadtime_s = -1.0;
    cfg->noise_codes = -1.0;
    cfg->vbus_v = -1.0;
    cfg->seed = 1u;
    cfg->substeps = 4;
    cfg->sample_at = -1.0;
    cfg->amp_tau_s = -1.0;
    cfg->offsets_set = false;
    cfg->offset_a_codes = 0.0;
    cfg->offset_b_codes = 0.0;
    cfg->j_extra_kgm2 = 0.0;
    cfg->b_scale = 1.0;
    cfg->coulomb_nm = -1.0;
    memset(&cfg->inv, 0, sizeof(cfg->inv)); /* averaged, linear band (automatic), no drops */
    cfg->csv_decim = 10;
    cfg->csv = NULL;
    cfg->record = NULL;
    cfg->progress = false;
    cfg->bus_model = false;
}

double simcore_pot_for_rpm(double rpm)
{
    double span = (double)SPEED_REF_MAX_RPM - (double)SPEED_REF_MIN_RPM;
    double pot;
    if (rpm == SIM_SPEED_MAX) {
        return 1.0;
    }
    if (rpm == SIM_SPEED_MIN) {
        return 0.0;
    }
    pot = (span > 0.0) ? (rpm - (double)SPEED_REF_MIN_RPM) / span : 0.0;
    if (pot < 0.0 || pot > 1.0) {
        fprintf(stderr, "sim: speed %.0f rpm outside the pot range %.0f..%.0f rpm, clamped\n", rpm,
                (double)SPEED_REF_MIN_RPM, (double)SPEED_REF_MAX_RPM);
        pot = (pot < 0.0) ? 0.0 : 1.0;
    }
    /* the simulated ADC rounds this to the nearest of its 1024 codes */
    return pot;
}

/* A motor or board the simulator has no profile for (one written by
 * tools/tune, say) is simulated with the firmware's own data for it, which
 * the core build sees through UserParms.h; what the firmware does not know
 * (inertia, friction, amplifier offsets) is assumed, and said so. */
static const sim_motor_profile_t *motor_from_firmware(const char *name)
{
#if defined(MOTOR_RS_OHM) && defined(MOTOR_LS_H) && defined(MOTOR_KE_VPK_LL_PER_KRPM)
    static sim_motor_profile_t mp;
#if defined(MC_MOTOR_HEADER)
    /* only the motor this core was built for: a misspelt name is refused,
     * not simulated as the build's motor under another name */
    char header[96];
    snprintf(header, sizeof(header), "motors/motor_%s.h", name);
    if (strcmp(header, MC_MOTOR_HEADER) != 0) {
        return NULL;
    }
#endif
    mp.name = name;
    mp.alias = NULL;
#if defined(MOTOR_INERTIA_KGM2)
    mp.desc = "firmware profile data, J from MOTOR_INERTIA_KGM2, friction assumed";
#else
    mp.desc = "firmware profile data, J 1e-5 kg m^2 and friction assumed";
#endif
    mp.rs_ohm = (double)MOTOR_RS_OHM;
    mp.l_h = (double)MOTOR_LS_H;
    mp.ke_ll = (double)MOTOR_KE_VPK_LL_PER_KRPM;
    mp.pole_pairs = (int)MOTOR_POLE_PAIRS;
#if defined(MOTOR_INERTIA_KGM2)
    mp.j_kgm2 = (double)MOTOR_INERTIA_KGM2; /* tools/tune writes the data sheet's value */
#else
    mp.j_kgm2 = 1e-5;
#endif
    mp.b_nms = 1e-5;
    mp.coulomb_nm = 1e-3;
#if defined(MOTOR_RATED_CURRENT_A)
    mp.rated_a = (double)MOTOR_RATED_CURRENT_A;
#else
    mp.rated_a = (double)MOTOR_CURRENT_MAX_A;
#endif
    mp.rated_rpm = (double)MOTOR_SPEED_NOMINAL_RPM;
    fprintf(stderr,
            "sim: no simulator profile '%s': simulating the firmware's motor data "
            "(%s)\n",
            name, mp.desc);
    return &mp;
#else
    (void)name;
    return NULL;
#endif
}

static const sim_board_profile_t *board_from_firmware(const char *name)
{
#if defined(BOARD_VBUS_NOMINAL_V) && defined(BOARD_DEADTIME_NS)
    static sim_board_profile_t bp;
#if defined(MC_BOARD_NAME)
    if (strcmp(name, MC_BOARD_NAME) != 0) {
        return NULL; /* only the board this core was built for */
    }
#endif
    bp.name = name;
    bp.vbus_v = (double)BOARD_VBUS_NOMINAL_V;
    bp.deadtime_s = (double)BOARD_DEADTIME_NS / 1e9;
    bp.offset_a_codes = SIM_AMP_OFFSET_A_CODES; /* assumed as for every board (sim_profiles.h) */
    bp.offset_b_codes = SIM_AMP_OFFSET_B_CODES;
    bp.noise_codes = SIM_ADC_NOISE_CODES;
    bp.amp_tau_s = SIM_AMP_TAU_S;
#if defined(BOARD_VBUS_CAPACITANCE_F) && defined(BOARD_SUPPLY_R_OHM)
    bp.bus_c_f = BOARD_VBUS_CAPACITANCE_F;
    bp.supply_r_ohm = BOARD_SUPPLY_R_OHM;
#endif
    fprintf(stderr, "sim: no simulator profile '%s': simulating the firmware's board data\n", name);
    return &bp;
#else
    (void)name;
    return NULL;
#endif
}

/* The core's vocabulary for the run's record (sim_log.h). */
static const sim_log_core_t LOG_CORE = {mc_state_name, mc_fault_name, (int)MC_STATE_CLOSED_LOOP,
                                        (int)MC_STATE_FAULT};

/* The bench's plant, inverter and ADC from the profiles and cfg. */
static void rig_params(const simcore_t *s, const simcore_cfg_t *cfg, sim_rig_params_t *rp)
{
    memset(rp, 0, sizeof(*rp));
    sim_motor_params_from_profile(s->mp, &rp->motor);
    rp->motor.rs_ohm *= cfg->rs_scale;
    rp->motor.ld_h *= cfg->l_scale;
    rp->motor.lq_h *= cfg->l_scale;
    rp->motor.psi_vs *= cfg->ke_scale;
    rp->motor.j_kgm2 = rp->motor.j_kgm2 * cfg->j_scale + cfg->j_extra_kgm2;
    rp->motor.b_nms *= cfg->b_scale;
    if (cfg->coulomb_nm >= 0.0) {
        rp->motor.coulomb_nm = cfg->coulomb_nm;
    }
    rp->inv = cfg->inv;
    rp->inv.vbus_v = (cfg->vbus_v >= 0.0) ? cfg->vbus_v : s->bp->vbus_v;
    rp->inv.ripple_v = 0.0;
    rp->inv.ripple_hz = 0.0;
    rp->inv.deadtime_s = (cfg->deadtime_s >= 0.0) ? cfg->deadtime_s : s->bp->deadtime_s;
    rp->inv.pwm_hz = (double)PWM_FREQUENCY_HZ;
    rp->inv.duty_max = (double)PWM_DUTY_MAX;
    rp->adc.i_fs_a = (double)BOARD_I_FULLSCALE_A;
    rp->adc.vbus_fs_v = (double)BOARD_VBUS_FULLSCALE_V;
    rp->adc.bits = 10;
    rp->adc.offset_a_codes = cfg->offsets_set ? cfg->offset_a_codes : s->bp->offset_a_codes;
    rp->adc.offset_b_codes = cfg->offsets_set ? cfg->offset_b_codes : s->bp->offset_b_codes;
    rp->adc.noise_codes = (cfg->noise_codes >= 0.0) ? cfg->noise_codes : s->bp->noise_codes;
    rp->adc.seed = (cfg->seed != 0u) ? cfg->seed : 1u;
    rp->substeps = cfg->substeps;
    rp->sample_at = (cfg->sample_at >= 0.0) ? cfg->sample_at : MC_SAMPLE_AT; /* the chip's (mc.h) */
    rp->amp_tau_s = (cfg->amp_tau_s >= 0.0) ? cfg->amp_tau_s : s->bp->amp_tau_s;
    rp->theta_e0 = cfg->theta0_rad;
    rp->omega0_m = cfg->rpm0 * 2.0 * M_PI / 60.0;
    rp->fan_rated_rpm = s->mp->rated_rpm;
    rp->bus_c_f = cfg->bus_model ? s->bp->bus_c_f : 0.0;
    rp->supply_r_ohm = s->bp->supply_r_ohm;
}

int simcore_init(simcore_t *s, const simcore_cfg_t *cfg)
{
    sim_rig_params_t rp;
    memset(s, 0, sizeof(*s));
    s->cfg = *cfg;
    s->mp = sim_motor_profile(cfg->motor);
    s->bp = sim_board_profile(cfg->board);
    if (s->mp == NULL) {
        s->mp = motor_from_firmware(cfg->motor);
    }
    if (s->bp == NULL) {
        s->bp = board_from_firmware(cfg->board);
    }
    if (s->mp == NULL || s->bp == NULL) {
        fprintf(stderr, "sim: unknown %s '%s': neither a simulator profile nor this build's (%s)\n",
                (s->mp == NULL) ? "motor" : "board", (s->mp == NULL) ? cfg->motor : cfg->board,
                sim_profiles_list());
        return -1;
    }
    if (s->mp->pole_pairs != (int)MOTOR_POLE_PAIRS) {
        fprintf(stderr,
                "sim: the simulated motor '%s' has %d pole pairs but the core was built for %d "
                "(MOTOR=%s?): rebuild with the same MOTOR\n",
                s->mp->name, s->mp->pole_pairs, (int)MOTOR_POLE_PAIRS, s->mp->name);
        return -1;
    }
    rig_params(s, cfg, &rp);
    sim_rig_init(&s->rig, &rp);
    s->rig.pot = cfg->pot;
    s->rig.pot_target = cfg->pot;
    mc_init(&s->mc);
    mc_status(&s->mc, &s->st);
    s->out.duty[0] = s->out.duty[1] = s->out.duty[2] = PWM_DUTY_MAX / 2U; /* before a step: off */
    s->out.outputs_on = false;
    s->rated_nm = sim_motor_rated_torque(s->mp);
    sim_log_init(&s->log, &LOG_CORE, (int)s->st.state);
    return 0;
}

void simcore_request(simcore_t *s, mc_request_t r)
{
    if (r == MC_REQUEST_START || r == MC_REQUEST_START_STOP) {
        sim_log_start(&s->log, s->rig.t);
    }
    if ((unsigned)r < 16U) {
        s->requests = (uint16_t)(s->requests | (1U << (unsigned)r));
    }
    mc_request(&s->mc, r);
}

void simcore_set_speed(simcore_t *s, double rpm)
{
    sim_event_t ev = {0.0, SIM_EV_POT, 0.0, 0.0};
    ev.v1 = simcore_pot_for_rpm(rpm);
    sim_rig_apply(&s->rig, &ev);
}

void simcore_event(simcore_t *s, const sim_event_t *ev)
{
    sim_event_t e = *ev;
    switch (ev->kind) {
        case SIM_EV_START:
            if (s->st.state == MC_STATE_STOPPED || s->st.state == MC_STATE_FAULT) {
                simcore_request(s, MC_REQUEST_START);
            }
            return;
        case SIM_EV_STOP:
            if (s->st.state != MC_STATE_STOPPED && s->st.state != MC_STATE_FAULT) {
                simcore_request(s, MC_REQUEST_STOP);
            }
            return;
        case SIM_EV_BUTTON:
            simcore_request(s, MC_REQUEST_START_STOP);
            return;
        case SIM_EV_IDENTIFY:
            simcore_request(s, MC_REQUEST_IDENTIFY);
            return;
        case SIM_EV_HW_FAULT:
            simcore_request(s, MC_REQUEST_HW_FAULT);
            return;
        case SIM_EV_MARK:
            return;
        case SIM_EV_ZOOM:
            s->zoom_until_s = s->rig.t + ((ev->v1 > 0.0) ? ev->v1 : 0.02);
            return;
        case SIM_EV_SPEED:
            e.kind = SIM_EV_POT;
            e.v1 = simcore_pot_for_rpm(ev->v1);
            break;
        case SIM_EV_SPEED_RAMP:
            e.kind = SIM_EV_POT_RAMP;
            e.v1 = simcore_pot_for_rpm(ev->v1);
            break;
        default:
            break;
    }
    (void)sim_rig_apply(&s->rig, &e);
}

static double wrap_deg(double d)
{
    d = fmod(d, 360.0);
    if (d >= 180.0) {
        d -= 360.0;
    } else if (d < -180.0) {
        d += 360.0;
    }
    return d;
}

static bool plant_diverged(const simcore_t *s)
{
    const sim_plant_t *p = &s->rig.plant;
    double step_rad =
        fabs((double)p->m.pole_pairs * p->s.omega_m) * s->rig.ts / (double)s->rig.substeps;
    /* written so that a NaN anywhere fails it */
    return !(isfinite(p->s.id) && isfinite(p->s.iq) && isfinite(p->s.theta_e) &&
             step_rad <= SIMCORE_MAX_STEP_RAD);
}

void simcore_diverged_msg(const simcore_t *s, char *buf, size_t len)
{
    double lim_rpm = SIMCORE_MAX_STEP_RAD * (double)s->rig.substeps / s->rig.ts /
                     (double)s->rig.plant.m.pole_pairs * 60.0 / (2.0 * M_PI);
    if (isfinite(s->diverged_rpm) && isfinite(s->rig.plant.s.id) && isfinite(s->rig.plant.s.iq)) {
        snprintf(buf, len,
                 "at %.4f s the simulated rotor turned at %.0f rpm, beyond the %.0f rpm the plant "
                 "integrates at %d sub-steps per period; run stopped (a load driving the rotor? "
                 "reduce it or raise --substeps)",
                 s->diverged_t_s, s->diverged_rpm, lim_rpm, s->rig.substeps);
    } else {
        snprintf(buf, len,
                 "at %.4f s the simulated plant's state became non-finite; run stopped (raise "
                 "--substeps or bring the scales nearer 1)",
                 s->diverged_t_s);
    }
}

void simcore_sample(simcore_t *s, mc_adc_frame_t *in)
{
    sim_sample_t *n = &s->now;
    const sim_plant_t *p = &s->rig.plant;
    sim_rig_sample(&s->rig, &s->frame);
    in->ia = s->frame.ia;
    in->ib = s->frame.ib;
    in->vbus = s->frame.vbus;
    in->pot = s->frame.pot;
    s->theta_sample = p->s.theta_e;
    s->rpm_sample = sim_plant_rpm(p);
    n->t_s = s->rig.t;
    n->speed_rpm = s->rpm_sample;
    n->id_true_a = p->s.id;
    n->iq_true_a = p->s.iq;
    n->ia_a = s->rig.i_abc[0];
    n->ib_a = s->rig.i_abc[1];
    n->ic_a = s->rig.i_abc[2];
    n->vbus_v = s->rig.vbus_sampled;
    n->load_nm =
        p->load.passive_nm + p->load.active_nm + p->load.fan_k * p->s.omega_m * fabs(p->s.omega_m);
    n->torque_nm = sim_plant_torque(p);
}

void simcore_finish(simcore_t *s)
{
    sim_sample_t *n = &s->now;
    mc_status(&s->mc, &s->st);
    n->state = (int)s->st.state;
    n->fault = s->st.fault;
    n->speed_target_rpm = Q15_TO(s->st.speed_target, MC_SPEED_FULLSCALE_RPM);
    n->speed_ref_rpm = Q15_TO(s->st.speed_ref, MC_SPEED_FULLSCALE_RPM);
    n->speed_est_rpm = Q15_TO(s->st.speed_est, MC_SPEED_FULLSCALE_RPM);
    n->theta_est_deg = (double)s->st.theta_est / 32768.0 * 180.0;
    n->theta_deg = s->theta_sample * RAD_TO_DEG;
    n->theta_err_deg = wrap_deg(n->theta_est_deg - n->theta_deg);
    n->id_ref_a = Q15_TO(s->st.id_ref, BOARD_I_FULLSCALE_A);
    n->iq_ref_a = Q15_TO(s->st.iq_ref, BOARD_I_FULLSCALE_A);
    n->id_a = Q15_TO(s->st.id, BOARD_I_FULLSCALE_A);
    n->iq_a = Q15_TO(s->st.iq, BOARD_I_FULLSCALE_A);
    n->vd_v = Q15_TO(s->st.vd, MC_VOLTAGE_FULLSCALE_V);
    n->vq_v = Q15_TO(s->st.vq, MC_VOLTAGE_FULLSCALE_V);
    n->duty[0] = (double)s->out.duty[0] / (double)PWM_DUTY_MAX;
    n->duty[1] = (double)s->out.duty[1] / (double)PWM_DUTY_MAX;
    n->duty[2] = (double)s->out.duty[2] / (double)PWM_DUTY_MAX;
    n->outputs_on = s->out.outputs_on;
    n->estimator_valid = s->st.estimator_valid;

    sim_rig_advance(&s->rig, s->out.duty, s->out.outputs_on);
    if (plant_diverged(s)) {
        s->diverged = true;
        s->diverged_t_s = s->rig.t;
        s->diverged_rpm = sim_plant_rpm(&s->rig.plant);
    }
    sim_log_add(&s->log, n, s->rig.ts);
    if (s->cfg.csv != NULL && s->cfg.csv_decim > 0 &&
        ((s->rig.period - 1) % s->cfg.csv_decim == 0 || n->t_s < s->zoom_until_s)) {
        sim_trace_row(s->cfg.csv, n, n->t_s < s->zoom_until_s);
    }
}

void simcore_step(simcore_t *s)
{
    mc_adc_frame_t in;
    if (s->diverged) {
        return;
    }
    simcore_sample(s, &in);
    mc_step(&s->mc, &in, &s->out);
    mc_slow_step(&s->mc); /* a no-op except after a window end (mc.h note 4) */
    if (s->cfg.record != NULL && !s->record_failed) {
        mc_status(&s->mc, &s->st);
        s->record_failed =
            sim_record_period(s->cfg.record, s->requests, &in, &s->out, (uint16_t)s->st.state) != 0;
    }
    s->requests = 0U;
    simcore_finish(s);
}

static double wall_s(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0) {
        return (double)clock() / CLOCKS_PER_SEC;
    }
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int simcore_run_scenario(simcore_t *s, const sim_scenario_t *sc, const char *name)
{
    int next = 0;
    long periods = (long)floor(sc->end_s * (double)PWM_FREQUENCY_HZ + 0.5);
    double w0 = wall_s();
    double last_report = 0.0;
    bool reported = false;

    sim_log_segments(&s->log, sc);
    while (s->rig.period < periods && !s->diverged) {
        double t = s->rig.t;
        while (next < sc->n && sc->ev[next].t_s <= t + 0.5 / (double)PWM_FREQUENCY_HZ) {
            if (sc->ev[next].kind != SIM_EV_END) {
                simcore_event(s, &sc->ev[next]);
            }
            next++;
        }
        simcore_step(s);
        if (s->cfg.progress && (s->rig.period & 4095) == 0) {
            double wall = wall_s() - w0;
            if (wall > 2.0 && wall - last_report >= 1.0) {
                fprintf(stderr, "\rsim %s: %.2f / %.2f s simulated (%3.0f %%), %.0f s wall", name,
                        s->rig.t, sc->end_s, 100.0 * s->rig.t / sc->end_s, wall);
                last_report = wall;
                reported = true;
            }
        }
    }
    if (reported) {
        fprintf(stderr, "\n");
    }
    return s->diverged ? -1 : 0;
}

void simcore_print_summary(const simcore_t *s, FILE *f, const char *name)
{
    fprintf(f,
            "\n== sim: scenario %s | motor %s (%s) | board %s, at the start: Vbus %.1f V, dead "
            "time %.1f us, ADC noise %.1f LSB\n",
            name, s->mp->name, s->mp->desc, s->bp->name,
            (s->cfg.vbus_v >= 0.0) ? s->cfg.vbus_v : s->bp->vbus_v,
            1e6 * ((s->cfg.deadtime_s >= 0.0) ? s->cfg.deadtime_s : s->bp->deadtime_s),
            (s->cfg.noise_codes >= 0.0) ? s->cfg.noise_codes : s->bp->noise_codes);
    if (s->rig.bus_c_f > 0.0) {
        fprintf(f,
                "   DC bus (the bus model)    peak %.2f V at %.3f s, lowest %.2f V (%.0f uF, a "
                "supply of %.2f ohm that only sources)\n",
                s->rig.vbus_peak_v, s->rig.t_vbus_peak_s, s->rig.vbus_low_v, s->rig.bus_c_f * 1e6,
                s->rig.supply_r_ohm);
    }
    if (s->cfg.rs_scale != 1.0 || s->cfg.l_scale != 1.0 || s->cfg.ke_scale != 1.0) {
        fprintf(f, "   plant mismatch vs UserParms.h: R x%.2f, L x%.2f, Ke x%.2f\n",
                s->cfg.rs_scale, s->cfg.l_scale, s->cfg.ke_scale);
    }
    sim_log_print_run(&s->log, f);
    fprintf(f,
            "   peak phase current        %.2f A at %.3f s (rated %.2f A, ADC full scale %.2f A)\n",
            s->log.i_peak_a, s->log.t_i_peak_s, s->mp->rated_a, (double)BOARD_I_FULLSCALE_A);
    fprintf(f, "   dead time compensated     %.2f us (the inverter's at the end: %.2f us)\n",
            (double)s->st.deadtime / (double)BOARD_FCY_HZ * 1e6, s->rig.inv.prm.deadtime_s * 1e6);
    if (s->rig.amp_tau_s > 0.0) {
        fprintf(f,
                "   shunt window              %ld samples short of the amplifiers' settling "
                "(%.2f us); shortest conduction before a sample %.2f us\n",
                s->rig.samples_short, SIM_AMP_SETTLE_TAUS * s->rig.amp_tau_s * 1e6,
                s->rig.t_cond_min_s * 1e6);
    }
    sim_log_print_states(&s->log, f);
    simcore_print_identify(s, f);
}

void simcore_identify_truth(const simcore_t *s, simcore_id_truth_t *t)
{
    const sim_motor_params_t *m = &s->rig.plant.m;
    t->rs_ohm = m->rs_ohm;
    t->ld_h = m->ld_h;
    t->lq_h = m->lq_h;
    t->ls_h = 0.5 * (m->ld_h + m->lq_h);
    /* peak line-to-line volts per 1000 mechanical rpm: sqrt(3) psi p 2 pi / 60 x 1000 */
    t->ke_v_per_krpm = sqrt(3.0) * m->psi_vs * m->pole_pairs * 2.0 * M_PI / 60.0 * 1e3;
    t->j_kgm2 = m->j_kgm2;
    t->deadtime_s = s->rig.inv.prm.deadtime_s;
}

static double rel_pct(double measured, double truth)
{
    return (truth > 0.0) ? 100.0 * (measured / truth - 1.0) : 0.0;
}

void simcore_identify_errors(const simcore_t *s, const mc_id_result_t *r, simcore_id_err_t *e)
{
    simcore_id_truth_t t;
    simcore_identify_truth(s, &t);
    e->rs = rel_pct(r->rs_uohm * 1e-6, t.rs_ohm);
    e->ld = rel_pct(r->ld_nh * 1e-9, t.ld_h);
    e->lq = rel_pct(r->lq_nh * 1e-9, t.lq_h);
    e->ls = rel_pct(r->ls_nh * 1e-9, t.ls_h);
    e->ke = rel_pct(r->ke_uv_per_rpm * 1e-6, t.ke_v_per_krpm * 1e-3);
    e->j = rel_pct(r->j_ng_m2 * 1e-9, t.j_kgm2);
    e->deadtime = rel_pct(r->deadtime_ns * 1e-9, t.deadtime_s);
}

void simcore_print_identify(const simcore_t *s, FILE *f)
{
    mc_id_result_t r;
    simcore_id_truth_t t;
    simcore_id_err_t e;
    mc_identify_result(&s->mc, &r);
    if (r.status == MC_ID_NONE) {
        return;
    }
    fprintf(f, "   identification            %s",
            (r.status == MC_ID_DONE)     ? "done"
            : (r.status == MC_ID_FAILED) ? "FAILED"
                                         : "running");
    if (r.status == MC_ID_FAILED) {
        fprintf(f, ", error %u (%s)\n", (unsigned)r.error, mc_id_error_name(r.error));
        return;
    }
    fprintf(f, " (measured / the plant's)\n");
    if (r.status != MC_ID_DONE) {
        return;
    }
    simcore_identify_truth(s, &t);
    simcore_identify_errors(s, &r, &e);
    fprintf(f, "     R   %9.4f / %9.4f ohm   %+6.2f %%\n", r.rs_uohm * 1e-6, t.rs_ohm, e.rs);
    fprintf(f, "     Ld  %9.4f / %9.4f mH    %+6.2f %%\n", r.ld_nh * 1e-6, t.ld_h * 1e3, e.ld);
    fprintf(f, "     Lq  %9.4f / %9.4f mH    %+6.2f %%\n", r.lq_nh * 1e-6, t.lq_h * 1e3, e.lq);
    fprintf(f, "     Ke  %9.3f / %9.3f V/krpm %+6.2f %%\n", r.ke_uv_per_rpm * 1e-3, t.ke_v_per_krpm,
            e.ke);
    fprintf(f, "     J   %9.3g / %9.3g kg m^2 %+6.2f %%\n", r.j_ng_m2 * 1e-9, t.j_kgm2, e.j);
    fprintf(f, "     dead time %u ns / %.0f ns   %+6.2f %%\n", (unsigned)r.deadtime_ns,
            t.deadtime_s * 1e9, e.deadtime);
}
