/* sim_profiles.c - parameter sets of the simulated motors and boards. */
#include "sim_profiles.h"

#include <string.h>

/*
 * Catalogue values are from docs/hardware.md 3.1 (AN1078 UserParms for the
 * Hurst075, Microchip's hurst300.h for the long Hurst). Inertia and friction
 * are not in the motor data sheets. Hurst075: a public MATLAB parameter
 * script for Microchip's low-voltage board gives J = 5.5e-6 kg m^2 and
 * B = 15.3e-6 N m s/rad for the bare motor; we add 2e-6 kg m^2 for a small
 * coupled load and 0.5 mN m of dry friction. Hurst300: about twice the rotor,
 * assumed. The high-speed motor is defined by us (same numbers as
 * firmware/motors/motor_hispeed.h): the motor behind AN1078's "500 to 17,000
 * rpm" is not documented. The low-inductance motor is ours too (a tenth of
 * the Hurst075's R and L, 4 pole pairs, 60 % of its Ke; the numbers of
 * tools/tune/examples/lowl.toml). See docs/sim.md.
 */
static const sim_motor_profile_t MOTORS[] = {
    {"hurst", "hurst075", "Hurst DMB0224C10002 (Hurst075, AC300020), 24 V", 2.67, 1.92e-3, 7.3, 5,
     7.5e-6, 15.3e-6, 0.5e-3, 1.64, 2700.0, 5300.0},
    {"hurst300", "hurst_long", "Hurst DMA0204024B101 (Hurst300, AC300022), 24 V", 0.40, 0.34e-3,
     7.3, 5, 1.5e-5, 25.0e-6, 1.0e-3, 4.88, 2500.0, 3000.0},
    {"hispeed", "hs2p", "2-pole-pair high-speed PMSM (assumed, see docs/sim.md), 320 V bus", 1.2,
     4.0e-3, 10.0, 2, 2.0e-5, 2.0e-6, 2.0e-3, 2.5, 17000.0, 17000.0},
    {"lowl", NULL, "low-inductance 4-pole-pair PMSM (assumed, see docs/sim.md), 24 V", 0.267,
     0.192e-3, 4.38, 4, 5.0e-6, 10.0e-6, 0.5e-3, 3.0, 4000.0, 4000.0},
};

/* The current amplifiers' time constant: not published for either board
 * (docs/sim.md); 0.35 us, an op-amp stage of about 450 kHz bandwidth,
 * settles to half an ADC code of a full-scale step in 2.4 us. */
#define SIM_AMP_TAU_S 0.35e-6

static const sim_board_profile_t BOARDS[] = {
    {"mclv", "dsPICDEM MCLV (DM330021), 24 V bus, +-4.4 A", 24.0, 2.0e-6, 20000.0, 4.4, 52.8, 6.0,
     -4.0, 1.0, SIM_AMP_TAU_S},
    {"mchv", "dsPICDEM MCHV (DM330023), 320 V bus (230 V AC rectified)", 320.0, 2.0e-6, 20000.0,
     8.0, 400.0, 6.0, -4.0, 1.0, SIM_AMP_TAU_S},
};

#define N_MOTORS (sizeof(MOTORS) / sizeof(MOTORS[0]))
#define N_BOARDS (sizeof(BOARDS) / sizeof(BOARDS[0]))

const sim_motor_profile_t *sim_motor_profile(const char *name)
{
    size_t i;
    for (i = 0; i < N_MOTORS; i++) {
        if (strcmp(MOTORS[i].name, name) == 0 ||
            (MOTORS[i].alias != NULL && strcmp(MOTORS[i].alias, name) == 0)) {
            return &MOTORS[i];
        }
    }
    return NULL;
}

const sim_board_profile_t *sim_board_profile(const char *name)
{
    size_t i;
    for (i = 0; i < N_BOARDS; i++) {
        if (strcmp(BOARDS[i].name, name) == 0) {
            return &BOARDS[i];
        }
    }
    return NULL;
}

void sim_motor_params_from_profile(const sim_motor_profile_t *mp, sim_motor_params_t *m)
{
    m->rs_ohm = mp->rs_ohm;
    m->ld_h = mp->l_h;
    m->lq_h = mp->l_h;
    m->psi_vs = sim_psi_from_ke(mp->ke_ll, mp->pole_pairs);
    m->pole_pairs = mp->pole_pairs;
    m->j_kgm2 = mp->j_kgm2;
    m->b_nms = mp->b_nms;
    m->coulomb_nm = mp->coulomb_nm;
}

double sim_motor_rated_torque(const sim_motor_profile_t *mp)
{
    return 1.5 * (double)mp->pole_pairs * sim_psi_from_ke(mp->ke_ll, mp->pole_pairs) * mp->rated_a;
}

const char *sim_profiles_list(void)
{
    return "motors: hurst (hurst075), hurst300 (hurst_long), hispeed (hs2p), lowl; boards: mclv, "
           "mchv";
}
