/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* mc_derived.h - UserParms.h and the profiles turned into Q15 constants, with named range checks.
 */
#ifndef MC_DERIVED_H
#define MC_DERIVED_H

/*
 * Nothing here is tuned: every constant is computed from UserParms.h and the
 * board and motor profiles. Each check stops the build with a first error
 * line that names the parameter to change (MC_CHECK below); the Q15()
 * conversions that follow carry their own range check.
 *
 * Scales used by the core (docs/design.md):
 *   current  Q15 of BOARD_I_FULLSCALE_A (A)
 *   voltage  Q15 of MC_VOLTAGE_FULLSCALE_V = BOARD_VBUS_NOMINAL_V / sqrt(3)
 *            (the SVGen full scale at the nominal bus, a phase amplitude)
 *   bus      Q15 of BOARD_VBUS_FULLSCALE_V (V)
 *   speed    mechanical, Q15 of MC_SPEED_FULLSCALE_RPM (rpm); the estimator's
 *            electrical Q15 speed uses omega_fs = MC_SPEED_FULLSCALE_RPM *
 *            MOTOR_POLE_PAIRS / 60 Hz so the two Q15 numbers are equal.
 *   angle    binary, one electrical turn = 2^16 (open loop: 2^32).
 *
 * Constants that become integers are computed in double and rounded once;
 * avr-gcc and XC16 evaluate them with a 32-bit double, so each is kept well
 * away from a .5 boundary or built from small exact integers (note 1).
 */

#include "q15.h"
#include "smc_params.h"
#include "UserParms.h"

/* MC_CHECK(PARAM, cond, "why"): stops the build when cond is false, the
 * first error line naming PARAM (q15.h, "compile-time checks"):
 *   gcc, avr-gcc, XC16:  error: negative width in bit-field 'PARAM__out_of_range'
 *   clang:               error: bit-field 'PARAM__out_of_range' has negative width (-1)
 * and the check's line, with "why", beside it. MC_CHECK_FOR(PARAM, OTHER,
 * cond, "why") names a second parameter the check involves, the one a user
 * may have changed instead ('PARAM__out_of_range_for__OTHER'): a bound
 * between two parameters, or a UserParms.h default computed from OTHER.
 * Each parameter is checked on its own before anything derived from it
 * (and before any Q15() of it, whose own range check names no parameter),
 * so the first error names the value to change. Both are q15.h's
 * Q15_CHECK_DECL written out: a pasted name passed on as a macro argument
 * is misread by cppcheck's preprocessor (make lint). */
#define MC_CHECK(param, cond, msg)                                                                 \
    extern char q15_check_[1 + (int)(0 * sizeof(struct {                                           \
                                         unsigned param##__out_of_range : Q15_CHECK_WIDTH_(cond);  \
                                     }))]
#define MC_CHECK_FOR(param, other, cond, msg)                                                      \
    extern char q15_check_[1 + (int)(0 * sizeof(struct {                                           \
                                         unsigned param##__out_of_range_for__##other               \
                                             : Q15_CHECK_WIDTH_(cond);                             \
                                     }))]

/* ---- a profile is data ----------------------------------------------------- */

/* Every number a motor profile gives, whoever reads it (the core, the
 * simulator, the campaigns, the tests): a constant arithmetic expression
 * of numbers and macros. A function call, an assignment or anything else
 * that is not a constant stops the build here, before a program that reads
 * the value could run it; the first error names the value (gcc, avr-gcc,
 * XC16: "bit-field 'NAME__out_of_range' width not an integer constant";
 * clang: "expression is not an integer constant expression", the check's
 * line naming it beside). Not a finite number (1e999) is refused too. The
 * table MOTOR_FW_ID_TABLE_A meets the same in its checks below; MOTOR_NAME
 * and MOTOR_TUNE_BOARD are strings, copied, never run. */
#define MC_IS_DATA_(x) ((double)(x)*0.0 == 0.0)
#define MC_NOT_DATA_   "must be a number or an arithmetic expression of numbers and macros"
MC_CHECK(MOTOR_POLE_PAIRS, MC_IS_DATA_(MOTOR_POLE_PAIRS), MC_NOT_DATA_);
MC_CHECK(MOTOR_RS_OHM, MC_IS_DATA_(MOTOR_RS_OHM), MC_NOT_DATA_);
MC_CHECK(MOTOR_LS_H, MC_IS_DATA_(MOTOR_LS_H), MC_NOT_DATA_);
MC_CHECK(MOTOR_KE_VPK_LL_PER_KRPM, MC_IS_DATA_(MOTOR_KE_VPK_LL_PER_KRPM), MC_NOT_DATA_);
MC_CHECK(MOTOR_RATED_CURRENT_A, MC_IS_DATA_(MOTOR_RATED_CURRENT_A), MC_NOT_DATA_);
MC_CHECK(MOTOR_CURRENT_MAX_A, MC_IS_DATA_(MOTOR_CURRENT_MAX_A), MC_NOT_DATA_);
MC_CHECK(MOTOR_OVERCURRENT_A, MC_IS_DATA_(MOTOR_OVERCURRENT_A), MC_NOT_DATA_);
MC_CHECK(MOTOR_SPEED_NOMINAL_RPM, MC_IS_DATA_(MOTOR_SPEED_NOMINAL_RPM), MC_NOT_DATA_);
MC_CHECK(MOTOR_SPEED_FW_MAX_RPM, MC_IS_DATA_(MOTOR_SPEED_FW_MAX_RPM), MC_NOT_DATA_);
MC_CHECK(MOTOR_SPEED_MIN_RPM, MC_IS_DATA_(MOTOR_SPEED_MIN_RPM), MC_NOT_DATA_);
MC_CHECK(MOTOR_SPEED_FULLSCALE_RPM, MC_IS_DATA_(MOTOR_SPEED_FULLSCALE_RPM), MC_NOT_DATA_);
MC_CHECK(MOTOR_LOCK_CURRENT_A, MC_IS_DATA_(MOTOR_LOCK_CURRENT_A), MC_NOT_DATA_);
MC_CHECK(MOTOR_LOCK_TIME_S, MC_IS_DATA_(MOTOR_LOCK_TIME_S), MC_NOT_DATA_);
MC_CHECK(MOTOR_RAMP_CURRENT_A, MC_IS_DATA_(MOTOR_RAMP_CURRENT_A), MC_NOT_DATA_);
MC_CHECK(MOTOR_RAMP_END_RPM, MC_IS_DATA_(MOTOR_RAMP_END_RPM), MC_NOT_DATA_);
MC_CHECK(MOTOR_RAMP_TIME_S, MC_IS_DATA_(MOTOR_RAMP_TIME_S), MC_NOT_DATA_);
MC_CHECK(MOTOR_OL_DAMP_S, MC_IS_DATA_(MOTOR_OL_DAMP_S), MC_NOT_DATA_);
MC_CHECK(MOTOR_CURRENT_KP_V_PER_A, MC_IS_DATA_(MOTOR_CURRENT_KP_V_PER_A), MC_NOT_DATA_);
MC_CHECK(MOTOR_CURRENT_KI_V_PER_AS, MC_IS_DATA_(MOTOR_CURRENT_KI_V_PER_AS), MC_NOT_DATA_);
MC_CHECK(MOTOR_CURRENT_LOOP_BW_RAD_S, MC_IS_DATA_(MOTOR_CURRENT_LOOP_BW_RAD_S), MC_NOT_DATA_);
MC_CHECK(MOTOR_SPEED_KP_A_PER_RPM, MC_IS_DATA_(MOTOR_SPEED_KP_A_PER_RPM), MC_NOT_DATA_);
MC_CHECK(MOTOR_SPEED_KI_A_PER_RPM_S, MC_IS_DATA_(MOTOR_SPEED_KI_A_PER_RPM_S), MC_NOT_DATA_);
MC_CHECK(MOTOR_SPEED_KP_FULL_RPM, MC_IS_DATA_(MOTOR_SPEED_KP_FULL_RPM), MC_NOT_DATA_);
MC_CHECK(MOTOR_SMC_GAIN_V, MC_IS_DATA_(MOTOR_SMC_GAIN_V), MC_NOT_DATA_);
MC_CHECK(MOTOR_SMC_LINEAR_BAND_A, MC_IS_DATA_(MOTOR_SMC_LINEAR_BAND_A), MC_NOT_DATA_);
/* The two only the simulator and the campaigns read, where a profile gives them. */
#ifdef MOTOR_INERTIA_KGM2
MC_CHECK(MOTOR_INERTIA_KGM2, MC_IS_DATA_(MOTOR_INERTIA_KGM2), MC_NOT_DATA_);
#endif
#ifdef MOTOR_START_LOAD_NM
MC_CHECK(MOTOR_START_LOAD_NM, MC_IS_DATA_(MOTOR_START_LOAD_NM), MC_NOT_DATA_);
#endif

/* 1 when x has an integer type: 3 / 2 is 1 only in integer arithmetic (a
 * floating x gives 1.5). Counts, switches and the rates that must divide
 * each other are integers: they meet %, #if and integer code. */
#define MC_IS_INTEGER_(x) (((x)*0 + 3) / 2 == 1)
/* 1 when a ratio x >= 0 is 0 or does not round to 0 at `scale` counts per
 * unit (32768 for Q15): a small positive gain or fraction that rounds to 0
 * would switch its function off without a word. */
#define MC_ZERO_OR_COUNTS_(x, scale) ((x) == 0.0 || (double)(x) * (double)(scale) >= 0.5)

/* ---- integer parameters ---------------------------------------------------- */

MC_CHECK(BOARD_FCY_HZ, MC_IS_INTEGER_(BOARD_FCY_HZ) && BOARD_FCY_HZ > 0,
         "must be a positive integer (Hz)");
MC_CHECK(PWM_FREQUENCY_HZ, MC_IS_INTEGER_(PWM_FREQUENCY_HZ),
         "must be an integer (Hz): it divides BOARD_FCY_HZ");
MC_CHECK(MC_SPEED_LOOP_HZ, MC_IS_INTEGER_(MC_SPEED_LOOP_HZ),
         "must be an integer (Hz): it divides PWM_FREQUENCY_HZ");
MC_CHECK(PWM_ADC_TRIGGER_TCY, MC_IS_INTEGER_(PWM_ADC_TRIGGER_TCY),
         "must be an integer (instruction cycles)");
MC_CHECK(BOARD_DEADTIME_NS, MC_IS_INTEGER_(BOARD_DEADTIME_NS),
         "must be an integer (ns; the HAL and #if use it)");
MC_CHECK(PWM_DEADTIME_NS, MC_IS_INTEGER_(PWM_DEADTIME_NS),
         "must be an integer (ns; the HAL and #if use it)");
MC_CHECK(BOARD_I_SIGN, MC_IS_INTEGER_(BOARD_I_SIGN) && (BOARD_I_SIGN == 1 || BOARD_I_SIGN == -1),
         "must be the integer +1 or -1 (the HAL's #if tests it)");
MC_CHECK(MOTOR_POLE_PAIRS,
         MC_IS_INTEGER_(MOTOR_POLE_PAIRS) && MOTOR_POLE_PAIRS >= 1 && MOTOR_POLE_PAIRS <= 32,
         "must be an integer in 1..32");
/* At most 10: every attempt heats a locked rotor at the start-up currents
 * (MC_RETRY_COAST_S below). */
MC_CHECK(MC_START_RETRIES,
         MC_IS_INTEGER_(MC_START_RETRIES) && MC_START_RETRIES >= 0 && MC_START_RETRIES <= 10,
         "must be an integer in 0..10");
MC_CHECK(MC_OL_DAMP_MEAN_WINDOWS,
         MC_IS_INTEGER_(MC_OL_DAMP_MEAN_WINDOWS) && MC_OL_DAMP_MEAN_WINDOWS >= 1 &&
             MC_OL_DAMP_MEAN_WINDOWS <= 1024,
         "must be an integer in 1..1024 speed-loop windows");
MC_CHECK(MC_DEADTIME_MEASURE,
         MC_IS_INTEGER_(MC_DEADTIME_MEASURE) &&
             (MC_DEADTIME_MEASURE == 0 || MC_DEADTIME_MEASURE == 1),
         "must be 0 or 1");
MC_CHECK(MC_TORQUE_MODE,
         MC_IS_INTEGER_(MC_TORQUE_MODE) && (MC_TORQUE_MODE == 0 || MC_TORQUE_MODE == 1),
         "must be 0 (speed mode) or 1 (torque mode)");
MC_CHECK(MC_VOLTAGE_RIPPLE,
         MC_IS_INTEGER_(MC_VOLTAGE_RIPPLE) && (MC_VOLTAGE_RIPPLE == 0 || MC_VOLTAGE_RIPPLE == 1),
         "must be 0 (off) or 1 (on)");
MC_CHECK(MC_DEADTIME_COMP,
         MC_IS_INTEGER_(MC_DEADTIME_COMP) && (MC_DEADTIME_COMP == 0 || MC_DEADTIME_COMP == 1),
         "must be 0 or 1");

/* ---- timing ------------------------------------------------------------- */

MC_CHECK(PWM_FREQUENCY_HZ, PWM_FREQUENCY_HZ >= 4000L && PWM_FREQUENCY_HZ <= 40000L,
         "must be in 4000..40000 Hz");
MC_CHECK_FOR(PWM_FREQUENCY_HZ, BOARD_FCY_HZ, (long)BOARD_FCY_HZ % (long)PWM_FREQUENCY_HZ == 0,
             "BOARD_FCY_HZ / PWM_FREQUENCY_HZ must be an integer "
             "(it is the duty full scale)");
MC_CHECK_FOR(PWM_FREQUENCY_HZ, BOARD_FCY_HZ, BOARD_FCY_HZ / PWM_FREQUENCY_HZ <= 32767L,
             "duty full scale BOARD_FCY_HZ / PWM_FREQUENCY_HZ must be "
             "<= 32767 counts");

/* PWM_DUTY_MAX, the duty full scale, is boards/board.h's. */
#define MC_TS_S (1.0 / (double)PWM_FREQUENCY_HZ)

/* The sample instant as a fraction of the period after its start (mc.h
 * timing contract): the midpoint of the center-aligned PWM, where every
 * low-side switch conducts, plus the trigger offset. 0.54 on the MCLV. */
#define MC_SAMPLE_AT                                                                               \
    (0.5 + (double)PWM_ADC_TRIGGER_TCY * (double)PWM_FREQUENCY_HZ / (double)BOARD_FCY_HZ)
MC_CHECK(PWM_ADC_TRIGGER_TCY,
         PWM_ADC_TRIGGER_TCY >= 0L && PWM_ADC_TRIGGER_TCY * 2L * PWM_FREQUENCY_HZ < BOARD_FCY_HZ,
         "the trigger must fall in the second half of the period");

MC_CHECK(MC_SPEED_LOOP_HZ,
         MC_SPEED_LOOP_HZ > 0 && (long)PWM_FREQUENCY_HZ % (long)MC_SPEED_LOOP_HZ == 0,
         "must divide PWM_FREQUENCY_HZ");
MC_CHECK(MC_SPEED_LOOP_HZ,
         PWM_FREQUENCY_HZ / MC_SPEED_LOOP_HZ >= 1 && PWM_FREQUENCY_HZ / MC_SPEED_LOOP_HZ <= 256,
         "IRP_PERCALC = PWM_FREQUENCY_HZ / MC_SPEED_LOOP_HZ must be "
         "in 1..256");
/* PWM periods per speed-loop run (AN1078 IRP_PERCALC). */
#define IRP_PERCALC ((uint16_t)(PWM_FREQUENCY_HZ / MC_SPEED_LOOP_HZ))
/* PWM periods after a window end at which the core takes the slow step's
 * results (mc.h): the time mc_slow_step() has to finish, 250 us at 20 kHz.
 * Short, because it sits inside the speed loop; docs/performance.md shows
 * the slow step's cycles against it. */
#define MC_SLOW_APPLY_PERIODS 5U
MC_CHECK(MC_SPEED_LOOP_HZ, PWM_FREQUENCY_HZ / MC_SPEED_LOOP_HZ > MC_SLOW_APPLY_PERIODS,
         "IRP_PERCALC = PWM_FREQUENCY_HZ / MC_SPEED_LOOP_HZ must exceed "
         "MC_SLOW_APPLY_PERIODS (5): the slow step's results come back inside the window");

/* ---- board scales and limits ----------------------------------------------- */

MC_CHECK(BOARD_I_FULLSCALE_A, BOARD_I_FULLSCALE_A > 0.0, "must be > 0");
MC_CHECK(BOARD_VBUS_FULLSCALE_V, BOARD_VBUS_FULLSCALE_V > 0.0, "must be > 0");
MC_CHECK_FOR(BOARD_VBUS_NOMINAL_V, BOARD_VBUS_FULLSCALE_V,
             BOARD_VBUS_NOMINAL_V > 0.0 && BOARD_VBUS_NOMINAL_V < BOARD_VBUS_FULLSCALE_V,
             "must be in (0, BOARD_VBUS_FULLSCALE_V)");
/* The board's default bus window (UserParms.h copies it into MC_VBUS_*),
 * checked as the board's own fact before the application's. */
MC_CHECK_FOR(BOARD_VBUS_UNDERVOLTAGE_V, BOARD_VBUS_NOMINAL_V,
             BOARD_VBUS_UNDERVOLTAGE_V > 0.0 && BOARD_VBUS_UNDERVOLTAGE_V < BOARD_VBUS_NOMINAL_V,
             "must be in (0, BOARD_VBUS_NOMINAL_V)");
MC_CHECK_FOR(BOARD_VBUS_OVERVOLTAGE_V, BOARD_VBUS_NOMINAL_V,
             BOARD_VBUS_OVERVOLTAGE_V > BOARD_VBUS_NOMINAL_V, "must be above BOARD_VBUS_NOMINAL_V");
MC_CHECK_FOR(BOARD_VBUS_OVERVOLTAGE_V, BOARD_VBUS_FULLSCALE_V,
             BOARD_VBUS_OVERVOLTAGE_V < BOARD_VBUS_FULLSCALE_V,
             "must be below BOARD_VBUS_FULLSCALE_V");
MC_CHECK_FOR(BOARD_VBUS_OVERVOLTAGE_V, BOARD_VBUS_MAX_V,
             BOARD_VBUS_OVERVOLTAGE_V <= BOARD_VBUS_MAX_V,
             "must be at most the power stage's rating BOARD_VBUS_MAX_V");
MC_CHECK_FOR(BOARD_DEADTIME_NS, PWM_FREQUENCY_HZ,
             BOARD_DEADTIME_NS >= 0L && (double)BOARD_DEADTIME_NS * 1e-9 * (double)BOARD_FCY_HZ <
                                            0.1 * (double)(BOARD_FCY_HZ / PWM_FREQUENCY_HZ),
             "must be below 10 % of the PWM period");
/* BOARD_DEADTIME_NS is the least the power stage needs (its profile): a
 * shorter PWM dead time lets a leg's two switches conduct together. The HAL,
 * which programs it, checks the same (hal_dspic33f.h). */
MC_CHECK_FOR(PWM_DEADTIME_NS, BOARD_DEADTIME_NS, PWM_DEADTIME_NS >= BOARD_DEADTIME_NS,
             "must be at least the power stage's BOARD_DEADTIME_NS (shoot-through)");

/* SVGen full scale: the largest linear phase amplitude at the nominal bus. */
#define MC_VOLTAGE_FULLSCALE_V (BOARD_VBUS_NOMINAL_V / 1.7320508075688772)
/* Electrical frequency of Q15 full-scale speed (the estimator's omega_fs). */
#define MC_OMEGA_FS_HZ ((double)MC_SPEED_FULLSCALE_RPM * (double)MOTOR_POLE_PAIRS / 60.0)

#define MC_Q15_AMPS(a)  Q15_SCALED((a), BOARD_I_FULLSCALE_A)
#define MC_Q15_VOLTS(v) Q15_SCALED((v), MC_VOLTAGE_FULLSCALE_V)
#define MC_Q15_VBUS(v)  Q15_SCALED((v), BOARD_VBUS_FULLSCALE_V)
#define MC_Q15_RPM(r)   Q15_SCALED((r), MC_SPEED_FULLSCALE_RPM)

/* Coefficients >= 1: Q15 mantissa and shift (q15.h). */
#define MC_SHIFT_OF(x) Q15_SHIFT7_OF(x)
#define MC_MANT_OF(x)  Q15_MANT7_OF(x)

/* ---- motor model ------------------------------------------------------------- */

/* The motor's electrical data first: the observer, the current gains, the
 * dead-time band and the speed limits below are all computed from them. */
MC_CHECK(MOTOR_RS_OHM, MOTOR_RS_OHM > 0.0, "must be > 0");
MC_CHECK(MOTOR_LS_H, MOTOR_LS_H > 0.0, "must be > 0");
MC_CHECK_FOR(MOTOR_RS_OHM, MOTOR_LS_H, MC_TS_S *MOTOR_RS_OHM / MOTOR_LS_H < 1.0,
             "F = 1 - Ts R / L must be > 0 (R too large for MOTOR_LS_H)");
MC_CHECK(MOTOR_LS_H, MC_TS_S / MOTOR_LS_H * MC_VOLTAGE_FULLSCALE_V / BOARD_I_FULLSCALE_A < 1.0,
         "G = Ts/L * V_FS/I_FS must be < 1 (L too small for the board "
         "scales)");
/* The observer's G (smc.h) in its Q15 mantissa: at least 1e-4. */
MC_CHECK(MOTOR_LS_H,
         SMC_GE_(MOTOR_RS_OHM, MOTOR_LS_H, MC_TS_S, MC_VOLTAGE_FULLSCALE_V, BOARD_I_FULLSCALE_A) >=
             1e-4,
         "G = (1 - F) / R * 2 V_FS / I_FS must be >= 1e-4 (L too large for the board scales)");
MC_CHECK(MOTOR_KE_VPK_LL_PER_KRPM, MOTOR_KE_VPK_LL_PER_KRPM > 0.0, "must be > 0");

/* ---- speed scale ---------------------------------------------------------------- */

MC_CHECK(MOTOR_SPEED_NOMINAL_RPM, MOTOR_SPEED_NOMINAL_RPM > 0.0, "must be > 0");
MC_CHECK_FOR(MOTOR_SPEED_FW_MAX_RPM, MOTOR_SPEED_NOMINAL_RPM,
             MOTOR_SPEED_FW_MAX_RPM >= MOTOR_SPEED_NOMINAL_RPM,
             "must be >= MOTOR_SPEED_NOMINAL_RPM (equal: no field "
             "weakening)");
/* The profile's speed scale (UserParms.h's default MC_SPEED_FULLSCALE_RPM),
 * checked as the profile's own fact, then the one the core uses. Above
 * the top speed by 5 % (room for overshoot); the electrical frequency at
 * full scale below fpwm / (2 pi) (the observer's speed-to-angle gain, smc.h,
 * and the core's one-period angle steps, mc.c) and high enough for the
 * observer's speed scale (smc.h); at most 8 times the top speed, so that
 * the speed keeps 4096 counts of resolution. */
/* The top speed's largest share of the speed full scale. */
#define MC_SPEED_FS_TOP_FRACTION 0.95
#define MC_FS_RPM_OK_(fs)                                                                          \
    ((fs) > 0.0 && MOTOR_SPEED_FW_MAX_RPM <= MC_SPEED_FS_TOP_FRACTION * (fs) &&                    \
     (fs) <= 8.0 * MOTOR_SPEED_FW_MAX_RPM &&                                                       \
     6.283185307179586 * (double)(fs) * (double)MOTOR_POLE_PAIRS / 60.0 * MC_TS_S < 1.0 &&         \
     SMC_KSPEED_(MC_TS_S, (double)(fs) * (double)MOTOR_POLE_PAIRS / 60.0, IRP_PERCALC) < 32768.0)
MC_CHECK_FOR(MOTOR_SPEED_FULLSCALE_RPM, MOTOR_SPEED_FW_MAX_RPM,
             MC_FS_RPM_OK_(MOTOR_SPEED_FULLSCALE_RPM),
             "must be in [MOTOR_SPEED_FW_MAX_RPM / 0.95, 8 MOTOR_SPEED_FW_MAX_RPM] and "
             "below 60 PWM_FREQUENCY_HZ / (2 pi MOTOR_POLE_PAIRS) rpm");
MC_CHECK_FOR(MC_SPEED_FULLSCALE_RPM, MOTOR_SPEED_FW_MAX_RPM, MC_FS_RPM_OK_(MC_SPEED_FULLSCALE_RPM),
             "must be in [MOTOR_SPEED_FW_MAX_RPM / 0.95, 8 MOTOR_SPEED_FW_MAX_RPM] and "
             "below 60 PWM_FREQUENCY_HZ / (2 pi MOTOR_POLE_PAIRS) rpm");

/* ---- speeds --------------------------------------------------------------- */

MC_CHECK_FOR(MOTOR_SPEED_MIN_RPM, MOTOR_SPEED_NOMINAL_RPM,
             MOTOR_SPEED_MIN_RPM > 0.0 && MOTOR_SPEED_MIN_RPM < MOTOR_SPEED_NOMINAL_RPM,
             "must be in (0, MOTOR_SPEED_NOMINAL_RPM)");
MC_CHECK_FOR(MOTOR_RAMP_END_RPM, MOTOR_SPEED_NOMINAL_RPM,
             MOTOR_RAMP_END_RPM > 0.0 && MOTOR_RAMP_END_RPM < MOTOR_SPEED_NOMINAL_RPM,
             "must be in (0, MOTOR_SPEED_NOMINAL_RPM)");
MC_CHECK_FOR(SPEED_REF_MIN_RPM, SPEED_REF_MAX_RPM,
             SPEED_REF_MIN_RPM > 0.0 && SPEED_REF_MIN_RPM < SPEED_REF_MAX_RPM,
             "must be in (0, SPEED_REF_MAX_RPM)");
MC_CHECK_FOR(SPEED_REF_MAX_RPM, MOTOR_SPEED_FW_MAX_RPM, SPEED_REF_MAX_RPM <= MOTOR_SPEED_FW_MAX_RPM,
             "must be <= MOTOR_SPEED_FW_MAX_RPM");
/* The observer's floor (smc.h): its angle step at this speed at least one
 * Q15 count per period. */
MC_CHECK_FOR(MC_ESTIMATOR_MIN_RPM, MOTOR_RAMP_END_RPM,
             MC_ESTIMATOR_MIN_RPM > 0.0 && MC_ESTIMATOR_MIN_RPM <= MOTOR_RAMP_END_RPM &&
                 SMC_KPW_(MC_TS_S, (double)MC_ESTIMATOR_MIN_RPM *MOTOR_POLE_PAIRS / 60.0) >=
                     1.0 / 32768.0,
             "must be in (0, MOTOR_RAMP_END_RPM], at least 1/32768 of an electrical radian per "
             "period");

#define MC_SPEED_REF_MIN_Q15 MC_Q15_RPM(SPEED_REF_MIN_RPM)
#define MC_SPEED_REF_MAX_Q15 MC_Q15_RPM(SPEED_REF_MAX_RPM)
/* Speed reference slew per speed-loop run, Q15 speed. */
#define MC_SPEED_RAMP_STEP_                                                                        \
    ((double)MC_SPEED_RAMP_RPM_PER_S / (double)MC_SPEED_LOOP_HZ / (double)MC_SPEED_FULLSCALE_RPM * \
     32768.0)
MC_CHECK_FOR(MC_SPEED_RAMP_RPM_PER_S, MC_SPEED_FULLSCALE_RPM,
             MC_SPEED_RAMP_STEP_ >= 1.0 && MC_SPEED_RAMP_STEP_ < 32767.0,
             "must give 1..32767 Q15 counts per speed-loop run");
#define MC_SPEED_RAMP_STEP ((q15_t)(MC_SPEED_RAMP_STEP_ + 0.5))

/* ---- currents -------------------------------------------------------------- */

MC_CHECK_FOR(MOTOR_CURRENT_MAX_A, BOARD_I_FULLSCALE_A,
             MOTOR_CURRENT_MAX_A > 0.0 && MOTOR_CURRENT_MAX_A < BOARD_I_FULLSCALE_A,
             "must be in (0, BOARD_I_FULLSCALE_A)");
/* The profile's trip (UserParms.h's default MC_OVERCURRENT_A) as the
 * profile's own fact, then the one the core uses. */
MC_CHECK_FOR(MOTOR_OVERCURRENT_A, MOTOR_CURRENT_MAX_A,
             MOTOR_OVERCURRENT_A > MOTOR_CURRENT_MAX_A && MOTOR_OVERCURRENT_A < BOARD_I_FULLSCALE_A,
             "must be in (MOTOR_CURRENT_MAX_A, BOARD_I_FULLSCALE_A)");
MC_CHECK_FOR(MC_OVERCURRENT_A, MOTOR_CURRENT_MAX_A,
             MC_OVERCURRENT_A > MOTOR_CURRENT_MAX_A && MC_OVERCURRENT_A < BOARD_I_FULLSCALE_A,
             "must be in (MOTOR_CURRENT_MAX_A, BOARD_I_FULLSCALE_A)");
MC_CHECK_FOR(MOTOR_LOCK_CURRENT_A, MC_OVERCURRENT_A,
             MOTOR_LOCK_CURRENT_A > 0.0 && MOTOR_LOCK_CURRENT_A < MC_OVERCURRENT_A,
             "must be in (0, MC_OVERCURRENT_A)");
MC_CHECK_FOR(MOTOR_RAMP_CURRENT_A, MOTOR_CURRENT_MAX_A,
             MOTOR_RAMP_CURRENT_A > 0.0 && MOTOR_RAMP_CURRENT_A <= MOTOR_CURRENT_MAX_A,
             "must be in (0, MOTOR_CURRENT_MAX_A]");
MC_CHECK(MC_OFFSET_MAX_A, MC_OFFSET_MAX_A > 0.0 && MC_OFFSET_MAX_A < BOARD_I_FULLSCALE_A,
         "must be in (0, BOARD_I_FULLSCALE_A)");
/* The largest trip a phase reaches on both polarities, A: the trip compares
 * offset-corrected readings (mc_measure), one polarity of the ADC reads at
 * most 2^(bits-1) - 1 codes of the 2^(bits-1) of full scale, and an offset
 * up to MC_OFFSET_MAX_A that calibration accepts comes off it. A trip above
 * this is never reached on that side of that phase. */
#define MC_TRIP_REACH_A                                                                            \
    (BOARD_I_FULLSCALE_A * (1.0 - 1.0 / (double)(1L << (BOARD_ADC_BITS - 1))) - MC_OFFSET_MAX_A)
MC_CHECK_FOR(MOTOR_OVERCURRENT_A, MC_OFFSET_MAX_A, MOTOR_OVERCURRENT_A <= MC_TRIP_REACH_A,
             "must be reachable: at most BOARD_I_FULLSCALE_A less one code and MC_OFFSET_MAX_A");
MC_CHECK_FOR(MC_OVERCURRENT_A, MC_OFFSET_MAX_A, MC_OVERCURRENT_A <= MC_TRIP_REACH_A,
             "must be reachable: at most BOARD_I_FULLSCALE_A less one code and MC_OFFSET_MAX_A");

#define MC_IQ_MAX_Q15       MC_Q15_AMPS(MOTOR_CURRENT_MAX_A)
#define MC_OVERCURRENT_Q15  MC_Q15_AMPS(MC_OVERCURRENT_A)
#define MC_LOCK_CURRENT_Q15 MC_Q15_AMPS(MOTOR_LOCK_CURRENT_A)
#define MC_RAMP_CURRENT_Q15 MC_Q15_AMPS(MOTOR_RAMP_CURRENT_A)
#define MC_OFFSET_MAX_Q15   MC_Q15_AMPS(MC_OFFSET_MAX_A)

/* ---- DC bus ---------------------------------------------------------------- */

MC_CHECK_FOR(MC_VBUS_UNDERVOLTAGE_V, BOARD_VBUS_NOMINAL_V,
             MC_VBUS_UNDERVOLTAGE_V > 0.0 && MC_VBUS_UNDERVOLTAGE_V < BOARD_VBUS_NOMINAL_V,
             "must be in (0, BOARD_VBUS_NOMINAL_V)");
MC_CHECK_FOR(MC_VBUS_OVERVOLTAGE_V, BOARD_VBUS_NOMINAL_V,
             MC_VBUS_OVERVOLTAGE_V > BOARD_VBUS_NOMINAL_V, "must be above BOARD_VBUS_NOMINAL_V");
MC_CHECK_FOR(MC_VBUS_OVERVOLTAGE_V, BOARD_VBUS_FULLSCALE_V,
             MC_VBUS_OVERVOLTAGE_V < BOARD_VBUS_FULLSCALE_V,
             "must be below BOARD_VBUS_FULLSCALE_V");
MC_CHECK_FOR(MC_VBUS_OVERVOLTAGE_V, BOARD_VBUS_MAX_V, MC_VBUS_OVERVOLTAGE_V <= BOARD_VBUS_MAX_V,
             "must be at most the power stage's rating BOARD_VBUS_MAX_V");
#define MC_VBUS_UV_Q15      MC_Q15_VBUS(MC_VBUS_UNDERVOLTAGE_V)
#define MC_VBUS_OV_Q15      MC_Q15_VBUS(MC_VBUS_OVERVOLTAGE_V)
#define MC_VBUS_NOMINAL_Q15 MC_Q15_VBUS(BOARD_VBUS_NOMINAL_V)
/* The braking limit (mc_regen_limit): from MC_VBUS_REGEN_Q15 up the allowed
 * braking current falls linearly to 0 over MC_VBUS_REGEN_BAND_Q15 counts;
 * MC_VBUS_REGEN_K = 32767 * 2^10 / band (the band at least 8 counts, so
 * that (band - over) K < 2^25). */
MC_CHECK_FOR(MC_VBUS_REGEN_V, BOARD_VBUS_NOMINAL_V, MC_VBUS_REGEN_V > BOARD_VBUS_NOMINAL_V,
             "must be above BOARD_VBUS_NOMINAL_V (the bus at rest would brake nothing)");
MC_CHECK_FOR(MC_VBUS_REGEN_BAND_V, MC_VBUS_OVERVOLTAGE_V,
             MC_VBUS_REGEN_BAND_V > 0.0 &&
                 MC_VBUS_REGEN_V + MC_VBUS_REGEN_BAND_V < MC_VBUS_OVERVOLTAGE_V,
             "must be > 0, and MC_VBUS_REGEN_V + it below MC_VBUS_OVERVOLTAGE_V");
#define MC_VBUS_REGEN_Q15      MC_Q15_VBUS(MC_VBUS_REGEN_V)
#define MC_VBUS_REGEN_BAND_Q15 MC_Q15_VBUS(MC_VBUS_REGEN_BAND_V)
MC_CHECK_FOR(MC_VBUS_REGEN_BAND_V, BOARD_VBUS_FULLSCALE_V, MC_VBUS_REGEN_BAND_Q15 >= 8,
             "must be at least 8 counts of BOARD_VBUS_FULLSCALE_V");
#define MC_VBUS_REGEN_K ((int32_t)(32767.0 * 1024.0 / (double)MC_VBUS_REGEN_BAND_Q15 + 0.5))
/* The release speed of a STOP (mc_release_speed): Q15 speed = vbus (Q15) *
 * MC_STOP_RELEASE_K >> 12, the speed whose line-to-line back-EMF peak is
 * MC_STOP_RELEASE_FRACTION of the bus. */
MC_CHECK(MC_STOP_RELEASE_FRACTION, MC_STOP_RELEASE_FRACTION > 0.0 && MC_STOP_RELEASE_FRACTION < 1.0,
         "must be in (0, 1): the back-EMF at release below the bus");
#define MC_STOP_RELEASE_K_                                                                         \
    ((double)MC_STOP_RELEASE_FRACTION * (double)BOARD_VBUS_FULLSCALE_V * 1000.0 /                  \
     ((double)MOTOR_KE_VPK_LL_PER_KRPM * (double)MC_SPEED_FULLSCALE_RPM) * 4096.0)
MC_CHECK_FOR(MC_STOP_RELEASE_FRACTION, MOTOR_KE_VPK_LL_PER_KRPM,
             MC_STOP_RELEASE_K_ >= 16.0 && MC_STOP_RELEASE_K_ < 32767.0,
             "with Ke and the bus's full scale, out of the release speed's scaling");
#define MC_STOP_RELEASE_K ((int32_t)(MC_STOP_RELEASE_K_ + 0.5))

/* ---- voltage limit ----------------------------------------------------------- */

MC_CHECK(MC_VOLTAGE_LIMIT_FRACTION,
         MC_VOLTAGE_LIMIT_FRACTION > 0.5 && MC_VOLTAGE_LIMIT_FRACTION <= 1.0,
         "must be in (0.5, 1]");
#define MC_VMAX_Q15 Q15(MC_VOLTAGE_LIMIT_FRACTION)

/* ---- current PI (d and q): gains in V/A and V/(A s) to Q15 of V_FS per I_FS ---- */

#define MC_CUR_KP_ ((double)MOTOR_CURRENT_KP_V_PER_A * BOARD_I_FULLSCALE_A / MC_VOLTAGE_FULLSCALE_V)
#define MC_CUR_KI_                                                                                 \
    ((double)MOTOR_CURRENT_KI_V_PER_AS * MC_TS_S * BOARD_I_FULLSCALE_A / MC_VOLTAGE_FULLSCALE_V)
/* The profiles' default gains come from a loop bandwidth: Kp = L wc,
 * Ki = R wc. The loop acts about 1.5 periods after its sample (mc.h note
 * 2), which takes 1.5 wc Ts rad of phase at the crossover: none is left of
 * the integrator's 90 deg at wc Ts = pi / 3, so wc Ts must stay below 1. */
#ifdef MOTOR_CURRENT_LOOP_BW_RAD_S
MC_CHECK(MOTOR_CURRENT_LOOP_BW_RAD_S,
         MOTOR_CURRENT_LOOP_BW_RAD_S > 0.0 && MOTOR_CURRENT_LOOP_BW_RAD_S * MC_TS_S < 1.0,
         "must be in (0, PWM_FREQUENCY_HZ) rad/s");
#endif
/* A gain that rounds to 0 leaves the loop without that term. The PIs take
 * a Kp below MC_KP_MAX (a Q15 mantissa and a left shift of 0..7) and a Ki
 * below MC_KI_MAX (plain Q15). */
#define MC_KP_MAX 128.0
#define MC_KI_MAX 1.0
MC_CHECK_FOR(MOTOR_CURRENT_KP_V_PER_A, BOARD_I_FULLSCALE_A,
             MC_CUR_KP_ * 32768.0 >= 0.5 && MC_CUR_KP_ < MC_KP_MAX,
             "Kp * I_FS / V_FS must be in [1 Q15 count, 128): > 0 and not rounding to 0");
MC_CHECK_FOR(MOTOR_CURRENT_KI_V_PER_AS, BOARD_I_FULLSCALE_A,
             MC_CUR_KI_ * 32768.0 >= 0.5 && MC_CUR_KI_ < MC_KI_MAX,
             "Ki * Ts * I_FS / V_FS must be in [1 Q15 count, 1): > 0 and not rounding to 0");
#define MC_CUR_KP       MC_MANT_OF(MC_CUR_KP_)
#define MC_CUR_KP_SHIFT ((uint8_t)MC_SHIFT_OF(MC_CUR_KP_))
#define MC_CUR_KI       Q15(MC_CUR_KI_)

/* ---- speed PI: A/rpm and A/(rpm s) to Q15 current per Q15 speed ------------------ */

#define MC_SPD_KP_ ((double)MOTOR_SPEED_KP_A_PER_RPM * MC_SPEED_FULLSCALE_RPM / BOARD_I_FULLSCALE_A)
#define MC_SPD_KI_                                                                                 \
    ((double)MOTOR_SPEED_KI_A_PER_RPM_S / (double)MC_SPEED_LOOP_HZ * MC_SPEED_FULLSCALE_RPM /      \
     BOARD_I_FULLSCALE_A)
MC_CHECK(MOTOR_SPEED_KP_A_PER_RPM, MC_SPD_KP_ * 32768.0 >= 0.5 && MC_SPD_KP_ < MC_KP_MAX,
         "Kp * speed FS / I_FS must be in [1 Q15 count, 128): > 0 and not rounding to 0");
MC_CHECK(MOTOR_SPEED_KI_A_PER_RPM_S, MC_SPD_KI_ * 32768.0 >= 0.5 && MC_SPD_KI_ < MC_KI_MAX,
         "Ki / MC_SPEED_LOOP_HZ * speed FS / I_FS must be in [1 Q15 count, 1): > 0 and not "
         "rounding to 0");
/* Kp's low-speed schedule divides by this speed in Q15 (mc.c): at least 16
 * counts. */
MC_CHECK_FOR(MOTOR_SPEED_KP_FULL_RPM, MOTOR_SPEED_FW_MAX_RPM,
             MOTOR_SPEED_KP_FULL_RPM <= MOTOR_SPEED_FW_MAX_RPM &&
                 MOTOR_SPEED_KP_FULL_RPM / MC_SPEED_FULLSCALE_RPM * 32768.0 >= 16.0,
             "must be in [16 Q15 counts of speed, MOTOR_SPEED_FW_MAX_RPM]");
MC_CHECK(MC_SPEED_KP_MIN_FRACTION,
         MC_SPEED_KP_MIN_FRACTION * 32768.0 >= 0.5 && MC_SPEED_KP_MIN_FRACTION <= 1.0,
         "must be in [1 Q15 count, 1]");
#define MC_SPD_KP       MC_MANT_OF(MC_SPD_KP_)
#define MC_SPD_KP_SHIFT ((uint8_t)MC_SHIFT_OF(MC_SPD_KP_))
#define MC_SPD_KI       Q15(MC_SPD_KI_)

/* Anti-windup gain of every loop: 1 - 2^-15 removes the whole excess each
 * call (AN1078's 0.99999). */
#define MC_PI_KC ((q15_t)32767)

/* ---- start-up -------------------------------------------------------------------- */

/* The lock's period count is a uint16_t. */
#define MC_LOCK_PERIODS_MAX 65000.0
MC_CHECK(MOTOR_LOCK_TIME_S,
         MOTOR_LOCK_TIME_S *PWM_FREQUENCY_HZ >= 1.0 &&
             MOTOR_LOCK_TIME_S * PWM_FREQUENCY_HZ <= MC_LOCK_PERIODS_MAX,
         "must be 1..65000 PWM periods");
#define MC_LOCK_PERIODS ((uint16_t)(MOTOR_LOCK_TIME_S * PWM_FREQUENCY_HZ + 0.5))

MC_CHECK(MC_OFFSET_CALIB_TIME_S,
         MC_OFFSET_CALIB_TIME_S *PWM_FREQUENCY_HZ >= 16.0 &&
             MC_OFFSET_CALIB_TIME_S * PWM_FREQUENCY_HZ <= 32767.0,
         "must be 16..32767 PWM periods (the offset mean is one div.sd)");
#define MC_CALIB_PERIODS ((uint16_t)(MC_OFFSET_CALIB_TIME_S * PWM_FREQUENCY_HZ + 0.5))

MC_CHECK(MC_RETRY_COAST_S,
         MC_RETRY_COAST_S *PWM_FREQUENCY_HZ >= 0.0 &&
             MC_RETRY_COAST_S * PWM_FREQUENCY_HZ <= 65000.0,
         "must be 0..65000 PWM periods");
#define MC_COAST_PERIODS ((uint16_t)(MC_RETRY_COAST_S * PWM_FREQUENCY_HZ + 0.5))

/* Periods CALIBRATE lets pass before it averages the offsets, at least: the
 * first conversions after the ADC is switched on may be off [MEM], and a
 * START can follow power-up at once (a remote start); the amplifiers also
 * settle from the last PWM edges. 16 periods = 0.8 ms at 20 kHz. */
#define MC_CALIB_SKIP_PERIODS 16U
/* A retry's wait before averaging: its coast, at least the skip. */
#define MC_RETRY_CALIB_WAIT                                                                        \
    ((uint16_t)(MC_COAST_PERIODS > MC_CALIB_SKIP_PERIODS ? MC_COAST_PERIODS                        \
                                                         : MC_CALIB_SKIP_PERIODS))

/* Open-loop ramp, constant acceleration: the 32-bit angle step grows by
 * MC_RAMP_STEP_INC each period; the ramp ends when the step reaches
 * MC_RAMP_STEP_END = MC_RAMP_STEP_INC * ramp periods (built from integers so
 * the 16-bit build gets the same numbers). */
#define MC_RAMP_PERIODS_ ((double)MOTOR_RAMP_TIME_S * (double)PWM_FREQUENCY_HZ)
#define MC_RAMP_STEP_INC_                                                                          \
    ((double)MOTOR_RAMP_END_RPM * MOTOR_POLE_PAIRS / 60.0 * MC_TS_S * 4294967296.0 /               \
     MC_RAMP_PERIODS_)
MC_CHECK(MOTOR_RAMP_TIME_S, MC_RAMP_PERIODS_ >= 100.0 && MC_RAMP_PERIODS_ <= 4.0e6,
         "must be 100..4e6 PWM periods");
/* The ramp's smallest step increment (32-bit angle counts per period). */
#define MC_RAMP_STEP_INC_MIN 8.0
MC_CHECK(MOTOR_RAMP_TIME_S, MC_RAMP_STEP_INC_ >= MC_RAMP_STEP_INC_MIN,
         "ramp too slow for the 32-bit angle (step increment < 8)");
#define MC_RAMP_STEP_INC ((uint32_t)(MC_RAMP_STEP_INC_ + 0.5))
#define MC_RAMP_STEP_END (MC_RAMP_STEP_INC * (uint32_t)(MC_RAMP_PERIODS_ + 0.5))
#define MC_RAMP_PERIODS  ((uint32_t)(MC_RAMP_PERIODS_ + 0.5))
MC_CHECK(MC_HANDOFF_WAIT_S,
         MC_HANDOFF_WAIT_S >= 0.0 && MC_HANDOFF_WAIT_S * PWM_FREQUENCY_HZ <= 1.0e6,
         "must be 0..1e6 PWM periods");
#define MC_HANDOFF_WAIT_PERIODS ((uint32_t)(MC_HANDOFF_WAIT_S * PWM_FREQUENCY_HZ + 0.5))
/* A locked rotor heats at the start-up currents for every attempt's lock,
 * ramp and hand-off wait, and a retry that does not coast first starts
 * from a rotor still turning from the last: at most 10 retries, each after
 * some coasting. */
MC_CHECK_FOR(MC_RETRY_COAST_S, MC_START_RETRIES,
             MC_START_RETRIES == 0 || MC_RETRY_COAST_S * PWM_FREQUENCY_HZ >= 0.5,
             "a retry must coast (the outputs off) before it locks again: more than 0 s");
/* In Q8 below (MC_HANDOFF_TOL_Q8): 0 would never agree. */
/* Above 1/2 the check would take a rotor at half or one and a half times the
 * forced speed (slipping poles, or the estimator reading its own model
 * errors) for one that follows. */
MC_CHECK(MC_HANDOFF_SPEED_TOL, MC_HANDOFF_SPEED_TOL * 256.0 >= 0.5 && MC_HANDOFF_SPEED_TOL <= 0.5,
         "must be in [1/256, 1/2]");
MC_CHECK_FOR(MC_HANDOFF_AGREE_S, MC_HANDOFF_WAIT_S,
             MC_HANDOFF_AGREE_S >= 0.0 && MC_HANDOFF_AGREE_S < MC_HANDOFF_WAIT_S &&
                 MC_HANDOFF_AGREE_S * PWM_FREQUENCY_HZ <= 65535.0,
             "must be in [0, MC_HANDOFF_WAIT_S) and at most 65535 PWM periods");
#define MC_HANDOFF_AGREE_PERIODS ((uint16_t)(MC_HANDOFF_AGREE_S * PWM_FREQUENCY_HZ + 0.5))
/* The agreement band in angle counts per period at the ramp end (Q8 of the
 * step's upper half, so the tolerance keeps 1/256 resolution). */
#define MC_HANDOFF_TOL_Q8 ((int32_t)(MC_HANDOFF_SPEED_TOL * 256.0 + 0.5))
/* Ramp end speed (mechanical Q15) = step end * fpwm * 60 / (2^32 pp FS). */
#define MC_RAMP_END_Q15 MC_Q15_RPM(MOTOR_RAMP_END_RPM)

/* Hand-off angle bleed per period, binary angle counts. */
#define MC_BLEED_STEP_                                                                             \
    ((double)MC_HANDOFF_BLEED_DEG_PER_S / (double)PWM_FREQUENCY_HZ * 65536.0 / 360.0)
MC_CHECK(MC_HANDOFF_BLEED_DEG_PER_S, MC_BLEED_STEP_ >= 1.0 && MC_BLEED_STEP_ <= 4096.0,
         "must give 1..4096 angle counts per period");
#define MC_BLEED_STEP ((int16_t)(MC_BLEED_STEP_ + 0.5))

/* Current-sensor plausibility (UserParms.h, mc.c note 5), judged once per
 * speed-loop window on the window's sums: the failing windows that trip
 * (each counts 2 in sens_cnt), the error floor, and the start's extra
 * low-pass over windows (a power of two: a shift). */
#define MC_SENSOR_WINDOWS_ ((double)MC_SENSOR_TIME_S * (double)MC_SPEED_LOOP_HZ)
MC_CHECK(MC_SENSOR_TIME_S, MC_SENSOR_WINDOWS_ >= 2.0 && MC_SENSOR_WINDOWS_ <= 100.0,
         "must be 2 to 100 speed-loop windows");
MC_CHECK(MC_SENSOR_CHECK,
         MC_IS_INTEGER_(MC_SENSOR_CHECK) && (MC_SENSOR_CHECK == 0 || MC_SENSOR_CHECK == 1),
         "must be 0 or 1");
/* the floor in Q15 counts of I_FS; halved at the start: at least one count there */
#define MC_SENSOR_FLOOR_                                                                           \
    (MC_SENSOR_ERR_FLOOR_FRACTION * (double)MOTOR_CURRENT_MAX_A / (double)BOARD_I_FULLSCALE_A *    \
     32768.0)
MC_CHECK(MC_SENSOR_ERR_FLOOR_FRACTION,
         MC_SENSOR_ERR_FLOOR_FRACTION <= 0.5 && MC_SENSOR_FLOOR_ >= 2.0,
         "must be at most 0.5 of MOTOR_CURRENT_MAX_A and at least 2 Q15 counts of it");
#define MC_SENSOR_TRIP      ((uint8_t)(2.0 * MC_SENSOR_WINDOWS_ + 0.5))
#define MC_SENSOR_FLOOR_Q15 ((q15_t)(MC_SENSOR_FLOOR_ + 0.5))
/* The start's low-pass over windows: 8 (8 ms at 1 kHz), so that a rotor still
 * spinning from a failed attempt, whose back-EMF the lock's current loop
 * cannot hold, averages out; in CLOSED_LOOP the window's own 1 ms average
 * is enough against a low-inductance motor's current noise. */
#define MC_SENSOR_START_WINDOWS 8
/* Windows of a back-EMF below the stall check's low fraction, running, after
 * which the sensor check defers to the stall check (mc.c, mc_slow_sensor): 3,
 * where a failed sensor on a turning rotor has shown at most 2 in a row. */
#define MC_SENSOR_DEFER_WINDOWS 3
/* The phase balance (mc.c note 5): the mean squares of ia and ib, one
 * sample per window, low-passed over 2^MC_SENSOR_BAL_SHIFT windows (8 ms at
 * 1 kHz: a 50 Hz sine's square ripples by about 20 % there, a failed phase
 * decays to an eighth in 17 ms). Samples one per window are blind near an
 * electrical frequency of a multiple of half the window rate (the samples
 * then fall at one phase of the sine): the test rests within a tenth of it
 * of each multiple (and below a tenth), in Q15 speed; a speed scale that
 * never reaches the first multiple needs no modulus (32767). The floor:
 * the squared half of MC_SENSOR_FLOOR_Q15. */
#define MC_SENSOR_BAL_SHIFT 3
/* Windows of a low back-EMF after which the balance may override the
 * sensor check's hold: the balance filters' two time constants (16). */
#define MC_SENSOR_BAL_REFILL (2U << MC_SENSOR_BAL_SHIFT)
#define MC_SENSOR_BAL_SYNC_                                                                        \
    ((double)MC_SPEED_LOOP_HZ / 2.0 * 60.0 / (double)MOTOR_POLE_PAIRS /                            \
     (double)MC_SPEED_FULLSCALE_RPM * 32768.0)
#define MC_SENSOR_BAL_SYNC16                                                                       \
    ((q15_t)((MC_SENSOR_BAL_SYNC_ < 32767.0) ? MC_SENSOR_BAL_SYNC_ + 0.5 : 32767.0))
#define MC_SENSOR_BAL_BAND16                                                                       \
    ((q15_t)((MC_SENSOR_BAL_SYNC_ / 10.0 < 32767.0) ? MC_SENSOR_BAL_SYNC_ / 10.0 + 0.5 : 32767.0))
#define MC_SENSOR_BAL_UPPER16                                                                      \
    ((q15_t)((MC_SENSOR_BAL_SYNC_ * 0.9 < 32767.0) ? MC_SENSOR_BAL_SYNC_ * 0.9 + 0.5 : 32767.0))
MC_CHECK(MC_SPEED_LOOP_HZ, MC_SENSOR_BAL_SYNC_ / 10.0 >= 1.0,
         "too low for the sensor check's phase balance at this speed scale");
#define MC_SENSOR_BAL_FLOOR ((int32_t)(MC_SENSOR_FLOOR_ / 8.0 * (MC_SENSOR_FLOOR_ / 8.0) / 32768.0))

/* Open-loop damping (UserParms.h): the forced angle's shift in angle
 * counts = (forced - estimated step, counts per period) * MC_OL_DAMP_K / 16,
 * MC_OL_DAMP_K = MOTOR_OL_DAMP_S * fpwm in Q4; held to +-MC_OL_DAMP_MAX. */
/* MC_OL_DAMP_K: at most MC_OL_DAMP_PERIODS_MAX periods, in Q4 periods. */
#define MC_OL_DAMP_PERIODS_MAX       1000.0
#define MC_OL_DAMP_COUNTS_PER_PERIOD 16.0
MC_CHECK(MOTOR_OL_DAMP_S,
         MOTOR_OL_DAMP_S >= 0.0 && MOTOR_OL_DAMP_S * PWM_FREQUENCY_HZ <= MC_OL_DAMP_PERIODS_MAX &&
             MC_ZERO_OR_COUNTS_(MOTOR_OL_DAMP_S * PWM_FREQUENCY_HZ, MC_OL_DAMP_COUNTS_PER_PERIOD),
         "must be 0 (off) or 1/16..1000 PWM periods");
MC_CHECK(MC_OL_DAMP_MAX_DEG,
         MC_OL_DAMP_MAX_DEG >= 0.0 && MC_OL_DAMP_MAX_DEG <= 90.0 &&
             MC_ZERO_OR_COUNTS_(MC_OL_DAMP_MAX_DEG / 360.0, 65536.0),
         "must be 0 or 1 angle count (0.0055 deg) .. 90 deg");
#define MC_OL_DAMP_MEAN_N ((int32_t)(MC_OL_DAMP_MEAN_WINDOWS))
#define MC_OL_DAMP_K                                                                               \
    ((int32_t)(MOTOR_OL_DAMP_S * PWM_FREQUENCY_HZ * MC_OL_DAMP_COUNTS_PER_PERIOD + 0.5))
#define MC_OL_DAMP_MAX ((int32_t)(MC_OL_DAMP_MAX_DEG * 65536.0 / 360.0 + 0.5))

/* ---- dead time ---------------------------------------------------------------------- */

/* Dead time in duty counts: Td / Ts * PWM_DUTY_MAX = Td * Fcy (80 on the MCLV). */
#define MC_DT_COUNTS_ ((double)PWM_DEADTIME_NS * 1e-9 * (double)BOARD_FCY_HZ)
MC_CHECK_FOR(PWM_DEADTIME_NS, PWM_FREQUENCY_HZ,
             MC_DT_COUNTS_ >= 0.0 && MC_DT_COUNTS_ < 0.1 * (BOARD_FCY_HZ / PWM_FREQUENCY_HZ),
             "must be below 10 % of the PWM period");
#define MC_DT_COUNTS ((int16_t)(MC_DT_COUNTS_ + 0.5))

/* Shunt window (mc.h timing contract). Centre-aligned with PTPER =
 * PWM_DUTY_MAX / 2 - 1, a phase's low-side switch is commanded on from the
 * up-count's PTMR = PDC / 2 to the down-count's, and conducts from the dead
 * time after that. The sample comes PWM_ADC_TRIGGER_TCY after the midpoint
 * (PTMR = PTPER). So, in Tcy:
 *   the switch is still on at the sample:  PDC / 2 < PTPER - trigger;
 *   it has conducted long enough:          (PTPER - PDC / 2) + trigger -
 *                                          dead time >= BOARD_SHUNT_MIN_ON_NS.
 * MC_DUTY_SAMPLE_MAX is the largest PDC that meets both (the second
 * decides on the MCLV: 1758 of 2000, 87.9 %; the first alone would be 1836).
 * Duty counts are PDC units, 1 count = 1 Tcy of on-time. */
#define MC_SHUNT_MIN_ON_COUNTS_ ((double)BOARD_SHUNT_MIN_ON_NS * 1e-9 * (double)BOARD_FCY_HZ)
#define MC_PTPER_               ((double)PWM_DUTY_MAX / 2.0 - 1.0)
#define MC_DUTY_SAMPLE_ON_      (2.0 * (MC_PTPER_ - (double)PWM_ADC_TRIGGER_TCY) - 2.0)
#define MC_DUTY_SAMPLE_SETTLED_                                                                    \
    (2.0 * (MC_PTPER_ + (double)PWM_ADC_TRIGGER_TCY - MC_DT_COUNTS_ - MC_SHUNT_MIN_ON_COUNTS_))
#define MC_DUTY_SAMPLE_MAX_                                                                        \
    ((MC_DUTY_SAMPLE_ON_ < MC_DUTY_SAMPLE_SETTLED_) ? MC_DUTY_SAMPLE_ON_ : MC_DUTY_SAMPLE_SETTLED_)
MC_CHECK(BOARD_SHUNT_MIN_ON_NS,
         BOARD_SHUNT_MIN_ON_NS >= 0L && MC_DUTY_SAMPLE_MAX_ >= 0.75 * (double)PWM_DUTY_MAX,
         "with PWM_ADC_TRIGGER_TCY and PWM_DEADTIME_NS it must leave the measured phases at "
         "least 75 % duty (shunt window, mc_derived.h)");
#define MC_DUTY_SAMPLE_MAX ((int16_t)MC_DUTY_SAMPLE_MAX_)
MC_CHECK(PWM_FREQUENCY_HZ, BOARD_FCY_HZ / PWM_FREQUENCY_HZ + MC_DT_COUNTS_ + 1.0 <= 32767.0,
         "duty full scale plus the dead-time counts must fit 16 bits (the "
         "compensated duty is formed in int16)");
/* The band's default is BOARD_VBUS_NOMINAL_V / (12 MOTOR_LS_H fpwm)
 * (UserParms.h): L is the value a user changes that moves it. */
#define MC_DEADTIME_BAND_MAX_FRACTION 0.25 /* of BOARD_I_FULLSCALE_A */
MC_CHECK_FOR(MC_DEADTIME_BAND_A, MOTOR_LS_H,
             MC_DEADTIME_BAND_A * 32768.0 >= 0.5 * BOARD_I_FULLSCALE_A &&
                 MC_DEADTIME_BAND_A < MC_DEADTIME_BAND_MAX_FRACTION * BOARD_I_FULLSCALE_A,
             "must be in [1 Q15 count, BOARD_I_FULLSCALE_A / 4)");
#define MC_DT_BAND_Q15 MC_Q15_AMPS(MC_DEADTIME_BAND_A)
/* Inside the band the correction is i * MC_DT_COUNTS / band = (i * MC_DT_SLOPE) >> 15. */
#define MC_DT_SLOPE_ ((double)MC_DT_COUNTS * 32768.0 / (double)MC_DT_BAND_Q15)
MC_CHECK_FOR(MC_DEADTIME_BAND_A, MOTOR_LS_H, MC_DT_SLOPE_ < 32767.0,
             "too narrow for the dead-time counts (slope >= 1)");
#define MC_DT_SLOPE ((q15_t)(MC_DT_SLOPE_ + 0.5))
/* The light-load Id floor (UserParms.h): by default 4 dead-time bands. */
MC_CHECK_FOR(MC_ID_MIN_A, MOTOR_CURRENT_MAX_A,
             MC_ID_MIN_A >= 0.0 && MC_ID_MIN_A <= 0.5 * MOTOR_CURRENT_MAX_A &&
                 MC_ZERO_OR_COUNTS_(MC_ID_MIN_A / BOARD_I_FULLSCALE_A, 32768.0),
             "must be 0 (off) or in [1 Q15 count, MOTOR_CURRENT_MAX_A / 2]");
#define MC_ID_MIN_Q15 MC_Q15_AMPS(MC_ID_MIN_A)

/* The dead-time measurement at the lock (mc.c note 4). The lock's current
 * (on the forced q axis at angle 0, i.e. along beta) puts +-sqrt(3)/2 of it
 * into phases B and C; at the second level, 3/4 of the lock current, that
 * must still be 1.5 band widths (the peak of the PWM ripple the band is
 * two thirds of), so that both the inverter's loss and the core's model of
 * it depend on the currents' signs only: I_lock >= 1.5 band / (3/4
 * sqrt(3)/2) = 2.31 band. The slow step runs it on speed-loop windows
 * (MC_SLOW_STEP_PERIODS each; 1 ms at the default rate). Each level's
 * average runs from one reversal of the rotor's swing to another at least
 * MC_DTM_N windows later: a reversal is waited for at most MC_DTM_WAIT
 * windows (from the lock's last MC_DTM_WAIT windows on for the first
 * level), which covers swings of up to 2 MC_DTM_WAIT windows (about 205
 * ms). The swing is measured against the alpha sums' mean over about
 * MC_DTM_MEAN windows (32 ms): slow enough to hold still through a swing
 * of the lock's usual 20 to 50 ms, quick enough to follow the alpha level
 * as the lock's first large swing dies away (at 128 windows it still lagged
 * by more than a small remaining swing's amplitude, and no reversal came). */
#define MC_DTM_N      ((uint16_t)(0.0256 * MC_SPEED_LOOP_HZ + 0.999)) /* windows, at least */
#define MC_DTM_WAIT   ((uint16_t)(0.1024 * MC_SPEED_LOOP_HZ + 0.999)) /* windows, at most */
#define MC_DTM_SETTLE ((uint16_t)(0.005 * MC_SPEED_LOOP_HZ + 0.999))  /* windows at level 2 */
#define MC_DTM_MEAN   32
#define MC_DTM_ON     (MC_DRIVE && MC_DEADTIME_MEASURE && PWM_DEADTIME_NS > 0)
/* The longest the measurement adds to the lock, periods: the first
 * window's end, the settling, the second window's wait and length, and a
 * window for the slow step's results to come back. */
#define MC_DTM_MAX_PERIODS                                                                         \
    (MC_DTM_ON ? (2L * MC_DTM_N + 5L * MC_DTM_WAIT + MC_DTM_SETTLE + 1L) * IRP_PERCALC : 0L)
MC_CHECK(MC_SPEED_LOOP_HZ,
         MC_DEADTIME_MEASURE == 0 || (MC_DTM_N + 2.0 * MC_DTM_WAIT) * IRP_PERCALC <= 32767.0,
         "too slow for the dead-time measurement's averages (mc.c note 4)");
/* The lock current the measurement needs, in dead-time bands: at 3/4 of
 * it, phases B and C (sqrt(3)/2 of it) stay 1.5 bands out of the band. */
#define MC_DTM_LOCK_BANDS (1.5 / (0.75 * 0.8660254037844386))
MC_CHECK_FOR(MOTOR_LOCK_CURRENT_A, MC_DEADTIME_BAND_A,
             MC_DEADTIME_MEASURE == 0 ||
                 MOTOR_LOCK_CURRENT_A >= MC_DTM_LOCK_BANDS * MC_DEADTIME_BAND_A,
             "must be at least 2.31 dead-time bands (MC_DEADTIME_BAND_A) to measure the dead time "
             "at the lock (mc.c note 4); raise it or set MC_DEADTIME_MEASURE 0");
#define MC_DTM_CURRENT_Q15 ((q15_t)((3L * (long)MC_LOCK_CURRENT_Q15) / 4L)) /* the second level */
/* What a measurement may set: a quarter to twice the programmed dead time,
 * and below one band's counts so that the in-band slope fits Q15. */
#define MC_DT_COUNTS_MIN ((int16_t)((MC_DT_COUNTS + 3) / 4))
#define MC_DT_COUNTS_MAX_                                                                          \
    ((2.0 * MC_DT_COUNTS < (double)MC_DT_BAND_Q15 - 1.0) ? 2.0 * MC_DT_COUNTS                      \
                                                         : (double)MC_DT_BAND_Q15 - 1.0)
#define MC_DT_COUNTS_MAX ((int16_t)MC_DT_COUNTS_MAX_)
MC_CHECK(PWM_FREQUENCY_HZ, BOARD_FCY_HZ / PWM_FREQUENCY_HZ + MC_DT_COUNTS_MAX_ + 1.0 <= 32767.0,
         "duty full scale plus twice the dead-time counts must fit 16 bits (the compensated "
         "duty is formed in int16 with the measured dead time)");

/* Applied voltage from duties (mc_internal.h): MC_VAPP_K = sqrt(3) / (3
 * PWM_DUTY_MAX) * VBUS_FS / VBUS_NOMINAL * 2^25, so that (2 da - db - dc) *
 * vbus * MC_VAPP_K / 2^25 is v_alpha in Q15 of V_FS; MC_VAPP_KB is beta's,
 * sqrt(3) larger, at 2^24 so that it fits 16 bits too. */
#define MC_VAPP_K_                                                                                 \
    (1.7320508075688772 / (3.0 * (double)PWM_DUTY_MAX) * (double)BOARD_VBUS_FULLSCALE_V /          \
     (double)BOARD_VBUS_NOMINAL_V * 33554432.0)
MC_CHECK_FOR(BOARD_VBUS_FULLSCALE_V, PWM_FREQUENCY_HZ, MC_VAPP_K_ >= 1024.0 && MC_VAPP_K_ < 32767.0,
             "VBUS_FS / VBUS_NOMINAL / PWM_DUTY_MAX out of the "
             "range of the applied-voltage scaling");
#define MC_VAPP_K  ((int16_t)(MC_VAPP_K_ + 0.5))
#define MC_VAPP_KB ((int16_t)(MC_VAPP_K_ * 0.8660254037844386 + 0.5)) /* sqrt(3)/2, at 2^24 */

/* ---- protections ------------------------------------------------------------------------ */

#define MC_STALL_TICKS_ ((double)MC_STALL_TIME_S * (double)MC_SPEED_LOOP_HZ)
MC_CHECK(MC_STALL_TIME_S, MC_STALL_TICKS_ >= 2.0 && MC_STALL_TICKS_ <= 0.05 * MC_SPEED_LOOP_HZ,
         "must be 2 speed-loop runs .. 50 ms");
#define MC_STALL_TICKS        ((uint16_t)(MC_STALL_TICKS_ + 0.5))
#define MC_STALL_TRACK_TICKS_ ((double)MC_STALL_TRACK_TIME_S * (double)MC_SPEED_LOOP_HZ)
MC_CHECK(MC_STALL_TRACK_TIME_S,
         MC_STALL_TRACK_TICKS_ >= 2.0 && MC_STALL_TRACK_TICKS_ <= 0.05 * MC_SPEED_LOOP_HZ,
         "must be 2 speed-loop runs .. 50 ms");
#define MC_STALL_TRACK_TICKS ((uint16_t)(MC_STALL_TRACK_TICKS_ + 0.5))
/* The limit-cycle check (mc_stall_check): a reversal of the speed PI
 * between its limits takes at least 2 speed-loop runs; a run of them ends
 * when the next does not come within the gap. */
#define MC_SWING_GAP_TICKS_ ((double)MC_SWING_GAP_S * (double)MC_SPEED_LOOP_HZ)
MC_CHECK(MC_SWING_GAP_S, MC_SWING_GAP_TICKS_ >= 4.0 && MC_SWING_GAP_TICKS_ <= 30000.0,
         "must be 4 speed-loop runs .. 30000 runs");
#define MC_SWING_GAP_TICKS ((uint16_t)(MC_SWING_GAP_TICKS_ + 0.5))
MC_CHECK(MC_SWING_FLIPS,
         MC_IS_INTEGER_(MC_SWING_FLIPS) && MC_SWING_FLIPS >= 3 && MC_SWING_FLIPS <= 100,
         "must be an integer 3..100 (a healthy loop reverses once or twice after a step)");
/* Its default is MOTOR_SPEED_MIN_RPM / 2 (UserParms.h). */
MC_CHECK_FOR(MC_STALL_SPEED_MIN_RPM, MOTOR_SPEED_MIN_RPM,
             MC_STALL_SPEED_MIN_RPM > 0.0 && MC_STALL_SPEED_MIN_RPM < MC_ESTIMATOR_MIN_RPM,
             "must be in (0, MC_ESTIMATOR_MIN_RPM)");
#define MC_STALL_SPEED_Q15 MC_Q15_RPM(MC_STALL_SPEED_MIN_RPM)
MC_CHECK_FOR(MC_STALL_SPEED_ERROR_RPM, MC_SPEED_FULLSCALE_RPM,
             MC_STALL_SPEED_ERROR_RPM > 0.0 && MC_STALL_SPEED_ERROR_RPM < MC_SPEED_FULLSCALE_RPM,
             "must be in (0, MC_SPEED_FULLSCALE_RPM)");
#define MC_STALL_SPEED_ERR_Q15 MC_Q15_RPM(MC_STALL_SPEED_ERROR_RPM)
MC_CHECK(MC_STALL_BEMF_LOW_FRACTION,
         MC_STALL_BEMF_LOW_FRACTION >= 0.0 && MC_STALL_BEMF_LOW_FRACTION < 1.0 &&
             MC_ZERO_OR_COUNTS_(MC_STALL_BEMF_LOW_FRACTION, 4096.0),
         "must be 0 (off) or in [1/4096, 1) (Q12 below)");
MC_CHECK(MC_STALL_BEMF_HIGH_FRACTION,
         MC_STALL_BEMF_HIGH_FRACTION > 1.0 && MC_STALL_BEMF_HIGH_FRACTION < 7.9,
         "must be in (1, 7.9)");
/* In the estimator's Q12 ratio format (4096 = as expected). */
#define MC_STALL_BEMF_LO_Q12 ((int16_t)(MC_STALL_BEMF_LOW_FRACTION * 4096.0 + 0.5))
#define MC_STALL_BEMF_HI_Q12 ((int16_t)(MC_STALL_BEMF_HIGH_FRACTION * 4096.0 + 0.5))

/* ---- estimator (the motor model is checked above) ------------------------------------- */

/* Kslide must exceed the largest back-EMF (docs/estimator.md note 5), which above the
 * base speed is larger than V_FS; the estimator's back-EMF full scale is
 * E_FS = 2 V_FS (docs/estimator.md note 2). */
MC_CHECK_FOR(MOTOR_SMC_GAIN_V, BOARD_VBUS_NOMINAL_V,
             MOTOR_SMC_GAIN_V > 0.0 && MOTOR_SMC_GAIN_V < 2.0 * MC_VOLTAGE_FULLSCALE_V,
             "Kslide must be in (0, 2 V_FS = 2 BOARD_VBUS_NOMINAL_V / sqrt 3)");
MC_CHECK_FOR(MOTOR_SMC_LINEAR_BAND_A, BOARD_I_FULLSCALE_A,
             MOTOR_SMC_LINEAR_BAND_A > BOARD_I_FULLSCALE_A / 32768.0 &&
                 MOTOR_SMC_LINEAR_BAND_A < BOARD_I_FULLSCALE_A,
             "must be in (1 LSB, BOARD_I_FULLSCALE_A)");
/* The speed filter's coefficient 2 pi fc / MC_SPEED_LOOP_HZ in Q15: at
 * least one count (0 would freeze the estimated speed). */
MC_CHECK_FOR(MC_SPEED_FILTER_HZ, MC_SPEED_LOOP_HZ,
             6.283185307179586 * MC_SPEED_FILTER_HZ / MC_SPEED_LOOP_HZ * 32768.0 >= 0.5 &&
                 6.283185307179586 * MC_SPEED_FILTER_HZ / MC_SPEED_LOOP_HZ < 1.0,
             "2 pi fc / MC_SPEED_LOOP_HZ must be in [1 Q15 count, 1)");

/* Back-EMF, phase peak volts per electrical Hz. */
#define MC_KE_V_PER_HZ                                                                             \
    ((double)MOTOR_KE_VPK_LL_PER_KRPM / 1.7320508075688772 / (1000.0 * MOTOR_POLE_PAIRS / 60.0))
/* The lowest closed-loop speed's back-EMF (phase peak) above the voltage
 * error of the dead time, its fundamental 4/pi 2/3 Td fpwm Vbus: below it
 * the estimator takes the inverter's error for the rotor's back-EMF (the
 * dead-time compensation removes most but not all of it; tools/tune
 * derives three times this). */
#define MC_VDT_ERR_V_                                                                              \
    (4.0 / 3.141592653589793 * 2.0 / 3.0 * (double)PWM_DEADTIME_NS * 1e-9 *                        \
     (double)PWM_FREQUENCY_HZ * BOARD_VBUS_NOMINAL_V)
MC_CHECK_FOR(MOTOR_SPEED_MIN_RPM, PWM_DEADTIME_NS,
             MC_KE_V_PER_HZ *(double)MOTOR_SPEED_MIN_RPM *MOTOR_POLE_PAIRS / 60.0 > MC_VDT_ERR_V_,
             "its back-EMF must exceed the dead time's voltage error 4/pi 2/3 Td fpwm Vbus");
/* The observer's expected back-EMF per unit speed (smc.h) below 8. */
MC_CHECK_FOR(MOTOR_KE_VPK_LL_PER_KRPM, MC_SPEED_FULLSCALE_RPM,
             SMC_EMFG_(MC_KE_V_PER_HZ, MC_OMEGA_FS_HZ, MC_VOLTAGE_FULLSCALE_V) < 8.0,
             "back-EMF at full-scale speed too large for the observer's consistency check");

#define MC_SMC_PARAMS_INIT                                                                         \
    SMC_PARAMS_INIT(MOTOR_RS_OHM, MOTOR_LS_H, MC_TS_S, MC_VOLTAGE_FULLSCALE_V,                     \
                    BOARD_I_FULLSCALE_A, (double)MOTOR_SMC_GAIN_V / MC_VOLTAGE_FULLSCALE_V,        \
                    (double)MOTOR_SMC_LINEAR_BAND_A / BOARD_I_FULLSCALE_A, MC_OMEGA_FS_HZ,         \
                    (double)MC_ESTIMATOR_MIN_RPM * MOTOR_POLE_PAIRS / 60.0, IRP_PERCALC,           \
                    MC_SPEED_FILTER_HZ, MC_KE_V_PER_HZ)

/* ---- field weakening ------------------------------------------------------------------- */

#define MC_FW_COUNT_(a) +1
MC_CHECK(MOTOR_FW_ID_TABLE_A, (0 MOTOR_FW_ID_TABLE_A(MC_FW_COUNT_)) == 16,
         "must have exactly 16 entries");
#define MC_FW_NONPOS_(a) &&((a) <= 0.0 && (a) > -BOARD_I_FULLSCALE_A)
MC_CHECK(MOTOR_FW_ID_TABLE_A, (1 MOTOR_FW_ID_TABLE_A(MC_FW_NONPOS_)),
         "every entry must be in (-BOARD_I_FULLSCALE_A, 0] amps");
/* The entries as macro arguments: MC_FW_APPLY_(m) is m(entry 0, ..., entry
 * 15, padding); the padding leaves a table of the wrong length to the
 * count's named error above (no preprocessor error about arguments). */
#define MC_FW_ARG_(a)       (a),
#define MC_FW_CALL_(m, ...) m(__VA_ARGS__)
#define MC_FW_APPLY_(m)                                                                            \
    MC_FW_CALL_(m, MOTOR_FW_ID_TABLE_A(MC_FW_ARG_) 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,    \
                0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
/* fieldweak interpolates Id between the entries (foc/fieldweak.h): |Id|
 * must not shrink as the speed, and with it the back-EMF, grows. */
#define MC_FW_FALLING_(a0, a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, a12, a13, a14, a15, ...)  \
    ((a1) <= (a0) && (a2) <= (a1) && (a3) <= (a2) && (a4) <= (a3) && (a5) <= (a4) &&               \
     (a6) <= (a5) && (a7) <= (a6) && (a8) <= (a7) && (a9) <= (a8) && (a10) <= (a9) &&              \
     (a11) <= (a10) && (a12) <= (a11) && (a13) <= (a12) && (a14) <= (a13) && (a15) <= (a14))
MC_CHECK(MOTOR_FW_ID_TABLE_A, MC_FW_APPLY_(MC_FW_FALLING_),
         "entries must not rise from entry 0 (MOTOR_SPEED_NOMINAL_RPM) to entry 15 "
         "(MOTOR_SPEED_FW_MAX_RPM): |Id| may only grow with speed");
/* Below the nominal speed Id is 0 (fieldweak.h): an entry 0 other than 0
 * steps Id at the nominal speed, a current step the speed loop meets at
 * every crossing. */
#define MC_FW_FIRST_(a0, ...) ((a0) == 0.0)
MC_CHECK(MOTOR_FW_ID_TABLE_A, MC_FW_APPLY_(MC_FW_FIRST_),
         "entry 0 (at MOTOR_SPEED_NOMINAL_RPM) must be 0.0: Id is 0 below it");

/* Speeds the bus can reach. Without load (Iq = 0) and with the table's Id
 * at a speed, the steady-state phase voltage is |(R Id, w (psi + L Id))|
 * (V peak; w electrical rad/s, psi = Ke / sqrt 3 per electrical rad/s,
 * V s). It must fit the largest voltage the core applies,
 * MC_VOLTAGE_LIMIT_FRACTION of V_FS. A motoring Iq adds Iq^2 (R^2 + w^2
 * L^2) + 2 R w Iq psi > 0 to the square, and a steady speed needs one (the
 * friction): so no load is the least a speed needs. (The shunt
 * window takes a little more in some sectors, MC_DUTY_SAMPLE_MAX: the
 * profiles' own margin, not refused here.) */
#define MC_W_E_(rpm) (6.283185307179586 * (double)(rpm) * (double)MOTOR_POLE_PAIRS / 60.0)
#define MC_PSI_VS_   (MC_KE_V_PER_HZ / 6.283185307179586)
#define MC_V_MAX_    ((double)MC_VOLTAGE_LIMIT_FRACTION * MC_VOLTAGE_FULLSCALE_V)

/* The ramp's acceleration within what its current can give a rotor of the
 * profile's inertia: at most half the torque 3/2 p psi I_ramp, the rest
 * for the load and the forced angle's lag (a rotor asked for more falls
 * out of step on every start). Checked where the profile gives the
 * inertia (the simulator's; tools/tune writes it). */
#ifdef MOTOR_INERTIA_KGM2
MC_CHECK_FOR(MOTOR_RAMP_TIME_S, MOTOR_INERTIA_KGM2,
             (double)MOTOR_INERTIA_KGM2 * 6.283185307179586 * (double)MOTOR_RAMP_END_RPM / 60.0 /
                     (double)MOTOR_RAMP_TIME_S <=
                 0.5 * 1.5 * MOTOR_POLE_PAIRS * MC_PSI_VS_ * (double)MOTOR_RAMP_CURRENT_A,
             "the ramp's acceleration needs more than half the torque of MOTOR_RAMP_CURRENT_A");
#endif
#define MC_REACHES_(rpm, id)                                                                       \
    ((MOTOR_RS_OHM * (id)) * (MOTOR_RS_OHM * (id)) +                                               \
         (MC_W_E_(rpm) * (MC_PSI_VS_ + MOTOR_LS_H * (id))) *                                       \
             (MC_W_E_(rpm) * (MC_PSI_VS_ + MOTOR_LS_H * (id))) <=                                  \
     MC_V_MAX_ * MC_V_MAX_)
#define MC_FW_REACH0_(a0, ...) MC_REACHES_(MOTOR_SPEED_NOMINAL_RPM, a0)
MC_CHECK_FOR(MOTOR_SPEED_NOMINAL_RPM, MOTOR_KE_VPK_LL_PER_KRPM, MC_FW_APPLY_(MC_FW_REACH0_),
             "the back-EMF at the nominal speed (Id of table entry 0, no load) needs more "
             "voltage than BOARD_VBUS_NOMINAL_V gives: lower the speed (field weakening "
             "starts there)");
/* The observer's back-EMF full scale is E_FS = 2 V_FS (docs/estimator.md note 2): the
 * back-EMF at the top speed must stay inside it. */
MC_CHECK_FOR(MOTOR_SPEED_FW_MAX_RPM, MOTOR_KE_VPK_LL_PER_KRPM,
             MC_W_E_(MOTOR_SPEED_FW_MAX_RPM) * MC_PSI_VS_ <
                 SMC_EMF_FS_RATIO * MC_VOLTAGE_FULLSCALE_V,
             "the back-EMF at the top speed must be below the observer's full scale "
             "2 V_FS = 2 BOARD_VBUS_NOMINAL_V / sqrt 3");
/* Entry k at MOTOR_SPEED_NOMINAL_RPM + k / 15 of the span (fieldweak.h). */
#define MC_FW_RPM_(k)                                                                              \
    (MOTOR_SPEED_NOMINAL_RPM + (k) / 15.0 * (MOTOR_SPEED_FW_MAX_RPM - MOTOR_SPEED_NOMINAL_RPM))
#define MC_FW_REACH_(a0, a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, a12, a13, a14, a15, ...)    \
    (MOTOR_SPEED_FW_MAX_RPM <= MOTOR_SPEED_NOMINAL_RPM ||                                          \
     (MC_REACHES_(MC_FW_RPM_(1.0), a1) && MC_REACHES_(MC_FW_RPM_(2.0), a2) &&                      \
      MC_REACHES_(MC_FW_RPM_(3.0), a3) && MC_REACHES_(MC_FW_RPM_(4.0), a4) &&                      \
      MC_REACHES_(MC_FW_RPM_(5.0), a5) && MC_REACHES_(MC_FW_RPM_(6.0), a6) &&                      \
      MC_REACHES_(MC_FW_RPM_(7.0), a7) && MC_REACHES_(MC_FW_RPM_(8.0), a8) &&                      \
      MC_REACHES_(MC_FW_RPM_(9.0), a9) && MC_REACHES_(MC_FW_RPM_(10.0), a10) &&                    \
      MC_REACHES_(MC_FW_RPM_(11.0), a11) && MC_REACHES_(MC_FW_RPM_(12.0), a12) &&                  \
      MC_REACHES_(MC_FW_RPM_(13.0), a13) && MC_REACHES_(MC_FW_RPM_(14.0), a14) &&                  \
      MC_REACHES_(MC_FW_RPM_(15.0), a15)))
MC_CHECK_FOR(MOTOR_SPEED_FW_MAX_RPM, MOTOR_FW_ID_TABLE_A, MC_FW_APPLY_(MC_FW_REACH_),
             "a speed of the field-weakening table needs more voltage than the bus gives "
             "with that entry's Id (no load): more |Id| there, or a lower top speed");

#define MC_FW_Q15_(a) MC_Q15_AMPS(a),
#define MC_FW_TABLE_Q15                                                                            \
    {                                                                                              \
        MOTOR_FW_ID_TABLE_A(MC_FW_Q15_)                                                            \
    }

/* ---- self-commissioning (mc_id.c) -------------------------------------------------- */

MC_CHECK(MC_IDENTIFY, MC_IDENTIFY == 0 || MC_IDENTIFY == 1, "must be 0 or 1");
MC_CHECK(MC_DRIVE, MC_DRIVE == 0 || MC_DRIVE == 1, "must be 0 or 1");
MC_CHECK(MC_DRIVE, MC_DRIVE == 1 || MC_IDENTIFY == 1,
         "0 (the commissioning image) needs MC_IDENTIFY 1: a core with neither does nothing");

MC_CHECK(MC_ID_CURRENT_A, MC_ID_CURRENT_A > 0.0, "must be > 0");
/* the ramp may overshoot to 1.45 times the target before it is trimmed,
 * and the injection swings a quarter of it on top: room below the trip */
MC_CHECK_FOR(MC_ID_CURRENT_A, MC_OVERCURRENT_A, 1.6 * MC_ID_CURRENT_A < MC_OVERCURRENT_A,
             "1.6 x MC_ID_CURRENT_A must stay below the overcurrent trip");
MC_CHECK(MC_ID_LOOP_BW_RAD_S, MC_ID_LOOP_BW_RAD_S >= 200.0 && MC_ID_LOOP_BW_RAD_S * MC_TS_S <= 0.15,
         "must be in 200 rad/s .. 0.15 x PWM_FREQUENCY_HZ");
MC_CHECK(MC_ID_ACCEL_HZ_S, MC_ID_ACCEL_HZ_S >= 1.0 && MC_ID_ACCEL_HZ_S <= 10000.0,
         "must be in 1..10000 Hz/s (electrical)");
MC_CHECK_FOR(MC_ID_SPEED_MAX_RPM, MC_SPEED_FULLSCALE_RPM,
             MC_ID_SPEED_MAX_RPM > 0.0 && MC_ID_SPEED_MAX_RPM <= MC_SPEED_FULLSCALE_RPM &&
                 (double)MC_ID_SPEED_MAX_RPM * MOTOR_POLE_PAIRS / 60.0 * MC_TS_S < 0.05,
             "must be in (0, MC_SPEED_FULLSCALE_RPM] and below PWM_FREQUENCY_HZ / 20 electrical");

/* the sequence's parameters (mc.c mc_id_params, mc_id.h) */
#define MC_ID_I_Q15     MC_Q15_AMPS(MC_ID_CURRENT_A)
#define MC_ID_I_MIN_Q15 ((q15_t)(16L << (16 - BOARD_ADC_BITS))) /* 16 ADC codes */
/* a current set too small is a mistake; the profile's, when the motor is small for the
 * board, only makes the identification end TOO_SMALL (the profile itself is sound) */
#if MC_IDENTIFY && !defined(MC_ID_CURRENT_DEFAULT)
MC_CHECK_FOR(MC_ID_CURRENT_A, BOARD_ADC_BITS, MC_ID_I_Q15 >= 2L * (16L << (16 - BOARD_ADC_BITS)),
             "must be at least 32 ADC codes of current");
#endif
#define MC_ID_WC_TS Q15(MC_ID_LOOP_BW_RAD_S *MC_TS_S)
#define MC_ID_ACCEL ((uint32_t)(MC_ID_ACCEL_HZ_S * MC_TS_S * MC_TS_S * 4294967296.0 + 0.5))
/* (the angle steps in 2^8 units before the shift: a 32-bit double holds them exactly, note 1) */
#define MC_ID_STEP_MAX                                                                             \
    ((uint32_t)((double)MC_ID_SPEED_MAX_RPM * MOTOR_POLE_PAIRS / 60.0 * MC_TS_S * 16777216.0) << 8)
/* The spin's dead-time band from the inductance measured (mc_id.c note 7):
 * the ripple Vbus / (12 L fpwm), with the bus in Q15 of BOARD_VBUS_FULLSCALE_V
 * and L in Q12 of Ts Z_FS, is ((vbus k) >> 4) / l in Q15 of I_FS for
 * k = BOARD_VBUS_FULLSCALE_V / (12 MC_VOLTAGE_FULLSCALE_V) in Q16 (mclv:
 * 20810, mchv: 11824). */
#define MC_ID_BAND_K_ ((double)BOARD_VBUS_FULLSCALE_V / (12.0 * MC_VOLTAGE_FULLSCALE_V) * 65536.0)
#if MC_IDENTIFY
MC_CHECK_FOR(BOARD_VBUS_FULLSCALE_V, BOARD_VBUS_NOMINAL_V,
             MC_ID_BAND_K_ >= 1.0 && MC_ID_BAND_K_ < 65535.0,
             "the identification's band constant (mc_derived.h MC_ID_BAND_K) must fit 16 bits: "
             "the bus's full scale below 6.9 times its nominal");
#endif
#define MC_ID_BAND_K ((uint16_t)(MC_ID_BAND_K_ + 0.5))
/* mc_id_params_t's initializer (mc_id.h), in its order: the build's values
 * the sequence runs with (mc.c; the tests and check-16bit take the same) */
#define MC_ID_PARAMS_INIT                                                                          \
    {                                                                                              \
        MC_ID_I_Q15, MC_ID_I_MIN_Q15,                                                              \
            (q15_t)((int32_t)MC_VMAX_Q15 * 7L / 10L), /* DC up to 70 % of the limit ... */         \
            (q15_t)(MC_VMAX_Q15 / 4),                 /* ... and the injection: 95 % */            \
            MC_ID_WC_TS, (uint16_t)MC_SLOW_STEP_PERIODS, (int16_t)PWM_DUTY_MAX, Q15(MC_SAMPLE_AT), \
            MC_ID_ACCEL, MC_ID_STEP_MAX, MC_ID_DAMP, MC_DT_BAND_Q15, MC_ID_BAND_K                  \
    }
/* the spin's damping (mc_id.c note 5): the forced speed moved by
 * -2 pi MC_ID_DAMP_HZ rad/s per radian the load angle swings */
#define MC_ID_DAMP_HZ 10.0
#define MC_ID_DAMP    ((uint32_t)(MC_ID_DAMP_HZ * MC_TS_S * 16777216.0 + 0.5) << 8)

/*
 * Notes
 *
 * 1. Every double above is rounded once to an integer whose exact value is
 *    not near a half: the 16-bit build (32-bit double) must produce the same
 *    integers, and make check-16bit compares the resulting mc_step outputs
 *    bit for bit.
 */

#endif /* MC_DERIVED_H */
