/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_motor_lowl.c - the simulated low-inductance motor ("lowl"), for the robustness campaign. */
#include <stddef.h>

#include "sim_profiles.h"

/* Defined by us (a tenth of the Hurst075's R and L, 4 pole pairs, 60 % of
 * its Ke): its description for tools/tune (tools/tune/examples/lowl.toml),
 * as the generated profile holds it. */
#include "../../firmware/motors/motor_lowl.h"

/* Not in the profile: friction (assumed) and the rated speed (the
 * description's rated_speed). */
const sim_motor_profile_t sim_motor_lowl = {
    "lowl",
    NULL,
    "low-inductance 4-pole-pair PMSM (assumed, see docs/sim.md), 24 V",
    MOTOR_RS_OHM,
    MOTOR_LS_H,
    MOTOR_KE_VPK_LL_PER_KRPM,
    MOTOR_POLE_PAIRS,
    MOTOR_INERTIA_KGM2,
    10.0e-6, /* B, N m s/rad */
    0.5e-3,  /* dry friction, N m */
    MOTOR_RATED_CURRENT_A,
    4000.0, /* rated speed, rpm */
};
