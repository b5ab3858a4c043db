/* sim_profiles.h - simulated motors and boards (physical parameters, by name). */
#ifndef SIM_PROFILES_H
#define SIM_PROFILES_H

#include "sim_plant.h"

typedef struct {
    const char *name;  /* as given to MOTOR= */
    const char *alias; /* second accepted name, may be NULL */
    const char *desc;
    double rs_ohm, l_h; /* per phase; Ld = Lq = l_h (surface magnets) */
    double ke_ll;       /* peak line-to-line V per 1000 rpm */
    int pole_pairs;
    double j_kgm2, b_nms, coulomb_nm; /* assumed, see docs/sim.md */
    double rated_a;                   /* rated phase current, A peak */
    double rated_rpm;                 /* rated (nominal) speed, rpm */
    double max_rpm;                   /* top speed with field weakening, rpm */
} sim_motor_profile_t;

typedef struct {
    const char *name;
    const char *desc;
    double vbus_v;     /* nominal DC bus, V */
    double deadtime_s; /* inverter dead time, s */
    double pwm_hz;     /* PWM frequency, Hz (default when the core gives none) */
    double i_fs_a;     /* current ADC full scale, A (overridden by the core's macro) */
    double vbus_fs_v;  /* bus ADC full scale, V (overridden by the core's macro) */
    double offset_a_codes, offset_b_codes; /* amplifier offsets, ADC codes */
    double noise_codes;                    /* ADC noise sigma, codes */
    double amp_tau_s; /* current amplifier's time constant, s (sim_rig.h: the shunt window) */
} sim_board_profile_t;

/* NULL when the name is unknown. */
const sim_motor_profile_t *sim_motor_profile(const char *name);
const sim_board_profile_t *sim_board_profile(const char *name);

/* Plant parameters of a profile (psi from ke_ll). */
void sim_motor_params_from_profile(const sim_motor_profile_t *mp, sim_motor_params_t *m);

/* Rated torque 3/2 p psi I_rated, N m. */
double sim_motor_rated_torque(const sim_motor_profile_t *mp);

/* Lists the profile names to a stream-like callback-free string (static). */
const char *sim_profiles_list(void);

#endif /* SIM_PROFILES_H */
