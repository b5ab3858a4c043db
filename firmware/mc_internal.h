/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* mc_internal.h - the core's pure helpers, exposed for the unit tests (not part of the seam). */
#ifndef MC_INTERNAL_H
#define MC_INTERNAL_H

#include "mc.h"

/*
 * Dead-time correction of one phase, in duty counts: +dt for a current at
 * or above +band (into the motor: during the dead time the low-side diode
 * conducts and the phase sits at the negative rail, so the inverter
 * applies less than commanded), -dt at or below -band, and linear in
 * between: (i * slope) >> 15 (rounded), so the correction does not chatter
 * around a zero crossing. dt: the dead time in use, duty counts
 * (MC_DT_COUNTS, or what the lock measured); band: the linear band, Q15 of
 * BOARD_I_FULLSCALE_A, above dt (MC_DT_BAND_Q15; the identification's
 * spin, one from the inductance it measured: mc_id.c note 7); slope:
 * mc_deadtime_slope(dt, band), below 2^15. i: Q15 of BOARD_I_FULLSCALE_A.
 * Result in [-dt, dt].
 */
Q15_INLINE int16_t mc_deadtime_counts(q15_t i, int16_t dt, q15_t slope, q15_t band)
{
    if (i >= band) {
        return dt;
    }
    if (i <= (q15_t)(-band)) {
        return (int16_t)(-dt);
    }
    return q15_mul(i, slope); /* round(i slope / 2^15), |.| < dt + 1 */
}

/* The in-band slope of a dead time dt (duty counts, 0 <= dt < band) and a
 * band (Q15 of BOARD_I_FULLSCALE_A, > 0): dt * 2^15 / band, rounded; below
 * 2^15. */
Q15_INLINE q15_t mc_deadtime_slope(int16_t dt, q15_t band)
{
    return q15_dsp_divsd(((int32_t)dt << 15) + band / 2, band);
}

/*
 * The dead time (duty counts) a lock's measurement gives (mc.c note 4):
 * dt + dt * avg / dv, within [MC_DT_COUNTS_MIN, MC_DT_COUNTS_MAX]. dt: the
 * dead time in use while measuring; avg: the mean of 4 u2 - 3 u1 (u1, u2:
 * the estimator's voltage on the lock's axis at the lock current and at
 * 3/4 of it, Q15 of V_FS), the voltage the model missed; dv: the model's
 * dead-time voltage on that axis at dt, Q15 of V_FS (> 0, else dt is kept).
 */
int16_t mc_deadtime_from_lock(int16_t dt, int32_t avg, q15_t dv);

/*
 * The alpha/beta voltage three phase duties produce on a bus vbus:
 *   v_alpha = (2 da - db - dc) / (3 PWM_DUTY_MAX) * Vbus / V_FS
 *   v_beta  = (db - dc) / (sqrt(3) PWM_DUTY_MAX) * Vbus / V_FS
 * with V_FS = BOARD_VBUS_NOMINAL_V / sqrt(3) (MC_VOLTAGE_FULLSCALE_V).
 * duty: effective duty counts, -PWM_DUTY_MAX/2..3 PWM_DUTY_MAX/2 (they may
 * lie outside 0..PWM_DUTY_MAX by the predicted dead-time loss); vbus: Q15 of
 * BOARD_VBUS_FULLSCALE_V (negative counts as 0). Output Q15 of V_FS,
 * saturated (the hexagon corners exceed the circle by 2/sqrt(3)).
 * Scaling: v_alpha = (2 da - db - dc) vbus MC_VAPP_K / 2^25 and v_beta =
 * (db - dc) vbus MC_VAPP_KB / 2^24, each one triple product on the
 * accumulator (q15_dsp_mul3_r), rounded to nearest; the duty combinations
 * are saturated to 16 bits first (beyond that the voltage saturates anyway
 * at any bus above PWM_DUTY_MAX / 32767 of the nominal). Error <= 0.5 LSB
 * plus the constants' rounding (test_mc.c).
 */
Q15_INLINE ab_q15_t mc_duty_to_voltage(const int16_t duty[3], q15_t vbus)
{
    ab_q15_t v;
    q15_t vb = (vbus < 0) ? 0 : vbus;
    q15_t na = q15_dsp_dbl_sub2_sat(duty[0], duty[1], duty[2]);
    q15_t nb = q15_dsp_sub_sat(duty[1], duty[2]);
    v.alpha = q15_dsp_mul3_r(na, vb, MC_VAPP_K, (int8_t)(25 - 30));
    v.beta = q15_dsp_mul3_r(nb, vb, MC_VAPP_KB, (int8_t)(24 - 30));
    return v;
}

/* mc_pot_to_speed and mc_pot_to_torque: mc.h (the application maps the pot
 * as the core does). */

/* The braking current the speed loop may ask (Q15 current) with the bus
 * at vbus (Q15 of BOARD_VBUS_FULLSCALE_V): iq_max up to MC_VBUS_REGEN_Q15,
 * then falling linearly to 0 at MC_VBUS_REGEN_Q15 + MC_VBUS_REGEN_BAND_Q15
 * and above (UserParms.h MC_VBUS_REGEN_V). iq_max >= 0. */
q15_t mc_regen_limit(q15_t iq_max, q15_t vbus);

/* The speed a STOP releases the switches below (Q15 speed, >= 0) with the
 * bus at vbus (Q15): its line-to-line back-EMF peak is
 * MC_STOP_RELEASE_FRACTION of the bus. */
Q15_INLINE q15_t mc_release_speed(q15_t vbus)
{
    int32_t w = ((int32_t)((vbus < 0) ? 0 : vbus) * MC_STOP_RELEASE_K) >> 12;
    return (q15_t)((w > 32767) ? 32767 : w);
}

/* Inputs of one stall check (one speed-loop run in CLOSED_LOOP). */
typedef struct {
    q15_t speed;      /* estimated speed, Q15 of MC_SPEED_FULLSCALE_RPM */
    q15_t emf_ratio;  /* estimator back-EMF / expected at that speed, Q12 (4096 = 1) */
    bool fw_active;   /* the speed reference is in field weakening */
    q15_t speed_err;  /* speed reference - estimated speed, Q15 speed */
    int8_t saturated; /* the speed PI output at its upper limit +1, at its lower -1, else 0 */
} mc_stall_in_t;

/*
 * The stall / loss-of-synchronisation detector. s->cnt[0..2] count
 * consecutive runs of each condition (reset when it clears):
 *   [0] |speed| < MC_STALL_SPEED_Q15                       -> STALL_SPEED
 *   [1] emf_ratio > MC_STALL_BEMF_HI_Q12, or, outside field weakening,
 *       emf_ratio < MC_STALL_BEMF_LO_Q12                   -> STALL_BEMF
 *   [2] |speed_err| > MC_STALL_SPEED_ERR_Q15 and saturated -> STALL_TRACK
 * [0] and [1] trip at MC_STALL_TICKS consecutive runs, [2] at
 * MC_STALL_TRACK_TICKS. A limit cycle of the speed loop escapes [2]: its
 * error passes through zero twice a cycle. So the reversals of the speed PI
 * between its limits are counted too (saturated at the other limit than
 * the last time it was at one), each within MC_SWING_GAP_TICKS of the one
 * before, and MC_SWING_FLIPS of them in a row -> SPEED_UNSTABLE. Returns
 * the fault code, MC_FAULT_NONE if none. A zeroed *s is the start.
 */
uint16_t mc_stall_check(mc_stall_t *s, const mc_stall_in_t *in);

#endif /* MC_INTERNAL_H */
