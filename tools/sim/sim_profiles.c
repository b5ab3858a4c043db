/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_profiles.c - the simulated motors and boards by name (one file per profile). */
#include "sim_profiles.h"

#include <stdio.h>
#include <string.h>

static const sim_motor_profile_t *const MOTORS[] = {
    &sim_motor_hurst,
    &sim_motor_hurst300,
    &sim_motor_hispeed,
    &sim_motor_lowl,
};

static const sim_board_profile_t *const BOARDS[] = {
    &sim_board_mclv,
    &sim_board_mchv,
};

#define N_MOTORS (sizeof(MOTORS) / sizeof(MOTORS[0]))
#define N_BOARDS (sizeof(BOARDS) / sizeof(BOARDS[0]))

const sim_motor_profile_t *sim_motor_profile(const char *name)
{
    size_t i;
    for (i = 0; i < N_MOTORS; i++) {
        if (strcmp(MOTORS[i]->name, name) == 0 ||
            (MOTORS[i]->alias != NULL && strcmp(MOTORS[i]->alias, name) == 0)) {
            return MOTORS[i];
        }
    }
    return NULL;
}

const sim_board_profile_t *sim_board_profile(const char *name)
{
    size_t i;
    for (i = 0; i < N_BOARDS; i++) {
        if (strcmp(BOARDS[i]->name, name) == 0) {
            return BOARDS[i];
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

/* Appends s to buf (size len, NUL-terminated), as much as fits. */
static void append(char *buf, size_t len, const char *s)
{
    size_t n = strlen(buf);
    if (n + 1 < len) {
        snprintf(buf + n, len - n, "%s", s);
    }
}

const char *sim_profiles_list(void)
{
    static char list[256];
    size_t i;
    if (list[0] != '\0') {
        return list;
    }
    append(list, sizeof(list), "motors: ");
    for (i = 0; i < N_MOTORS; i++) {
        append(list, sizeof(list), (i > 0) ? ", " : "");
        append(list, sizeof(list), MOTORS[i]->name);
        if (MOTORS[i]->alias != NULL) {
            append(list, sizeof(list), " (");
            append(list, sizeof(list), MOTORS[i]->alias);
            append(list, sizeof(list), ")");
        }
    }
    append(list, sizeof(list), "; boards: ");
    for (i = 0; i < N_BOARDS; i++) {
        append(list, sizeof(list), (i > 0) ? ", " : "");
        append(list, sizeof(list), BOARDS[i]->name);
    }
    return list;
}
