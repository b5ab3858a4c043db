/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_plant.c - PMSM rotor-frame model, RK4 integration, stick-slip mechanics. */
#include "sim_plant.h"

#include <math.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

typedef struct {
    double id, iq, w, th;
} plant_x_t;

typedef struct {
    const sim_plant_t *p;
    double va, vb; /* alpha-beta voltage, V */
    double dir;    /* -1, 0 (mechanics frozen), +1: sign the passive torque opposes */
    bool mech;     /* integrate the mechanics */
    bool open;     /* open stator: no current */
} plant_ctx_t;

double sim_wrap_pi(double a)
{
    double w = fmod(a + M_PI, 2.0 * M_PI);
    if (w < 0.0) {
        w += 2.0 * M_PI;
    }
    return w - M_PI;
}

double sim_psi_from_ke(double ke_ll_v_per_krpm, int pole_pairs)
{
    /* Peak phase EMF = ke_ll / sqrt(3) at 1000 rpm, where we = 1000 * 2 pi / 60 * p. */
    double we_1000 = 1000.0 * 2.0 * M_PI / 60.0 * (double)pole_pairs;
    return ke_ll_v_per_krpm / sqrt(3.0) / we_1000;
}

static double torque_of(const sim_motor_params_t *m, double id, double iq)
{
    return 1.5 * (double)m->pole_pairs * (m->psi_vs * iq + (m->ld_h - m->lq_h) * id * iq);
}

/* Torques that do not depend on the passive (stick-slip) part, N m. */
static double drive_torque(const sim_plant_t *p, double te, double w)
{
    return te - p->m.b_nms * w - p->load.fan_k * w * fabs(w) - p->load.active_nm;
}

static plant_x_t deriv(const plant_ctx_t *c, plant_x_t x)
{
    const sim_motor_params_t *m = &c->p->m;
    plant_x_t d = {0.0, 0.0, 0.0, 0.0};
    double pp = (double)m->pole_pairs;
    double we = pp * x.w;
    if (!c->open) {
        double cs = cos(x.th);
        double sn = sin(x.th);
        double vd = c->va * cs + c->vb * sn;
        double vq = -c->va * sn + c->vb * cs;
        d.id = (vd - m->rs_ohm * x.id + we * m->lq_h * x.iq) / m->ld_h;
        d.iq = (vq - m->rs_ohm * x.iq - we * (m->ld_h * x.id + m->psi_vs)) / m->lq_h;
    }
    if (c->mech) {
        double te = torque_of(m, x.id, x.iq);
        double tp = m->coulomb_nm + c->p->load.passive_nm;
        d.w = (drive_torque(c->p, te, x.w) - tp * c->dir) / m->j_kgm2;
        d.th = we;
    }
    return d;
}

static plant_x_t axpy(plant_x_t x, double h, plant_x_t k)
{
    plant_x_t r = {x.id + h * k.id, x.iq + h * k.iq, x.w + h * k.w, x.th + h * k.th};
    return r;
}

void sim_plant_init(sim_plant_t *p, const sim_motor_params_t *m, double theta_e0)
{
    p->m = *m;
    p->load.passive_nm = 0.0;
    p->load.active_nm = 0.0;
    p->load.fan_k = 0.0;
    p->s.id = 0.0;
    p->s.iq = 0.0;
    p->s.omega_m = 0.0;
    p->s.theta_e = sim_wrap_pi(theta_e0);
    p->s.theta_m = p->s.theta_e / (double)m->pole_pairs;
    p->s.locked = false;
    p->s.stuck = true;
}

void sim_plant_step(sim_plant_t *p, double v_alpha, double v_beta, double dt, bool open)
{
    plant_ctx_t c;
    plant_x_t x = {p->s.id, p->s.iq, p->s.omega_m, p->s.theta_e};
    plant_x_t k1, k2, k3, k4;
    double tp = p->m.coulomb_nm + p->load.passive_nm;
    double te0;

    if (open) {
        x.id = 0.0;
        x.iq = 0.0;
    }
    te0 = torque_of(&p->m, x.id, x.iq);
    c.p = p;
    c.va = v_alpha;
    c.vb = v_beta;
    c.open = open;
    c.mech = true;
    c.dir = 0.0;

    /* Note 1: stick-slip. At rest the rotor stays put while the net driving
     * torque is within the passive torque; otherwise the passive torque
     * opposes the direction of motion (or of the breakaway). */
    if (p->s.locked) {
        x.w = 0.0;
        c.mech = false;
    } else if (p->s.stuck || x.w == 0.0) {
        double drive = drive_torque(p, te0, 0.0);
        if (fabs(drive) <= tp) {
            x.w = 0.0;
            c.mech = false;
            p->s.stuck = true;
        } else {
            p->s.stuck = false;
            c.dir = (drive > 0.0) ? 1.0 : -1.0;
        }
    } else {
        c.dir = (x.w > 0.0) ? 1.0 : -1.0;
    }

    k1 = deriv(&c, x);
    k2 = deriv(&c, axpy(x, 0.5 * dt, k1));
    k3 = deriv(&c, axpy(x, 0.5 * dt, k2));
    k4 = deriv(&c, axpy(x, dt, k3));
    x.id += dt / 6.0 * (k1.id + 2.0 * k2.id + 2.0 * k3.id + k4.id);
    x.iq += dt / 6.0 * (k1.iq + 2.0 * k2.iq + 2.0 * k3.iq + k4.iq);
    x.w += dt / 6.0 * (k1.w + 2.0 * k2.w + 2.0 * k3.w + k4.w);
    x.th += dt / 6.0 * (k1.th + 2.0 * k2.th + 2.0 * k3.th + k4.th);

    if (c.mech && x.w * c.dir < 0.0) {
        /* The speed crossed zero inside the step: the passive torque stops it. */
        x.w = 0.0;
        p->s.stuck = true;
    }
    p->s.theta_m += (x.th - p->s.theta_e) / (double)p->m.pole_pairs;
    p->s.id = x.id;
    p->s.iq = x.iq;
    p->s.omega_m = x.w;
    p->s.theta_e = sim_wrap_pi(x.th);
}

void sim_plant_currents(const sim_plant_t *p, double *ia, double *ib, double *ic)
{
    double cs = cos(p->s.theta_e);
    double sn = sin(p->s.theta_e);
    double ial = p->s.id * cs - p->s.iq * sn;
    double ibe = p->s.id * sn + p->s.iq * cs;
    *ia = ial;
    *ib = -0.5 * ial + 0.5 * sqrt(3.0) * ibe;
    *ic = -0.5 * ial - 0.5 * sqrt(3.0) * ibe;
}

double sim_plant_torque(const sim_plant_t *p)
{
    return torque_of(&p->m, p->s.id, p->s.iq);
}

double sim_plant_emf_ll_peak(const sim_plant_t *p)
{
    return sqrt(3.0) * fabs(p->m.psi_vs * (double)p->m.pole_pairs * p->s.omega_m);
}

double sim_plant_rpm(const sim_plant_t *p)
{
    return p->s.omega_m * 60.0 / (2.0 * M_PI);
}
