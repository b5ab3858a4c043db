/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_motor_hurst300.c - the simulated Hurst DMA0204024B101 ("hurst300", "hurst_long"). */
#include "sim_profiles.h"

/* Its description for tools/tune (tools/tune/examples/hurst300.toml, from
 * Microchip's hurst300.h), as the generated profile holds it. */
#include "../../firmware/motors/motor_hurst300.h"

/* Not in the profile: friction (assumed: the Hurst075's scaled to about
 * twice its rotor) and the rated speed (the description's rated_speed). */
const sim_motor_profile_t sim_motor_hurst300 = {
    "hurst300",
    "hurst_long",
    "Hurst DMA0204024B101 (Hurst300, AC300022), 24 V",
    MOTOR_RS_OHM,
    MOTOR_LS_H,
    MOTOR_KE_VPK_LL_PER_KRPM,
    MOTOR_POLE_PAIRS,
    MOTOR_INERTIA_KGM2,
    25.0e-6, /* B, N m s/rad */
    1.0e-3,  /* dry friction, N m */
    MOTOR_RATED_CURRENT_A,
    2500.0, /* rated speed, rpm */
};
