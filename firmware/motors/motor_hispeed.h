/* motor_hispeed.h - a 2-pole-pair high-speed PMSM for the MCHV (320 V bus): ASSUMED data. */
#ifndef MOTOR_HISPEED_H
#define MOTOR_HISPEED_H

/*
 * ASSUMED DATA: the motor behind AN1078's "17 000 rpm" MCHV claim was not
 * found (docs/hardware.md 3.1). These are plausible values for a small 2-pole-pair
 * high-speed PMSM on a 320 V bus, to exercise the build and the simulator;
 * replace every electrical value with your motor's before running it.
 * Tuning that depends on the motor. Every macro can be overridden with -D or by
 * defining it before UserParms.h includes this file. Units are in every
 * name; per-phase values are half the line-to-line meter reading.
 */

#define MOTOR_NAME "high-speed 2pp (assumed)"

/* ---- electrical data -------------------------------------------------- */
#ifndef MOTOR_POLE_PAIRS
#define MOTOR_POLE_PAIRS 2
#endif
#ifndef MOTOR_RS_OHM
#define MOTOR_RS_OHM 1.2 /* per phase, ASSUMED */
#endif
#ifndef MOTOR_LS_H
#define MOTOR_LS_H 4.0e-3 /* per phase, ASSUMED */
#endif
#ifndef MOTOR_KE_VPK_LL_PER_KRPM
#define MOTOR_KE_VPK_LL_PER_KRPM                                                                   \
    10.0 /* ASSUMED */ /* back-EMF, peak line-to-line volts per 1000 rpm */
#endif

/* ---- speeds ------------------------------------------------------------- */
#ifndef MOTOR_SPEED_NOMINAL_RPM
#define MOTOR_SPEED_NOMINAL_RPM 17000.0 /* = FW max: no field weakening */
#endif
#ifndef MOTOR_SPEED_FW_MAX_RPM
#define MOTOR_SPEED_FW_MAX_RPM 17000.0 /* top speed */
#endif
#ifndef MOTOR_SPEED_MIN_RPM
#define MOTOR_SPEED_MIN_RPM 2000.0 /* lowest closed-loop speed */
#endif
#ifndef MOTOR_SPEED_FULLSCALE_RPM
#define MOTOR_SPEED_FULLSCALE_RPM 24000.0 /* Q15 full scale of every speed in the core */
#endif

/* ---- currents ----------------------------------------------------------- */
#ifndef MOTOR_CURRENT_MAX_A
#define MOTOR_CURRENT_MAX_A 2.0 /* |Iq| limit of the speed loop */
#endif
#ifndef MOTOR_OVERCURRENT_A
#define MOTOR_OVERCURRENT_A 4.0 /* software trip, any phase */
#endif

/* ---- start-up (AN1078 "Motor start-up") ------------------------------------ */
#ifndef MOTOR_LOCK_TIME_S
#define MOTOR_LOCK_TIME_S 0.25 /* rotor alignment at a fixed angle */
#endif
#ifndef MOTOR_LOCK_CURRENT_A
#define MOTOR_LOCK_CURRENT_A 1.0 /* Iq during the lock (AN1078 INITIALTORQUE) */
#endif
#ifndef MOTOR_RAMP_TIME_S
#define MOTOR_RAMP_TIME_S 1.0 /* open-loop ramp 0 -> MOTOR_RAMP_END_RPM */
#endif
#ifndef MOTOR_RAMP_END_RPM
#define MOTOR_RAMP_END_RPM 2000.0 /* speed at the hand-off to closed loop */
#endif
#ifndef MOTOR_RAMP_CURRENT_A
#define MOTOR_RAMP_CURRENT_A 1.0 /* Iq during the open-loop ramp */
#endif

/* ---- sliding-mode observer ------------------------------------------------ */
/* The estimator's recommended gains (docs/estimator.md note 5), by one rule for every
 * profile: MaxSMCError dead-beat, = SMC_MAXERR_DEADBEAT(...) in amps =
 * Kslide (exp(Ts R / L) - 1) / R at 20 kHz, so the observer is a linear,
 * ripple-free loop (AN1078's relay gains chatter: 2 to 13 deg); Kslide =
 * 1.12 x the largest phase back-EMF (all of it must be carried from a wrong
 * state), capped at 0.975 V_FS because tools/tune --check still refuses
 * Kslide >= V_FS (the core accepts up to 2 V_FS). High-speed: 98.1 V at 17000 rpm -> 110 V.
 * Written as numbers (tools/tune reads these headers),
 * to 6 digits: a band rounded to 4 leaves the pole p = F - c a few Q15
 * counts off 0 (1.385 A here gave -8.49, a rounding tie that a 32-bit
 * double resolves the other way: check-16bit failed on the MCHV). */
#ifndef MOTOR_SMC_GAIN_V
#define MOTOR_SMC_GAIN_V 110.0 /* Kslide, V (0.595 V_FS on 320 V) */
#endif
#ifndef MOTOR_SMC_LINEAR_BAND_A
#define MOTOR_SMC_LINEAR_BAND_A 1.38536 /* dead-beat for 110 V: 110 (exp(0.015) - 1) / 1.2 */
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
#define MOTOR_SPEED_KP_FULL_RPM 6000.0
#endif
#ifndef MOTOR_SPEED_KP_A_PER_RPM
#define MOTOR_SPEED_KP_A_PER_RPM 0.0005
#endif
#ifndef MOTOR_SPEED_KI_A_PER_RPM_S
#define MOTOR_SPEED_KI_A_PER_RPM_S 0.005
#endif

/* ---- field weakening: Id (A) at 16 speeds evenly spaced from
 * MOTOR_SPEED_NOMINAL_RPM (entry 0) to MOTOR_SPEED_FW_MAX_RPM (entry 15).
 * At 17 000 rpm the assumed back-EMF (170 V peak line to line) is well inside
 * a 320 V bus, so no field weakening: the table is all zeros and nominal
 * speed = FW max speed, as AN1078 says to disable it. ------------------------ */
#ifndef MOTOR_FW_ID_TABLE_A
/* X-macro: edit the numbers, keep X( ) around each (exactly 16 entries). */
/* clang-format off */
#define MOTOR_FW_ID_TABLE_A(X) \
    X(0.0) X(0.0) X(0.0) X(0.0) X(0.0) X(0.0) X(0.0) X(0.0) \
    X(0.0) X(0.0) X(0.0) X(0.0) X(0.0) X(0.0) X(0.0) X(0.0)
/* clang-format on */
#endif

#endif /* MOTOR_HISPEED_H */
