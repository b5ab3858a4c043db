/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* params_probe.c - instantiates every derived constant, so a bad UserParms.h value fails here. */
#include "mc.h"

static const smc_params_t probe_smc = MC_SMC_PARAMS_INIT;
static const q15_t probe_fw[16] = MC_FW_TABLE_Q15;

int main(void)
{
    long sum = (long)probe_smc.f + probe_fw[15] + MC_CUR_KP + MC_SPD_KP + MC_CUR_KI + MC_SPD_KI;
    return (int)(sum & 1);
}
