/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_profiles.h - the simulated motors and boards, by name. */
#ifndef SIM_PROFILES_H
#define SIM_PROFILES_H

#include "sim_plant.h"

/*
 * Each profile is one small file (sim_motor_<name>.c, sim_board_<name>.c)
 * that reads what the firmware's profile header of the same motor or board
 * holds (firmware/motors/motor_*.h, boards/board_*.h) and states the rest,
 * the plant's own facts that no firmware header has: friction, the rated
 * speed, the amplifiers' offsets and noise. A plant meant to differ from
 * what the firmware believes (a motor measured apart from its profile) is
 * written out in its own file under its own name, not read.
 */
typedef struct {
    const char *name;  /* as given to MOTOR= */
    const char *alias; /* second accepted name, may be NULL */
    const char *desc;
    double rs_ohm, l_h; /* per phase; Ld = Lq = l_h (surface magnets) */
    double ke_ll;       /* peak line-to-line V per 1000 rpm */
    int pole_pairs;
    double j_kgm2;     /* rotor plus coupled load, kg m^2 */
    double b_nms;      /* viscous friction, N m s/rad */
    double coulomb_nm; /* dry friction, N m */
    double rated_a;    /* rated phase current, A peak */
    double rated_rpm;  /* rated speed, rpm (load_fan gives its nominal torque there) */
} sim_motor_profile_t;

typedef struct {
    const char *name;
    double vbus_v;                         /* nominal DC bus, V */
    double deadtime_s;                     /* inverter dead time, s */
    double offset_a_codes, offset_b_codes; /* current amplifiers' offsets, ADC codes */
    double noise_codes;                    /* ADC noise sigma, codes */
    double amp_tau_s;    /* current amplifiers' time constant, s (sim_rig.h: the shunt window) */
    double bus_c_f;      /* the DC bus's bulk capacitance, F (the bus model, sim_rig.h) */
    double supply_r_ohm; /* the supply's output resistance, ohm (it only sources current) */
} sim_board_profile_t;

/* What no board header holds, assumed alike for every board: the current
 * amplifiers' offsets (ADC codes, phases A and B; the core calibrates them),
 * the ADC noise (sigma, codes) and the amplifiers' time constant (s; not
 * published for either board, docs/sim.md: an op-amp stage of about 450 kHz
 * bandwidth, which settles to half an ADC code of a full-scale step in
 * 2.4 us). */
#define SIM_AMP_OFFSET_A_CODES 6.0
#define SIM_AMP_OFFSET_B_CODES (-4.0)
#define SIM_ADC_NOISE_CODES    1.0
#define SIM_AMP_TAU_S          0.35e-6

/* The profiles (one file each). */
extern const sim_motor_profile_t sim_motor_hurst, sim_motor_hurst300, sim_motor_hispeed,
    sim_motor_lowl;
extern const sim_board_profile_t sim_board_mclv, sim_board_mchv;

/* NULL when the name is unknown. */
const sim_motor_profile_t *sim_motor_profile(const char *name);
const sim_board_profile_t *sim_board_profile(const char *name);

/* Plant parameters of a profile (psi from ke_ll). */
void sim_motor_params_from_profile(const sim_motor_profile_t *mp, sim_motor_params_t *m);

/* Rated torque 3/2 p psi I_rated, N m. */
double sim_motor_rated_torque(const sim_motor_profile_t *mp);

/* The profile names, one line ("motors: hurst (hurst075), ...; boards: ..."). */
const char *sim_profiles_list(void);

#endif /* SIM_PROFILES_H */
