/* mc_derived.h - UserParms.h and the profiles turned into Q15 constants, with named range checks.
 */
#ifndef MC_DERIVED_H
#define MC_DERIVED_H

/*
 * Nothing here is tuned: every constant is computed from UserParms.h and the
 * board and motor profiles. Each check stops the build with a message that
 * starts with the parameter to change (MC_CHECK below); the Q15()
 * conversions that follow carry their own range check.
 *
 * Scales used by the core (DESIGN.md):
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
#include "smc.h"
#include "UserParms.h"

/* MC_CHECK(PARAM, cond, "why"): stops the build when cond is false, naming
 * PARAM. With a C11-capable compiler: "static assertion failed: "PARAM: why"".
 * Where _Static_assert is unavailable or hidden (glibc's <sys/cdefs.h>
 * redefines it as a macro in C99 mode, losing the message): "negative width
 * in bit-field 'PARAM__out_of_range'" (__COUNTER__, gcc >= 4.3, keeps the
 * struct tags of two checks apart even on the same line of two files). */
#if defined(_Static_assert) || !defined(__GNUC__) ||                                               \
    (__GNUC__ < 4 || (__GNUC__ == 4 && __GNUC_MINOR__ < 6))
#define MC_CHECK(param, cond, msg)                                                                 \
    struct Q15_CAT(mc_check_, __COUNTER__) {                                                       \
        unsigned param##__out_of_range : Q15_CHECK_WIDTH_(cond);                                   \
    }
#else
#define MC_CHECK(param, cond, msg) _Static_assert((int)(cond), #param ": " msg)
#endif

/* ---- timing ------------------------------------------------------------- */

MC_CHECK(PWM_FREQUENCY_HZ, PWM_FREQUENCY_HZ >= 4000L && PWM_FREQUENCY_HZ <= 40000L,
         "must be in 4000..40000 Hz");
MC_CHECK(PWM_FREQUENCY_HZ, BOARD_FCY_HZ % PWM_FREQUENCY_HZ == 0,
         "BOARD_FCY_HZ / PWM_FREQUENCY_HZ must be an integer "
         "(it is the duty full scale)");
MC_CHECK(PWM_FREQUENCY_HZ, BOARD_FCY_HZ / PWM_FREQUENCY_HZ <= 32767L,
         "duty full scale BOARD_FCY_HZ / PWM_FREQUENCY_HZ must be "
         "<= 32767 counts");

/* Duty counts for 100 % (AN1078 LOOPINTCY, PDCx units: 2000 at 40 MIPS, 20 kHz). */
#define PWM_DUTY_MAX ((uint16_t)(BOARD_FCY_HZ / PWM_FREQUENCY_HZ))
#define MC_TS_S      (1.0 / (double)PWM_FREQUENCY_HZ)

/* The sample instant as a fraction of the period after its start (mc.h
 * timing contract): the midpoint of the center-aligned PWM, where every
 * low-side switch conducts, plus the trigger offset. 0.54 on the MCLV. */
#define MC_SAMPLE_AT                                                                               \
    (0.5 + (double)PWM_ADC_TRIGGER_TCY * (double)PWM_FREQUENCY_HZ / (double)BOARD_FCY_HZ)
MC_CHECK(PWM_ADC_TRIGGER_TCY,
         PWM_ADC_TRIGGER_TCY >= 0L && PWM_ADC_TRIGGER_TCY * 2L * PWM_FREQUENCY_HZ < BOARD_FCY_HZ,
         "the trigger must fall in the second half of the period");

MC_CHECK(MC_SPEED_LOOP_HZ, MC_SPEED_LOOP_HZ > 0 && PWM_FREQUENCY_HZ % MC_SPEED_LOOP_HZ == 0,
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

/* ---- scales -------------------------------------------------------------- */

MC_CHECK(BOARD_I_FULLSCALE_A, BOARD_I_FULLSCALE_A > 0.0, "must be > 0");
MC_CHECK(BOARD_VBUS_FULLSCALE_V, BOARD_VBUS_FULLSCALE_V > 0.0, "must be > 0");
MC_CHECK(BOARD_VBUS_NOMINAL_V,
         BOARD_VBUS_NOMINAL_V > 0.0 && BOARD_VBUS_NOMINAL_V < BOARD_VBUS_FULLSCALE_V,
         "must be in (0, BOARD_VBUS_FULLSCALE_V)");
MC_CHECK(MOTOR_POLE_PAIRS, MOTOR_POLE_PAIRS >= 1 && MOTOR_POLE_PAIRS <= 32, "must be in 1..32");
MC_CHECK(MC_SPEED_FULLSCALE_RPM, MC_SPEED_FULLSCALE_RPM > 0.0, "must be > 0");

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

/* ---- speeds --------------------------------------------------------------- */

MC_CHECK(MOTOR_SPEED_MIN_RPM,
         MOTOR_SPEED_MIN_RPM > 0.0 && MOTOR_SPEED_MIN_RPM < MOTOR_SPEED_NOMINAL_RPM,
         "must be in (0, MOTOR_SPEED_NOMINAL_RPM)");
MC_CHECK(MOTOR_SPEED_FW_MAX_RPM, MOTOR_SPEED_FW_MAX_RPM >= MOTOR_SPEED_NOMINAL_RPM,
         "must be >= MOTOR_SPEED_NOMINAL_RPM (equal: no field "
         "weakening)");
MC_CHECK(MC_SPEED_FULLSCALE_RPM, MOTOR_SPEED_FW_MAX_RPM <= 0.95 * MC_SPEED_FULLSCALE_RPM,
         "must be >= MOTOR_SPEED_FW_MAX_RPM / 0.95 "
         "(room for overshoot)");
MC_CHECK(SPEED_REF_MIN_RPM, SPEED_REF_MIN_RPM > 0.0 && SPEED_REF_MIN_RPM < SPEED_REF_MAX_RPM,
         "must be in (0, SPEED_REF_MAX_RPM)");
MC_CHECK(SPEED_REF_MAX_RPM, SPEED_REF_MAX_RPM <= MOTOR_SPEED_FW_MAX_RPM,
         "must be <= MOTOR_SPEED_FW_MAX_RPM");
MC_CHECK(MC_ESTIMATOR_MIN_RPM,
         MC_ESTIMATOR_MIN_RPM > 0.0 && MC_ESTIMATOR_MIN_RPM <= MOTOR_RAMP_END_RPM,
         "must be in (0, MOTOR_RAMP_END_RPM]");

#define MC_SPEED_REF_MIN_Q15 MC_Q15_RPM(SPEED_REF_MIN_RPM)
#define MC_SPEED_REF_MAX_Q15 MC_Q15_RPM(SPEED_REF_MAX_RPM)
/* Speed reference slew per speed-loop run, Q15 speed. */
#define MC_SPEED_RAMP_STEP_                                                                        \
    ((double)MC_SPEED_RAMP_RPM_PER_S / (double)MC_SPEED_LOOP_HZ / (double)MC_SPEED_FULLSCALE_RPM * \
     32768.0)
MC_CHECK(MC_SPEED_RAMP_RPM_PER_S, MC_SPEED_RAMP_STEP_ >= 1.0 && MC_SPEED_RAMP_STEP_ < 32767.0,
         "must give 1..32767 Q15 counts per speed-loop run");
#define MC_SPEED_RAMP_STEP ((q15_t)(MC_SPEED_RAMP_STEP_ + 0.5))

/* ---- currents -------------------------------------------------------------- */

MC_CHECK(MOTOR_CURRENT_MAX_A,
         MOTOR_CURRENT_MAX_A > 0.0 && MOTOR_CURRENT_MAX_A < BOARD_I_FULLSCALE_A,
         "must be in (0, BOARD_I_FULLSCALE_A)");
MC_CHECK(MC_OVERCURRENT_A,
         MC_OVERCURRENT_A > MOTOR_CURRENT_MAX_A && MC_OVERCURRENT_A < BOARD_I_FULLSCALE_A,
         "must be in (MOTOR_CURRENT_MAX_A, BOARD_I_FULLSCALE_A)");
MC_CHECK(MOTOR_LOCK_CURRENT_A,
         MOTOR_LOCK_CURRENT_A > 0.0 && MOTOR_LOCK_CURRENT_A < MC_OVERCURRENT_A,
         "must be in (0, MC_OVERCURRENT_A)");
MC_CHECK(MOTOR_RAMP_CURRENT_A,
         MOTOR_RAMP_CURRENT_A > 0.0 && MOTOR_RAMP_CURRENT_A <= MOTOR_CURRENT_MAX_A,
         "must be in (0, MOTOR_CURRENT_MAX_A]");
MC_CHECK(MC_OFFSET_MAX_A, MC_OFFSET_MAX_A > 0.0 && MC_OFFSET_MAX_A < BOARD_I_FULLSCALE_A,
         "must be in (0, BOARD_I_FULLSCALE_A)");

#define MC_IQ_MAX_Q15 MC_Q15_AMPS(MOTOR_CURRENT_MAX_A)
MC_CHECK(MC_ID_MIN_A, MC_ID_MIN_A >= 0.0 && MC_ID_MIN_A <= 0.5 * MOTOR_CURRENT_MAX_A,
         "must be in [0, MOTOR_CURRENT_MAX_A / 2]");
#define MC_ID_MIN_Q15       MC_Q15_AMPS(MC_ID_MIN_A)
#define MC_OVERCURRENT_Q15  MC_Q15_AMPS(MC_OVERCURRENT_A)
#define MC_LOCK_CURRENT_Q15 MC_Q15_AMPS(MOTOR_LOCK_CURRENT_A)
#define MC_RAMP_CURRENT_Q15 MC_Q15_AMPS(MOTOR_RAMP_CURRENT_A)
#define MC_OFFSET_MAX_Q15   MC_Q15_AMPS(MC_OFFSET_MAX_A)

/* ---- DC bus ---------------------------------------------------------------- */

MC_CHECK(MC_VBUS_UNDERVOLTAGE_V,
         MC_VBUS_UNDERVOLTAGE_V > 0.0 && MC_VBUS_UNDERVOLTAGE_V < BOARD_VBUS_NOMINAL_V,
         "must be in (0, BOARD_VBUS_NOMINAL_V)");
MC_CHECK(MC_VBUS_OVERVOLTAGE_V,
         MC_VBUS_OVERVOLTAGE_V > BOARD_VBUS_NOMINAL_V &&
             MC_VBUS_OVERVOLTAGE_V < BOARD_VBUS_FULLSCALE_V,
         "must be in (BOARD_VBUS_NOMINAL_V, "
         "BOARD_VBUS_FULLSCALE_V)");
#define MC_VBUS_UV_Q15      MC_Q15_VBUS(MC_VBUS_UNDERVOLTAGE_V)
#define MC_VBUS_OV_Q15      MC_Q15_VBUS(MC_VBUS_OVERVOLTAGE_V)
#define MC_VBUS_NOMINAL_Q15 MC_Q15_VBUS(BOARD_VBUS_NOMINAL_V)

/* ---- voltage limit ----------------------------------------------------------- */

MC_CHECK(MC_VOLTAGE_LIMIT_FRACTION,
         MC_VOLTAGE_LIMIT_FRACTION > 0.5 && MC_VOLTAGE_LIMIT_FRACTION <= 1.0,
         "must be in (0.5, 1]");
#define MC_VMAX_Q15 Q15(MC_VOLTAGE_LIMIT_FRACTION)

/* ---- current PI (d and q): gains in V/A and V/(A s) to Q15 of V_FS per I_FS ---- */

#define MC_CUR_KP_ ((double)MOTOR_CURRENT_KP_V_PER_A * BOARD_I_FULLSCALE_A / MC_VOLTAGE_FULLSCALE_V)
#define MC_CUR_KI_                                                                                 \
    ((double)MOTOR_CURRENT_KI_V_PER_AS * MC_TS_S * BOARD_I_FULLSCALE_A / MC_VOLTAGE_FULLSCALE_V)
MC_CHECK(MOTOR_CURRENT_KP_V_PER_A, MC_CUR_KP_ >= 0.0 && MC_CUR_KP_ < 128.0,
         "Kp * I_FS / V_FS must be in [0, 128)");
MC_CHECK(MOTOR_CURRENT_KI_V_PER_AS, MC_CUR_KI_ >= 0.0 && MC_CUR_KI_ < 1.0,
         "Ki * Ts * I_FS / V_FS must be in [0, 1)");
#define MC_CUR_KP       MC_MANT_OF(MC_CUR_KP_)
#define MC_CUR_KP_SHIFT ((uint8_t)MC_SHIFT_OF(MC_CUR_KP_))
#define MC_CUR_KI       Q15(MC_CUR_KI_)

/* ---- speed PI: A/rpm and A/(rpm s) to Q15 current per Q15 speed ------------------ */

#define MC_SPD_KP_ ((double)MOTOR_SPEED_KP_A_PER_RPM * MC_SPEED_FULLSCALE_RPM / BOARD_I_FULLSCALE_A)
#define MC_SPD_KI_                                                                                 \
    ((double)MOTOR_SPEED_KI_A_PER_RPM_S / (double)MC_SPEED_LOOP_HZ * MC_SPEED_FULLSCALE_RPM /      \
     BOARD_I_FULLSCALE_A)
MC_CHECK(MOTOR_SPEED_KP_A_PER_RPM, MC_SPD_KP_ >= 0.0 && MC_SPD_KP_ < 128.0,
         "Kp * speed FS / I_FS must be in [0, 128)");
MC_CHECK(MOTOR_SPEED_KI_A_PER_RPM_S, MC_SPD_KI_ >= 0.0 && MC_SPD_KI_ < 1.0,
         "Ki / MC_SPEED_LOOP_HZ * speed FS / I_FS must be "
         "in [0, 1)");
MC_CHECK(MOTOR_SPEED_KP_FULL_RPM,
         MOTOR_SPEED_KP_FULL_RPM > 0.0 && MOTOR_SPEED_KP_FULL_RPM <= MOTOR_SPEED_FW_MAX_RPM,
         "must be in (0, MOTOR_SPEED_FW_MAX_RPM]");
MC_CHECK(MC_SPEED_KP_MIN_FRACTION,
         MC_SPEED_KP_MIN_FRACTION > 0.0 && MC_SPEED_KP_MIN_FRACTION <= 1.0, "must be in (0, 1]");
#define MC_SPD_KP       MC_MANT_OF(MC_SPD_KP_)
#define MC_SPD_KP_SHIFT ((uint8_t)MC_SHIFT_OF(MC_SPD_KP_))
#define MC_SPD_KI       Q15(MC_SPD_KI_)

/* Anti-windup gain of every loop: 1 - 2^-15 removes the whole excess each
 * call (AN1078's 0.99999). */
#define MC_PI_KC ((q15_t)32767)

/* ---- start-up -------------------------------------------------------------------- */

MC_CHECK(MOTOR_LOCK_TIME_S,
         MOTOR_LOCK_TIME_S *PWM_FREQUENCY_HZ >= 1.0 &&
             MOTOR_LOCK_TIME_S * PWM_FREQUENCY_HZ <= 65000.0,
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

MC_CHECK(MC_START_RETRIES, MC_START_RETRIES >= 0 && MC_START_RETRIES <= 250, "must be in 0..250");

/* Open-loop ramp, constant acceleration: the 32-bit angle step grows by
 * MC_RAMP_STEP_INC each period; the ramp ends when the step reaches
 * MC_RAMP_STEP_END = MC_RAMP_STEP_INC * ramp periods (built from integers so
 * the 16-bit build gets the same numbers). */
#define MC_RAMP_PERIODS_ ((double)MOTOR_RAMP_TIME_S * (double)PWM_FREQUENCY_HZ)
#define MC_RAMP_STEP_INC_                                                                          \
    ((double)MOTOR_RAMP_END_RPM * MOTOR_POLE_PAIRS / 60.0 * MC_TS_S * 4294967296.0 /               \
     MC_RAMP_PERIODS_)
MC_CHECK(MOTOR_RAMP_END_RPM,
         MOTOR_RAMP_END_RPM >= MC_ESTIMATOR_MIN_RPM && MOTOR_RAMP_END_RPM < MOTOR_SPEED_NOMINAL_RPM,
         "must be in [MC_ESTIMATOR_MIN_RPM, MOTOR_SPEED_NOMINAL_RPM)");
MC_CHECK(MOTOR_RAMP_TIME_S, MC_RAMP_PERIODS_ >= 100.0 && MC_RAMP_PERIODS_ <= 4.0e6,
         "must be 100..4e6 PWM periods");
MC_CHECK(MOTOR_RAMP_TIME_S, MC_RAMP_STEP_INC_ >= 8.0,
         "ramp too slow for the 32-bit angle (step increment < 8)");
#define MC_RAMP_STEP_INC ((uint32_t)(MC_RAMP_STEP_INC_ + 0.5))
#define MC_RAMP_STEP_END (MC_RAMP_STEP_INC * (uint32_t)(MC_RAMP_PERIODS_ + 0.5))
#define MC_RAMP_PERIODS  ((uint32_t)(MC_RAMP_PERIODS_ + 0.5))
MC_CHECK(MC_HANDOFF_WAIT_S,
         MC_HANDOFF_WAIT_S >= 0.0 && MC_HANDOFF_WAIT_S * PWM_FREQUENCY_HZ <= 1.0e6,
         "must be 0..1e6 PWM periods");
#define MC_HANDOFF_WAIT_PERIODS ((uint32_t)(MC_HANDOFF_WAIT_S * PWM_FREQUENCY_HZ + 0.5))
MC_CHECK(MC_HANDOFF_SPEED_TOL, MC_HANDOFF_SPEED_TOL > 0.0 && MC_HANDOFF_SPEED_TOL <= 1.0,
         "must be in (0, 1]");
MC_CHECK(MC_HANDOFF_AGREE_S,
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

/* Open-loop damping (UserParms.h): the forced angle's shift in angle
 * counts = (forced - estimated step, counts per period) * MC_OL_DAMP_K / 16,
 * MC_OL_DAMP_K = MOTOR_OL_DAMP_S * fpwm in Q4; held to +-MC_OL_DAMP_MAX. */
MC_CHECK(MOTOR_OL_DAMP_S, MOTOR_OL_DAMP_S >= 0.0 && MOTOR_OL_DAMP_S * PWM_FREQUENCY_HZ <= 1000.0,
         "must be 0..1000 PWM periods");
MC_CHECK(MC_OL_DAMP_MAX_DEG, MC_OL_DAMP_MAX_DEG >= 0.0 && MC_OL_DAMP_MAX_DEG <= 90.0,
         "must be 0..90 deg");
MC_CHECK(MC_OL_DAMP_MEAN_WINDOWS, MC_OL_DAMP_MEAN_WINDOWS >= 1 && MC_OL_DAMP_MEAN_WINDOWS <= 1024,
         "must be 1..1024 speed-loop windows");
#define MC_OL_DAMP_MEAN_N ((int32_t)(MC_OL_DAMP_MEAN_WINDOWS))
#define MC_OL_DAMP_K      ((int32_t)(MOTOR_OL_DAMP_S * PWM_FREQUENCY_HZ * 16.0 + 0.5))
#define MC_OL_DAMP_MAX    ((int32_t)(MC_OL_DAMP_MAX_DEG * 65536.0 / 360.0 + 0.5))

/* ---- dead time ---------------------------------------------------------------------- */

/* Dead time in duty counts: Td / Ts * PWM_DUTY_MAX = Td * Fcy (80 on the MCLV). */
#define MC_DT_COUNTS_ ((double)PWM_DEADTIME_NS * 1e-9 * (double)BOARD_FCY_HZ)
MC_CHECK(PWM_DEADTIME_NS,
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
MC_CHECK(MC_DEADTIME_BAND_A,
         MC_DEADTIME_BAND_A > 0.0 && MC_DEADTIME_BAND_A < 0.25 * BOARD_I_FULLSCALE_A,
         "must be in (0, BOARD_I_FULLSCALE_A / 4)");
#define MC_DT_BAND_Q15 MC_Q15_AMPS(MC_DEADTIME_BAND_A)
/* Inside the band the correction is i * MC_DT_COUNTS / band = (i * MC_DT_SLOPE) >> 15. */
#define MC_DT_SLOPE_ ((double)MC_DT_COUNTS * 32768.0 / (double)MC_DT_BAND_Q15)
MC_CHECK(MC_DEADTIME_BAND_A, MC_DT_SLOPE_ < 32767.0,
         "too narrow for the dead-time counts (slope >= 1)");
#define MC_DT_SLOPE ((q15_t)(MC_DT_SLOPE_ + 0.5))

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
#define MC_DTM_ON     (MC_DEADTIME_MEASURE && PWM_DEADTIME_NS > 0)
/* The longest the measurement adds to the lock, periods: the first
 * window's end, the settling, the second window's wait and length, and a
 * window for the slow step's results to come back. */
#define MC_DTM_MAX_PERIODS                                                                         \
    (MC_DTM_ON ? (2L * MC_DTM_N + 5L * MC_DTM_WAIT + MC_DTM_SETTLE + 1L) * IRP_PERCALC : 0L)
MC_CHECK(MC_SPEED_LOOP_HZ,
         MC_DEADTIME_MEASURE == 0 || (MC_DTM_N + 2.0 * MC_DTM_WAIT) * IRP_PERCALC <= 32767.0,
         "too slow for the dead-time measurement's averages (mc.c note 4)");
MC_CHECK(MC_DEADTIME_MEASURE, MC_DEADTIME_MEASURE == 0 || MC_DEADTIME_MEASURE == 1,
         "must be 0 or 1");
MC_CHECK(MOTOR_LOCK_CURRENT_A,
         MC_DEADTIME_MEASURE == 0 ||
             MOTOR_LOCK_CURRENT_A >= 1.5 * MC_DEADTIME_BAND_A / (0.75 * 0.8660254037844386),
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
MC_CHECK(BOARD_VBUS_FULLSCALE_V, MC_VAPP_K_ >= 1024.0 && MC_VAPP_K_ < 32767.0,
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
MC_CHECK(MC_STALL_SPEED_MIN_RPM,
         MC_STALL_SPEED_MIN_RPM > 0.0 && MC_STALL_SPEED_MIN_RPM < MC_ESTIMATOR_MIN_RPM,
         "must be in (0, MC_ESTIMATOR_MIN_RPM)");
#define MC_STALL_SPEED_Q15 MC_Q15_RPM(MC_STALL_SPEED_MIN_RPM)
MC_CHECK(MC_STALL_SPEED_ERROR_RPM,
         MC_STALL_SPEED_ERROR_RPM > 0.0 && MC_STALL_SPEED_ERROR_RPM < MC_SPEED_FULLSCALE_RPM,
         "must be in (0, MC_SPEED_FULLSCALE_RPM)");
#define MC_STALL_SPEED_ERR_Q15 MC_Q15_RPM(MC_STALL_SPEED_ERROR_RPM)
MC_CHECK(MC_STALL_BEMF_LOW_FRACTION,
         MC_STALL_BEMF_LOW_FRACTION >= 0.0 && MC_STALL_BEMF_LOW_FRACTION < 1.0,
         "must be in [0, 1)");
MC_CHECK(MC_STALL_BEMF_HIGH_FRACTION,
         MC_STALL_BEMF_HIGH_FRACTION > 1.0 && MC_STALL_BEMF_HIGH_FRACTION < 7.9,
         "must be in (1, 7.9)");
/* In the estimator's Q12 ratio format (4096 = as expected). */
#define MC_STALL_BEMF_LO_Q12 ((int16_t)(MC_STALL_BEMF_LOW_FRACTION * 4096.0 + 0.5))
#define MC_STALL_BEMF_HI_Q12 ((int16_t)(MC_STALL_BEMF_HIGH_FRACTION * 4096.0 + 0.5))

/* ---- motor model and estimator -------------------------------------------------------- */

MC_CHECK(MOTOR_RS_OHM, MOTOR_RS_OHM > 0.0, "must be > 0");
MC_CHECK(MOTOR_LS_H, MOTOR_LS_H > 0.0, "must be > 0");
MC_CHECK(MOTOR_LS_H, MC_TS_S *MOTOR_RS_OHM / MOTOR_LS_H < 1.0,
         "F = 1 - Ts R / L must be > 0 (L too small for MOTOR_RS_OHM)");
MC_CHECK(MOTOR_LS_H, MC_TS_S / MOTOR_LS_H * MC_VOLTAGE_FULLSCALE_V / BOARD_I_FULLSCALE_A < 1.0,
         "G = Ts/L * V_FS/I_FS must be < 1 (L too small for the board "
         "scales)");
MC_CHECK(MOTOR_KE_VPK_LL_PER_KRPM, MOTOR_KE_VPK_LL_PER_KRPM > 0.0, "must be > 0");
/* Kslide must exceed the largest back-EMF (smc.h note 5), which above the
 * base speed is larger than V_FS; the estimator's back-EMF full scale is
 * E_FS = 2 V_FS (smc.h note 2). */
MC_CHECK(MOTOR_SMC_GAIN_V,
         MOTOR_SMC_GAIN_V > 0.0 && MOTOR_SMC_GAIN_V < 2.0 * MC_VOLTAGE_FULLSCALE_V,
         "Kslide must be in (0, 2 V_FS = 2 BOARD_VBUS_NOMINAL_V / sqrt 3)");
MC_CHECK(MOTOR_SMC_LINEAR_BAND_A,
         MOTOR_SMC_LINEAR_BAND_A > BOARD_I_FULLSCALE_A / 32768.0 &&
             MOTOR_SMC_LINEAR_BAND_A < BOARD_I_FULLSCALE_A,
         "must be in (1 LSB, BOARD_I_FULLSCALE_A)");
MC_CHECK(MC_SPEED_FILTER_HZ,
         MC_SPEED_FILTER_HZ > 0.0 &&
             6.283185307179586 * MC_SPEED_FILTER_HZ / MC_SPEED_LOOP_HZ < 1.0,
         "2 pi fc / MC_SPEED_LOOP_HZ must be in (0, 1)");

/* Back-EMF, phase peak volts per electrical Hz. */
#define MC_KE_V_PER_HZ                                                                             \
    ((double)MOTOR_KE_VPK_LL_PER_KRPM / 1.7320508075688772 / (1000.0 * MOTOR_POLE_PAIRS / 60.0))

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
#define MC_FW_Q15_(a) MC_Q15_AMPS(a),
#define MC_FW_TABLE_Q15                                                                            \
    {                                                                                              \
        MOTOR_FW_ID_TABLE_A(MC_FW_Q15_)                                                            \
    }

/*
 * Notes
 *
 * 1. Every double above is rounded once to an integer whose exact value is
 *    not near a half: the 16-bit build (32-bit double) must produce the same
 *    integers, and make check-16bit compares the resulting mc_step outputs
 *    bit for bit.
 */

#endif /* MC_DERIVED_H */
