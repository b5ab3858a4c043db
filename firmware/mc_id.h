/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* mc_id.h - self-commissioning's sequence: the windows of measurement that give R, L, Ke, J. */
#ifndef MC_ID_H
#define MC_ID_H

/*
 * The core's identification (MC_REQUEST_IDENTIFY, mc.h) in two halves, like
 * the rest of the core (mc.h note 4): the ADC interrupt runs the current
 * loops at the angle and with the gains this sequence asks for, adds an
 * injected voltage and sums what it measures over each speed-loop window
 * (mc_id_win_t, posted at the window end); once per window the slow step
 * runs mc_id_window(), which judges the sums, moves the sequence on and
 * returns what the interrupt does next (mc_id_cmd_t, applied
 * MC_SLOW_APPLY_PERIODS later). Nothing here touches the hardware or the
 * core's object: the sequence is a pure function of its windows, tested on
 * its own and in closed loop (test/firmware/test_mc_id.c,
 * test/closedloop/test_cl_identify.c). The method and its error budget are
 * in docs/identify.md; mc_id.c's notes say why each stage is as it is.
 *
 * Frame. The interrupt's d/q frame is the forced angle (mc_t.ol_angle),
 * standing at 90 degrees while the rotor stands, turning during the spin.
 * At 90 degrees d is the beta axis: phases B and C carry 0.87 of the d
 * current, phase A none (mc.c note 4's axis), and q is -alpha. Units: currents Q15 of
 * BOARD_I_FULLSCALE_A, voltages Q15 of MC_VOLTAGE_FULLSCALE_V (the applied phase amplitude), Z_FS =
 * V_FS / I_FS ohm for their ratio, angles per period in the open loop's 2^32 units.
 */

#include <stdbool.h>
#include <stdint.h>

#include "frames.h"
#include "q15.h"

/* Why an identification failed (mc.h mc_id_result_t.error): */
#define MC_ID_ERROR_LIST(X)                                                                        \
    X(NONE, 0)         /* none */                                                                  \
    X(NOT_STOPPED, 1)  /* requested while not STOPPED: nothing done */                             \
    X(ABORTED, 2)      /* a stop request (S2, STOP) ended it */                                    \
    X(FAULT, 3)        /* a fault of the core ended it (mc_status_t.fault says which) */           \
    X(OPEN_CIRCUIT, 4) /* no current at the largest voltage: no motor, or its wires open */        \
    X(OPEN_PHASE, 5)   /* current on one axis but not as commanded on the other: a phase open */   \
    X(TOO_SMALL, 6)    /* the current reached is under 16 ADC codes: motor too small for the       \
                          board's resolution (or MC_ID_CURRENT_A too low) */                       \
    X(OUT_OF_RANGE, 7) /* R or L outside what the board can measure (R above 16 V_FS/I_FS, L       \
                          beyond the injection's reach, a non-physical reading) */                 \
    X(ROTOR_MOVING, 8) /* the rotor turned while it should stand still */                          \
    X(ROTOR_LOCKED, 9) /* no back-EMF while the current turned: rotor locked (or Ke too small) */  \
    X(NO_SYNC, 10)     /* the rotor did not follow the turning current (or slipped poles) */       \
    X(TIMEOUT, 11)     /* a stage did not settle within its time */                                \
    X(UNAVAILABLE, 12) /* the build has no identification (UserParms.h MC_IDENTIFY 0) */

#define MC_ID_ERROR_ENUM_(name, code) MC_ID_ERROR_##name = code,
enum { MC_ID_ERROR_LIST(MC_ID_ERROR_ENUM_) MC_ID_ERROR_COUNT };
#undef MC_ID_ERROR_ENUM_

/* The sequence's stages (mc_id_t.stage), in order. */
#define MC_ID_STAGE_LIST(X)                                                                        \
    X(IDLE)   /* not running */                                                                    \
    X(RAMP)   /* d voltage raised in open loop until the current reaches the target */             \
    X(R)      /* open loop at four d voltages: R and the inverter's voltage error */               \
    X(LD)     /* voltage injected on d, the d current held: Ld */                                  \
    X(LQ)     /* injected on q, with a quarter of the current on q: Lq */                          \
    X(SPIN1)  /* the current vector turned faster: to the first speed */                           \
    X(HOLD1)  /* ... held: the back-EMF at it */                                                   \
    X(SPIN2)  /* up to twice the first speed (the torque that accelerates) */                      \
    X(HOLD2)  /* ... held: the back-EMF at it */                                                   \
    X(SPIN3)  /* back down to the first speed (the torque that decelerates) */                     \
    X(SPIN4)  /* down to rest */                                                                   \
    X(DONE)   /* finished: results valid */                                                        \
    X(FAILED) /* stopped with an error */

#define MC_ID_STAGE_ENUM_(name) MC_ID_STAGE_##name,
enum { MC_ID_STAGE_LIST(MC_ID_STAGE_ENUM_) MC_ID_STAGE_COUNT };
#undef MC_ID_STAGE_ENUM_

/* What the sequence needs of the build (mc.c fills it from UserParms.h, the
 * board and the core's scales; mc_derived.h checks the settings). */
typedef struct {
    q15_t i_target;    /* the DC current measured at (MC_ID_CURRENT_A) */
    q15_t i_min;       /* the least it may be: 16 ADC codes */
    q15_t v_max;       /* the largest DC voltage (70 % of the voltage limit) */
    q15_t inj_max;     /* the largest injected amplitude (a quarter of it) */
    q15_t wc_ts;       /* the loops' crossover times Ts (MC_ID_LOOP_BW_RAD_S), Q15 */
    uint16_t n;        /* periods per window (MC_SLOW_STEP_PERIODS) */
    int16_t duty_max;  /* PWM_DUTY_MAX: the dead time in duty counts */
    q15_t w_new;       /* MC_SAMPLE_AT: the share of a sample interval the last command acts */
    uint32_t accel;    /* the spin's acceleration, 2^32 a turn per period per period */
    uint32_t step_max; /* its speed limit (MC_ID_SPEED_MAX_RPM), 2^32 a turn per period */
    uint32_t damp;     /* the spin's damping: forced speed per radian of the rotor's swing
                          (MC_ID_DAMP_HZ), 2^32 a turn per period */
    q15_t dt_band;     /* the build's dead-time band (MC_DT_BAND_Q15), Q15 I_FS: until the spin */
    uint16_t band_k;   /* the spin's band from L (mc_id.c note 7): V_bus_FS / (12 V_FS), Q16 */
} mc_id_params_t;

/* What the interrupt summed over one window (MC_SLOW_STEP_PERIODS periods). */
typedef struct {
    int32_t v_d; /* applied voltage on d (the modelled one, mc.c v_hist), sum, Q15 V_FS */
    int32_t i_d; /* measured current on d, sum, Q15 I_FS */
    int32_t i_q; /* ... on q */
    int32_t u_d; /* the current loops' outputs (their voltage in the frame), sums */
    int32_t u_q; /*  */
    int32_t v_q; /* applied voltage on q, sum */
    /* the injection (mc_id.c note 2), on the injected axis: sums of z i_n,
     * z i_n-1, z u_n, z u_o (z the injected wave over the sample interval,
     * +-1 Q15; u_n, u_o the voltages of the last two periods, which act over
     * it), and the same four with w (the wave's sign a quarter cycle
     * earlier) */
    int32_t c[8];
    uint32_t step; /* the forced speed at the window end, angle per period (2^32 a turn) */
} mc_id_win_t;

/* What the interrupt does next, from the window's apply on. */
typedef struct {
    dq_q15_t i_ref;    /* current references (closed loop) */
    q15_t kp;          /* current PIs' Kp mantissa, both axes (0 with ki 0: open loop) */
    uint8_t kp_shift;  /* ... its exponent */
    q15_t ki;          /* ... Ki (and Kc) per period */
    q15_t v_d;         /* open loop: the d voltage (the PI's integral), Q15 V_FS */
    q15_t v_q;         /* ... and the q voltage */
    q15_t inj;         /* injected voltage's amplitude, Q15 V_FS; 0: none */
    uint8_t inj_q;     /* injected on q (else d) */
    uint8_t inj_half;  /* periods per half cycle of the injected square wave */
    int32_t accel;     /* change of the forced speed per period, 2^32 a turn per period */
    int16_t dt_counts; /* dead-time compensation, duty counts (0 while measuring it) */
    q15_t dt_band;     /* ... its linear band, Q15 I_FS, above dt_counts (mc_id.c note 7) */
    bool open_loop;    /* the PI integrals are set to v_d, v_q (and the injection) */
    bool end;          /* the sequence is over: outputs off, STOPPED */
} mc_id_cmd_t;

/* The sequence's state and its results (slow step's; read by
 * mc_identify_result from the main loop once status is final). */
typedef struct {
    const mc_id_params_t *p;
    uint8_t stage;   /* MC_ID_STAGE_* */
    uint8_t error;   /* MC_ID_ERROR_* (mc.h) */
    uint16_t wins;   /* windows in this stage */
    uint8_t sub;     /* the stage's step: level, injection setting, ... */
    uint8_t ok;      /* consecutive settled windows */
    uint8_t tries;   /* R levels measured again (the rotor still swinging) */
    mc_id_cmd_t cmd; /* what the interrupt does now */
    int32_t last;    /* the previous window's value the stage watches */
    int32_t acc[5];  /* the stage's sums over its measuring windows */
    int32_t lo, hi;  /* smallest and largest window value in the measurement */
    q15_t i_dc;      /* RAMP, LD, LQ: the d current reached in open loop */
    /* results, internal units (mc_id.c note 1) */
    int32_t lv[3], li[3]; /* R: sums of v and i over the measuring windows of each level */
    int32_t iq_top;       /* R: the q current's sum at the top level (a cut lead, mc_id.c note 6) */
    int32_t l_c[2][8];    /* Ld, Lq: the injection's sums (mc_id_win_t.c) over the measurement */
    q15_t vbus;           /* the bus while R was measured, Q15 of BOARD_VBUS_FULLSCALE_V */
    int32_t lq_i[2];      /* LQ: sums of the d and q currents (the rotor's angle to d) */
    q15_t inj_set;        /* the injection's amplitude LD found, LQ's start */
    uint8_t lq_half;      /* LQ's half cycle, periods (the rotor's vibration, mc.c) */
    int32_t r_q16;        /* R, Q16 of Z_FS */
    int32_t l_q12;        /* (Ld + Lq) / 2 over Ts, Q12 of Z_FS */
    int32_t l_dq[2];      /* Ld, Lq (the q one as measured, at the rotor's angle) by the
                             difference quotient, the same units (mc_identify_result's
                             fallback where the exact model's solve fails) */
    int32_t dv, di;       /* R = dv / di (Z_FS); the intercept: */
    int32_t v0;           /* the d voltage at zero current, sum over the windows, Q15 V_FS */
    int32_t nwin;         /* windows in each level's sums (the same for all) */
    int32_t m1, m2;       /* mean |back-EMF| at the two speeds, Q15 V_FS x 16 */
    uint32_t x1, x2;      /* the two forced speeds, 2^32 a turn per period */
    /* J: the torque current i (Q15) against the window's acceleration a
     * (ID_A_UNIT = the spin's), fitted over the ramps between the speeds */
    int32_t j_n, j_a, j_aa, j_i, j_ia; /* windows, sums of a, a^2, i, i a */
    int32_t a_prev;                    /* the acceleration that acted over the last window */
    int32_t goal;                      /* the acceleration ramp eases to */
    int32_t ramp;                      /* the spin's acceleration without the damping's */
    int32_t damp;      /* the damping's forced-speed offset now, 2^32 a turn per period */
    int32_t damp_goal; /* ... and the one this window's swing asks */
    int32_t it_lp;     /* sin(load angle)'s low-pass (the swing's mean), Q15 x 64 */
    int32_t ang_f;     /* the swing's angle, low-passed (ID_DAMP_F), rad Q15 x 16 */
} mc_id_t;

/* Starts the sequence (the core is entering MC_STATE_IDENTIFY, offsets
 * calibrated) with the build's parameters (kept by reference); *cmd: the
 * first window's command. */
void mc_id_begin(mc_id_t *id, const mc_id_params_t *p, mc_id_cmd_t *cmd);

/* One window: w the interrupt's sums over it (under the command given by
 * the previous call), vbus the bus at its end (Q15 of
 * BOARD_VBUS_FULLSCALE_V); returns the next command in *cmd. */
void mc_id_window(mc_id_t *id, const mc_id_win_t *w, q15_t vbus, mc_id_cmd_t *cmd);

/* Ends the sequence with an error (a fault or a stop of the core). */
void mc_id_fail(mc_id_t *id, uint8_t error);

/* The spin's dead-time band (mc_id.c note 7), Q15 of I_FS: the PWM ripple's
 * amplitude Vbus / (12 L fpwm) of the inductance measured, ((vbus k) >> 4)
 * / l, held to [dt + 1, 8192] (the slope dt 2^15 / band below 2^15; at
 * most a quarter of I_FS). dt: the dead time compensated, duty counts (a
 * dt below 0 counts as 0); vbus: Q15 of BOARD_VBUS_FULLSCALE_V (below 0
 * counts as 0); l: L / (Ts Z_FS), Q12, > 0; k: p->band_k. */
q15_t mc_id_dt_band(int16_t dt, q15_t vbus, int32_t l, uint16_t k);

/* -ln(a), a = a_q30 / 2^30 in (0, 1], as Q24 (0 for a outside): the
 * inductance's exact discrete model (mc.c mc_identify_result). 64-bit
 * integer arithmetic: for the main loop. */
uint32_t mc_id_neg_ln_q24(uint32_t a_q30);

/* exp(-x), x = x_q24 / 2^24 >= 0, as Q30. */
uint32_t mc_id_exp_neg_q30(uint32_t x_q24);

/* floor((a1 b1 + a2 b2) / 2^s), b1 and b2 in 0..32768, s in 1..16, modulo
 * 2^32 as an int32 (what the int64 expression cast to int32 gives; the
 * callers' results fit). Four 16 x 16 products and 32-bit adds: the slow
 * step's windows carry no 64-bit multiply, whose helper is a loop on the
 * dsPIC (docs/identify.md). */
int32_t mc_id_mac2_shr(int32_t a1, uint16_t b1, int32_t a2, uint16_t b2, uint8_t s);

/* x / d truncated, d > 0: a d below 2^16 by two 32 / 16 hardware divisions
 * (div.ud) instead of the 32 / 32 helper's loop, for the windows' means and
 * ratios (docs/performance.md has what the windows take). */
uint32_t mc_id_udiv(uint32_t x, uint32_t d);

/* floor(a b / 2^32): the high half of the 64-bit product, from four 16 x 16
 * products. */
uint32_t mc_id_mulhi(uint32_t a, uint32_t b);

#endif /* MC_ID_H */
