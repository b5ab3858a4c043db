/* motor_hurst300.h - Hurst300 "long Hurst" DMA0204024B101 (AC300022), 24 V: data and tuning. */
#ifndef MOTOR_HURST300_H
#define MOTOR_HURST300_H

/*
 * Motor data (docs/hardware.md 3.1, from AN1299's hurst300.h) and the tuning that
 * depends on the motor. Every macro can be overridden with -D or by
 * defining it before UserParms.h includes this file. Units are in every
 * name; per-phase values are half the line-to-line meter reading.
 */

#define MOTOR_NAME "Hurst300 DMA0204024B101"

/* ---- electrical data -------------------------------------------------- */
#ifndef MOTOR_POLE_PAIRS
#define MOTOR_POLE_PAIRS 5
#endif
#ifndef MOTOR_RS_OHM
#define MOTOR_RS_OHM 0.40 /* per phase */
#endif
#ifndef MOTOR_LS_H
#define MOTOR_LS_H 0.34e-3 /* per phase */
#endif
#ifndef MOTOR_KE_VPK_LL_PER_KRPM
#define MOTOR_KE_VPK_LL_PER_KRPM 7.3 /* back-EMF, peak line-to-line volts per 1000 rpm */
#endif

/* ---- speeds ------------------------------------------------------------- */
#ifndef MOTOR_SPEED_NOMINAL_RPM
#define MOTOR_SPEED_NOMINAL_RPM 2500.0 /* field weakening starts above this */
#endif
#ifndef MOTOR_SPEED_FW_MAX_RPM
#define MOTOR_SPEED_FW_MAX_RPM                                                                     \
    3000.0 /* top of the table (3500 needs -5.4 A: beyond the MCLV scale) */
#endif
#ifndef MOTOR_SPEED_MIN_RPM
#define MOTOR_SPEED_MIN_RPM 500.0 /* lowest closed-loop speed (AN1078 MINSPEEDINRPM) */
#endif
#ifndef MOTOR_SPEED_FULLSCALE_RPM
#define MOTOR_SPEED_FULLSCALE_RPM 6000.0 /* Q15 full scale of every speed in the core */
#endif

/* ---- currents ----------------------------------------------------------- */
#ifndef MOTOR_CURRENT_MAX_A
#define MOTOR_CURRENT_MAX_A 3.0 /* |Iq| limit (rated 4.88 A peak; MCLV reads +-4.4 A) */
#endif
#ifndef MOTOR_OVERCURRENT_A
#define MOTOR_OVERCURRENT_A 4.0 /* software trip, any phase (below the 4.4 A scale) */
#endif

/* ---- start-up (AN1078 "Motor start-up") ------------------------------------ */
#ifndef MOTOR_LOCK_TIME_S
#define MOTOR_LOCK_TIME_S 0.25 /* rotor alignment at a fixed angle */
#endif
#ifndef MOTOR_LOCK_CURRENT_A
#define MOTOR_LOCK_CURRENT_A 1.5 /* Iq during the lock */
#endif
#ifndef MOTOR_RAMP_TIME_S
#define MOTOR_RAMP_TIME_S                                                                          \
    1.0 /* open-loop ramp 0 -> MOTOR_RAMP_END_RPM (AN1078: 5 s with a brake) */
#endif
#ifndef MOTOR_RAMP_END_RPM
#define MOTOR_RAMP_END_RPM 500.0 /* speed at the hand-off to closed loop */
#endif
#ifndef MOTOR_RAMP_CURRENT_A
#define MOTOR_RAMP_CURRENT_A 1.5 /* Iq during the open-loop ramp */
#endif

/* ---- sliding-mode observer ------------------------------------------------ */
/* The estimator's recommended gains (docs/estimator.md note 5), by one rule for every
 * profile: MaxSMCError dead-beat, = SMC_MAXERR_DEADBEAT(...) in amps =
 * Kslide (exp(Ts R / L) - 1) / R at 20 kHz, so the observer is a linear,
 * ripple-free loop (AN1078's relay gains chatter: 2 to 13 deg); Kslide =
 * 1.12 x the largest phase back-EMF (all of it must be carried from a wrong
 * state), capped at 0.975 V_FS because tools/tune --check still refuses
 * Kslide >= V_FS (the core accepts up to 2 V_FS). Hurst300: 12.6 V at 3000 rpm -> 14.2 V, capped
 * to 13.5 V. Written as numbers (tools/tune reads these headers),
 * to 6 digits: a band rounded to 4 leaves the pole p = F - c a few Q15
 * counts off 0 (1.385 A for the high-speed motor gave -8.49, a rounding tie that a 32-bit
 * double resolves the other way: check-16bit failed on the MCHV). */
#ifndef MOTOR_SMC_GAIN_V
#define MOTOR_SMC_GAIN_V 13.5 /* Kslide, V (0.974 V_FS on 24 V) */
#endif
#ifndef MOTOR_SMC_LINEAR_BAND_A
#define MOTOR_SMC_LINEAR_BAND_A 2.04485 /* dead-beat for 13.5 V: 13.5 (exp(0.05882) - 1) / 0.40 */
#endif
#ifndef MC_SPEED_FILTER_HZ
#define MC_SPEED_FILTER_HZ 100.0 /* estimated-speed filter (docs/estimator.md note 7) */
#endif

/* ---- current PI (d and q): Kp = L * wc, Ki = R * wc cancels the winding pole,
 * giving a first-order current loop of bandwidth wc. ------------------------ */
#ifndef MOTOR_CURRENT_LOOP_BW_RAD_S
#define MOTOR_CURRENT_LOOP_BW_RAD_S 2000.0
#endif
#ifndef MOTOR_CURRENT_KP_V_PER_A
#define MOTOR_CURRENT_KP_V_PER_A (MOTOR_LS_H * MOTOR_CURRENT_LOOP_BW_RAD_S)
#endif
#ifndef MOTOR_CURRENT_KI_V_PER_AS
#define MOTOR_CURRENT_KI_V_PER_AS (MOTOR_RS_OHM * MOTOR_CURRENT_LOOP_BW_RAD_S)
#endif

/* ---- speed PI (Kp is full above MOTOR_SPEED_KP_FULL_RPM, scaled down below) --- */
#ifndef MOTOR_SPEED_KP_FULL_RPM
#define MOTOR_SPEED_KP_FULL_RPM 1500.0
#endif
#ifndef MOTOR_SPEED_KP_A_PER_RPM
#define MOTOR_SPEED_KP_A_PER_RPM 0.003
#endif
#ifndef MOTOR_SPEED_KI_A_PER_RPM_S
#define MOTOR_SPEED_KI_A_PER_RPM_S 0.03
#endif

/* ---- field weakening: Id (A) at 16 speeds evenly spaced from
 * MOTOR_SPEED_NOMINAL_RPM (entry 0) to MOTOR_SPEED_FW_MAX_RPM (entry 15).
 * Derived, not copied: the smallest |Id| that keeps the steady-state
 * voltage sqrt((R Id - w L Iq)^2 + (R Iq + w (psi + L Id))^2) within 92 %
 * of the 0.95 circle at 24 V (headroom for the current loops), with
 * psi = 8.05 mWb and a load Iq = 1.0 A. --------------------------------- */
#ifndef MOTOR_FW_ID_TABLE_A
/* X-macro: edit the numbers, keep X( ) around each (exactly 16 entries). */
/* clang-format off */
#define MOTOR_FW_ID_TABLE_A(X) \
    X(0.000) X(0.000) X(0.000) X(0.000) X(0.000) X(0.000) X(0.000) X(0.000) \
    X(0.000) X(-0.210) X(-0.499) X(-0.783) X(-1.063) X(-1.339) X(-1.610) X(-1.876)
/* clang-format on */
#endif

#endif /* MOTOR_HURST300_H */
