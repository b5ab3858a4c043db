/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_plant.h - PMSM in the rotor (d-q) frame with its mechanics, double precision. */
#ifndef SIM_PLANT_H
#define SIM_PLANT_H

#include <stdbool.h>

/*
 * Model (amplitude-invariant Clarke/Park, so the d-q currents are phase peak
 * amperes and the flux linkage is the peak phase flux):
 *
 *   vd = R id + Ld did/dt - we Lq iq
 *   vq = R iq + Lq diq/dt + we (Ld id + psi)
 *   Te = 3/2 p (psi iq + (Ld - Lq) id iq)                      [N m]
 *   J dwm/dt = Te - B wm - Tfan(wm) - Tactive - Tpassive        [N m]
 *   dtheta_e/dt = we = p wm
 *
 * theta_e is the angle of the d axis (rotor north) from the phase-A axis;
 * positive rotation goes a -> b -> c. Tfan = k_fan wm |wm|. The passive part
 * (Coulomb friction plus a brake-like load) opposes the motion and, at rest,
 * holds the rotor against any net torque smaller than itself (stick-slip,
 * see note 1 in sim_plant.c). Tactive is a signed constant torque that can
 * drive the rotor backwards.
 *
 * The stator voltages are given in the stationary alpha-beta frame, held
 * constant over one call of sim_plant_step(), which integrates with one
 * classical fourth-order Runge-Kutta step (the caller sub-steps).
 */

typedef struct {
    double rs_ohm;     /* phase resistance, ohm */
    double ld_h, lq_h; /* d and q inductance, H */
    double psi_vs;     /* rotor flux linkage, V s / rad (elec), peak phase */
    int pole_pairs;    /* p */
    double j_kgm2;     /* rotor + coupled load inertia, kg m^2 */
    double b_nms;      /* viscous friction, N m s / rad (mechanical) */
    double coulomb_nm; /* dry friction, N m, opposes motion */
} sim_motor_params_t;

typedef struct {
    double passive_nm; /* brake-like load: opposes motion, holds at rest, N m >= 0 */
    double active_nm;  /* signed constant torque against positive rotation, N m */
    double fan_k;      /* fan load coefficient, N m / (rad/s)^2 (mechanical) */
} sim_load_t;

typedef struct {
    double id, iq;  /* A, rotor frame */
    double omega_m; /* mechanical speed, rad/s */
    double theta_e; /* electrical angle, rad, kept in [-pi, pi) */
    double theta_m; /* mechanical angle, rad, unwrapped (turns counted) */
    bool locked;    /* rotor held at its present angle (locked-rotor fault) */
    bool stuck;     /* at rest, held by the passive torque */
} sim_plant_state_t;

typedef struct {
    sim_motor_params_t m;
    sim_load_t load;
    sim_plant_state_t s;
} sim_plant_t;

/* Rotor at rest at theta_e0 (rad), no current. */
void sim_plant_init(sim_plant_t *p, const sim_motor_params_t *m, double theta_e0);

/* Integrates dt seconds with the stator voltage (v_alpha, v_beta) in V, held
 * constant. When open is true the stator is open-circuited: the currents are
 * zero and only the mechanics move. */
void sim_plant_step(sim_plant_t *p, double v_alpha, double v_beta, double dt, bool open);

/* Phase currents (A, + = into the motor) from the rotor-frame state. */
void sim_plant_currents(const sim_plant_t *p, double *ia, double *ib, double *ic);

/* Electromagnetic torque for the present currents, N m. */
double sim_plant_torque(const sim_plant_t *p);

/* Peak line-to-line back-EMF magnitude at the present speed, V. */
double sim_plant_emf_ll_peak(const sim_plant_t *p);

/* Mechanical speed in rpm. */
double sim_plant_rpm(const sim_plant_t *p);

/* Flux linkage (V s/rad, peak phase) from the catalogue back-EMF constant
 * ke_ll = peak line-to-line volts per 1000 rpm (mechanical). */
double sim_psi_from_ke(double ke_ll_v_per_krpm, int pole_pairs);

/* Wraps an angle to [-pi, pi). */
double sim_wrap_pi(double a);

#endif /* SIM_PLANT_H */
