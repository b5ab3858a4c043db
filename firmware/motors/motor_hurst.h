/* motor_hurst.h - Hurst075 "short Hurst" DMB0224C10002 (AC300020), 24 V: data and tuning. */
#ifndef MOTOR_HURST_H
#define MOTOR_HURST_H

/*
 * Motor data (docs/hardware.md 3.1, AN1078's Hurst build) and the tuning that
 * depends on the motor. Every macro can be overridden with -D or by
 * defining it before UserParms.h includes this file. Units are in every
 * name; per-phase values are half the line-to-line meter reading.
 */

#define MOTOR_NAME "Hurst075 DMB0224C10002"

/* ---- electrical data -------------------------------------------------- */
#ifndef MOTOR_POLE_PAIRS
#define MOTOR_POLE_PAIRS 5
#endif
#ifndef MOTOR_RS_OHM
#define MOTOR_RS_OHM 2.67 /* per phase (5.34 ohm line to line) */
#endif
#ifndef MOTOR_LS_H
#define MOTOR_LS_H 1.92e-3 /* per phase (3.84 mH line to line) */
#endif
#ifndef MOTOR_KE_VPK_LL_PER_KRPM
#define MOTOR_KE_VPK_LL_PER_KRPM 7.3 /* back-EMF, peak line-to-line volts per 1000 rpm */
#endif

/* ---- speeds ------------------------------------------------------------- */
#ifndef MOTOR_SPEED_NOMINAL_RPM
#define MOTOR_SPEED_NOMINAL_RPM 2500.0 /* field weakening starts above this (the table below) */
#endif
#ifndef MOTOR_SPEED_FW_MAX_RPM
#define MOTOR_SPEED_FW_MAX_RPM 5300.0 /* top of the field-weakening table */
#endif
#ifndef MOTOR_SPEED_MIN_RPM
#define MOTOR_SPEED_MIN_RPM 500.0 /* lowest closed-loop speed (AN1078 MINSPEEDINRPM) */
#endif
#ifndef MOTOR_SPEED_FULLSCALE_RPM
#define MOTOR_SPEED_FULLSCALE_RPM 8000.0 /* Q15 full scale of every speed in the core */
#endif

/* ---- currents ----------------------------------------------------------- */
#ifndef MOTOR_CURRENT_MAX_A
#define MOTOR_CURRENT_MAX_A 2.0 /* |Iq| limit of the speed loop (rated 1.64 A peak) */
#endif
#ifndef MOTOR_OVERCURRENT_A
#define MOTOR_OVERCURRENT_A 3.5 /* software trip, any phase (AN1299's Hurst value) */
#endif

/* ---- start-up (AN1078 "Motor start-up") ------------------------------------ */
#ifndef MOTOR_LOCK_TIME_S
#define MOTOR_LOCK_TIME_S 0.25 /* rotor alignment at a fixed angle */
#endif
#ifndef MOTOR_LOCK_CURRENT_A
#define MOTOR_LOCK_CURRENT_A 1.0 /* Iq during the lock (AN1078 INITIALTORQUE) */
#endif
#ifndef MOTOR_RAMP_TIME_S
#define MOTOR_RAMP_TIME_S                                                                          \
    1.0 /* open-loop ramp 0 -> MOTOR_RAMP_END_RPM (AN1078: 5 s with a brake) */
#endif
#ifndef MOTOR_RAMP_END_RPM
#define MOTOR_RAMP_END_RPM 500.0 /* speed at the hand-off to closed loop */
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
 * Kslide >= V_FS (the core accepts up to 2 V_FS). Hurst: 22.3 V at 5300 rpm -> 25 V, capped to 13.5
 * V (closed loop measured 25 V: same figures within 0.3 deg). Written as numbers (tools/tune reads
 * these headers), to 6 digits: a band rounded to 4 leaves the pole p = F - c a few Q15 counts off 0
 * (1.385 A for the high-speed motor gave -8.49, a rounding tie that a 32-bit double resolves the
 * other way: check-16bit failed on the MCHV). */
#ifndef MOTOR_SMC_GAIN_V
#define MOTOR_SMC_GAIN_V 13.5 /* Kslide, V (0.974 V_FS on 24 V) */
#endif
#ifndef MOTOR_SMC_LINEAR_BAND_A
#define MOTOR_SMC_LINEAR_BAND_A                                                                    \
    0.364073 /* dead-beat for 13.5 V: 13.5 (exp(0.06953) - 1) / 2.67                               \
              */
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
#define MOTOR_SPEED_KI_A_PER_RPM_S 0.08
#endif

/* ---- field weakening: Id (A) at 16 speeds evenly spaced from
 * MOTOR_SPEED_NOMINAL_RPM (entry 0) to MOTOR_SPEED_FW_MAX_RPM (entry 15).
 * Derived, not copied: the smallest |Id| that keeps the steady-state
 * voltage sqrt((R Id - w L Iq)^2 + (R Iq + w (psi + L Id))^2) within 92 %
 * of what the shunt window leaves at 24 V (headroom for the current loops):
 * the measured phases' duties at most MC_DUTY_SAMPLE_MAX = 87.9 %, so a
 * circle of 0.879 x 24 V / sqrt 3, below the 0.95 limit. psi = Ke / sqrt(3)
 * / w_e(1 krpm) = 8.05 mWb; the load is Iq = 0.3 A up to 4,370 rpm (entry
 * 10); above, |(Id, Iq)| <= 3.0 A leaves less, down to 0.165 A (10 mN m) at
 * 5,300 rpm, and Id stays at about -2.98 A (entries 11..15, made monotonic).
 * Nominal: 2,460 rpm is where Iq = 0.3 A needs field weakening in that
 * budget, rounded to 2,500; entry 0 is 0 there (computed -0.05 A). Above
 * about 3,800 rpm (entry 7) |Id| exceeds the rated 1.64 A peak: the top of
 * the range is for short bursts. (AN1078 reaches -2.1 A.) Before the shunt
 * window (0.95 circle, nominal 2,700 rpm) the table ended at -2.891 A. */
#ifndef MOTOR_FW_ID_TABLE_A
/* X-macro: edit the numbers, keep X( ) around each (exactly 16 entries). */
/* clang-format off */
#define MOTOR_FW_ID_TABLE_A(X) \
    X(0.000) X(-0.399) X(-0.710) X(-1.004) X(-1.280) X(-1.541) X(-1.790) X(-2.029) \
    X(-2.263) X(-2.501) X(-2.769) X(-2.984) X(-2.984) X(-2.984) X(-2.984) X(-2.985)
/* clang-format on */
#endif

#endif /* MOTOR_HURST_H */
