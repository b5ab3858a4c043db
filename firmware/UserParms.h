/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* UserParms.h - the one file a user tunes: board and motor selection plus application settings. */
#ifndef USERPARMS_H
#define USERPARMS_H

/*
 * Engineering units only, the unit in every name. docs/tuning.md says what
 * each parameter does and which symptom it fixes. The derived-constants
 * header (mc_derived.h) turns these into Q15 and stops the build, naming the
 * parameter, when a value cannot work.
 *
 * Board and motor are chosen at build time, never by editing this file:
 *   make BOARD=mclv MOTOR=hurst      (the defaults)
 *   make BOARD=mchv MOTOR=hispeed
 * CMake turns BOARD/MOTOR into MC_BOARD_<BOARD> / MC_MOTOR_<MOTOR>
 * definitions; with neither, MCLV + motor_hurst.h (the Hurst075). The
 * board's profile and the PWM it runs are in boards/, which the HAL reads
 * too.
 * Every setting below is wrapped in #ifndef so it can also be overridden
 * with -D on the compiler command line.
 */

/* ---- board profile and PWM ------------------------------------------------ */
/* The power stage, read by the HAL too: boards/board.h (PWM_FREQUENCY_HZ,
 * PWM_ADC_TRIGGER_TCY, PWM_DEADTIME_NS, override with -D) and the profile
 * it selects, boards/board_<BOARD>.h. */
#include "../boards/board.h"

/* ---- motor profile ------------------------------------------------------- */
/* The build passes MC_MOTOR_HEADER="motors/motor_<MOTOR>.h", so any profile
 * dropped into firmware/motors/ (e.g. one written by tools/tune) is selected
 * with make MOTOR=<name>; the list below serves builds that pass only the
 * MC_MOTOR_<NAME> definition. */
#if defined(MC_MOTOR_HEADER)
#include MC_MOTOR_HEADER
#elif defined(MC_MOTOR_HURST300)
#include "motors/motor_hurst300.h"
#elif defined(MC_MOTOR_HISPEED)
#include "motors/motor_hispeed.h"
#else /* MC_MOTOR_HURST, the default */
#include "motors/motor_hurst.h"
#endif

/* Motor-profile values added after the first profiles were written, with
 * defaults that keep an older profile's behaviour. */
#ifndef MOTOR_SPEED_KP_FULL_RPM
#define MOTOR_SPEED_KP_FULL_RPM MOTOR_SPEED_MIN_RPM /* no low-speed gain schedule */
#endif

/* ---- operating mode -------------------------------------------------------- */

/* Every switch below is a 0/1 macro, defined here unless the build (-D) or a
 * profile set it first; the code tests it with `if (MC_X)`, so the
 * compiler drops what is off (mc_derived.h refuses anything but 0 and 1).
 * AN1078's own names still work: defining TORQUEMODE selects torque mode,
 * and ENVOLTRIPPLE is defined whenever the ripple compensation is on. */

/* MC_TORQUE_MODE: the pot (or mc_set_reference) sets the Iq reference
 * directly, 0..MOTOR_CURRENT_MAX_A; the speed loop is bypassed (AN1078
 * "Torque Mode", its TORQUEMODE). 0 = speed mode. */
#ifndef MC_TORQUE_MODE
#if defined(TORQUEMODE)
#define MC_TORQUE_MODE 1
#else
#define MC_TORQUE_MODE 0
#endif
#endif

/* MC_VOLTAGE_RIPPLE: compensate Vd and Vq for DC-bus ripple (AN1078
 * Equation 8, its ENVOLTRIPPLE). 1 = on. */
#ifndef MC_VOLTAGE_RIPPLE
#define MC_VOLTAGE_RIPPLE 1
#endif
#if MC_VOLTAGE_RIPPLE && !defined(ENVOLTRIPPLE)
#define ENVOLTRIPPLE
#endif

/* MC_DEADTIME_COMP: add the dead-time voltage back by the sign of each phase
 * current, and feed the estimator the voltage actually applied. 1 = on. */
#ifndef MC_DEADTIME_COMP
#define MC_DEADTIME_COMP 1
#endif

/* MC_DEADTIME_MEASURE: measure the inverter's dead-time voltage at every
 * lock (mc.c note 4) and compensate and model that instead of
 * PWM_DEADTIME_NS; 0 = trust PWM_DEADTIME_NS. The real loss differs from
 * the programmed dead time by the switches' delays and the diodes' drop,
 * which on a high-voltage bus is a large share of the back-EMF at the
 * lowest closed-loop speed (docs/tuning.md, "Behind the defaults"). Needs
 * MOTOR_LOCK_CURRENT_A of at least 2.31 dead-time bands
 * (MC_DEADTIME_BAND_A) and lengthens the lock (mc_derived.h MC_DTM_*). */
#ifndef MC_DEADTIME_MEASURE
#define MC_DEADTIME_MEASURE 1
#endif

/* ---- loop timing ------------------------------------------------------------ */
#ifndef MC_SPEED_LOOP_HZ
#define MC_SPEED_LOOP_HZ 1000L /* speed loop rate; IRP_PERCALC = PWM_FREQUENCY_HZ / this */
#endif
/* Band of phase current around zero in which the dead-time correction is
 * scaled linearly instead of switching sign. A phase current smaller than
 * its own PWM ripple reverses inside each period, so the dead time is spent
 * partly on either diode and the real voltage loss is proportional to the
 * mean current: the band must match the ripple, which depends on the motor.
 * Peak ripple of one phase ~ Vbus Ts / (8 L) at 50 % duty; with space-vector
 * modulation sharing it between phases, about Vbus / (12 L fpwm). A band
 * much narrower than the ripple switches the full dead-time voltage on the
 * ripple (chatter, and an applied-voltage error at light load that the
 * estimator reads as back-EMF); a wider one under-compensates. */
#ifndef MC_DEADTIME_BAND_A
#define MC_DEADTIME_BAND_A                                                                         \
    ((double)BOARD_VBUS_NOMINAL_V / (12.0 * (double)MOTOR_LS_H * (double)PWM_FREQUENCY_HZ))
#endif
/* Light-load floor of the Id reference (A, magnitude): the core asks
 * Id <= -(MC_ID_MIN_A - |Iq|), so it is off once |Iq| reaches it and no
 * torque capacity is lost. Inside the dead-time band the inverter loses
 * Td/Ts Vbus / band volts per amp, so at light load one ADC code of
 * current error is a large applied-voltage error for the estimator, which
 * reads it as back-EMF. Kept out of the band (only zero crossings pass
 * through it), the loss depends on the current's sign only. Costs
 * 1.5 R Id^2, no torque (surface magnets). Default: 4 band-widths, at most
 * 40 % of MOTOR_CURRENT_MAX_A; the trials behind it are in docs/tuning.md
 * ("Behind the defaults"). 0 = off. */
#ifndef MC_ID_MIN_A
#define MC_ID_MIN_A                                                                                \
    ((4.0 * MC_DEADTIME_BAND_A < 0.4 * MOTOR_CURRENT_MAX_A) ? 4.0 * MC_DEADTIME_BAND_A             \
                                                            : 0.4 * MOTOR_CURRENT_MAX_A)
#endif
/* Largest voltage vector, fraction of the SVGen circle (AN1078 uses 0.95).
 * The shunt sampling has its own limit, on the measured phases' duties
 * (MC_DUTY_SAMPLE_MAX, from the board's BOARD_SHUNT_MIN_ON_NS), which
 * leaves less in the sectors where phase A or B is the highest: the
 * field-weakening tables are derived for that. */
#ifndef MC_VOLTAGE_LIMIT_FRACTION
#define MC_VOLTAGE_LIMIT_FRACTION 0.95
#endif

/* ---- speed reference --------------------------------------------------------- */
#ifndef SPEED_REF_MIN_RPM
#define SPEED_REF_MIN_RPM MOTOR_SPEED_MIN_RPM /* pot at 0 */
#endif
#ifndef SPEED_REF_MAX_RPM
#define SPEED_REF_MAX_RPM MOTOR_SPEED_FW_MAX_RPM /* pot at full travel */
#endif
#ifndef MC_SPEED_FULLSCALE_RPM
#define MC_SPEED_FULLSCALE_RPM MOTOR_SPEED_FULLSCALE_RPM
#endif
#ifndef MC_SPEED_RAMP_RPM_PER_S
#define MC_SPEED_RAMP_RPM_PER_S 1000.0 /* slew of the speed reference */
#endif

/* ---- start-up ------------------------------------------------------------------ */
#ifndef MC_OFFSET_CALIB_TIME_S
#define MC_OFFSET_CALIB_TIME_S 0.0128 /* current-offset averaging (256 periods at 20 kHz) */
#endif
#ifndef MC_HANDOFF_WAIT_S
#define MC_HANDOFF_WAIT_S 0.25 /* end speed held at most this long for a valid estimate */
#endif
/* The hand-off also needs the rotor to follow: the estimate valid and its
 * speed within MC_HANDOFF_SPEED_TOL of the forced speed for
 * MC_HANDOFF_AGREE_S without a break (mc.c note 1). A rotor that slipped
 * poles, or sits still while the estimator reads its model errors as
 * back-EMF, is retried from the lock instead of handed to the speed loop. */
#ifndef MC_HANDOFF_SPEED_TOL
#define MC_HANDOFF_SPEED_TOL 0.25
#endif
#ifndef MC_HANDOFF_AGREE_S
#define MC_HANDOFF_AGREE_S 0.02
#endif
#ifndef MC_RETRY_COAST_S
#define MC_RETRY_COAST_S 0.5 /* outputs off before a retry, so the rotor stops */
#endif
#ifndef MC_START_RETRIES
#define MC_START_RETRIES 3 /* failed starts retried before FAULT START_FAILED */
#endif
/* Angle difference at hand-off is bled off at this rate (AN1078: 0.05 deg
 * per period = 1000 deg/s at 20 kHz). */
#ifndef MC_HANDOFF_BLEED_DEG_PER_S
#define MC_HANDOFF_BLEED_DEG_PER_S 1000.0
#endif

/* Open-loop damping (mc.c note 1): once the estimator is valid in
 * OPEN_LOOP, the forced angle is moved back by MOTOR_OL_DAMP_S times the
 * rotor's excess speed (electrical rad per electrical rad/s). A rotor
 * driven by a current at a forced angle is an undamped spring and mass:
 * with little friction it swings about the forced angle for the whole ramp,
 * and the hand-off meets it at any phase of the swing. The shift gives a
 * damping ratio zeta = MOTOR_OL_DAMP_S wn / 2 to a swing of natural
 * frequency wn = sqrt(1.5 p^2 psi I_ramp / J) (rad/s) as long as the
 * estimated speed it acts on is fresh; but that speed lags the rotor's by
 * several ms at the hand-off speed (the estimator's two back-EMF filters at
 * the electrical frequency, its speed filter, the window), and a swing
 * faster than about 1 / (2 x that lag) is pushed, not damped, by any gain.
 * So profiles aim low, zeta 0.35 at their inertia (tools/tune computes it):
 * enough for the slow swings of a heavy rotor with little friction, small
 * harm to the fast ones of a light rotor. Without a profile value, 2.5 ms
 * (zeta 0.35 for wn = 280 rad/s; the Hurst075: wn = 200 rad/s). The shift
 * is held to +-MC_OL_DAMP_MAX_DEG. 0 = off. */
#ifndef MOTOR_OL_DAMP_S
#define MOTOR_OL_DAMP_S 0.0025
#endif
#ifndef MC_OL_DAMP_MAX_DEG
#define MC_OL_DAMP_MAX_DEG 30.0
#endif
/* The damping acts on the swing: forced minus estimated speed less its
 * mean over about this many speed-loop windows (a high-pass, corner
 * loop rate / (2 pi N) = 5 Hz at 1 kHz and 32, below the swings it damps).
 * A steady difference is the estimate's bias under a mismatched model, not
 * a swing, and damping it moves the forced angle back by a steady amount:
 * torque a loaded start needs. */
#ifndef MC_OL_DAMP_MEAN_WINDOWS
#define MC_OL_DAMP_MEAN_WINDOWS 32
#endif

/* ---- estimator ------------------------------------------------------------------ */
/* Lowest speed the estimator is trusted at (its filter floor and validity
 * threshold); below the hand-off speed so a start is judged with margin. */
#ifndef MC_ESTIMATOR_MIN_RPM
#define MC_ESTIMATOR_MIN_RPM (0.8 * MOTOR_RAMP_END_RPM)
#endif
/* Speed-PI Kp at low speed: MOTOR_SPEED_KP_A_PER_RPM times |speed ref| /
 * MOTOR_SPEED_KP_FULL_RPM below that speed, never less than this fraction. */
#ifndef MC_SPEED_KP_MIN_FRACTION
#define MC_SPEED_KP_MIN_FRACTION 0.25
#endif
/* Cut-off of the estimated-speed filter (the speed loop's feedback): a
 * tenth of the speed-loop rate, 100 Hz at 1 kHz, the rule tools/tune
 * writes into every profile (docs/estimator.md: it converges fastest from
 * a wrong state at that window). */
#ifndef MC_SPEED_FILTER_HZ
#define MC_SPEED_FILTER_HZ ((double)MC_SPEED_LOOP_HZ / 10.0)
#endif

/* ---- protections ------------------------------------------------------------------- */
#ifndef MC_OVERCURRENT_A
#define MC_OVERCURRENT_A MOTOR_OVERCURRENT_A /* any phase, one sample */
#endif
#ifndef MC_VBUS_UNDERVOLTAGE_V
#define MC_VBUS_UNDERVOLTAGE_V BOARD_VBUS_UNDERVOLTAGE_V /* while the outputs are on */
#endif
#ifndef MC_VBUS_OVERVOLTAGE_V
#define MC_VBUS_OVERVOLTAGE_V BOARD_VBUS_OVERVOLTAGE_V /* in any state but FAULT */
#endif
/* A STOP in CLOSED_LOOP with the rotor above the speed whose line-to-line
 * back-EMF peak is MC_STOP_RELEASE_FRACTION of the bus (measured) does not
 * release the switches at once: the six diodes would rectify that back-EMF
 * into the bus, and a supply that takes no current back leaves it in the
 * capacitor (the Hurst stopped at 5,300 rpm charged 470 uF past the 32 V
 * trip in 4.7 ms). The current loops hold zero torque (Iq 0, Id as field
 * weakening needs) while the rotor coasts, and release it below that
 * speed (checked once a window): STOPPED. mc_status_t.stopping says so;
 * S2 (MC_REQUEST_START_STOP) meanwhile takes the speed loop back. */
#ifndef MC_STOP_RELEASE_FRACTION
#define MC_STOP_RELEASE_FRACTION 0.9
#endif
/* Braking into the bus: a decelerating rotor returns its energy to the DC
 * bus, and a supply that cannot take current back (a bench supply, a
 * rectifier) leaves it in the bus capacitor, which charges towards the
 * overvoltage trip. Above MC_VBUS_REGEN_V (V) the speed loop may ask less
 * and less braking current, none from MC_VBUS_REGEN_V +
 * MC_VBUS_REGEN_BAND_V on, and the speed ramp waits for the rotor; the
 * rotor then slows by its losses. Defaults: halfway from the nominal bus to
 * the trip, over a quarter of that span. */
#ifndef MC_VBUS_REGEN_V
#define MC_VBUS_REGEN_V                                                                            \
    (BOARD_VBUS_NOMINAL_V + 0.5 * (MC_VBUS_OVERVOLTAGE_V - BOARD_VBUS_NOMINAL_V))
#endif
#ifndef MC_VBUS_REGEN_BAND_V
#define MC_VBUS_REGEN_BAND_V (0.25 * (MC_VBUS_OVERVOLTAGE_V - BOARD_VBUS_NOMINAL_V))
#endif
#ifndef MC_OFFSET_MAX_A
#define MC_OFFSET_MAX_A 0.5 /* current offset at calibration above this: amplifier fault */
#endif
/* Current-sensor plausibility (mc.c note 5): with the outputs on, the
 * measured current must follow the current loops' reference. A speed-loop
 * window fails when the mean error on either axis exceeds half the
 * reference plus MC_SENSOR_ERR_FLOOR_FRACTION of MOTOR_CURRENT_MAX_A (half
 * of that in LOCK and OPEN_LOOP, whose errors are low-passed further; the
 * floor stands above a low-inductance motor's current ringing). In
 * CLOSED_LOOP, with the q PI at the voltage limit, the bus may hold q short
 * by any amount: such a window is judged on d and on the estimator's
 * validity instead; a window whose two measured phases' mean squares
 * differ by more than 8:1 (a turning rotor's phases are balanced) fails
 * too. MC_SENSOR_TIME_S of failing windows, net of passing ones at half
 * weight, is a MC_FAULT_CURRENT_SENSOR. */
#ifndef MC_SENSOR_TIME_S
#define MC_SENSOR_TIME_S 0.005
#endif
/* 1: the check trips. 0: it only runs (a unit test without a plant, whose
 * currents never follow the loops). */
#ifndef MC_SENSOR_CHECK
#define MC_SENSOR_CHECK 1
#endif
#ifndef MC_SENSOR_ERR_FLOOR_FRACTION
#define MC_SENSOR_ERR_FLOOR_FRACTION 0.2
#endif
/* Stall / loss of synchronisation in closed loop. Each condition must
 * persist for MC_STALL_TIME_S (checked at the speed-loop rate). */
#ifndef MC_STALL_TIME_S
#define MC_STALL_TIME_S 0.02
#endif
#ifndef MC_STALL_SPEED_MIN_RPM
#define MC_STALL_SPEED_MIN_RPM (0.5 * MOTOR_SPEED_MIN_RPM) /* estimated speed below this */
#endif
/* Estimated back-EMF outside [low, high] times the back-EMF Ke predicts at
 * the estimated speed (a locked rotor reads a back-EMF far too small for
 * the speed the estimator claims). */
#ifndef MC_STALL_BEMF_LOW_FRACTION
#define MC_STALL_BEMF_LOW_FRACTION 0.4
#endif
#ifndef MC_STALL_BEMF_HIGH_FRACTION
#define MC_STALL_BEMF_HIGH_FRACTION 2.5
#endif
/* |speed reference - estimated speed| above this for MC_STALL_TRACK_TIME_S
 * while the speed PI is saturated. */
#ifndef MC_STALL_SPEED_ERROR_RPM
#define MC_STALL_SPEED_ERROR_RPM 1500.0
#endif
#ifndef MC_STALL_TRACK_TIME_S
#define MC_STALL_TRACK_TIME_S 0.04
#endif
/* The speed PI swinging from one limit to the other and back: a limit cycle
 * of the speed loop, whose gains are too high for the rotor on the shaft (a
 * rotor several times lighter than the profile's inertia, or a client's
 * gains). MC_SWING_FLIPS reversals between its limits in CLOSED_LOOP, each
 * within MC_SWING_GAP_S (s) of the one before: SPEED_UNSTABLE. A limit
 * cycle reverses every few ms; a healthy loop once or twice after a large
 * step, and a loop that an estimate's noise drives to its limits now and
 * then, tens of ms apart at random (docs/robustness.md); a locked rotor's
 * estimate makes it reverse every 2 ms, and the stall checks (20 ms) must
 * name that first, so the run takes more than MC_STALL_TIME_S. */
#ifndef MC_SWING_FLIPS
#define MC_SWING_FLIPS 16
#endif
#ifndef MC_SWING_GAP_S
#define MC_SWING_GAP_S 0.025
#endif

/* ---- self-commissioning (MC_REQUEST_IDENTIFY, mc.h; docs/identify.md) ------------ */
/* 1: the build can identify the motor; 0: it cannot (MC_REQUEST_IDENTIFY
 * ends at once, FAILED, MC_ID_ERROR_UNAVAILABLE). The sequence and its unit
 * conversions take about 6,000 instruction words of flash and 600 bytes of
 * RAM with XC16 (docs/performance.md): more than the dsPIC33FJ32MC204 has
 * left beside the drive and the X2Cscope target, so that chip's image
 * leaves it out by default. */
#ifndef MC_IDENTIFY
#if defined(__dsPIC33FJ32MC204__)
#define MC_IDENTIFY 0
#else
#define MC_IDENTIFY 1
#endif
#endif

/* MC_DRIVE: the sensorless drive (LOCK, OPEN_LOOP, CLOSED_LOOP: the
 * estimator, the speed loop, field weakening, the current-sensor check, the
 * lock's dead-time measurement). 0 builds the commissioning image (make
 * firmware IMAGE=identify, docs/identify.md): the core measures the motor
 * and nothing else, and a START (S2, MC_REQUEST_START, x2c.tune.run) starts
 * the identification as MC_REQUEST_IDENTIFY does. Needs MC_IDENTIFY 1. */
#ifndef MC_DRIVE
#define MC_DRIVE 1
#endif
/* The largest current the measurement drives (A, peak phase): the DC level
 * at which R, the inverter's error and L are measured (1.5 times it may flow
 * for a moment while the voltage is found), a third of it turns the rotor
 * for Ke and J. Your motor's rated current, or less; the profile in the
 * build is the motor's *before* it is known, so set this one for the motor
 * you measure. Must leave room below MC_OVERCURRENT_A: by default the
 * profile's MOTOR_CURRENT_MAX_A, or less where 1.6 times that would come
 * within 5 % of the trip. */
#ifndef MC_ID_CURRENT_A
#define MC_ID_CURRENT_DEFAULT                                                                      \
    1 /* the profile's, not set: a small motor fails TOO_SMALL at run time */
#define MC_ID_CURRENT_A                                                                            \
    ((1.6 * MOTOR_CURRENT_MAX_A < 0.95 * MC_OVERCURRENT_A) ? MOTOR_CURRENT_MAX_A                   \
                                                           : 0.95 * MC_OVERCURRENT_A / 1.6)
#endif
/* The current loops' bandwidth while measuring (rad/s): set from the
 * measured L, whatever the profile says. */
#ifndef MC_ID_LOOP_BW_RAD_S
#define MC_ID_LOOP_BW_RAD_S 1000.0
#endif
/* The spin: electrical acceleration of the turning current (Hz/s) and the
 * highest mechanical speed it may reach (rpm). The back-EMF is measured at
 * the speed where it reaches a fifth of the voltage scale and at twice
 * that, or at half this limit and at the limit. */
#ifndef MC_ID_ACCEL_HZ_S
#define MC_ID_ACCEL_HZ_S 100.0
#endif
#ifndef MC_ID_SPEED_MAX_RPM
#define MC_ID_SPEED_MAX_RPM SPEED_REF_MAX_RPM
#endif

#endif /* USERPARMS_H */
