/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* probe_facts.h - the numbers tools/tune's probe reads from the core's headers: one list for its
 * two files. */
#ifndef PROBE_FACTS_H
#define PROBE_FACTS_H

/*
 * tools/tune computes nothing the core computes: it compiles this probe
 * against firmware/UserParms.h, firmware/mc_derived.h, the board and a
 * motor profile, runs it, and reads the lines it prints (motortune/probe.py).
 * FACT(name, expression) lists one number each; probe_values.c evaluates
 * the expressions (constant expressions: data only), probe_main.c prints
 * them by name and builds the --check table from them.
 *
 * TUNE_PROBE_BOARD_FACTS: the board and UserParms.h, no motor (tools/tune
 * derives a profile from them). TUNE_PROBE_PROFILE_FACTS: a whole profile
 * as the core compiles it (tools/tune --check).
 */

/* The ranges tools/tune holds a derived value to are firmware/mc_derived.h's
 * own names (MC_KP_MAX, MC_LOCK_PERIODS_MAX, ...), the ones its MC_CHECK
 * lines use; the ADC's resolution is the board profile's (BOARD_ADC_BITS). */

#define TUNE_PROBE_BOARD_FACTS(FACT)                                                               \
    FACT(BOARD_FCY_HZ, BOARD_FCY_HZ)                                                               \
    FACT(PWM_FREQUENCY_HZ, PWM_FREQUENCY_HZ)                                                       \
    FACT(PWM_DUTY_MAX, PWM_DUTY_MAX)                                                               \
    FACT(BOARD_I_FULLSCALE_A, BOARD_I_FULLSCALE_A)                                                 \
    FACT(MC_TRIP_REACH_A, MC_TRIP_REACH_A)                                                         \
    FACT(BOARD_VBUS_NOMINAL_V, BOARD_VBUS_NOMINAL_V)                                               \
    FACT(BOARD_VBUS_FULLSCALE_V, BOARD_VBUS_FULLSCALE_V)                                           \
    FACT(BOARD_ADC_BITS, BOARD_ADC_BITS)                                                           \
    FACT(MC_VOLTAGE_FULLSCALE_V, MC_VOLTAGE_FULLSCALE_V)                                           \
    FACT(PWM_DEADTIME_NS, PWM_DEADTIME_NS)                                                         \
    FACT(MC_DT_COUNTS, MC_DT_COUNTS)                                                               \
    FACT(PWM_ADC_TRIGGER_TCY, PWM_ADC_TRIGGER_TCY)                                                 \
    FACT(MC_DUTY_SAMPLE_MAX, MC_DUTY_SAMPLE_MAX)                                                   \
    FACT(MC_SPEED_LOOP_HZ, MC_SPEED_LOOP_HZ)                                                       \
    FACT(IRP_PERCALC, IRP_PERCALC)                                                                 \
    FACT(MC_VOLTAGE_LIMIT_FRACTION, MC_VOLTAGE_LIMIT_FRACTION)                                     \
    FACT(MC_SPEED_RAMP_RPM_PER_S, MC_SPEED_RAMP_RPM_PER_S)                                         \
    FACT(MC_STALL_SPEED_ERROR_RPM, MC_STALL_SPEED_ERROR_RPM)                                       \
    FACT(SMC_EMF_FS_RATIO, SMC_EMF_FS_RATIO)                                                       \
    FACT(MC_KP_MAX, MC_KP_MAX)                                                                     \
    FACT(MC_KI_MAX, MC_KI_MAX)                                                                     \
    FACT(MC_LOCK_PERIODS_MAX, MC_LOCK_PERIODS_MAX)                                                 \
    FACT(MC_OL_DAMP_PERIODS_MAX, MC_OL_DAMP_PERIODS_MAX)                                           \
    FACT(MC_OL_DAMP_COUNTS_PER_PERIOD, MC_OL_DAMP_COUNTS_PER_PERIOD)                               \
    FACT(MC_RAMP_STEP_INC_MIN, MC_RAMP_STEP_INC_MIN)                                               \
    FACT(MC_DEADTIME_BAND_MAX_FRACTION, MC_DEADTIME_BAND_MAX_FRACTION)                             \
    FACT(MC_DTM_LOCK_BANDS, MC_DTM_LOCK_BANDS)                                                     \
    FACT(MC_SPEED_FS_TOP_FRACTION, MC_SPEED_FS_TOP_FRACTION)

/* The observer's quantities, with the arguments MC_SMC_PARAMS_INIT gives
 * smc.h (mc_derived.h). */
#define TUNE_KS_ ((double)MOTOR_SMC_GAIN_V / MC_VOLTAGE_FULLSCALE_V)
#define TUNE_ME_ ((double)MOTOR_SMC_LINEAR_BAND_A / BOARD_I_FULLSCALE_A)
#define TUNE_SMC_G_                                                                                \
    SMC_G_(MOTOR_RS_OHM, MOTOR_LS_H, MC_TS_S, MC_VOLTAGE_FULLSCALE_V, BOARD_I_FULLSCALE_A)
#define TUNE_SMC_GE_                                                                               \
    SMC_GE_(MOTOR_RS_OHM, MOTOR_LS_H, MC_TS_S, MC_VOLTAGE_FULLSCALE_V, BOARD_I_FULLSCALE_A)
#define TUNE_SMC_C_                                                                                \
    SMC_C_(MOTOR_RS_OHM, MOTOR_LS_H, MC_TS_S, MC_VOLTAGE_FULLSCALE_V, BOARD_I_FULLSCALE_A,         \
           TUNE_KS_, TUNE_ME_)

#define TUNE_PROBE_PROFILE_FACTS(FACT)                                                             \
    TUNE_PROBE_BOARD_FACTS(FACT)                                                                   \
    FACT(MOTOR_POLE_PAIRS, MOTOR_POLE_PAIRS)                                                       \
    FACT(MOTOR_RS_OHM, MOTOR_RS_OHM)                                                               \
    FACT(MOTOR_LS_H, MOTOR_LS_H)                                                                   \
    FACT(MOTOR_KE_VPK_LL_PER_KRPM, MOTOR_KE_VPK_LL_PER_KRPM)                                       \
    FACT(MC_TS_S, MC_TS_S)                                                                         \
    FACT(MC_SPEED_FULLSCALE_RPM, MC_SPEED_FULLSCALE_RPM)                                           \
    FACT(MC_OMEGA_FS_HZ, MC_OMEGA_FS_HZ)                                                           \
    FACT(SPEED_REF_MIN_RPM, SPEED_REF_MIN_RPM)                                                     \
    FACT(MC_SPEED_REF_MIN_Q15, MC_SPEED_REF_MIN_Q15)                                               \
    FACT(SPEED_REF_MAX_RPM, SPEED_REF_MAX_RPM)                                                     \
    FACT(MC_SPEED_REF_MAX_Q15, MC_SPEED_REF_MAX_Q15)                                               \
    FACT(MOTOR_SPEED_MIN_RPM, MOTOR_SPEED_MIN_RPM)                                                 \
    FACT(MC_VBUS_OVERVOLTAGE_V, MC_VBUS_OVERVOLTAGE_V)                                             \
    FACT(MOTOR_SPEED_NOMINAL_RPM, MOTOR_SPEED_NOMINAL_RPM)                                         \
    FACT(MC_SPEED_NOMINAL_Q15, MC_Q15_RPM(MOTOR_SPEED_NOMINAL_RPM))                                \
    FACT(MOTOR_SPEED_FW_MAX_RPM, MOTOR_SPEED_FW_MAX_RPM)                                           \
    FACT(MC_SPEED_FW_MAX_Q15, MC_Q15_RPM(MOTOR_SPEED_FW_MAX_RPM))                                  \
    FACT(MC_SPEED_RAMP_STEP, MC_SPEED_RAMP_STEP)                                                   \
    FACT(MOTOR_CURRENT_MAX_A, MOTOR_CURRENT_MAX_A)                                                 \
    FACT(MC_IQ_MAX_Q15, MC_IQ_MAX_Q15)                                                             \
    FACT(MC_OVERCURRENT_A, MC_OVERCURRENT_A)                                                       \
    FACT(MC_OVERCURRENT_Q15, MC_OVERCURRENT_Q15)                                                   \
    FACT(MOTOR_LOCK_CURRENT_A, MOTOR_LOCK_CURRENT_A)                                               \
    FACT(MC_LOCK_CURRENT_Q15, MC_LOCK_CURRENT_Q15)                                                 \
    FACT(MOTOR_RAMP_CURRENT_A, MOTOR_RAMP_CURRENT_A)                                               \
    FACT(MC_RAMP_CURRENT_Q15, MC_RAMP_CURRENT_Q15)                                                 \
    FACT(MOTOR_OL_DAMP_S, MOTOR_OL_DAMP_S)                                                         \
    FACT(MC_OL_DAMP_K, MC_OL_DAMP_K)                                                               \
    FACT(MC_VMAX_Q15, MC_VMAX_Q15)                                                                 \
    FACT(MOTOR_CURRENT_KP_V_PER_A, MOTOR_CURRENT_KP_V_PER_A)                                       \
    FACT(MC_CUR_KP, MC_CUR_KP)                                                                     \
    FACT(MC_CUR_KP_SHIFT, MC_CUR_KP_SHIFT)                                                         \
    FACT(MOTOR_CURRENT_KI_V_PER_AS, MOTOR_CURRENT_KI_V_PER_AS)                                     \
    FACT(MC_CUR_KI, MC_CUR_KI)                                                                     \
    FACT(MOTOR_SPEED_KP_A_PER_RPM, MOTOR_SPEED_KP_A_PER_RPM)                                       \
    FACT(MC_SPD_KP, MC_SPD_KP)                                                                     \
    FACT(MC_SPD_KP_SHIFT, MC_SPD_KP_SHIFT)                                                         \
    FACT(MOTOR_SPEED_KI_A_PER_RPM_S, MOTOR_SPEED_KI_A_PER_RPM_S)                                   \
    FACT(MC_SPD_KI, MC_SPD_KI)                                                                     \
    FACT(MOTOR_SPEED_KP_FULL_RPM, MOTOR_SPEED_KP_FULL_RPM)                                         \
    FACT(MC_SPEED_KP_FULL_Q15, MC_Q15_RPM(MOTOR_SPEED_KP_FULL_RPM))                                \
    FACT(MC_SPEED_KP_MIN_FRACTION, MC_SPEED_KP_MIN_FRACTION)                                       \
    FACT(MC_SPEED_KP_MIN_Q15, Q15(MC_SPEED_KP_MIN_FRACTION))                                       \
    FACT(MOTOR_LOCK_TIME_S, MOTOR_LOCK_TIME_S)                                                     \
    FACT(MC_LOCK_PERIODS, MC_LOCK_PERIODS)                                                         \
    FACT(MOTOR_RAMP_TIME_S, MOTOR_RAMP_TIME_S)                                                     \
    FACT(MC_RAMP_PERIODS, MC_RAMP_PERIODS)                                                         \
    FACT(MOTOR_RAMP_END_RPM, MOTOR_RAMP_END_RPM)                                                   \
    FACT(MC_RAMP_STEP_END, MC_RAMP_STEP_END)                                                       \
    FACT(MC_RAMP_STEP_INC, MC_RAMP_STEP_INC)                                                       \
    FACT(MC_ESTIMATOR_MIN_RPM, MC_ESTIMATOR_MIN_RPM)                                               \
    FACT(MOTOR_SMC_GAIN_V, MOTOR_SMC_GAIN_V)                                                       \
    FACT(MOTOR_SMC_LINEAR_BAND_A, MOTOR_SMC_LINEAR_BAND_A)                                         \
    FACT(MC_SPEED_FILTER_HZ, MC_SPEED_FILTER_HZ)                                                   \
    FACT(SMC_F, SMC_F_(MOTOR_RS_OHM, MOTOR_LS_H, MC_TS_S))                                         \
    FACT(SMC_G, TUNE_SMC_G_)                                                                       \
    FACT(SMC_GE, TUNE_SMC_GE_)                                                                     \
    FACT(SMC_KZ, SMC_KZ_(TUNE_KS_, TUNE_ME_))                                                      \
    FACT(SMC_C, TUNE_SMC_C_)                                                                       \
    FACT(SMC_KPW, SMC_KPW_(MC_TS_S, MC_OMEGA_FS_HZ))                                               \
    FACT(MC_DEADTIME_BAND_A, MC_DEADTIME_BAND_A)                                                   \
    FACT(MC_DT_BAND_Q15, MC_DT_BAND_Q15)

#endif /* PROBE_FACTS_H */
