/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* mc_parts.h - what the core's files share: constants, small inline helpers, their entry points.
 */
#ifndef MC_PARTS_H
#define MC_PARTS_H

/*
 * The core is one object (mc.h) in files by job, so an image compiles each
 * for what it needs (docs/performance.md, "Code size"):
 *   mc.c         the 50 us path: mc_step_control and mc_step_finish, their
 *                pieces inline (one translation unit, as fast as it gets);
 *   mc_state.c   the changes of state: once per transition, called from it;
 *   mc_slow.c    the slow step (mc_slow_step): speed ramp and PI, field
 *                weakening, stall check, the open loop's torque current;
 *   mc_sensor.c  the current-sensor check's judgement (slow step, note 5);
 *   mc_dtm.c     the lock's dead-time measurement (slow step, note 4);
 *   mc_api.c     mc_init, the mailbox, mc_status (the main loop's calls);
 *   mc_id_isr.c  the identification's interrupt side (MC_IDENTIFY);
 *   mc_id_units.c its results in engineering units (the main loop's);
 *   mc_id.c      the identification's sequence (the slow step's).
 * "note N" is mc.h's notes 1-4 or mc.c's notes 1-5, as each file says.
 * Not part of the seam: nothing outside firmware/mc*.c includes this.
 */

#include "mc.h"
#include "mc_internal.h"

/* ---- constants ---------------------------------------------------------------- */

/* Inverse-Park advance (mc.h note 2): the sample is taken at MC_SAMPLE_AT
 * of period n, the voltage computed from it acts over the whole period n+1,
 * centred (1.5 - MC_SAMPLE_AT) Ts after the sample (0.96 Ts on the MCLV),
 * so it is rotated by that much. In binary angle counts: speed_q15 *
 * 2 (1.5 - a) omega_fs Ts (omega_fs in Hz); open loop: the forced step per
 * period times (1.5 - a). */
#define MC_ADV_PERIODS_ (1.5 - MC_SAMPLE_AT)
#define MC_ADV_K_       (2.0 * MC_ADV_PERIODS_ * MC_OMEGA_FS_HZ * MC_TS_S)
MC_CHECK(MC_SPEED_FULLSCALE_RPM, MC_ADV_K_ < 1.0,
         "the advance at full speed must be < pi (PWM too slow for the speed range)");
#define MC_ADV_K Q15(MC_ADV_K_)
/* The estimator's angle is one sample old when the current loops use it
 * (mc.h note 2): one period of the estimated speed, speed_q15 * 2
 * omega_fs Ts angle counts. */
#define MC_PRED_K_ (2.0 * MC_OMEGA_FS_HZ * MC_TS_S)
MC_CHECK(MC_SPEED_FULLSCALE_RPM, MC_PRED_K_ < 1.0,
         "one period at full speed must be < pi (PWM too slow for the speed range)");
#define MC_PRED_K      Q15(MC_PRED_K_)
#define MC_ADV_PERIODS Q15(MC_ADV_PERIODS_)

/* One period of an estimated speed (Q15), angle counts: the interrupt's
 * prediction (mc_set_advance) and the slow step's damping compare with it. */
Q15_INLINE int16_t mc_pred_counts(q15_t omega)
{
    return q15_mul(omega, MC_PRED_K);
}
/* The open-loop step per period (binary angle counts) must stay below 2^15
 * for the advance's Q15 product: the ramp's end below half the PWM rate. */
MC_CHECK(MOTOR_RAMP_END_RPM, (double)MOTOR_RAMP_END_RPM *MOTOR_POLE_PAIRS / 60.0 * MC_TS_S < 0.5,
         "the ramp's end must be below half the PWM frequency (electrical)");

/* The voltage the current evolved under between the previous sample and
 * this one (mc.h note 2): the duty of period n-1 (computed two steps ago,
 * v_hist[1]) for the part of the interval before the boundary, 1 - a, and
 * the one of period n (computed one step ago, v_hist[0]) for the part
 * after it, a. Weights sum to exactly 1.0, so a steady voltage passes
 * unchanged. */
#define MC_VEST_W_NEW Q15(MC_SAMPLE_AT)
#define MC_VEST_W_OLD ((q15_t)(32768L - (long)MC_VEST_W_NEW))

/* A compiler barrier: the stores before it are not moved after it. Every
 * supported compiler (gcc, clang, XC16's gcc) understands it; the dsPIC
 * executes stores in order. */
#define MC_BARRIER() __asm__ __volatile__("" ::: "memory")

/* sqrt(3) / 2 and -1/2 in Q15, for the phase currents from alpha/beta. */
#define MC_SQRT3_2    Q15(0.86602540378443865)
#define MC_MINUS_HALF Q15(-0.5)

/* ---- small helpers, inline where they are used --------------------------------- */

/* The states that drive the motor, outputs on: LOCK, OPEN_LOOP, CLOSED_LOOP,
 * IDENTIFY (consecutive in MC_STATE_LIST: one unsigned compare). */
Q15_STATIC_ASSERT(MC_STATE_OPEN_LOOP == MC_STATE_LOCK + 1 &&
                      MC_STATE_CLOSED_LOOP == MC_STATE_LOCK + 2 &&
                      MC_STATE_IDENTIFY == MC_STATE_LOCK + 3,
                  "mc_driving needs LOCK, OPEN_LOOP, CLOSED_LOOP, IDENTIFY consecutive");
Q15_INLINE bool mc_driving(mc_state_t s)
{
    return (unsigned)s - (unsigned)MC_STATE_LOCK <=
           (unsigned)MC_STATE_IDENTIFY - (unsigned)MC_STATE_LOCK;
}

/* Id reference with the light-load floor (UserParms.h MC_ID_MIN_A): at
 * least MC_ID_MIN_Q15 - |iq| of negative Id, so the current vector is never
 * shorter than MC_ID_MIN_Q15 / sqrt 2 and the phase currents stay outside
 * the dead-time band, where the inverter's voltage loss depends only on
 * the current's sign and the estimator's applied voltage is exact. Under
 * load (|iq| >= MC_ID_MIN_Q15) it is off and costs no torque. id <= 0
 * (field weakening), |iq| <= 32767: no overflow. */
static inline q15_t mc_id_floor(q15_t id, q15_t iq)
{
    int32_t f = (int32_t)MC_ID_MIN_Q15 - (int32_t)q15_abs_sat(iq); /* > -32768 */
    return ((int32_t)id > -f) ? (q15_t)(-f) : id;
}

/* ---- the estimator, as the core uses it ----------------------------------------- */

/* The drive's estimator (smc.h) through the core: without the drive
 * (MC_DRIVE 0, the commissioning image) there is no estimator, and these
 * are constants and no-ops the compiler drops with the code that uses them.
 * (The core's own paths test MC_DRIVE; these keep the members out of them.) */
#if MC_DRIVE
Q15_INLINE q15_t mc_est_omega(const mc_t *mc)
{
    return smc_omega(&mc->smc);
}
Q15_INLINE angle_q15_t mc_est_theta(const mc_t *mc)
{
    return smc_theta(&mc->smc);
}
Q15_INLINE bool mc_est_valid(const mc_t *mc)
{
    return smc_valid(&mc->smc);
}
Q15_INLINE q15_t mc_est_emf_ratio(const mc_t *mc)
{
    return smc_emf_ratio(&mc->smc);
}
Q15_INLINE q15_t mc_est_emf_amplitude(const mc_t *mc)
{
    return smc_emf_amplitude(&mc->smc);
}
Q15_INLINE void mc_est_update(mc_t *mc, ab_q15_t i, ab_q15_t v)
{
    smc_update(&mc->smc, i, v);
}
#define mc_est_window_end(mc)    smc_window_end(&(mc)->smc)
#define mc_est_apply(mc)         smc_apply(&(mc)->smc)
#define mc_est_reset(mc)         smc_reset(&(mc)->smc)
#define mc_est_preset(mc, omega) smc_preset_speed(&(mc)->smc, omega)
#else
Q15_INLINE q15_t mc_est_omega(const mc_t *mc)
{
    (void)mc;
    return 0;
}
Q15_INLINE angle_q15_t mc_est_theta(const mc_t *mc)
{
    (void)mc;
    return 0;
}
Q15_INLINE bool mc_est_valid(const mc_t *mc)
{
    (void)mc;
    return false;
}
Q15_INLINE q15_t mc_est_emf_ratio(const mc_t *mc)
{
    (void)mc;
    return 0;
}
Q15_INLINE q15_t mc_est_emf_amplitude(const mc_t *mc)
{
    (void)mc;
    return 0;
}
Q15_INLINE void mc_est_update(mc_t *mc, ab_q15_t i, ab_q15_t v)
{
    (void)mc;
    (void)i;
    (void)v;
}
#define mc_est_window_end(mc)    ((void)(mc))
#define mc_est_apply(mc)         ((void)(mc))
#define mc_est_reset(mc)         ((void)(mc))
#define mc_est_preset(mc, omega) ((void)(mc), (void)(omega))
#endif

/* ---- the changes of state (mc_state.c) -------------------------------------------- */

/* s from the next period on, its timer from 0. */
void mc_enter(mc_t *mc, mc_state_t s);
/* Everything the power stage and the loops hold, back to rest. */
void mc_outputs_off(mc_t *mc);
/* FAULT's entry: the cause recorded, the outputs off. */
void mc_enter_fault(mc_t *mc, uint16_t code);
/* A fault raised in any state; in FAULT the first cause stays. */
void mc_fault(mc_t *mc, uint16_t code);
/* CALIBRATE, after coasting for `wait` periods. */
void mc_begin_calibration(mc_t *mc, uint16_t wait);
/* STOPPED, from any state. */
void mc_stop(mc_t *mc);
/* CLOSED_LOOP, from the end of the ramp (mc.c note 1). */
void mc_enter_closed_loop(mc_t *mc);
/* The end of CALIBRATE: the offsets, then LOCK (or IDENTIFY) from the next
 * period, or FAULT OFFSET. The caller prepares the next period's angle
 * when the outputs are to turn on (mc_step_finish). */
void mc_calibrate_end(mc_t *mc);
/* The posted gains into the loops (mc.h note 3). */
void mc_apply_gains(mc_t *mc);
/* CLOSED_LOOP's voltage advance and the angle's prediction from the
 * estimator's speed (mc.c, inline there; a call from the state changes). */
void mc_set_advance(mc_t *mc);

/* ---- the slow step's parts (mc_slow.c, mc_sensor.c, mc_dtm.c) ----------------------- */

/* The slow step's state at mc_init. */
void mc_slow_init(mc_slow_t *sl);

/* The sensor check's state at the start of a run. */
void mc_sensor_reset(mc_sensor_t *s);
/* One window's judgement (mc.c note 5): so->sensor_fault. */
void mc_sensor_window(mc_sensor_t *s, const mc_slow_in_t *si, mc_slow_out_t *so);

/* The dead-time measurement's phases (mc.c note 4). */
enum {
    MC_DTM_ALIGN, /* the lock proper, MC_LOCK_PERIODS */
    MC_DTM_WAIT1, /* at the lock current, until the swing reverses */
    MC_DTM_ACC1,  /* averaging, to a reversal at least MC_DTM_N periods on */
    MC_DTM_SETTLE2,
    MC_DTM_WAIT2, /* at 3/4 of it */
    MC_DTM_ACC2,
    MC_DTM_DONE /* OPEN_LOOP next */
};
/* The measurement's state at the start of a run. */
void mc_dtm_reset(mc_dtm_t *d);
/* LOCK, one window (mc.c note 4): so->lock_iq, and with so->lock_done the
 * measured dead time. */
void mc_dtm_window(mc_dtm_t *d, const mc_slow_in_t *si, mc_slow_out_t *so);

/* ---- the identification's interrupt side (mc_id_isr.c, MC_IDENTIFY) --------------- */

/* The sequence's command into the interrupt's loops. */
void mc_id_apply(mc_t *mc, const mc_id_cmd_t *c);
/* IDENTIFY, after CALIBRATE. */
void mc_enter_identify(mc_t *mc);
/* A run ended, or was ended (error MC_ID_ERROR_*, NONE when it finished):
 * the status, the loops back to the build's gains and dead time. Any state
 * may call it; only a run that is going changes. */
void mc_id_stop(mc_t *mc, uint16_t error);
/* IDENTIFY's work in each period after the duties (mc_step_finish). */
void mc_id_period(mc_t *mc);
/* IDENTIFY, MC_SLOW_APPLY_PERIODS after a window end of this run: the
 * sequence's next command in; true when it was the last (outputs off,
 * STOPPED). */
bool mc_id_take(mc_t *mc);
/* IDENTIFY's window end: its sums into the hand-over (mc_window_end). */
void mc_id_post(mc_t *mc);
/* Whether a START before IDENTIFY is in CALIBRATE. */
bool mc_id_pending(const mc_t *mc);
/* The START of an identification has been taken (from STOPPED): pending
 * when it reached CALIBRATE, else FAILED (the bus out of its window). */
void mc_id_started(mc_t *mc);

#endif /* MC_PARTS_H */
