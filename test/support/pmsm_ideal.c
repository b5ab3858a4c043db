/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* pmsm_ideal.c - ideal PMSM and sensored drive in double precision: what an estimator sees. */
#include "test_support.h"

#include <math.h>
#include <stddef.h>

#include "pmsm_ideal.h"

/* ---- small complex helpers (C99 without <complex.h>, to stay plain) ------- */

typedef struct {
    double re, im;
} cplx_t;

static cplx_t c_make(double re, double im)
{
    cplx_t c;
    c.re = re;
    c.im = im;
    return c;
}
static cplx_t c_add(cplx_t a, cplx_t b)
{
    return c_make(a.re + b.re, a.im + b.im);
}
static cplx_t c_sub(cplx_t a, cplx_t b)
{
    return c_make(a.re - b.re, a.im - b.im);
}
static cplx_t c_mul(cplx_t a, cplx_t b)
{
    return c_make(a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re);
}
static cplx_t c_scale(cplx_t a, double k)
{
    return c_make(a.re * k, a.im * k);
}
static cplx_t c_div(cplx_t a, cplx_t b)
{
    double d = b.re * b.re + b.im * b.im;
    return c_make((a.re * b.re + a.im * b.im) / d, (a.im * b.re - a.re * b.im) / d);
}
static cplx_t c_expj(double x)
{
    return c_make(cos(x), sin(x));
}
static double c_abs(cplx_t a)
{
    return sqrt(a.re * a.re + a.im * a.im);
}

/* ---- Gaussian noise (test_support's xorshift32, state per instance) ------- */

static double rng_uniform(uint32_t *st)
{
    return ((double)test_rand_u32(st) + 0.5) / 4294967296.0;
}

static double rng_gauss(uint32_t *st)
{
    double u1 = rng_uniform(st);
    double u2 = rng_uniform(st);
    return sqrt(-2.0 * log(u1)) * cos(2.0 * M_PI * u2);
}

/* ---- plant ------------------------------------------------------------- */

pmsm_motor_t pmsm_motor_from_ke(double r_ohm, double l_h, double ke_vpk_ll_per_krpm, int pole_pairs)
{
    pmsm_motor_t m;
    double w_e = 1000.0 / 60.0 * 2.0 * M_PI * (double)pole_pairs; /* rad/s at 1000 rpm */
    m.r_ohm = r_ohm;
    m.l_h = l_h;
    m.psi_vs = ke_vpk_ll_per_krpm / sqrt(3.0) / w_e;
    m.pole_pairs = pole_pairs;
    return m;
}

/* Speed after dt along the profile. */
static double profile_speed(const pmsm_ideal_t *s, double w0, double dt)
{
    double w;
    if (s->accel <= 0.0) {
        return s->omega_target;
    }
    if (w0 < s->omega_target) {
        w = w0 + s->accel * dt;
        return (w > s->omega_target) ? s->omega_target : w;
    }
    w = w0 - s->accel * dt;
    return (w < s->omega_target) ? s->omega_target : w;
}

/* Dead-time-like voltage error for the current i (alpha/beta, V). */
static cplx_t deadtime_error(const pmsm_ideal_t *s, cplx_t i)
{
    double dv = s->d.deadtime_frac * s->d.vbus_v;
    double ia = i.re;
    double ib = -0.5 * i.re + 0.5 * sqrt(3.0) * i.im;
    double ic = -0.5 * i.re - 0.5 * sqrt(3.0) * i.im;
    double va = (ia > 0.0) ? -dv : (ia < 0.0) ? dv : 0.0;
    double vb = (ib > 0.0) ? -dv : (ib < 0.0) ? dv : 0.0;
    double vc = (ic > 0.0) ? -dv : (ic < 0.0) ? dv : 0.0;
    if (dv == 0.0) {
        return c_make(0.0, 0.0);
    }
    return c_make((2.0 / 3.0) * (va - 0.5 * vb - 0.5 * vc), (vb - vc) / sqrt(3.0));
}

/*
 * Advance (i, theta, omega) over one PWM period under the voltage v, exactly
 * per sub-step: with a = R/L and the speed w held at the sub-step's mid
 * value, theta(t) = th0 + w t,
 *   i(h) = e^(-a h) i0 + (1 - e^(-a h)) / R v
 *          - (j w psi / L) e^(j th0) (e^(j w h) - e^(-a h)) / (a + j w).
 * th0 is chosen so the linearised angle equals the exact one (speed ramp) at
 * the sub-step's midpoint. With dead_time the voltage error is evaluated from
 * the current at each sub-step's start.
 */
static void advance(const pmsm_ideal_t *s, cplx_t *i, double *theta, double *omega, cplx_t v,
                    int dead_time, cplx_t *dv_avg)
{
    const double h = s->d.ts_s / (double)PMSM_SUBSTEPS;
    const double a = s->m.r_ohm / s->m.l_h;
    const double ea = exp(-a * h);
    int k;
    for (k = 0; k < PMSM_SUBSTEPS; k++) {
        double w0 = *omega;
        double wmid = profile_speed(s, w0, 0.5 * h);
        double w1 = profile_speed(s, w0, h);
        double thmid = *theta + 0.5 * h * 0.5 * (w0 + wmid);
        double th0 = thmid - 0.5 * h * wmid;
        cplx_t vk = v;
        cplx_t emf;
        cplx_t term;
        if (dead_time) {
            cplx_t dv = deadtime_error(s, *i);
            vk = c_add(vk, dv);
            if (dv_avg != NULL) {
                *dv_avg = c_add(*dv_avg, c_scale(dv, 1.0 / (double)PMSM_SUBSTEPS));
            }
        }
        term = c_div(c_sub(c_expj(wmid * h), c_make(ea, 0.0)), c_make(a, wmid));
        emf = c_mul(c_mul(c_make(0.0, wmid * s->m.psi_vs / s->m.l_h), c_expj(th0)), term);
        *i = c_sub(c_add(c_scale(*i, ea), c_scale(vk, (1.0 - ea) / s->m.r_ohm)), emf);
        *theta = thmid + 0.5 * h * 0.5 * (wmid + w1);
        *omega = w1;
    }
}

/* The d-current reference at speed w: 0, or the smallest negative value that
 * keeps the steady-state voltage inside v_limit_frac * V_FS. */
static double fw_id(const pmsm_ideal_t *s, double w, double iq)
{
    double vlim = s->d.v_limit_frac * s->d.v_fs_v;
    double wl = w * s->m.l_h;
    /* |v| is smallest at id* = -w L e / (R^2 + (w L)^2) (e = w psi); search
     * between id* and 0, where |v| is monotonic. */
    double lo = -wl * w * s->m.psi_vs / (s->m.r_ohm * s->m.r_ohm + wl * wl);
    double hi = 0.0;
    int it;
#define VMAG(id)                                                                                   \
    hypot(s->m.r_ohm *(id)-w * s->m.l_h * iq,                                                      \
          s->m.r_ohm * iq + w * s->m.l_h * (id) + w * s->m.psi_vs)
    if (VMAG(0.0) <= vlim) {
        return 0.0;
    }
    if (VMAG(lo) > vlim) {
        return lo;
    }
    for (it = 0; it < 60; it++) {
        double mid = 0.5 * (lo + hi);
        if (VMAG(mid) > vlim) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
#undef VMAG
    return lo;
}

/* The drive: at t_n, with v_now applied over [t_n, t_(n+1)], choose the
 * command over [t_(n+1), t_(n+2)] that puts the current on its reference at
 * t_(n+2) (the model is exact; the dead-time error is unknown to it). */
static cplx_t drive_command(pmsm_ideal_t *s, cplx_t v_now)
{
    cplx_t i = c_make(s->i_re, s->i_im);
    double th = s->theta;
    double w = s->omega;
    double a = s->m.r_ohm / s->m.l_h;
    double gam = (1.0 - exp(-a * s->d.ts_s)) / s->m.r_ohm;
    double iq = (w < 0.0) ? -s->d.iq_a : s->d.iq_a;
    cplx_t iref;
    cplx_t v;
    double mag;
    advance(s, &i, &th, &w, v_now, 0, NULL);
    advance(s, &i, &th, &w, c_make(0.0, 0.0), 0, NULL); /* zero-input response */
    s->id_a = fw_id(s, w, iq);
    iref = c_mul(c_make(s->id_a, iq), c_expj(th));
    v = c_scale(c_sub(iref, i), 1.0 / gam);
    mag = c_abs(v);
    if (mag > s->d.v_fs_v) {
        v = c_scale(v, s->d.v_fs_v / mag);
    }
    return v;
}

static void ideal_period(pmsm_ideal_t *s)
{
    cplx_t i = c_make(s->i_re, s->i_im);
    cplx_t v_now = c_make(s->v_now_re, s->v_now_im);
    cplx_t v_next = drive_command(s, v_now);
    cplx_t dv = c_make(0.0, 0.0);
    advance(s, &i, &s->theta, &s->omega, v_now, s->d.deadtime_frac > 0.0, &dv);
    s->i_re = i.re;
    s->i_im = i.im;
    /* What the estimator is fed: the command, or (feed_applied) the voltage
     * the inverter actually applied, i.e. a perfect dead-time compensation
     * of the estimator input. */
    s->v_prev_re = v_now.re + (s->d.feed_applied ? dv.re : 0.0);
    s->v_prev_im = v_now.im + (s->d.feed_applied ? dv.im : 0.0);
    s->v_now_re = v_next.re;
    s->v_now_im = v_next.im;
    s->n++;
}

void pmsm_ideal_init(pmsm_ideal_t *s, const pmsm_motor_t *m, const pmsm_drive_t *d, double rpm0,
                     double theta0)
{
    int k;
    double w = rpm0 / 60.0 * 2.0 * M_PI * (double)m->pole_pairs;
    s->m = *m;
    s->d = *d;
    if (s->d.adc_lsb < 1) {
        s->d.adc_lsb = 1;
    }
    s->theta = theta0;
    s->omega = w;
    s->omega_target = w;
    s->accel = 0.0;
    s->i_re = 0.0;
    s->i_im = 0.0;
    s->v_now_re = 0.0;
    s->v_now_im = 0.0;
    s->v_prev_re = 0.0;
    s->v_prev_im = 0.0;
    s->id_a = 0.0;
    s->rng = (d->seed != 0U) ? d->seed : 0x2545F491UL;
    s->n = 0;
    /* Settle the drive (the deadbeat loop needs two periods; a few more for
     * the transient of the initial zero current). */
    for (k = 0; k < 64; k++) {
        ideal_period(s);
    }
    s->theta_sample = s->theta;
    s->omega_sample = s->omega;
}

void pmsm_ideal_set_speed(pmsm_ideal_t *s, double rpm, double rpm_per_s)
{
    double pp = (double)s->m.pole_pairs;
    s->omega_target = rpm / 60.0 * 2.0 * M_PI * pp;
    s->accel = rpm_per_s / 60.0 * 2.0 * M_PI * pp;
}

/* An integral value in double, clamped to the q15 range. */
static q15_t q15_of_integral(double x)
{
    if (x > 32767.0) {
        x = 32767.0;
    }
    if (x < -32768.0) {
        x = -32768.0;
    }
    return (q15_t)x;
}

static q15_t adc_quantise(pmsm_ideal_t *s, double amps)
{
    double x = amps / s->d.i_fs_a * 32768.0;
    double step = (double)s->d.adc_lsb;
    if (s->d.noise_lsb > 0.0) {
        x += s->d.noise_lsb * rng_gauss(&s->rng);
    }
    return q15_of_integral(floor(x / step + 0.5) * step);
}

static q15_t volt_q15(const pmsm_ideal_t *s, double volts)
{
    return q15_of_integral(floor(volts / s->d.v_fs_v * 32768.0 + 0.5));
}

void pmsm_ideal_step(pmsm_ideal_t *s, ab_q15_t *i_meas, ab_q15_t *v_fed)
{
    s->theta_sample = s->theta;
    s->omega_sample = s->omega;
    i_meas->alpha = adc_quantise(s, s->i_re);
    i_meas->beta = adc_quantise(s, s->i_im);
    v_fed->alpha = volt_q15(s, s->v_prev_re);
    v_fed->beta = volt_q15(s, s->v_prev_im);
    ideal_period(s);
}

double pmsm_ideal_theta(const pmsm_ideal_t *s)
{
    double t = fmod(s->theta_sample + M_PI, 2.0 * M_PI);
    if (t < 0.0) {
        t += 2.0 * M_PI;
    }
    return t - M_PI;
}

double pmsm_ideal_rpm(const pmsm_ideal_t *s)
{
    return s->omega_sample / (2.0 * M_PI * (double)s->m.pole_pairs) * 60.0;
}

double pmsm_ideal_freq_hz(const pmsm_ideal_t *s)
{
    return s->omega_sample / (2.0 * M_PI);
}
