/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_rig.c - one PWM period of plant, inverter and ADC; the diode model with outputs off. */
#include "sim_rig.h"

#include <math.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

void sim_rig_init(sim_rig_t *r, const sim_rig_params_t *prm)
{
    int k;
    double l = (prm->motor.ld_h < prm->motor.lq_h) ? prm->motor.ld_h : prm->motor.lq_h;
    sim_plant_init(&r->plant, &prm->motor, prm->theta_e0);
    r->plant.s.omega_m = prm->omega0_m;
    r->plant.s.stuck = (prm->omega0_m == 0.0);
    sim_inverter_init(&r->inv, &prm->inv, l);
    sim_adc_init(&r->adc, &prm->adc);
    r->substeps = (prm->substeps >= 1) ? prm->substeps : 1;
    r->sample_at = (prm->sample_at > 0.0 && prm->sample_at < 1.0) ? prm->sample_at : 0.0;
    if (r->sample_at > 0.0 && r->substeps < 2) {
        r->substeps = 2; /* one step on each side of the boundary */
    }
    r->ts = 1.0 / prm->inv.pwm_hz;
    r->t = 0.0;
    r->period = 0;
    r->pot = 0.0;
    r->pot_target = 0.0;
    r->pot_rate = 0.0;
    r->spike_a = 0.0;
    r->spike_left = 0;
    for (k = 0; k < 2; k++) {
        r->sensor[k].mode = SIM_SENSOR_OK;
        r->sensor[k].stuck_a = 0.0;
        r->sensor[k].gain = 1.0;
        r->sensor[k].drift_a_s = 0.0;
        r->sensor[k].drift_t0_s = 0.0;
        r->sensor[k].drift_a = 0.0;
    }
    for (k = 0; k < 3; k++) {
        r->floating[k] = true;
        r->i_abc[k] = 0.0;
    }
    r->was_on = false;
    r->open_lead = -1;
    r->amp_tau_s = (prm->amp_tau_s > 0.0) ? prm->amp_tau_s : 0.0;
    r->samples_short = 0;
    r->t_cond_min_s = r->ts;
    r->fan_rated_w = prm->fan_rated_rpm * 2.0 * M_PI / 60.0;
    r->bus_c_f = (prm->bus_c_f > 0.0) ? prm->bus_c_f : 0.0;
    r->supply_r_ohm = (prm->supply_r_ohm > 0.0) ? prm->supply_r_ohm : 0.0;
    r->vcap_v = sim_inverter_vbus(&r->inv, 0.0); /* charged at the start */
    r->vbus_peak_v = r->vcap_v;
    r->vbus_low_v = r->vcap_v;
    r->t_vbus_peak_s = 0.0;
    r->e_bus_in_j = 0.0;
    r->vbus_sampled = r->vcap_v;
}

/* The bus the pins see at t (s, absolute): the capacitor's with the bus
 * model, else the supply's (sim_rig.h note 2). */
static double rig_vbus(const sim_rig_t *r, double t)
{
    return (r->bus_c_f > 0.0) ? r->vcap_v : sim_inverter_vbus(&r->inv, t);
}

/* The DC current the inverter draws from the bus with pins v at a bus of
 * vbus and phase currents i (A, into the motor): each pin's share of the
 * bus times its current. */
static double bus_current(const double v[3], const double i[3], double vbus)
{
    double i_dc = 0.0;
    int k;
    if (vbus <= 0.0) {
        return 0.0;
    }
    for (k = 0; k < 3; k++) {
        double sh = v[k] / vbus;
        sh = (sh < 0.0) ? 0.0 : ((sh > 1.0) ? 1.0 : sh);
        i_dc += sh * i[k];
    }
    return i_dc;
}

/* The bus model over h (s) with the inverter drawing i_dc (A) from t (s):
 * the supply conducts while the capacitor is below its level (an exact
 * exponential for constant i_dc), else only i_dc moves it (note 2). */
static void bus_step(sim_rig_t *r, double t, double i_dc, double h)
{
    double vs = sim_inverter_vbus(&r->inv, t);
    double c = r->bus_c_f, v = r->vcap_v, v1;
    if (c <= 0.0) {
        return;
    }
    r->e_bus_in_j -= v * i_dc * h;
    if (v < vs || i_dc > 0.0) {
        if (r->supply_r_ohm > 0.0) {
            double tau = r->supply_r_ohm * c;
            double v_inf = vs - r->supply_r_ohm * i_dc;
            v1 = v_inf + (v - v_inf) * exp(-h / tau);
        } else {
            v1 = vs; /* an ideal source holds the bus at its level from below */
        }
        if (v1 > vs) {
            /* the supply stopped conducting within the step */
            double vo = v - i_dc * h / c;
            v1 = (vo > vs) ? vo : vs;
        }
    } else {
        v1 = v - i_dc * h / c;
        if (v1 < vs) {
            v1 = vs; /* down to the supply's level: it conducts again */
        }
    }
    r->vcap_v = (v1 > 0.0) ? v1 : 0.0;
    if (r->vcap_v > r->vbus_peak_v) {
        r->vbus_peak_v = r->vcap_v;
        r->t_vbus_peak_s = t + h;
    }
    if (r->vcap_v < r->vbus_low_v) {
        r->vbus_low_v = r->vcap_v;
    }
}

/* What a phase's amplifier passes to the ADC for a current i (A): an open
 * input reads the bias, 0 A (the ADC adds the offset and the noise); a gain
 * error and a drifting offset act on the current. A stuck reading replaces
 * the ADC's code (sim_rig_sample). */
static double sensor_reading(const sim_rig_t *r, int k, double i)
{
    const sim_sensor_t *s = &r->sensor[k];
    if (s->mode == SIM_SENSOR_OPEN) {
        return 0.0;
    }
    return i * s->gain + s->drift_a + s->drift_a_s * (r->t - s->drift_t0_s);
}

void sim_rig_sample(sim_rig_t *r, sim_adc_frame_t *out)
{
    double ia, ib, ic;
    sim_plant_currents(&r->plant, &ia, &ib, &ic);
    r->i_abc[0] = ia;
    r->i_abc[1] = ib;
    r->i_abc[2] = ic;
    if (r->inv.on && r->amp_tau_s > 0.0) {
        double t_s = r->sample_at * r->ts;
        double ta = sim_inverter_low_conduction(&r->inv, 0, t_s, ia);
        double tb = sim_inverter_low_conduction(&r->inv, 1, t_s, ib);
        double t = (ta < tb) ? ta : tb;
        if (t < r->t_cond_min_s) {
            r->t_cond_min_s = t;
        }
        if (t < SIM_AMP_SETTLE_TAUS * r->amp_tau_s) {
            r->samples_short++;
        }
        ia *= 1.0 - exp(-ta / r->amp_tau_s);
        ib *= 1.0 - exp(-tb / r->amp_tau_s);
    }
    r->vbus_sampled = rig_vbus(r, r->t + r->sample_at * r->ts);
    if (r->spike_left > 0) {
        ia += r->spike_a;
        ib -= r->spike_a;
        r->spike_left--;
    }
    ia = sensor_reading(r, 0, ia);
    ib = sensor_reading(r, 1, ib);
    sim_adc_sample(&r->adc, ia, ib, r->vbus_sampled, r->pot, out);
    if (r->sensor[0].mode == SIM_SENSOR_STUCK) {
        out->ia = sim_adc_bipolar_exact(&r->adc, r->sensor[0].stuck_a / r->adc.prm.i_fs_a,
                                        r->adc.prm.offset_a_codes);
    }
    if (r->sensor[1].mode == SIM_SENSOR_STUCK) {
        out->ib = sim_adc_bipolar_exact(&r->adc, r->sensor[1].stuck_a / r->adc.prm.i_fs_a,
                                        r->adc.prm.offset_b_codes);
    }
}

static void phase_emfs(const sim_plant_t *p, double e[3])
{
    double we = (double)p->m.pole_pairs * p->s.omega_m;
    double th = p->s.theta_e;
    e[0] = -we * p->m.psi_vs * sin(th);
    e[1] = -we * p->m.psi_vs * sin(th - 2.0 * M_PI / 3.0);
    e[2] = -we * p->m.psi_vs * sin(th + 2.0 * M_PI / 3.0);
}

static double clamp_rail(double v, double vbus, bool *hit)
{
    if (v > vbus) {
        *hit = true;
        return vbus;
    }
    if (v < 0.0) {
        *hit = true;
        return 0.0;
    }
    *hit = false;
    return v;
}

/* Forces the floating phases' currents to zero (the other two carry +-i). */
static void zero_phase(sim_rig_t *r, int fk);

static void project_floating(sim_rig_t *r)
{
    int nf = 0, k, fk = -1;
    for (k = 0; k < 3; k++) {
        if (r->floating[k]) {
            nf++;
            fk = k;
        }
    }
    if (nf == 0) {
        return;
    }
    if (nf >= 2) {
        r->plant.s.id = 0.0;
        r->plant.s.iq = 0.0;
        r->floating[0] = r->floating[1] = r->floating[2] = true;
        return;
    }
    zero_phase(r, fk);
}

/* The plant's current of phase fk forced to zero, the other two keeping
 * their difference: a floating phase (outputs off) or a cut lead. */
static void zero_phase(sim_rig_t *r, int fk)
{
    double i[3];
    sim_plant_currents(&r->plant, &i[0], &i[1], &i[2]);
    {
        int j = (fk + 1) % 3, l = (fk + 2) % 3;
        double ij = 0.5 * (i[j] - i[l]);
        double ial, ibe, cs, sn;
        i[fk] = 0.0;
        i[j] = ij;
        i[l] = -ij;
        ial = i[0];
        ibe = (i[0] + 2.0 * i[1]) / sqrt(3.0);
        cs = cos(r->plant.s.theta_e);
        sn = sin(r->plant.s.theta_e);
        r->plant.s.id = ial * cs + ibe * sn;
        r->plant.s.iq = -ial * sn + ibe * cs;
    }
}

/* One sub-step with all six switches off (note 1); *i_dc the DC current
 * the conducting diodes carried from the bus (negative: into it). */
static void diode_step(sim_rig_t *r, double vbus, double h, double *i_dc)
{
    double i[3], e[3], v[3], inew[3];
    double va, vb;
    bool started[3] = {false, false, false};
    int k, ncond = 0;

    sim_plant_currents(&r->plant, &i[0], &i[1], &i[2]);
    phase_emfs(&r->plant, e);
    for (k = 0; k < 3; k++) {
        if (!r->floating[k]) {
            ncond++;
            v[k] = (i[k] > 0.0) ? 0.0 : vbus;
        }
    }
    if (ncond == 3) {
        /* all pins set by their diodes */
    } else if (ncond == 2) {
        int fk = r->floating[0] ? 0 : (r->floating[1] ? 1 : 2);
        int j = (fk + 1) % 3, l = (fk + 2) % 3;
        double vn = 0.5 * (v[j] + v[l]) - 0.5 * (e[j] + e[l]);
        bool hit;
        v[fk] = clamp_rail(vn + e[fk], vbus, &hit);
        if (hit) {
            r->floating[fk] = false;
            started[fk] = true;
        }
    } else {
        double emax = e[0], emin = e[0], vn;
        bool any = false;
        for (k = 1; k < 3; k++) {
            emax = (e[k] > emax) ? e[k] : emax;
            emin = (e[k] < emin) ? e[k] : emin;
        }
        vn = 0.5 * vbus - 0.5 * (emax + emin);
        for (k = 0; k < 3; k++) {
            bool hit;
            v[k] = clamp_rail(vn + e[k], vbus, &hit);
            if (hit) {
                any = true;
                r->floating[k] = false;
                started[k] = true;
            }
        }
        if (!any) {
            r->floating[0] = r->floating[1] = r->floating[2] = true;
            sim_plant_step(&r->plant, 0.0, 0.0, h, true);
            *i_dc = 0.0;
            return;
        }
    }
    *i_dc = bus_current(v, i, vbus);
    sim_pins_to_ab(v, &va, &vb);
    sim_plant_step(&r->plant, va, vb, h, false);
    sim_plant_currents(&r->plant, &inew[0], &inew[1], &inew[2]);
    for (k = 0; k < 3; k++) {
        if (!r->floating[k] && !started[k] && inew[k] * i[k] <= 0.0) {
            r->floating[k] = true; /* the current died out: its diode blocks */
        }
    }
    project_floating(r);
    if (r->open_lead >= 0) {
        zero_phase(r, r->open_lead);
    }
}

/* One sub-step of h with the outputs on and the pins at v. A cut lead
 * carries no current: the step's current in it is taken away (the
 * constraint as a projection, like a floating phase's). */
static void on_step(sim_rig_t *r, const double v[3], double h)
{
    double va, vb;
    sim_pins_to_ab(v, &va, &vb);
    sim_plant_step(&r->plant, va, vb, h, false);
    if (r->open_lead >= 0) {
        zero_phase(r, r->open_lead);
    }
    r->was_on = true;
}

/* The latched duties from tau0 to tau1 within the period (s), n sub-steps;
 * the period started at t_start (absolute, s). The switching model splits
 * the span at every edge as well, no sub-step longer than the averaged
 * one's (sim_inverter.h). */
static void run_span(sim_rig_t *r, double t_start, double tau0, double tau1, int n)
{
    double h = (tau1 - tau0) / (double)n;
    int s, k;
    if (r->inv.on && r->inv.prm.model == SIM_INV_SWITCHING) {
        double edge[SIM_INV_MAX_EDGES + 1];
        int ne = sim_inverter_edges(&r->inv, tau0, tau1, edge);
        double a = tau0;
        edge[ne] = tau1;
        for (k = 0; k <= ne; k++) {
            double len = edge[k] - a;
            int m = (int)ceil(len / h - 1e-9);
            m = (m < 1) ? 1 : m;
            for (s = 0; s < m; s++) {
                double t = a + len * (double)s / (double)m;
                double vbus = rig_vbus(r, t_start + t + 0.5 * len / (double)m);
                double i[3], v[3];
                sim_plant_currents(&r->plant, &i[0], &i[1], &i[2]);
                sim_inverter_pins_at(&r->inv, vbus, i, t, v);
                on_step(r, v, len / (double)m);
                bus_step(r, t_start + t, bus_current(v, i, vbus), len / (double)m);
            }
            a = edge[k];
        }
        return;
    }
    for (s = 0; s < n; s++) {
        double t = t_start + tau0 + (double)s * h;
        double vbus = rig_vbus(r, t + 0.5 * h);
        double i[3], i_dc;
        sim_plant_currents(&r->plant, &i[0], &i[1], &i[2]);
        if (r->inv.on) {
            double v[3];
            sim_inverter_pins(&r->inv, vbus, i, v);
            on_step(r, v, h);
            i_dc = bus_current(v, i, vbus);
        } else {
            if (r->was_on) {
                for (k = 0; k < 3; k++) {
                    r->floating[k] = (fabs(i[k]) < 1e-9);
                }
                r->was_on = false;
                project_floating(r);
            }
            diode_step(r, vbus, h, &i_dc);
        }
        bus_step(r, t, i_dc, h);
    }
}

void sim_rig_advance(sim_rig_t *r, const uint16_t duty[3], bool on)
{
    /* Sub-steps before and after the boundary in proportion to the two
     * spans, at least one each. */
    double rest = 1.0 - r->sample_at;
    int n1 = r->substeps;
    int n2 = 0;
    if (r->sample_at > 0.0) {
        n1 = (int)lround((double)r->substeps * rest);
        n1 = (n1 < 1) ? 1 : ((n1 > r->substeps - 1) ? r->substeps - 1 : n1);
        n2 = r->substeps - n1;
    }
    run_span(r, r->t, r->sample_at * r->ts, r->ts, n1);
    sim_inverter_latch(&r->inv, duty, on);
    if (n2 > 0) {
        run_span(r, r->t + r->ts, 0.0, r->sample_at * r->ts, n2);
    }
    if (r->pot_rate > 0.0) {
        double step = r->pot_rate * r->ts;
        if (fabs(r->pot_target - r->pot) <= step) {
            r->pot = r->pot_target;
            r->pot_rate = 0.0;
        } else {
            r->pot += (r->pot_target > r->pot) ? step : -step;
        }
    }
    r->t += r->ts;
    r->period++;
}

static double clamp01(double x)
{
    return (x < 0.0) ? 0.0 : ((x > 1.0) ? 1.0 : x);
}

bool sim_rig_apply(sim_rig_t *r, const sim_event_t *ev)
{
    switch (ev->kind) {
        case SIM_EV_POT:
            r->pot = clamp01(ev->v1);
            r->pot_rate = 0.0;
            return true;
        case SIM_EV_POT_RAMP:
            r->pot_target = clamp01(ev->v1);
            if (ev->v2 > 0.0) {
                r->pot_rate = fabs(r->pot_target - r->pot) / ev->v2;
            }
            if (ev->v2 <= 0.0 || r->pot_rate <= 0.0) {
                r->pot = r->pot_target;
                r->pot_rate = 0.0;
            }
            return true;
        case SIM_EV_LOAD:
            r->plant.load.passive_nm = fabs(ev->v1);
            return true;
        case SIM_EV_LOAD_ACTIVE:
            r->plant.load.active_nm = ev->v1;
            return true;
        case SIM_EV_LOAD_FAN:
            r->plant.load.fan_k =
                (r->fan_rated_w > 0.0) ? fabs(ev->v1) / (r->fan_rated_w * r->fan_rated_w) : 0.0;
            return true;
        case SIM_EV_VBUS:
            r->inv.prm.vbus_v = ev->v1;
            return true;
        case SIM_EV_VBUS_RIPPLE:
            r->inv.prm.ripple_v = ev->v1;
            r->inv.prm.ripple_hz = ev->v2;
            return true;
        case SIM_EV_LOCK_ROTOR:
            r->plant.s.locked = true;
            r->plant.s.omega_m = 0.0;
            return true;
        case SIM_EV_OPEN_LEAD:
            r->open_lead = (int)ev->v1;
            zero_phase(r, r->open_lead);
            return true;
        case SIM_EV_CLOSE_LEAD:
            r->open_lead = -1;
            return true;
        case SIM_EV_UNLOCK_ROTOR:
            r->plant.s.locked = false;
            r->plant.s.stuck = true;
            return true;
        case SIM_EV_CURRENT_SPIKE:
            r->spike_a = ev->v1;
            r->spike_left = (ev->v2 >= 1.0) ? (long)ev->v2 : 1;
            return true;
        case SIM_EV_DEADTIME:
            r->inv.prm.deadtime_s = ev->v1 * 1e-6;
            return true;
        case SIM_EV_INVERTER:
            r->inv.prm.model = (int)ev->v1;
            return true;
        case SIM_EV_DEADTIME_SHAPE:
            r->inv.prm.dt_shape = (int)ev->v1;
            return true;
        case SIM_EV_NOISE:
            r->adc.prm.noise_codes = ev->v1;
            return true;
        case SIM_EV_SENSOR_STUCK:
            r->sensor[(ev->v1 > 0.5) ? 1 : 0].mode = SIM_SENSOR_STUCK;
            r->sensor[(ev->v1 > 0.5) ? 1 : 0].stuck_a = ev->v2;
            return true;
        case SIM_EV_SENSOR_OPEN:
            r->sensor[(ev->v1 > 0.5) ? 1 : 0].mode = SIM_SENSOR_OPEN;
            return true;
        case SIM_EV_SENSOR_GAIN:
            r->sensor[(ev->v1 > 0.5) ? 1 : 0].gain = ev->v2;
            return true;
        case SIM_EV_SENSOR_DRIFT: {
            sim_sensor_t *s = &r->sensor[(ev->v1 > 0.5) ? 1 : 0];
            /* the offset built up so far is kept (a rate of 0 holds it) */
            s->drift_a += s->drift_a_s * (r->t - s->drift_t0_s);
            s->drift_a_s = ev->v2;
            s->drift_t0_s = r->t;
            return true;
        }
        case SIM_EV_SENSOR_OK: {
            sim_sensor_t *s = &r->sensor[(ev->v1 > 0.5) ? 1 : 0];
            s->mode = SIM_SENSOR_OK;
            s->gain = 1.0;
            s->drift_a_s = 0.0;
            s->drift_a = 0.0;
            return true;
        }
        default:
            return false;
    }
}

/*
 * Notes
 * 1. Outputs off. A phase whose current is non-zero conducts through the
 *    diode of the rail its current flows into (current into the motor comes
 *    from the negative rail's diode: pin at 0 V; out of the motor: pin at
 *    Vbus). A phase whose current has reached zero floats: its pin follows its
 *    own back-EMF above the star point (computed from the two conducting
 *    phases), until that would pass a rail, when its diode starts to conduct.
 *    With no phase conducting the star point sits mid-way and the stator is
 *    open until the line-to-line back-EMF exceeds the bus (the uncontrolled
 *    rectifier then brakes the motor). Zero crossings are caught at the end of
 *    a sub-step and the crossing current is projected to zero; the error is one
 *    sub-step of di/dt, which decays with the rest of the current.
 */
