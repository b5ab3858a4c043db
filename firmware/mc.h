/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* mc.h - the motor-control core: one object, one step per PWM period, no hardware access. */
#ifndef MC_H
#define MC_H

/*
 * The core seam (docs/design.md "The core seam"). Everything a program needs to
 * drive the core is reachable from this header alone:
 *
 *   - the scale macros, in engineering units (from UserParms.h and the board
 *     and motor profiles it selects at build time):
 *       BOARD_I_FULLSCALE_A     current that reads as Q15 full scale (A)
 *       BOARD_VBUS_FULLSCALE_V  DC-bus voltage that reads as 32767 (V)
 *       PWM_FREQUENCY_HZ        PWM and control-loop frequency (Hz)
 *       PWM_DUTY_MAX            duty counts for 100 % (PDCx units)
 *       MOTOR_POLE_PAIRS        pole pairs of the selected motor
 *       MC_SPEED_FULLSCALE_RPM  mechanical speed that reads as Q15 full scale
 *       SPEED_REF_MIN_RPM       speed reference at pot = 0 (speed mode)
 *       SPEED_REF_MAX_RPM       speed reference at pot = 32767 (speed mode)
 *     plus MC_VOLTAGE_FULLSCALE_V, the voltage scale of vd/vq (the SVGen full
 *     scale: the nominal bus over sqrt(3), a phase-voltage amplitude);
 *   - the types and the entry points below, and mc_t as a complete type
 *     so the caller allocates it (normally one static instance owned by the
 *     ADC interrupt).
 *
 * Timing contract (note 2): mc_step() is called once per PWM period n with
 * the frame sampled at MC_SAMPLE_AT of the period (its midpoint, where
 * every low-side switch conducts, plus the ADC trigger offset
 * PWM_ADC_TRIGGER_TCY); the duties it returns are loaded at the next period
 * boundary, half a period after the sample (the dsPIC loads PDCx there),
 * and act for the whole period n+1. On the dsPIC that boundary comes about
 * 700 cycles into the interrupt, before the whole step could finish, so
 * the step is also offered in two parts: mc_step_control() returns the
 * duties, mc_step_finish() then does the rest (the estimator's update, the
 * hand-off, the slow step's hand-over); mc_step() is exactly the two in
 * a row.
 *
 * Concurrency: mc_step() runs in the ADC interrupt, mc_slow_step() in a
 * context the interrupt pre-empts (note 4). mc_request(),
 * mc_set_reference() and mc_set_gain() may be called from the main loop
 * (or any other one context) while mc_step() runs: they only post into a
 * mailbox that mc_step() reads at its next call, each field of which has
 * exactly one writing context (see note 1). mc_status() takes a snapshot; called outside the
 * interrupt it may mix fields of two consecutive periods.
 *
 * Extensions beyond docs/design.md's minimum (added, nothing renamed):
 *   MC_REQUEST_START, MC_REQUEST_STOP       unambiguous start / stop for a
 *                                           remote interface (START_STOP is
 *                                           the S2 button's toggle);
 *   MC_REQUEST_REF_POT                      return to the pot after
 *                                           mc_set_reference();
 *   mc_set_reference()                      remote speed reference (speed
 *                                           mode) or Iq reference (TORQUEMODE);
 *   MC_STATE_CALIBRATE, MC_STATE_LOCK,
 *   MC_STATE_OPEN_LOOP                      the start-up states;
 *   MC_FAULT_* codes                        below, readable in mc_status_t;
 *   mc_status_t fields after vq             Vbus, start-up retry count,
 *                                           references, estimator validity,
 *                                           back-EMF, duties;
 *   mc_set_gain()                           live PI gains (note 3);
 *   mc_slow_step(), MC_SLOW_STEP_PERIODS    the optional slow step of the seam,
 *                                           taken (note 4), with
 *                                           MC_SLOW_APPLY_PERIODS and
 *                                           MC_FAULT_OVERRUN.
 */

#include <stdbool.h>
#include <stdint.h>

#include "../hal/hal_frame.h"
#include "UserParms.h"
#include "mc_derived.h"

#include "fieldweak.h"
#include "frames.h"
#include "mc_id.h"
#include "lpf.h"
#include "pi.h"
#include "smc.h"

/* ---- input and output of one period ------------------------------------ */

/* The seam's two value types (hal/hal_frame.h, in the board's scalings):
 * the ADC set of one period in, the duties for the next out. */
typedef hal_adc_frame_t mc_adc_frame_t;
typedef hal_pwm_out_t mc_pwm_out_t;

/* ---- requests ----------------------------------------------------------- */

typedef enum {
    MC_REQUEST_START_STOP, /* the S2 button: start when stopped or faulted, stop when running */
    MC_REQUEST_HW_FAULT,   /* the FLTA pin latched: FAULT with MC_FAULT_HARDWARE */
    MC_REQUEST_START,      /* start (also leaves FAULT once the cause is gone); no-op if running */
    MC_REQUEST_STOP,       /* stop: outputs off, STOPPED; no-op if stopped; FAULT stays FAULT */
    MC_REQUEST_REF_POT,    /* take the reference from the pot again (undoes mc_set_reference) */
    MC_REQUEST_IDENTIFY,   /* from STOPPED: measure the motor (mc_identify_result), then STOPPED */
    MC_REQUEST_COUNT       /* number of requests, not a request */
} mc_request_t;

/* ---- states -------------------------------------------------------------- */

/* The one list of states, in their order (tools read the names from here:
 * mc_state_name, tools/sim/plot.py, tools/scope). */
#define MC_STATE_LIST(X)                                                                           \
    X(STOPPED)     /* outputs off, duties 50 %, waiting for START */                               \
    X(CALIBRATE)   /* outputs off, averaging the current-amplifier offsets */                      \
    X(LOCK)        /* outputs on, rotor aligned at a fixed angle with controlled current */        \
    X(OPEN_LOOP)   /* forced angle at constant acceleration, d/q current loops running */          \
    X(CLOSED_LOOP) /* sensorless: angle and speed from the estimator, speed loop running */        \
    X(IDENTIFY)    /* outputs on, measuring the motor (MC_REQUEST_IDENTIFY); then STOPPED */       \
    X(FAULT)       /* outputs off, duties 50 %; left only by a START once the cause is gone */

#define MC_STATE_ENUM_(name) MC_STATE_##name,
typedef enum { MC_STATE_LIST(MC_STATE_ENUM_) MC_STATE_COUNT } mc_state_t;
#undef MC_STATE_ENUM_

/* ---- fault codes (mc_status_t.fault) ------------------------------------ *
 * The code of the first fault that tripped; it stays until a START clears
 * it. A START while the bus is still out of its window ends in FAULT again
 * in the same step, with the present cause: at or below the undervoltage
 * threshold (code 2), at or above the overvoltage one (code 3). The core
 * cannot see the FLTA pin: the HAL posts MC_REQUEST_HW_FAULT again while
 * the pin is still asserted. */
#define MC_FAULT_LIST(X)                                                                           \
    X(NONE, 0)            /* no fault */                                                           \
    X(OVERCURRENT, 1)     /* |ia|, |ib| or |ic| >= MC_OVERCURRENT_A in one sample */               \
    X(UNDERVOLTAGE, 2)    /* Vbus <= MC_VBUS_UNDERVOLTAGE_V, outputs on or at START */             \
    X(OVERVOLTAGE, 3)     /* Vbus >= MC_VBUS_OVERVOLTAGE_V (any state) */                          \
    X(HARDWARE, 4)        /* MC_REQUEST_HW_FAULT: the FLTA pin tripped */                          \
    X(START_FAILED, 5)    /* no valid estimate at the end of the ramp, retries used up */          \
    X(STALL_SPEED, 6)     /* closed loop: |speed| < MC_STALL_SPEED_MIN_RPM, persisting */          \
    X(STALL_BEMF, 7)      /* closed loop: back-EMF inconsistent with speed, persisting */          \
    X(STALL_TRACK, 8)     /* closed loop: speed error with the speed PI saturated */               \
    X(OFFSET, 9)          /* current offset out of range at calibration (amplifier) */             \
    X(OVERRUN, 10)        /* mc_slow_step of a window not finished at the next window end */       \
    X(CURRENT_SENSOR, 11) /* measured currents do not follow the current loops (mc.c note 5) */    \
    X(SPEED_UNSTABLE, 12) /* closed loop: the speed PI swings between its limits (a limit cycle)   \
                           */

#define MC_FAULT_ENUM_(name, code) MC_FAULT_##name = code,
enum { MC_FAULT_LIST(MC_FAULT_ENUM_) MC_FAULT_COUNT };
#undef MC_FAULT_ENUM_

/* ---- status ---------------------------------------------------------------- */

typedef struct {
    mc_state_t state;
    uint16_t fault;    /* 0 = none; MC_FAULT_* above */
    int16_t theta_est; /* electrical angle used by the Park transforms, Q15: -32768..32767 =
                          -pi..pi (CLOSED_LOOP: the estimator's plus the hand-off
                          difference being bled off; LOCK, OPEN_LOOP: the forced one) */
    int16_t speed_est; /* mechanical speed, Q15 of MC_SPEED_FULLSCALE_RPM */
    int16_t speed_ref; /* same scale (the ramped reference the speed loop follows) */
    int16_t id, iq;    /* measured, on the axes at theta_est, Q15 of BOARD_I_FULLSCALE_A */
    int16_t vd, vq;    /* commanded (after the circle limit and ripple compensation),
                          Q15 of the SVGen full scale (MC_VOLTAGE_FULLSCALE_V) */
    /* additions */
    int16_t vbus;           /* DC bus, Q15 of BOARD_VBUS_FULLSCALE_V (last sample) */
    uint8_t start_retries;  /* failed start-up attempts since the last START request */
    bool estimator_valid;   /* the estimator reports a usable angle */
    int16_t id_ref, iq_ref; /* current references on the estimated rotor axes, Q15 of
                               BOARD_I_FULLSCALE_A */
    int16_t speed_target;   /* speed reference before the ramp, Q15 of MC_SPEED_FULLSCALE_RPM */
    int16_t theta_forced;   /* open-loop angle, Q15 binary angle */
    int16_t bemf;           /* the estimator's filtered back-EMF magnitude |e_final|, Q15 of
                               its E_FS = SMC_EMF_FS_RATIO (2) x MC_VOLTAGE_FULLSCALE_V; the two
                               filter stages leave about SMC_STAGE_GAIN (0.3..0.4) of the true
                               phase amplitude, so this is a consistency figure (the stall
                               check's), not volts of back-EMF */
    int16_t ia, ib;         /* offset-corrected phase currents, Q15 of BOARD_I_FULLSCALE_A */
    uint16_t duty[3];       /* duties of the last step (what the next period applies) */
    bool outputs_on;        /* as in the last mc_pwm_out_t */
    bool stopping;          /* CLOSED_LOOP after a STOP: zero torque while the rotor coasts
                               down to the speed the switches can be released at (UserParms.h
                               MC_STOP_RELEASE_FRACTION), then STOPPED */
    int16_t deadtime;       /* the dead time compensated and modelled, Tcy (duty counts):
                               PWM_DEADTIME_NS's until a lock measured it (MC_DEADTIME_MEASURE) */
    bool ref_remote;        /* the reference is a set one (mc_set_reference), not the pot */
    uint8_t ref_seq;        /* choices of reference so far (mc_set_reference, REF_POT), mod
                               256: a writer that finds it moved since its own last call has
                               lost the reference */
} mc_status_t;

/* ---- self-commissioning (MC_REQUEST_IDENTIFY) ---------------------------- *
 * mc_request(mc, MC_REQUEST_IDENTIFY) from STOPPED calibrates the current
 * offsets (CALIBRATE), then measures the motor in MC_STATE_IDENTIFY (the
 * sequence of mc_id.h: R and the inverter's voltage error by DC current at
 * three levels, Ld and Lq by an injected voltage, the back-EMF constant and
 * the inertia by turning the rotor in current-controlled open loop) and
 * ends in STOPPED; mc_identify_result() then holds the result. Currents
 * stay within MC_ID_CURRENT_A (UserParms.h) and every protection of the
 * core stays armed: a fault ends it in FAULT (status FAILED, error
 * MC_ID_ERROR_FAULT, the cause in mc_status_t.fault), a stop (S2, STOP) in
 * STOPPED (MC_ID_ERROR_ABORTED). A request in any other state is refused
 * (MC_ID_ERROR_NOT_STOPPED) and changes nothing else. Pole pairs are the
 * build's MOTOR_POLE_PAIRS (Ke is per mechanical rpm). docs/identify.md
 * has the method and its accuracy. */
typedef enum { MC_ID_NONE, MC_ID_RUNNING, MC_ID_DONE, MC_ID_FAILED } mc_id_status_t;

/* Why an identification failed (mc_id_result_t.error): MC_ID_ERROR_LIST in
 * mc_id.h (included above), the codes and their meaning. */

typedef struct {
    mc_id_status_t status;
    uint16_t error;         /* why it failed: MC_ID_ERROR_* (mc_id.h) */
    uint32_t rs_uohm;       /* phase resistance, micro-ohms */
    uint32_t ls_nh;         /* phase inductance, (Ld + Lq) / 2, nH */
    uint32_t ke_uv_per_rpm; /* back-EMF, peak line-to-line microvolts per mechanical rpm
                               (= mV per 1000 rpm) */
    uint32_t j_ng_m2;       /* rotor + load inertia, 1e-9 kg m^2 (0 = not measured) */
    uint16_t deadtime_ns;   /* the inverter's effective dead-time voltage, as ns of the bus */
    /* additions */
    uint32_t ld_nh, lq_nh; /* d and q inductance, nH (the rotor aligned on d) */
    uint8_t pole_pairs;    /* the pole pairs Ke and J were computed with (MOTOR_POLE_PAIRS) */
} mc_id_result_t;

/* ---- run-time gains -------------------------------------------------------- *
 * The PI gains a tuning interface may change while the motor runs (the live
 * X2Cscope target's tunables). Values are the Q15 mantissas of pi_params_t; each
 * loop's exponent (kp_shift) stays as built. */
typedef enum {
    MC_GAIN_CUR_KP, /* d and q current PIs: Kp mantissa */
    MC_GAIN_CUR_KI, /* d and q current PIs: Ki, and Kc = Ki (AN1078) */
    MC_GAIN_SPD_KP, /* speed PI: Kp before the low-speed schedule */
    MC_GAIN_SPD_KI, /* speed PI: Ki before the low-speed schedule, and Kc = Ki */
    MC_GAIN_COUNT   /* number of gains, not a gain */
} mc_gain_t;

/* The region a client's gains stay in (note 3), against the built-in gains:
 * each at least MIN8 / 8 of its built-in and at most 8 times it, and a
 * loop's Ki / Kp at most MC_GAIN_ZERO_MAX times the built-in ratio. */
#define MC_GAIN_CUR_KP_MIN8 1U /* 1/8 */
#define MC_GAIN_CUR_KI_MIN8 1U /* 1/8 */
#define MC_GAIN_SPD_KP_MIN8                                                                        \
    8U                         /* the built-in: softer stalls the lowest speeds under a load step  \
                                */
#define MC_GAIN_SPD_KI_MIN8 4U /* 1/2: less stalls them too */
#define MC_GAIN_ZERO_MAX    8U

/* ---- the slow step ------------------------------------------------------ *
 * The work that follows the speed loop's rate runs outside the PWM
 * interrupt, in mc_slow_step(): the estimator's speed, K and phase
 * compensation, the speed ramp and PI, field weakening and stall detection.
 * mc_step() posts a window's inputs every MC_SLOW_STEP_PERIODS calls
 * (counting from mc_init) and applies the results of the window before at
 * the same moment (note 4). */

/* mc_step() calls per mc_slow_step() call: the speed loop's period. */
#define MC_SLOW_STEP_PERIODS IRP_PERCALC

/* MC_SLOW_APPLY_PERIODS (mc_derived.h): mc_step() calls after a window end
 * at which the slow step's results are taken, i.e. the time mc_slow_step()
 * has to finish. */

/* What mc_step() hands the slow step at a window end. */
typedef struct {
    uint8_t epoch;          /* the run it belongs to (mc_t.epoch) */
    mc_state_t state;       /* state at the window end */
    int16_t pot;            /* the pot, for the reference */
    int16_t ref_remote;     /* the remote reference ... */
    bool ref_from_remote;   /* ... when it replaces the pot */
    q15_t spd_kp, spd_ki;   /* the speed gains as posted (mc_set_gain) */
    bool stopping;          /* CLOSED_LOOP after a STOP: zero torque (mc_t.stopping) */
    bool preset;            /* closed loop entered in this window: */
    q15_t preset_iq;        /* the speed PI's integral, Q15 current */
    q15_t preset_speed_ref; /* the ramp's start, Q15 speed */
    uint32_t ol_step;       /* OPEN_LOOP: the forced angle's step (mc_t.ol_step) ... */
    ab_q15_t i_ab;          /* the window end's current (OPEN_LOOP, the sensor check) ... */
    angle_q15_t theta_est;  /* ... and estimated angle (the load's share, mc.c note 1) */
    int32_t lock_va;        /* LOCK: the window's sums of the estimator's alpha and beta */
    int32_t lock_vb;        /* voltage, Q15 of V_FS (mc.c note 4) */
    uint32_t timer;         /* periods in the state at the window end */
    int16_t dt_counts;      /* the dead time in use, duty counts */
    q15_t vbus;             /* the window end's bus, Q15 */
    int32_t sens_d, sens_q; /* the window's current-error sums (mc.c note 5) ... */
    uint16_t sens_qsat;     /* ... periods with the q PI at its limit ... */
    dq_q15_t sens_ref;      /* ... the current reference at the window end ... */
    bool est_valid;         /* ... whether the estimator vouches for its estimate ... */
    q15_t emf_ratio;        /* ... its back-EMF against the speed's, Q12 (smc.h) ... */
    q15_t speed_est;        /* ... and its speed, Q15 */
#if MC_IDENTIFY
    mc_id_win_t id; /* IDENTIFY: the window's sums (mc_id.h) */
#endif
} mc_slow_in_t;

/* What the slow step hands back; applied at the next window end. */
typedef struct {
    uint8_t epoch;       /* of the window it was computed from */
    bool loop;           /* the speed loop ran (CLOSED_LOOP): the fields below count */
    dq_q15_t i_ref;      /* current references for the next window */
    q15_t speed_ref;     /* the ramped reference */
    uint16_t fault;      /* a stall fault, or MC_FAULT_NONE */
    bool release;        /* stopping: the rotor below the release speed (mc_release_speed) */
    q15_t speed_target;  /* the reference before the ramp (every state) */
    q15_t torque_target; /* TORQUEMODE: the Iq reference (every state) */
    q15_t ol_iq;         /* OPEN_LOOP: the torque current, low-passed (mc.c note 1) */
    int16_t ol_shift;    /* OPEN_LOOP: the damping's shift of the forced angle, counts */
    q15_t lock_iq;       /* LOCK: the lock's current reference (mc.c note 4) */
    bool sensor_fault;   /* the current-sensor check failed (mc.c note 5) */
    bool lock_done;      /* LOCK: the dead-time measurement is done: */
    int16_t dt_counts;   /* its dead time, duty counts, */
    q15_t dt_slope;      /* and in-band slope */
} mc_slow_out_t;

/* ---- the instance ------------------------------------------------------- *
 * Complete so the caller can allocate it; its members are private to the
 * core and may change between versions (read them through mc_status()).
 * Each part has one writing context: the mailbox the main loop's, the
 * hand-over's results and the slow step's state the slow step's (mc.h note
 * 4), everything else the ADC interrupt's (mc_step). The slow step's
 * functions take only their part (mc_slow.c, mc_sensor.c, mc_dtm.c), so
 * the compiler holds them to it; the interrupt's fields stay at the top
 * level, where the X2Cscope clients name them by path (x2c_vars.h). */

/* The mailbox (note 1): written only by mc_request, mc_set_reference and
 * mc_set_gain (the main loop), read by mc_step. */
typedef struct {
    volatile uint8_t req_posted[MC_REQUEST_COUNT];
    volatile uint8_t req_seq;                    /* incremented last by each of the three */
    volatile int16_t ref_remote;                 /* remote reference (speed or Iq), Q15 */
    volatile bool ref_to_pot;                    /* the last choice: the pot (REF_POT) */
    volatile uint8_t ref_seq;                    /* incremented by mc_set_reference and REF_POT */
    volatile int16_t gain_posted[MC_GAIN_COUNT]; /* mc_set_gain; Q15 mantissas */
    volatile uint8_t gain_seq;                   /* incremented by mc_set_gain */
} mc_mailbox_t;

/* The current-sensor check's slow side (mc_sensor.c, mc.c note 5). */
typedef struct {
    int32_t fd, fq;  /* the window error sums low-passed over windows (at the start) */
    uint8_t cnt;     /* failing windows x 2, less passing ones */
    uint8_t emf_low; /* consecutive windows of a back-EMF too low for the speed, up to the defer */
    uint8_t low_n;   /* the same, up to MC_SENSOR_BAL_REFILL */
    uint8_t pend;    /* failing windows held while emf_low is below the defer */
    int32_t sa, sb;  /* ia^2 and ib^2 low-passed, Q15 of I_FS^2 << MC_SENSOR_BAL_SHIFT */
    uint8_t bal_n;   /* CLOSED_LOOP windows they have filtered, up to 2 time constants */
} mc_sensor_t;

/* The lock's dead-time measurement (mc_dtm.c, mc.c note 4), per window. */
typedef struct {
    int32_t sum;  /* the windows' beta sums (lock_vb), Q15 of V_FS */
    int32_t mean; /* MC_DTM_MEAN x the windows' alpha sums (lock_va), low-passed */
    int32_t hi;   /* the largest and smallest alpha sum in the windows */
    int32_t lo;
    int32_t range1; /* the first level's alpha range (hi - lo) */
    uint16_t cnt;   /* windows in the phase */
    q15_t u1;       /* the first level's mean voltage, Q15 of V_FS */
    uint8_t phase;  /* MC_DTM_* phase (mc_dtm.c) */
    bool pos;       /* the alpha sum was above its mean last window */
    bool slow;      /* a window waited MC_DTM_WAIT for a reversal */
} mc_dtm_t;

/* The stall and limit-cycle detector's state (mc_stall_check, mc_internal.h). */
typedef struct {
    uint16_t cnt[3];     /* speed-loop runs each stall condition has persisted */
    uint16_t swing_gap;  /* runs since the speed PI last went from one limit to the other */
    uint8_t swing_flips; /* such reversals in a row, each within MC_SWING_GAP_S of the last */
    int8_t swing_side;   /* the limit it was last at: +1 upper, -1 lower, 0 none yet */
} mc_stall_t;

/* The slow step's own state (mc_slow.c). */
typedef struct {
    pi_t pi_w;          /* speed PI */
    fieldweak_t fw;     /* its Id table (constant after mc_init) */
    int16_t spd_ref;    /* the ramp's state, Q15 speed */
    mc_stall_t stall;   /* the stall and limit-cycle detector's counts */
    uint8_t epoch;      /* the run the slow step's state belongs to */
    int32_t ol_iq_acc;  /* OPEN_LOOP: 32 x the low-passed torque current, Q15 */
    int32_t ol_dmean;   /* OPEN_LOOP: forced - estimated step, mean, Q4 counts/period */
    bool ol_dlive;      /* OPEN_LOOP: ol_dmean holds a valid estimate's history */
    mc_sensor_t sensor; /* the current-sensor check */
    mc_dtm_t dtm;       /* LOCK: the dead-time measurement */
} mc_slow_t;

/* The hand-over (note 4): the interrupt writes in while !busy, the slow
 * step out while busy; the flag passes them. */
typedef struct {
    volatile bool busy; /* a window posted, its slow step not finished */
    mc_slow_in_t in;
    mc_slow_out_t out;
} mc_handover_t;

#if MC_IDENTIFY
/* IDENTIFY (mc_id.h): the interrupt's side (mc_id_isr.c). */
typedef struct {
    mc_id_win_t win; /* this window's sums */
    uint32_t inc;    /* the forced speed's change per period (the spin's) */
    q15_t inj;       /* the injected square wave's amplitude, Q15 V_FS (0: none) */
    uint8_t inj_q;   /* ... on q (else d) */
    uint8_t half;    /* ... periods per half cycle */
    uint8_t cnt;     /* ... periods into this half */
    int8_t sign;     /* ... its sign in this period's command */
    int8_t z;        /* ... in the previous period's */
    int8_t z2;       /* ... in the one before */
    uint32_t zh;     /* ... the signs of the commands before, one bit a period (1: +) */
    q15_t i_prev;    /* the injected axis's current at the previous sample */
    q15_t u_prev;    /* ... and the voltage commanded two periods ago */
    q15_t dt_band;   /* the dead-time compensation's band, Q15 I_FS (MC_DT_BAND_Q15 but while
                        the sequence's command sets another) */
    bool open;       /* the last command was open loop */
    bool pending;    /* CALIBRATE before IDENTIFY */
} mc_id_isr_t;
#endif

typedef struct {
    mc_mailbox_t mbox; /* the main loop's (note 1) */
    /* the interrupt's view of the mailbox: what it has taken */
    uint8_t req_taken[MC_REQUEST_COUNT];
    uint8_t req_seen;
    uint8_t ref_seen;
    bool ref_from_remote;
    uint8_t gain_seen;
    q15_t spd_kp_base, spd_ki_base; /* speed PI gains the schedule scales */

    mc_state_t state;
    uint16_t fault;
    uint32_t timer;      /* periods spent in the current state (saturates) */
    uint8_t retries;     /* failed starts since START */
    uint16_t agree;      /* ramp end: periods the estimate has agreed with the rotor (note 1) */
    uint16_t calib_wait; /* CALIBRATE: periods to coast before averaging */

    /* current offsets, Q15 */
    int32_t offset_acc_a, offset_acc_b;
    int16_t offset_a, offset_b;

    /* measurements of this period */
    int16_t ia, ib, ic, vbus, pot;
    ab_q15_t i_ab;
    dq_q15_t i_dq;

    /* current control */
    pi_t pi_d, pi_q;
    dq_q15_t i_ref;
    dq_q15_t i_ref_frame;   /* i_ref in the transforms' frame this period (theta_offset) */
    int32_t sens_d, sens_q; /* current-sensor plausibility (mc.c note 5): this window's sums of
                               the current error on d and q, Q15 of I_FS */
    uint16_t sens_qsat;     /* ... and of periods with the q PI at its voltage limit */
    dq_q15_t v_dq;          /* after the circle limit and ripple compensation */
    uint16_t circle_redos;  /* periods the q step was redone at the circle (mc.c note 3),
                               saturates */
    int16_t speed_target;   /* unramped reference, Q15 speed (from the slow step) */
    int16_t speed_ref;      /* ramped reference, Q15 speed (from the slow step) */
    int16_t torque_target;  /* Iq from the pot or remote, TORQUEMODE (from the slow step) */

    /* angle */
    angle_q15_t theta;      /* angle the transforms use this period */
    angle_q15_t theta_next; /* the next period's, prepared by mc_step_finish */
    sincos_q15_t sc_next;   /* its sin/cos */
    sincos_q15_t scv_next;  /* sin/cos of the angle the next voltage acts at */
    uint32_t ol_angle;      /* open-loop angle, 32-bit binary angle */
    uint32_t ol_step;       /* open-loop angle increment per period, 32-bit binary angle */
    int16_t theta_offset;   /* theta_forced - theta_est at hand-off, bled to 0 */
    int16_t ol_damp;        /* OPEN_LOOP: the damping shift in ol_angle, angle counts */
    q15_t ol_iq;            /* OPEN_LOOP: the load's torque current (slow_out.ol_iq), Q15 */
    sincos_q15_t adv_sc;    /* sin/cos of CLOSED_LOOP's voltage advance (mc_set_advance) */

    /* estimator and the voltage it is fed (note 2) */
#if MC_DRIVE
    smc_t smc;
#endif
    ab_q15_t v_hist[2]; /* applied voltage: [0] for the next step, [1] for this one */
    int16_t eff[3];     /* this period's effective duties (dead-time loss off), counts */
    int16_t dt_counts;  /* the dead time compensated and modelled, duty counts (mc.c note 4) */
    q15_t dt_slope;     /* its in-band slope, dt_counts * 2^15 / MC_DT_BAND_Q15 */
    int32_t lock_va, lock_vb; /* LOCK: this window's sums of v_hist[0] (mc.c note 4) */
    bool lock_done;           /* LOCK: the dead-time measurement has its result */
    uint16_t ripple_gain;     /* bus ripple gain for the next period (foc/ripple.h), Q15 */
    int16_t pred;             /* one period of the estimated speed, angle counts (note 2) */

    /* outputs */
    uint16_t duty[3];
    bool outputs_on;

    /* the interrupt's side of the hand-over (note 4) */
    uint16_t slow_div;   /* mc_step calls since the last window end */
    uint8_t epoch;       /* incremented when a run starts, hands off or stops */
    bool slow_posted;    /* ho.out holds a result to apply */
    bool preset_pending; /* closed loop entered since the last window end */
    q15_t preset_iq;
    q15_t preset_speed_ref;
    mc_handover_t ho;

#if MC_DRIVE
    mc_slow_t slow; /* the slow step's */
#endif

    bool sums_on;      /* LOCK (MC_DTM_ON) or IDENTIFY: the window's voltage sums run */
    bool stopping;     /* CLOSED_LOOP after a STOP above the release speed: zero torque until
                          the rotor is below it (MC_STOP_RELEASE_FRACTION); with the cold
                          fields, whose offsets do not count */
    uint8_t id_status; /* mc_id_status_t, the interrupt's view */
    uint16_t id_error; /* MC_ID_ERROR_* of a run the interrupt ended */
#if MC_IDENTIFY
    mc_id_isr_t id_isr; /* IDENTIFY: the interrupt's side */
    mc_id_t id;         /* ... and the slow step's: the sequence and its results */
#endif
} mc_t;

/* The names of a state and of a fault code, as MC_STATE_LIST and
 * MC_FAULT_LIST spell them ("none" for no fault, "?" for a number outside
 * them): for tools and tests (tools/sim/mc_names.c, not linked into the
 * dsPIC image). */
const char *mc_state_name(int state);
const char *mc_fault_name(unsigned fault);
const char *mc_id_error_name(unsigned error); /* MC_ID_ERROR_LIST's, "none" for 0 */

/* Reset everything, outputs off, MC_STATE_STOPPED. */
void mc_init(mc_t *mc);

/* One PWM period: in = the frame sampled in this period; out = the
 * duties for the next period (timing contract above). Every path writes
 * *out; in STOPPED, CALIBRATE and FAULT the duties are PWM_DUTY_MAX / 2 and
 * outputs_on is false. Protections run first, in every state. */
void mc_step(mc_t *mc, const mc_adc_frame_t *in, mc_pwm_out_t *out);

/* mc_step() in two parts, for a caller that must load the duties before the
 * whole step could finish (the dsPIC's interrupt): mc_step_control() does
 * everything up to the duties and fills *out as mc_step() does;
 * mc_step_finish() must follow it, with the same out, before the next
 * period's call, and nothing else may touch mc in between. The two in a
 * row are mc_step(), bit for bit. mc_step_finish() returns true when the
 * finishing part faulted (a failed start, a stall, an overrun) and turned
 * *out off (duties PWM_DUTY_MAX / 2, outputs_on false): the caller switches
 * the outputs off at once, not at the next period. */
void mc_step_control(mc_t *mc, const mc_adc_frame_t *in, mc_pwm_out_t *out);
bool mc_step_finish(mc_t *mc, mc_pwm_out_t *out);

/* The slow work of one window (the slow step above): call it after every
 * MC_SLOW_STEP_PERIODS-th mc_step() (counting from mc_init()), from a
 * context the PWM interrupt may pre-empt; it must finish before the
 * MC_SLOW_STEP_PERIODS-th mc_step() after that, or that step faults with
 * MC_FAULT_OVERRUN. A call with no window posted does nothing. */
void mc_slow_step(mc_t *mc);

/* Post a request; mc_step() acts on it at its next call. */
void mc_request(mc_t *mc, mc_request_t r);

/* The pot's map, as the core applies it (one map: the application's S3
 * doubles this one). Speed reference (Q15 speed) for a reading 0..32767:
 * SPEED_REF_MIN + pot (SPEED_REF_MAX - SPEED_REF_MIN) / 32768, floor (full
 * pot is one count under SPEED_REF_MAX: a multiply and a shift in the
 * 50 us path, no division). Iq reference (Q15 current, TORQUEMODE):
 * pot * MC_IQ_MAX_Q15 / 32768, floor. Negative readings count as 0. */
q15_t mc_pot_to_speed(int16_t pot);
q15_t mc_pot_to_torque(int16_t pot);

/* Remote reference, replacing the pot until MC_REQUEST_REF_POT:
 * speed mode: mechanical speed, Q15 of MC_SPEED_FULLSCALE_RPM, clamped to
 * [SPEED_REF_MIN_RPM, SPEED_REF_MAX_RPM]; TORQUEMODE: Iq reference, Q15 of
 * BOARD_I_FULLSCALE_A, clamped to +-MOTOR_CURRENT_MAX_A. Returns the number
 * of this choice of reference (what mc_status_t.ref_seq reports from now
 * on): the caller's claim, for mc_reference_held(). */
uint8_t mc_set_reference(mc_t *mc, int16_t ref);

/* The reference's owner rule, for every side that sets it: the reference
 * has one owner at a time, the last explicit choice (mc_set_reference or
 * MC_REQUEST_REF_POT). A writer whose own last choice was number seq
 * (mc_status_t.ref_seq right after it) still holds the reference while the
 * status shows a set reference and no choice since. */
bool mc_reference_held(const mc_status_t *st, uint8_t seq);

/* Run-time gain change (note 3): posted like mc_request(), applied at the
 * start of the next mc_step() to every loop it concerns at once, so the d
 * and q current loops never run a period with different gains. Returns
 * false, and changes nothing, for an unknown gain or a value that would
 * take its loop out of the region proven stable (note 3: MC_GAIN_MIN/MAX
 * and the PI zero's bound, with the loop's other gain as posted).
 * mc_init() restores the built-in gains. */
bool mc_set_gain(mc_t *mc, mc_gain_t g, int16_t value);

/* Whether mc_set_gain(mc, g, value) would take it (the loop's other gain as
 * posted now). */
bool mc_gain_allowed(const mc_t *mc, mc_gain_t g, int16_t value);

/* The gain as posted: the value in effect from the next period on. */
int16_t mc_get_gain(const mc_t *mc, mc_gain_t g);

/* Snapshot of the state for display, logging and tests. */
void mc_status(const mc_t *mc, mc_status_t *st);

/* The identification's status and, once DONE, its result (values 0 unless
 * DONE: a failed run never gives numbers). For the main loop: the unit
 * conversions run here (64-bit integer arithmetic), never in an interrupt. */
void mc_identify_result(const mc_t *mc, mc_id_result_t *r);

/*
 * Notes
 *
 * 1. The mailbox. A request r is pending while req_posted[r] != req_taken[r]
 *    (both uint8_t, compared modulo 256). mc_request() increments
 *    req_posted[r], then req_seq; mc_step() looks at the requests (and at
 *    the reference and gain counters, whose setters also increment req_seq
 *    last) only when req_seq has moved (one compare in the usual period),
 *    and copies each req_posted[r] into req_taken[r] once it has acted. A
 *    step that runs between the two increments sees the request one period
 *    later. Each byte has one writing context (mc_request, mc_set_reference
 *    and mc_set_gain are called from one context, never from mc_step's) and
 *    byte writes are atomic on the dsPIC, so no interrupt masking is
 *    needed; a request posted twice before the step sees it counts once.
 *
 * 2. Timing and the voltage fed to the estimator. Period n runs from t_n
 *    to t_(n+1); the frame is sampled at t_n + a Ts, a = MC_SAMPLE_AT (the
 *    midpoint plus the ADC trigger offset: 0.5 + 80 / 2000 = 0.54 on the
 *    MCLV); the duties mc_step returns for it are loaded at t_(n+1) and act
 *    over period n+1. So:
 *    - the voltage computed now acts centred at t_(n+1) + Ts/2, which is
 *      (1.5 - a) Ts after the sample: the inverse Park turns it by
 *      (1.5 - a) omega Ts (0.96 omega Ts; a sample at the period start
 *      with a whole period of delay would be 1.5);
 *    - between the previous sample and this one the current evolved under
 *      the command of period n-1 (computed two steps ago) for (1 - a) Ts and
 *      under the one of period n (computed one step ago) for a Ts; the
 *      estimator gets their weighted mean (its model holds one voltage
 *      over the interval; the mean is right to first order in Ts R/L).
 *    Each command is the applied voltage: the duties less the
 *    dead-time loss predicted from each phase current, times the bus
 *    voltage sampled then; a duty at 0 or PWM_DUTY_MAX does not switch and
 *    loses nothing. So duty clamping, bus ripple and the dead time itself
 *    (compensated or not) are all seen by the model. Inside the dead-time
 *    band the loss is a steep function of the current (Td/Ts Vbus / band,
 *    so at light load any current error is volts of model error: the Id
 *    floor (MC_ID_MIN_A) keeps the phase currents out of the band. (The
 *    loss is predicted from this sample's currents, not evaluated after the
 *    fact at the mean of both ends of the period: docs/tuning.md, "Behind
 *    the defaults".)
 *    The duties must be ready by t_(n+1), half a period after the sample,
 *    which on the dsPIC is less time than the whole step takes, so the
 *    current loops do not wait for this sample's estimator update: they
 *    run on the estimator's angle of sample n-1 advanced by one period of
 *    the estimated speed (pred), and the update follows the duties
 *    (mc_step_finish). At a steady speed the two angles are the same; the
 *    estimator's own filtering is far slower than one period.
 *
 * 3. Run-time gains. mc_set_gain() writes gain_posted[g] (one 16-bit store)
 *    and then increments gain_seq; mc_step() applies all posted gains when
 *    gain_seq has moved. A store that races the step is applied at the latest
 *    one period later, and always to d and q together. The speed loop's
 *    low-speed schedule multiplies spd_kp_base / spd_ki_base each speed-loop
 *    tick, so a posted speed gain survives it (writing pi_w's gains directly
 *    would be overwritten within IRP_PERCALC periods).
 *    A posted pair stays inside the region the simulated drive holds its
 *    speed in, under a load step, from the lowest closed-loop speed to the
 *    top, posted running or before START (test_mc_gains): each gain
 *    between MC_GAIN_MIN and MC_GAIN_MAX times the built-in one, and Ki
 *    over Kp at most MC_GAIN_ZERO_MAX times the built-in ratio (a PI zero
 *    far above the design's: the integral outruns the proportional part
 *    and the loop limit-cycles, with the speed loop at the full Iq limit
 *    and no fault, or the current loops into a false CURRENT_SENSOR). The
 *    speed loop may not go below its built-in Kp: at the lowest speeds a
 *    load step then stalls it.
 *
 * 4. The slow step. Every MC_SLOW_STEP_PERIODS-th mc_step() ends a window:
 *    it applies the slow step's results of the window before (the
 *    estimator's through smc_window_end, the speed loop's current
 *    references and a stall fault if they belong to the present run,
 *    epoch) and posts this window's inputs (slow_in and the estimator's
 *    snapshot), then sets slow_busy. mc_slow_step() computes from those
 *    alone into slow_out and the estimator's res, and clears slow_busy
 *    last. Each side writes only its own fields while the flag says it
 *    may, so on the dsPIC mc_slow_step() runs in a lower-priority interrupt
 *    with no masking, and the outcome is the same bits whenever it runs
 *    inside the window (the simulator calls it straight after the step).
 *    The cost is one window of delay in the speed loop and in the
 *    estimator's K and compensation; in exchange the PWM interrupt never
 *    carries the slow work. A window end that finds slow_busy still set
 *    faults with MC_FAULT_OVERRUN (the CPU is overloaded, or no context
 *    runs mc_slow_step()).
 */

#endif /* MC_H */
