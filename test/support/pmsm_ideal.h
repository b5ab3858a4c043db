/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* pmsm_ideal.h - ideal PMSM and sensored drive in double precision: what an estimator sees. */
#ifndef PMSM_IDEAL_H
#define PMSM_IDEAL_H

#include <stdint.h>

#include "frames.h"

/*
 * The plant: per-phase R, L and a sinusoidal back-EMF in the stationary frame,
 *
 *   L di/dt = v - R i - e,   e = j omega psi exp(j theta)    (alpha + j beta)
 *
 * (the back-EMF leads the rotor flux psi exp(j theta) by 90 degrees). The
 * current is integrated exactly for a piecewise-constant voltage over
 * PMSM_SUBSTEPS sub-steps per PWM period (closed form, speed constant within
 * a sub-step, the angle following the speed profile exactly).
 *
 * The drive: an ideal sensored current controller that knows the rotor angle
 * and the motor. At sample n (instant t_n) it computes the voltage applied
 * over [t_(n+1), t_(n+2)] (the one-period delay of a real PWM update) so that
 * the current reaches (id + j iq) exp(j theta) at t_(n+2); id = 0 unless the
 * steady-state voltage would exceed v_limit_frac * V_FS, then the smallest
 * negative id (field weakening) that keeps it there. The commanded voltage is
 * limited to |v| <= V_FS.
 *
 * What the estimator is fed at sample n (pmsm_ideal_step):
 *   i_meas   the current at t_n in Q15 of I_FS, plus optional Gaussian noise
 *            (noise_lsb), rounded to the ADC grid (adc_lsb counts of Q15 per
 *            ADC step, e.g. 64 for a 10-bit ADC; 1 = plain Q15 rounding);
 *   v_fed    the command that was applied over [t_(n-1), t_n], Q15 of V_FS
 *            (with feed_applied: that command plus the period's mean
 *            dead-time error, i.e. the voltage really applied).
 * The plant itself receives the command plus the dead-time-like error:
 * each phase voltage is reduced by deadtime_frac * vbus_v in the direction
 * of that phase's current (v_k -= deadtime_frac * Vbus * sign(i_k)).
 */

#define PMSM_SUBSTEPS 4

typedef struct {
    double r_ohm;  /* per phase */
    double l_h;    /* per phase */
    double psi_vs; /* flux linkage: phase peak back-EMF (V) per electrical rad/s */
    int pole_pairs;
} pmsm_motor_t;

typedef struct {
    double ts_s;          /* PWM period */
    double v_fs_v;        /* voltage full scale (phase peak) */
    double i_fs_a;        /* current full scale */
    double iq_a;          /* torque current reference (A) */
    double v_limit_frac;  /* field weakening keeps |v| <= this * V_FS (e.g. 0.9) */
    double noise_lsb;     /* std of ADC noise per current, Q15 LSB (0 = none) */
    int adc_lsb;          /* quantisation step in Q15 LSB (1 = Q15 rounding) */
    double vbus_v;        /* DC bus (for the dead-time error) */
    double deadtime_frac; /* dead time / PWM period (0 = none) */
    uint32_t seed;        /* noise PRNG seed, non-zero */
    int feed_applied;     /* 1: v_fed is the voltage actually applied (command + dead-time error) */
} pmsm_drive_t;

typedef struct {
    pmsm_motor_t m;
    pmsm_drive_t d;
    double i_re, i_im;           /* current at the present instant, A */
    double theta;                /* electrical angle, rad (unwrapped) */
    double omega;                /* electrical speed, rad/s */
    double omega_target;         /* ramp end point, rad/s */
    double accel;                /* |d omega / dt|, electrical rad/s^2 (0 = step) */
    double v_now_re, v_now_im;   /* command applied over the present period, V */
    double v_prev_re, v_prev_im; /* v_fed: last command (+ dead-time error, feed_applied), V */
    double id_a;                 /* the d current reference in use (field weakening) */
    double theta_sample;         /* angle at the last sample instant, rad */
    double omega_sample;         /* speed at the last sample instant, rad/s */
    uint32_t rng;
    long n;
} pmsm_ideal_t;

/* Motor from catalogue data: Ke in V peak line-to-line per 1000 rpm. */
pmsm_motor_t pmsm_motor_from_ke(double r_ohm, double l_h, double ke_vpk_ll_per_krpm,
                                int pole_pairs);

/* Start at rpm0 (mechanical), angle theta0 (electrical rad), at the steady
 * state of the drive (current on its reference, commands settled). */
void pmsm_ideal_init(pmsm_ideal_t *s, const pmsm_motor_t *m, const pmsm_drive_t *d, double rpm0,
                     double theta0);

/* Speed profile: move towards rpm (mechanical) at rpm_per_s (0 = at once). */
void pmsm_ideal_set_speed(pmsm_ideal_t *s, double rpm, double rpm_per_s);

/* One PWM period: returns the sample at t_n (i_meas) and the command that
 * was applied over [t_(n-1), t_n] (v_fed), then advances the plant to
 * t_(n+1). pmsm_ideal_theta()/pmsm_ideal_rpm() refer to t_n afterwards. */
void pmsm_ideal_step(pmsm_ideal_t *s, ab_q15_t *i_meas, ab_q15_t *v_fed);

/* Rotor electrical angle at the last sample instant, rad in [-pi, pi). */
double pmsm_ideal_theta(const pmsm_ideal_t *s);
/* Mechanical speed at the last sample instant, rpm. */
double pmsm_ideal_rpm(const pmsm_ideal_t *s);
/* Electrical frequency at the last sample instant, Hz (signed). */
double pmsm_ideal_freq_hz(const pmsm_ideal_t *s);

#endif /* PMSM_IDEAL_H */
