/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_motor_hispeed.c - the simulated 2-pole-pair high-speed motor ("hispeed", "hs2p"). */
#include "sim_profiles.h"

/* Defined by us (the motor behind AN1078's "500 to 17,000 rpm" is not
 * documented): its description for tools/tune
 * (tools/tune/examples/hispeed.toml), as the generated profile holds it. */
#include "../../firmware/motors/motor_hispeed.h"

/* Not in the profile: friction (assumed) and the rated speed (the
 * description's rated_speed, its top speed). */
const sim_motor_profile_t sim_motor_hispeed = {
    "hispeed",
    "hs2p",
    "2-pole-pair high-speed PMSM (assumed, see docs/sim.md), 320 V bus",
    MOTOR_RS_OHM,
    MOTOR_LS_H,
    MOTOR_KE_VPK_LL_PER_KRPM,
    MOTOR_POLE_PAIRS,
    MOTOR_INERTIA_KGM2,
    2.0e-6, /* B, N m s/rad */
    2.0e-3, /* dry friction, N m */
    MOTOR_RATED_CURRENT_A,
    17000.0, /* rated speed, rpm */
};
