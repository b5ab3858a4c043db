/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* probe_values.c - the core's numbers for a board or a profile, as data only (tools/tune's probe).
 */

/*
 * Compiled with the build's include paths and -D options (MC_BOARD_<BOARD>,
 * MC_MOTOR_HEADER), this file is the core's headers and nothing else: the
 * values below are constant expressions of their macros, so this object
 * holds data and no code. probe_main.c, which never sees a profile,
 * prints it. tools/tune (motortune/probe.py) screens a profile before it
 * is compiled here: preprocessor definitions only, no code, no #include,
 * no #pragma (docs/tune.md, "Input safety").
 *
 * TUNE_PROBE_BOARD: the board and UserParms.h with an empty motor profile.
 * The core's checks are switched off (their conditions name motor values
 * that are not there), so only the board's values are read; probe.py runs
 * the same headers once more with the checks on for the board's refusals.
 */

#if defined(TUNE_PROBE_BOARD) && !defined(TUNE_PROBE_CHECK)
#include "q15.h"
#undef Q15_CHECK_WIDTH_
#define Q15_CHECK_WIDTH_(cond) 1
#endif
#include "mc_derived.h"
#include "probe_facts.h"

#ifndef TUNE_PROBE_CHECK
#define TUNE_VALUE_(name, expr) (double)(expr),
#ifdef TUNE_PROBE_BOARD
const double tune_probe_facts[] = {TUNE_PROBE_BOARD_FACTS(TUNE_VALUE_) 0.0};
#else
const double tune_probe_facts[] = {TUNE_PROBE_PROFILE_FACTS(TUNE_VALUE_) 0.0};
const smc_params_t tune_probe_smc = MC_SMC_PARAMS_INIT;
#define TUNE_FW_AMPS_(a) (double)(a),
#define TUNE_FW_Q15_(a)  (double)MC_Q15_AMPS(a),
const double tune_probe_fw_amps[] = {MOTOR_FW_ID_TABLE_A(TUNE_FW_AMPS_) 0.0};
const double tune_probe_fw_q15[] = {MOTOR_FW_ID_TABLE_A(TUNE_FW_Q15_) 0.0};
#ifdef MOTOR_NAME
const char tune_probe_motor_name[] = MOTOR_NAME;
#else
const char tune_probe_motor_name[] = "";
#endif
#ifdef MOTOR_TUNE_BOARD
const char tune_probe_tune_board[] = MOTOR_TUNE_BOARD;
#else
const char tune_probe_tune_board[] = "";
#endif
#endif
const unsigned tune_probe_nfacts = (unsigned)(sizeof tune_probe_facts / sizeof tune_probe_facts[0]);
const char tune_probe_board_name[] = BOARD_NAME;
#endif
