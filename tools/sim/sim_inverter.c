/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_inverter.c - inverter: duty to pin voltage (averaged or per edge), dead time, bus ripple. */
#include "sim_inverter.h"

#include <math.h>
#include <stdbool.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

const sim_word_t sim_inverter_models[] = {
    {"averaged", (double)SIM_INV_AVERAGED},
    {"switching", (double)SIM_INV_SWITCHING},
    {NULL, 0.0},
};

const sim_word_t sim_inverter_shapes[] = {
    {"linear", (double)SIM_DT_LINEAR},
    {"hard", (double)SIM_DT_HARD},
    {"ripple", (double)SIM_DT_RIPPLE},
    {NULL, 0.0},
};

void sim_inverter_init(sim_inverter_t *inv, const sim_inverter_params_t *prm, double l_h)
{
    inv->prm = *prm;
    inv->i_band_a = prm->i_band_a;
    if (inv->i_band_a <= 0.0) {
        inv->i_band_a = prm->vbus_v / (12.0 * l_h * prm->pwm_hz);
        if (inv->i_band_a < 1e-3) {
            inv->i_band_a = 1e-3;
        }
    }
    inv->duty[0] = 0;
    inv->duty[1] = 0;
    inv->duty[2] = 0;
    inv->on = false;
}

void sim_inverter_latch(sim_inverter_t *inv, const uint16_t duty[3], bool on)
{
    inv->duty[0] = duty[0];
    inv->duty[1] = duty[1];
    inv->duty[2] = duty[2];
    inv->on = on;
}

double sim_inverter_vbus(const sim_inverter_t *inv, double t_s)
{
    double v = inv->prm.vbus_v;
    if (inv->prm.ripple_v != 0.0) {
        v += inv->prm.ripple_v * sin(2.0 * M_PI * inv->prm.ripple_hz * t_s);
    }
    return (v > 0.0) ? v : 0.0;
}

void sim_inverter_pins(const sim_inverter_t *inv, double vbus, const double i_abc[3],
                       double v_pin[3])
{
    double td_frac = inv->prm.deadtime_s * inv->prm.pwm_hz;
    int k;
    for (k = 0; k < 3; k++) {
        double d = (double)inv->duty[k] / inv->prm.duty_max;
        if (d <= 0.0) {
            v_pin[k] = 0.0;
        } else if (d >= 1.0) {
            v_pin[k] = vbus;
        } else {
            double s = i_abc[k] / inv->i_band_a;
            if (s > 1.0) {
                s = 1.0;
            } else if (s < -1.0) {
                s = -1.0;
            }
            if (inv->prm.dt_shape == SIM_DT_HARD) {
                s = (i_abc[k] > 0.0) ? 1.0 : ((i_abc[k] < 0.0) ? -1.0 : 0.0);
            } else if (inv->prm.dt_shape == SIM_DT_RIPPLE) {
                s = asin(s) * (2.0 / M_PI);
            }
            /* Current out of the pin (s > 0): the low-side diode carries it
             * during the dead time, so the pin loses Td/Ts of Vbus. */
            d -= td_frac * s;
            if (d < 0.0) {
                d = 0.0;
            } else if (d > 1.0) {
                d = 1.0;
            }
            v_pin[k] = d * vbus;
        }
    }
}

/* Phase k's half-duty time h = d Ts / 2, s; < 0 for duty 0 (low side on
 * all period), > Ts / 2 for 100 % (high side on all period). */
static double half_on(const sim_inverter_t *inv, int k)
{
    double ts = 1.0 / inv->prm.pwm_hz;
    if (inv->duty[k] == 0U) {
        return -1.0;
    }
    if ((double)inv->duty[k] >= inv->prm.duty_max) {
        return ts;
    }
    return 0.5 * ((double)inv->duty[k] / inv->prm.duty_max) * ts;
}

int sim_inverter_edges(const sim_inverter_t *inv, double t0, double t1, double edge[])
{
    double ts = 1.0 / inv->prm.pwm_hz;
    double td = inv->prm.deadtime_s;
    int n = 0, k, a, b;
    for (k = 0; k < 3; k++) {
        double h = half_on(inv, k);
        double e[5];
        if (h < 0.0 || h >= 0.5 * ts) {
            continue; /* no edge */
        }
        e[0] = td - h;      /* high on, carried from the previous period's end */
        e[1] = h;           /* high off */
        e[2] = h + td;      /* low on */
        e[3] = ts - h;      /* low off */
        e[4] = ts - h + td; /* high on */
        for (a = 0; a < 5; a++) {
            if (e[a] > t0 && e[a] < t1 && n < SIM_INV_MAX_EDGES) {
                edge[n++] = e[a];
            }
        }
    }
    for (a = 1; a < n; a++) { /* insertion sort: at most 15 */
        double x = edge[a];
        for (b = a - 1; b >= 0 && edge[b] > x; b--) {
            edge[b + 1] = edge[b];
        }
        edge[b + 1] = x;
    }
    return n;
}

void sim_inverter_pins_at(const sim_inverter_t *inv, double vbus, const double i_abc[3], double t,
                          double v_pin[3])
{
    double ts = 1.0 / inv->prm.pwm_hz;
    double td = inv->prm.deadtime_s;
    double ron = inv->prm.r_on_ohm;
    int k;
    for (k = 0; k < 3; k++) {
        double h = half_on(inv, k);
        double i = i_abc[k];
        bool hi, lo;
        if (h < 0.0) {
            hi = false;
            lo = true;
        } else if (h >= 0.5 * ts) {
            hi = true;
            lo = false;
        } else {
            hi = (t >= td - h && t < h) || t >= ts - h + td;
            lo = t >= h + td && t < ts - h;
        }
        if (hi) {
            v_pin[k] = vbus - i * ron;
        } else if (lo) {
            v_pin[k] = -i * ron;
        } else if (i >= 0.0) {
            v_pin[k] = -inv->prm.v_diode_v; /* into the motor: the low diode */
        } else {
            v_pin[k] = vbus + inv->prm.v_diode_v;
        }
    }
}

double sim_inverter_low_conduction(const sim_inverter_t *inv, int k, double t, double i)
{
    double ts = 1.0 / inv->prm.pwm_hz;
    double h = half_on(inv, k);
    double on;
    if (h < 0.0) {
        return ts; /* no edge: the low side conducts all period */
    }
    if (h >= 0.5 * ts || t < h || t >= ts - h) {
        return 0.0; /* the high switch or its dead time before: not the low leg */
    }
    on = t - h - ((i >= 0.0) ? 0.0 : inv->prm.deadtime_s);
    return (on > 0.0) ? on : 0.0;
}

void sim_pins_to_ab(const double v_pin[3], double *v_alpha, double *v_beta)
{
    double vn = (v_pin[0] + v_pin[1] + v_pin[2]) / 3.0;
    *v_alpha = v_pin[0] - vn;
    *v_beta = (v_pin[1] - v_pin[2]) / sqrt(3.0);
}

/*
 * Notes
 * 1. The band: a phase current smaller than the PWM ripple around it reverses
 *    inside each period, so the dead-time interval is spent partly on either
 *    diode and the mean error is proportional to the mean current. The peak
 *    ripple of one phase is about Vbus Ts / (8 L) at 50 % duty; a band of
 *    Vbus / (12 L fpwm) is about two thirds of it (space-vector modulation
 *    shares the ripple between phases). It also keeps the explicit treatment
 *    stable: the band acts as a resistance Td/Ts Vbus / i_band whose time
 *    constant is >= 2 sub-steps for any motor as long as N >= 1.
 * 2. The shapes bracket what an averaged model can say about a current near
 *    zero: HARD is a current without ripple (the error at full size until
 *    the current reverses), LINEAR a triangular ripple of peak i_band (the
 *    mean of sign(i + u), u uniform in +-i_band), RIPPLE a sinusoidal one.
 *    HARD is also the stiffest: its error jumps by 2 Td/Ts Vbus when the
 *    current crosses zero, which the explicit sub-steps resolve only to
 *    one sub-step (the current chatters about zero, as on a real inverter).
 */
