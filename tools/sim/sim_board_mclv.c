/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_board_mclv.c - the simulated dsPICDEM MCLV (DM330021). */
#include "sim_profiles.h"

#include "../../boards/board_mclv.h"

/* Bus and dead time from the board's profile; offsets, noise and the
 * amplifiers' settling assumed (sim_profiles.h). The ADC full scales are
 * the core's own (BOARD_I_FULLSCALE_A, BOARD_VBUS_FULLSCALE_V). */
const sim_board_profile_t sim_board_mclv = {
    "mclv",
    BOARD_VBUS_NOMINAL_V,
    (double)BOARD_DEADTIME_NS / 1e9, /* ns to s */
    SIM_AMP_OFFSET_A_CODES,
    SIM_AMP_OFFSET_B_CODES,
    SIM_ADC_NOISE_CODES,
    SIM_AMP_TAU_S,
    BOARD_VBUS_CAPACITANCE_F,
    BOARD_SUPPLY_R_OHM,
};
