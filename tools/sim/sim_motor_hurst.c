/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_motor_hurst.c - the simulated Hurst DMB0224C10002 ("hurst", "hurst075"). */
#include "sim_profiles.h"

/* Its description for tools/tune (tools/tune/examples/hurst.toml), as
 * the generated profile holds it: R, L, Ke, pole pairs, inertia, rated
 * current. */
#include "../../firmware/motors/motor_hurst.h"

/*
 * Not in the profile: friction and the rated speed. Neither friction nor the
 * inertia is in the Hurst data sheets: a public MATLAB parameter script for
 * Microchip's low-voltage board gives B = 15.3e-6 N m s/rad (and J =
 * 5.5e-6 kg m^2 for the bare rotor, 2e-6 more for a small coupled load in
 * the description); 0.5 mN m of dry friction is assumed (a no-load current
 * of about 0.06 A at 2,000 rpm). The rated speed is the description's
 * rated_speed (docs/sim.md "Profiles").
 */
const sim_motor_profile_t sim_motor_hurst = {
    "hurst",
    "hurst075",
    "Hurst DMB0224C10002 (Hurst075, AC300020), 24 V",
    MOTOR_RS_OHM,
    MOTOR_LS_H,
    MOTOR_KE_VPK_LL_PER_KRPM,
    MOTOR_POLE_PAIRS,
    MOTOR_INERTIA_KGM2,
    15.3e-6, /* B, N m s/rad */
    0.5e-3,  /* dry friction, N m */
    MOTOR_RATED_CURRENT_A,
    2700.0, /* rated speed, rpm */
};
