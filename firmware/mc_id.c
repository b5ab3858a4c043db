/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* mc_id.c - self-commissioning's sequence, one speed-loop window at a time (see mc_id.h). */
#include "mc_id.h"

#include <string.h>

#include "UserParms.h" /* MC_IDENTIFY alone: the sequence reads no profile */
#include "q15_dsp.h"
#include "q15_sqrt.h"

#if MC_IDENTIFY

/*
 * The stages (mc_id.h), each judged on window means (sums over N =
 * MC_SLOW_STEP_PERIODS periods), the frame fixed at 90 degrees (d = beta,
 * q = -alpha) until the spin:
 *
 *   RAMP  open loop: the d voltage grows by 1/32 a window (1/128 past half
 *         the target) from ID_V_START until the current's magnitude reaches
 *         the target p->i_target (or the voltage limit: a motor whose R takes
 *         more than the bus is measured at the current it allows); then
 *         held, trimmed to the target, until the current has settled. The
 *         rotor turns to the current's axis on the way; while it turns
 *         (the d current falls or the q current moves) the voltage is held.
 *   R     still open loop (no current loop before L is known): four d
 *         voltages, the ramp's, a probe 1/16 below it (the slope), and
 *         those for 3/4 and 1/2 of the current; each settled, then its mean
 *         voltage and current over ID_R_WINDOWS windows. R is the slope,
 *         the intercept the inverter's voltage error (note 4). A level the
 *         swinging rotor disturbs is measured again.
 *   LD    at the 1/2 level's voltage, a square wave on d summed into the
 *         open loop's voltage, its amplitude and half period set until the
 *         current swings a quarter of the DC current peak to peak; then L
 *         from ID_L_WINDOWS windows of correlation (note 2).
 *   LQ    the same on q, with a quarter of the current on q as a bias.
 *   SPIN1 the loops closed (gains from L and R, note 3), the dead time
 *         compensated as measured, a third of the current on d turned at an
 *         acceleration eased in over ID_JERK windows (more current while
 *         the load angle passes 45 degrees) until the back-EMF reaches
 *         ID_E1, twice the speed would ask 0.8 of the voltage limit, or
 *         the speed reaches half of p->step_max; HOLD1 holds that speed
 *         and averages the back-EMF's magnitude; SPIN2 accelerates to
 *         twice the speed, HOLD2 averages again; SPIN3 decelerates to the
 *         first speed and SPIN4 to rest at four times the rate. Ke from
 *         the two holds, J from the torque current while accelerating and
 *         decelerating over the same speeds, the rotor's swing damped
 *         throughout (note 5).
 *
 * Every stage has a time limit; every check that fails ends the sequence
 * with an error code (mc.h MC_ID_ERROR_*), the outputs off.
 */

/* The sequence's own timing, in windows (1 ms at the default speed-loop rate). */
#define ID_HALF_MIN         4U /* periods per half of the injected square wave: 2.5 kHz at 20 kHz */
#define ID_HALF_MAX         32U   /* ... at the longest */
#define ID_L_WINDOWS        32U   /* windows of correlation for each L */
#define ID_INJ_WINDOWS_MAX  200U  /* to set the injection's amplitude */
#define ID_SETTLE           4U    /* windows in a row within tolerance: settled */
#define ID_V_SETTLE         32    /* ... a voltage moving less than this (Q15, window mean) */
#define ID_R_SETTLE_MAX     300U  /* windows for a level to settle, or the ramp's rotor to rest */
#define ID_RAMP_WINDOWS_MAX 3000U /* the ramp's windows at most (some 400 at a steady rotor) */
#define ID_R_WINDOWS        100   /* windows each level is measured over */
#define ID_MOVING_TRIES     8     /* levels measured again while the rotor swings */
#define ID_R_BAND_TOL       20    /* the lower slope 1/20 steeper: the band */
#define ID_R_MAX_Q16        (16L * 65536L) /* R at most 16 Z_FS */
#define ID_V_START          ((q15_t)64)    /* the ramp's first voltage: 1/512 of V_FS */
#define ID_E1               ((q15_t)6554)  /* |E| at the first speed: 0.2 V_FS */
#define ID_E_MIN            ((q15_t)655)   /* less at the speed limit: no back-EMF */
#define ID_HOLD_SETTLE      100U           /* windows a hold waits before measuring */
#define ID_HOLD_WINDOWS     200            /* windows it measures, at least ... */
#define ID_HOLD_TURNS       20L            /* ... and electrical turns, ... */
#define ID_HOLD_WINDOWS_MAX 3000           /* ... but no more windows than this */
#define ID_SPIN_WINDOWS_MAX 8000U
#define ID_TWO_PI_Q12       25736L         /* 2 pi x 4096 */
#define ID_WL_MAX           (256L * 4096L) /* w L at most 256 Z_FS (Q12) */
#define ID_SPIN_START       20U            /* windows the loops settle at the spin's start */
#define ID_JERK             32U            /* windows the spin's acceleration takes to change */
#define ID_A_UNIT           32             /* the J fit's unit of acceleration: the spin's = 32 */
#define ID_DAMP_LP          64             /* windows: the low-pass that finds the swing's mean */
#define ID_DAMP_F           8 /* windows: the damping's own low-pass, against the loop's delay */
#define ID_DAMP_ANGLE_MAX   16384 /* the swing's angle the damping acts on, at most 0.5 rad (Q15) */
#define ID_SPIN_SWING_MAX   4096  /* the swing's angle the first speed is taken at, at most (Q15) */
#define ID_DT_BAND_MAX      8192U /* the spin's dead-time band at most: a quarter of I_FS */

#define N_ ((int32_t)id->p->n)

/* ---- helpers ---------------------------------------------------------------------- */

uint32_t mc_id_udiv(uint32_t x, uint32_t d)
{
    uint16_t n, hi, qh;
    if (d > 0xFFFFU) {
        return x / d;
    }
    /* long division in two 32 / 16 steps (div.ud): the first a 16-bit
     * one, whose remainder below d keeps the second's quotient in 16 bits */
    n = (uint16_t)d;
    hi = (uint16_t)(x >> 16);
    qh = (uint16_t)(hi / n);
    hi = (uint16_t)(hi - qh * n);
    return ((uint32_t)qh << 16) | q15_dsp_divud(((uint32_t)hi << 16) | (x & 0xFFFFU), n);
}

uint32_t mc_id_mulhi(uint32_t a, uint32_t b)
{
    uint16_t al = (uint16_t)a, ah = (uint16_t)(a >> 16);
    uint16_t bl = (uint16_t)b, bh = (uint16_t)(b >> 16);
    uint32_t lh = (uint32_t)al * bh, hl = (uint32_t)ah * bl;
    /* the carry out of the low 32 bits: three terms below 2^16 each */
    uint32_t mid = (((uint32_t)al * bl) >> 16) + (lh & 0xFFFFU) + (hl & 0xFFFFU);
    return (uint32_t)ah * bh + (lh >> 16) + (hl >> 16) + (mid >> 16);
}

/* round(n 2^q / d), d > 0: n is shifted left as far as it goes, d right
 * for the rest, so the quotient comes out of 32-bit arithmetic with at least
 * the significant bits d keeps (the callers' d keep 15 or more). */
static int32_t id_ratio(int32_t n, int32_t d, uint8_t q)
{
    bool neg = n < 0;
    uint32_t un = neg ? (uint32_t)0 - (uint32_t)n : (uint32_t)n;
    uint32_t ud = (uint32_t)d;
    uint32_t r;
    while (q > 0U && un < (uint32_t)0x40000000L) {
        un <<= 1;
        q--;
    }
    ud >>= q;
    if (ud == 0U) {
        return neg ? -INT32_MAX : INT32_MAX;
    }
    r = mc_id_udiv(un + ud / 2U, ud);
    if (r > (uint32_t)INT32_MAX) {
        r = (uint32_t)INT32_MAX;
    }
    return neg ? -(int32_t)r : (int32_t)r;
}

/* A 32-bit pattern as the int32 it encodes (two's complement), without the
 * implementation-defined conversion. */
static int32_t id_s32(uint32_t r)
{
    return (r >= 0x80000000UL) ? (int32_t)(r - 0x80000000UL) - INT32_MAX - 1 : (int32_t)r;
}

int32_t mc_id_mac2_shr(int32_t a1, uint16_t b1, int32_t a2, uint16_t b2, uint8_t s)
{
    /* a = h 2^16 + l (h signed, l = 0..65535): a b = h b 2^16 + l b, and
     * floor((H 2^16 + L) / 2^s) = H 2^(16 - s) + floor(L / 2^s) exactly,
     * H = h1 b1 + h2 b2 (|H| <= 2^31 - 2^16), L = l1 b1 + l2 b2 < 2^32. */
    int16_t h1 = (int16_t)(uint16_t)((uint32_t)a1 >> 16);
    int16_t h2 = (int16_t)(uint16_t)((uint32_t)a2 >> 16);
    uint32_t l = (uint32_t)(uint16_t)a1 * b1 + (uint32_t)(uint16_t)a2 * b2;
    int32_t h = (int32_t)h1 * (int32_t)b1 + (int32_t)h2 * (int32_t)b2;
    return id_s32(((uint32_t)h << (16U - s)) + (l >> s));
}

static int32_t id_abs(int32_t x)
{
    return (x < 0) ? -x : x;
}

/* x / d truncated toward zero, d > 0 (a 16-bit d takes mc_id_udiv's
 * hardware divisions). */
static int32_t id_sdiv(int32_t x, int32_t d)
{
    uint32_t q = mc_id_udiv((x < 0) ? (uint32_t)0 - (uint32_t)x : (uint32_t)x, (uint32_t)d);
    return (x < 0) ? -(int32_t)q : (int32_t)q;
}

/* floor(a b / 2^s), s in 1..16, |a| < 2^31, the result within int32: the
 * product is the same with both signs turned, which mc_id_mac2_shr's
 * b >= 0 takes. */
static int32_t id_mul_shr(int32_t a, int16_t b, uint8_t s)
{
    return (b < 0) ? mc_id_mac2_shr(-a, (uint16_t)(-(int32_t)b), 0, 0U, s)
                   : mc_id_mac2_shr(a, (uint16_t)b, 0, 0U, s);
}

/* The window mean of a sum over the window's periods, rounded half away
 * from zero and held to Q15: one 32 / 16 division where it fits, as the
 * quotient below 2^15 does. */
static q15_t id_mean(const mc_id_t *id, int32_t sum)
{
    uint32_t u = ((sum < 0) ? (uint32_t)0 - (uint32_t)sum : (uint32_t)sum) + id->p->n / 2U;
    int32_t m = (u >= (uint32_t)id->p->n << 15) ? 32768 : (int32_t)q15_dsp_divud(u, id->p->n);
    return q15_sat((sum < 0) ? -m : m);
}

/* The PI gains for a loop crossing over at p->wc_ts (wc Ts, Q15): Kp = L wc
 * as a Q15 mantissa and a shift, Ki = Kp wz Ts (wz the PI's zero: R / L when
 * R is known, else wc / 8). l: L / (Ts Z_FS), Q12; r: R / Z_FS, Q16 (< 0:
 * unknown). */
static void id_gains(const mc_id_t *id, mc_id_cmd_t *c, int32_t l, int32_t r)
{
    /* Kp = l wcTs / 2^12 in Z_FS units; in Q15: l wcTs / 2^12 */
    int32_t kp = mc_id_mac2_shr(l, (uint16_t)id->p->wc_ts, 0, 0U, 12U); /* Q15, may exceed 1 */
    uint8_t sh = 0;
    int32_t ki;
    while (kp > 32767L && sh < 7U) {
        kp = (kp + 1) >> 1;
        sh++;
    }
    c->kp = q15_sat(kp);
    c->kp_shift = sh;
    if (r >= 0) {
        ki = mc_id_mac2_shr(r, (uint16_t)id->p->wc_ts, 0, 0U, 16U); /* R wc Ts: Q15 */
    } else {
        ki = (int32_t)(((int64_t)l * id->p->wc_ts * id->p->wc_ts) >> (12 + 15 + 3));
    }
    c->ki = (q15_t)((ki < 1) ? 1 : (ki > 32767L) ? 32767L : ki);
}

static void id_stage(mc_id_t *id, uint8_t stage)
{
    uint8_t k;
    id->stage = stage;
    id->wins = 0U;
    id->sub = 0U;
    id->ok = 0U;
    id->last = 0;
    for (k = 0; k < 5U; k++) {
        id->acc[k] = 0;
    }
    id->lo = INT32_MAX;
    id->hi = INT32_MIN;
}

uint32_t mc_id_neg_ln_q24(uint32_t a_q30)
{
    /* -ln a = k ln 2 - ln m, a = m 2^-k with m in [1/2, 1]; -ln m = 2 atanh y,
     * y = (1 - m) / (1 + m) <= 1/3: the series y + y^3/3 + ... (Q30 terms,
     * y^2 <= 1/9: twelve terms reach below 2^-30) */
    int64_t acc = 0, y, y2, t;
    uint8_t k;
    if (a_q30 == 0U || a_q30 > ((uint32_t)1 << 30)) {
        return 0U;
    }
    while (a_q30 < ((uint32_t)1 << 29)) {
        a_q30 <<= 1;
        acc += 744261118; /* ln 2, Q30 */
    }
    y = (((int64_t)1 << 30) - a_q30) * ((int64_t)1 << 30) / (((int64_t)1 << 30) + a_q30);
    y2 = (y * y) >> 30;
    t = y;
    for (k = 1; k < 25U && t != 0; k = (uint8_t)(k + 2U)) {
        acc += 2 * t / k;
        t = (t * y2) >> 30;
    }
    return (uint32_t)(acc >> 6); /* Q24 */
}

uint32_t mc_id_exp_neg_q30(uint32_t x_q24)
{
    /* e^-x = 2^-k e^-r, r = x - k ln 2 in [0, ln 2): the series 1 - r + r^2/2 - ... */
    int64_t r = (int64_t)x_q24 << 6, t = (int64_t)1 << 30, acc = 0; /* Q30 */
    uint8_t k = 0, n;
    while (r >= 744261118) { /* ln 2, Q30 */
        if (++k > 30U) {
            return 0U; /* below 2^-30 */
        }
        r -= 744261118;
    }
    for (n = 1; n < 16U && t != 0; n++) {
        acc += t;
        t = -(t * r >> 30) / n;
    }
    return (uint32_t)(acc >> k);
}

void mc_id_fail(mc_id_t *id, uint8_t error)
{
    if (id->stage != MC_ID_STAGE_DONE && id->stage != MC_ID_STAGE_FAILED) {
        id->error = error;
        id->stage = MC_ID_STAGE_FAILED;
    }
    id->cmd.end = true;
}

/* Settled: |x - the previous window's x| <= tol for ID_SETTLE windows in a row. */
static bool id_settled(mc_id_t *id, int32_t x, int32_t tol)
{
    if (id_abs(x - id->last) <= tol) {
        if (id->ok < 255U) {
            id->ok++;
        }
    } else {
        id->ok = 0U;
    }
    id->last = x;
    return id->ok >= ID_SETTLE;
}

static void id_track(mc_id_t *id, int32_t x)
{
    if (x < id->lo) {
        id->lo = x;
    }
    if (x > id->hi) {
        id->hi = x;
    }
}

void mc_id_begin(mc_id_t *id, const mc_id_params_t *p, mc_id_cmd_t *cmd)
{
    /* every sum, result and command at zero (MC_ID_ERROR_NONE, no current,
     * no injection, no acceleration, no dead-time compensation), then
     * what is not */
    memset(id, 0, sizeof *id);
    id->p = p;
    id->r_q16 = -1; /* R unknown */
    id->cmd.v_d = ID_V_START;
    id->cmd.dt_band = p->dt_band; /* the build's band until the spin (note 7) */
    id->cmd.inj_half = ID_HALF_MIN;
    id->cmd.open_loop = true;
    id_stage(id, MC_ID_STAGE_RAMP);
    *cmd = id->cmd;
}

q15_t mc_id_dt_band(int16_t dt, q15_t vbus, int32_t l, uint16_t k)
{
    /* vbus k < 2^31; >> 4: Q15 x Q16 / Q12 -> Q15 */
    uint32_t n = ((uint32_t)((vbus > 0) ? vbus : 0) * k) >> 4;
    uint32_t d = (uint32_t)l;
    int32_t lo = (dt > 0) ? (int32_t)dt + 1 : 1;
    int32_t b;
    /* one 32 / 16 division (div.ud): an l past 16 bits loses its low bits
     * with n's (the quotient, below 2^11 there, by less than 2^-15 of it) */
    while (d > 0xFFFFU) {
        d >>= 1;
        n >>= 1;
    }
    b = (n >= (uint32_t)ID_DT_BAND_MAX * d) ? (int32_t)ID_DT_BAND_MAX
                                            : (int32_t)q15_dsp_divud(n, (uint16_t)d);
    return (q15_t)((b < lo) ? lo : b);
}

/* ---- RAMP ------------------------------------------------------------------------------ */

static void id_ramp(mc_id_t *id, const mc_id_win_t *w)
{
    mc_id_cmd_t *c = &id->cmd;
    q15_t i = id_mean(id, w->i_d);
    q15_t iq = id_mean(id, w->i_q);
    /* the current's magnitude is what the target limits: with a lead cut
     * the d current is half of it (note 6) */
    uint32_t m = q15_isqrt_u32((uint32_t)((int32_t)i * i) + (uint32_t)((int32_t)iq * iq));
    q15_t im = q15_sat((int32_t)m); /* m <= 46341 */
    if (id->wins > ID_RAMP_WINDOWS_MAX) {
        mc_id_fail(id, MC_ID_ERROR_TIMEOUT);
        return;
    }
    if (id->sub == 0U) { /* raising */
        if (im >= id->p->i_target) {
            id->sub = 1U;
            id->ok = 0U;
        } else if (c->v_d >= id->p->v_max) {
            /* the most the bus gives: measure at the current it drives */
            if (im < id->p->i_min) {
                mc_id_fail(id, (im < id->p->i_min / 4) ? MC_ID_ERROR_OPEN_CIRCUIT
                                                       : MC_ID_ERROR_TOO_SMALL);
                return;
            }
            id->sub = 1U;
            id->ok = 0U;
        } else if (i < id->last - id->p->i_target / 64 ||
                   id_abs(iq - id->acc[1]) > i / 32 + id->p->i_target / 64) {
            /* the rotor turning to the current's axis: its back-EMF pulls
             * the current off d and down and moves it on q; the voltage
             * held until it rests, else the current overshoots as it stops
             * (a rotor starting near 180 degrees swings through at speed) */
            if (++id->acc[0] > (int32_t)ID_R_SETTLE_MAX) {
                mc_id_fail(id, MC_ID_ERROR_ROTOR_MOVING);
                return;
            }
        } else {
            /* 1/32 a window, 1/128 past half the target: the current lags by
             * L / R, up to tens of ms, and the target is passed by that lag
             * times the rate */
            int32_t v =
                (int32_t)c->v_d + (int32_t)c->v_d / ((im < id->p->i_target / 2) ? 32 : 128) + 1;
            c->v_d = (q15_t)((v > id->p->v_max) ? id->p->v_max : v);
        }
        id->last = i;
        id->acc[1] = iq;
        return;
    }
    if (id_settled(id, i, id->p->i_target / 64)) {
        if (id->sub < 3U && im > id->p->i_target + id->p->i_target / 8) {
            /* overshot while the current lagged the voltage: trimmed */
            c->v_d = (q15_t)id_ratio((int32_t)c->v_d * (int32_t)id->p->i_target, im, 0);
            id->sub++;
            id->ok = 0U;
            return;
        }
        if (i < id->p->i_min) {
            mc_id_fail(id, MC_ID_ERROR_TOO_SMALL);
            return;
        }
        id->i_dc = i;
        id_stage(id, MC_ID_STAGE_R);
    }
}

/* ---- LD, LQ (note 2) ----------------------------------------------------------------------- */

/* L of an axis over Ts, Q12 of Z_FS, by the difference quotient (note 2):
 * L di = Ts (u - R i), summed with z; for the spin's gains and back-EMF
 * (mc_identify_result has the exact model). */
static int32_t id_l_trap(const mc_id_t *id, uint8_t ax)
{
    const int32_t *c = id->l_c[ax];
    int32_t zm = c[0] / 2 + c[1] / 2;
    /* the interval's voltage: the two commands weighted as they act, 0.54 / 0.46 (Q15) */
    int32_t zu =
        mc_id_mac2_shr(c[2], (uint16_t)id->p->w_new, c[3], (uint16_t)(32768 - id->p->w_new), 15U);
    /* zm R: R = rh 2^16 + rl (R >= 0, at most ID_R_MAX_Q16), zm rh exact */
    uint32_t zr = (uint32_t)zm * (uint32_t)((uint32_t)id->r_q16 >> 16) +
                  (uint32_t)mc_id_mac2_shr(zm, (uint16_t)id->r_q16, 0, 0U, 16U);
    return id_ratio(id_s32((uint32_t)zu - zr), c[0] - c[1], 12);
}

static void id_inductance(mc_id_t *id, const mc_id_win_t *w)
{
    mc_id_cmd_t *c = &id->cmd;
    uint8_t ax = c->inj_q, k;
    /* peak-to-peak swing: each half cycle adds about one swing to |sum z di| */
    int32_t swing = id_abs(w->c[0] - w->c[1]) * (int32_t)c->inj_half / N_;
    int32_t target = id->i_dc / 4;
    if (c->inj == 0) { /* the DC currents settled first (LQ: the rotor turns to its bias) */
        if (id_settled(id, ax ? w->i_q : w->i_d, id->p->i_target / 128 * N_)) {
            c->inj = (q15_t)((id->inj_set != 0) ? id->inj_set : c->v_d / 4 + 1);
        } else if (id->wins > ID_R_SETTLE_MAX) {
            mc_id_fail(id, MC_ID_ERROR_TIMEOUT);
        }
        return;
    }
    if (id->sub == 0U) { /* the window after a change: its transient */
        id->sub = 1U;
        return;
    }
    if (id->sub == 1U) { /* setting the amplitude */
        int32_t inj = c->inj;
        /* the DC voltage and the injection below 0.8 of the limit: a phase
         * clipped at 0 or 100 % loses its dead time in that half only,
         * which the correlation would take for inductance */
        int32_t room = (int32_t)id->p->v_max * 8 / 7 - id_abs(c->v_d) - id_abs(c->v_q);
        int32_t most = (room < id->p->inj_max) ? room : id->p->inj_max;
        if (swing < target - target / 4 || swing > target + target / 4) {
            if (swing < target / 4) {
                inj *= 4;
            } else {
                inj = id_ratio(inj * target, swing, 0);
            }
            if (inj > most) {
                inj = most;
                if (c->inj >= most) { /* at its largest: a longer half cycle */
                    if (c->inj_half >= ID_HALF_MAX) {
                        /* the swing it gives, if a quarter of the aim: measured */
                        if (swing >= target / 4) {
                            id->sub = 2U;
                            return;
                        }
                        /* LQ, where LD reached its aim: q (alpha, phase A's
                         * current) is no inductance but a cut lead (note 6) */
                        mc_id_fail(id, (swing < target / 16 || ax != 0U)
                                           ? MC_ID_ERROR_OPEN_PHASE
                                           : MC_ID_ERROR_OUT_OF_RANGE);
                        return;
                    }
                    c->inj_half = (uint8_t)(c->inj_half * 2U);
                }
            }
            c->inj = (q15_t)((inj < 1) ? 1 : inj);
            id->sub = 0U;
            if (id->wins > ID_INJ_WINDOWS_MAX) {
                mc_id_fail(id, MC_ID_ERROR_TIMEOUT);
            }
            return;
        }
        id->sub = 2U; /* in range: measure from the next window */
        return;
    }
    for (k = 0; k < 8U; k++) {
        id->l_c[ax][k] += w->c[k];
    }
    id->acc[3] += w->i_d;
    id->acc[4] += w->i_q;
    if (++id->sub < (uint8_t)(2U + ID_L_WINDOWS)) {
        return;
    }
    /* q is -alpha, the interrupt sums alpha: one sign for all eight */
    if (id->l_c[ax][2] < 0) {
        for (k = 0; k < 8U; k++) {
            id->l_c[ax][k] = -id->l_c[ax][k];
        }
    }
    if (ax == 0U) {
        /* LQ with a quarter of the current on q as well, so that phase A's
         * current does not cross zero under the injection (note 2): the
         * rotor turns by atan(1/4) to the current, the correction for which
         * is in the result (mc.c mc_identify_result). Its voltage: R i and,
         * of the inverter's error, Vd 2/3 = v0 / sqrt(3) (Q15 18919) */
        int32_t v0 = id_sdiv(id->v0, ID_R_WINDOWS * N_);
        id->inj_set = c->inj;
        c->inj = 0;
        c->inj_q = 1U;
        c->v_q = q15_sat(id_mul_shr(id->r_q16, (int16_t)(id->i_dc / 4), 16U) +
                         (int32_t)((v0 * 18919L) >> 15));
        id_stage(id, MC_ID_STAGE_LQ);
        return;
    }
    id->lq_i[0] = id->acc[3];
    id->lq_i[1] = id->acc[4];
    id->lq_half = c->inj_half;
    /* both: L for the gains and the spin's back-EMF (note 2): the R term
     * taken off, Lq corrected for the rotor's angle to the current */
    {
        int32_t ld = id_l_trap(id, 0U), lq = id_l_trap(id, 1U);
        id->l_dq[0] = ld;
        id->l_dq[1] = lq;
        {
            /* Lq cos^2 + Ld sin^2 was measured: Lq = lq + (lq - ld) q^2 / d^2,
             * with (q / d)^2 in Q15 from one 32-bit ratio (q is a quarter of
             * d by design; a q as large as d is no such measurement and
             * left uncorrected, as is a d of 0) */
            int32_t d = id_abs(id->lq_i[0]), q = id_abs(id->lq_i[1]);
            if (d > 0 && q < d) {
                int32_t t = id_ratio(q, d, 15); /* q / d, Q15, < 2^15 */
                uint16_t rho = (uint16_t)(((uint32_t)t * (uint32_t)t + 16384U) >> 15);
                int32_t dl = id_s32((uint32_t)lq - (uint32_t)ld);
                lq = id_s32((uint32_t)lq + (uint32_t)mc_id_mac2_shr(dl, rho, 0, 0U, 15U));
            }
        }
        if (ld <= 0 || lq <= 0) {
            mc_id_fail(id, MC_ID_ERROR_OUT_OF_RANGE);
            return;
        }
        id->l_q12 = (ld + lq) / 2;
        /* the spin: the loops closed with the PI's zero on R / L (note 3),
         * the dead time compensated as measured, a third of the current */
        c->inj = 0;
        c->open_loop = false;
        c->v_q = 0;
        id_gains(id, c, id->l_q12, id->r_q16);
        /* Vd = sqrt(3)/2 v0 = v0 / 32768 Vnom / 2 volts, in duty counts of the bus */
        c->dt_counts =
            (int16_t)((id_sdiv(id->v0, ID_R_WINDOWS * N_) * id->p->duty_max + 32768L) / 65536L);
        c->i_ref.d = (q15_t)(id->i_dc / 3);
        c->i_ref.q = 0;
        id->goal = (int32_t)id->p->accel;
        id_stage(id, MC_ID_STAGE_SPIN1);
    }
}

/* ---- R (note 4) ---------------------------------------------------------------------------- */

/* Open loop at 90 degrees, four levels of d voltage, each settled and then
 * measured over ID_R_WINDOWS windows: the ramp's (the target current), a
 * probe 1/16 below it (the slope, for the next two), and the voltages for
 * 3/4 and 1/2 of the current. */
static void id_resistance(mc_id_t *id, const mc_id_win_t *w)
{
    mc_id_cmd_t *c = &id->cmd;
    uint8_t lev = (uint8_t)(id->sub >> 1);
    if ((id->sub & 1U) == 0U) { /* settling */
        if (id_settled(id, w->i_d, id->p->i_target / 128 * N_)) {
            id->sub++;
            id->acc[0] = 0;
            id->acc[1] = 0;
            id->acc[2] = 0;
            id->acc[3] = 0;
            id->lo = INT32_MAX;
            id->hi = INT32_MIN;
        } else if (id->wins > ID_R_SETTLE_MAX * (uint16_t)(lev + 1U + id->tries)) {
            mc_id_fail(id, MC_ID_ERROR_TIMEOUT);
        }
        return;
    }
    id->acc[0] += w->v_d;
    id->acc[1] += w->i_d;
    id->acc[3] += w->i_q;
    id->acc[2]++;
    id_track(id, w->i_q);
    if (id->acc[2] < ID_R_WINDOWS) {
        return;
    }
    /* a rotor that turns drives a current on q through R by its back-EMF:
     * still swinging from its alignment (the short circuit of q damps it),
     * the level is measured again, up to ID_MOVING_TRIES times */
    if (id->hi - id->lo > (int32_t)id->p->i_target / 16 * N_) {
        if (++id->tries > ID_MOVING_TRIES) {
            mc_id_fail(id, MC_ID_ERROR_ROTOR_MOVING);
        } else {
            id->sub--;
            id->ok = 0U;
        }
        return;
    }
    id->lv[lev < 2U ? 0U : lev - 1U] = id->acc[0];
    id->li[lev < 2U ? 0U : lev - 1U] = id->acc[1];
    if (lev == 0U) { /* the top level, kept in [1] while the probe runs */
        id->lv[1] = id->acc[0];
        id->li[1] = id->acc[1];
        id->iq_top = id->acc[3];
        c->v_d = (q15_t)(c->v_d - c->v_d / 16);
        id->sub++;
        id->ok = 0U;
        return;
    }
    if (lev == 1U) {
        /* slope from the top and the probe, Q16 of Z_FS, then 3/4 of the top current */
        int32_t dvp = id->lv[1] - id->acc[0], dip = id->li[1] - id->acc[1];
        if (dip <= 0 || dvp <= 0) {
            mc_id_fail(id, MC_ID_ERROR_OUT_OF_RANGE);
            return;
        }
        id->lv[0] = id->lv[1];
        id->li[0] = id->li[1];
        id->r_q16 = id_ratio(dvp, dip, 16);
    }
    if (lev < 3U) {
        /* the voltage for 3/4 (then 1/2) of the top current: v_top - R (i_top - i),
         * i_top - i a quarter (then a half) of the top mean: within int16 */
        int32_t di = id_sdiv(id->li[0] / ((lev == 1U) ? 4 : 2), ID_R_WINDOWS * N_);
        c->v_d = q15_sat(id_sdiv(id->lv[0], ID_R_WINDOWS * N_) -
                         id_mul_shr(id->r_q16, (int16_t)di, 16U));
        id->sub++;
        id->ok = 0U;
        return;
    }
    {
        /* R from the outer levels (the top, 1/2), unless the middle one says
         * the lowest is in the dead-time band (note 4): then from the upper two */
        int32_t dv = id->lv[0] - id->lv[2], di = id->li[0] - id->li[2];
        int32_t dvm = id->lv[1] - id->lv[2], dim = id->li[1] - id->li[2];
        int32_t dvu = id->lv[0] - id->lv[1], diu = id->li[0] - id->li[1];
        if (di < id->p->i_min * N_ * ID_R_WINDOWS / 4 || dv <= 0 || dim <= 0 || diu <= 0) {
            mc_id_fail(id, (dv <= 0) ? MC_ID_ERROR_OUT_OF_RANGE : MC_ID_ERROR_TOO_SMALL);
            return;
        }
        /* a d voltage that drives current on q in proportion: a cut lead (note 6) */
        if (2 * id_abs(id->iq_top - id->acc[3]) > di) {
            mc_id_fail(id, MC_ID_ERROR_OPEN_PHASE);
            return;
        }
        if (id_ratio(dvm, dim, 16) - id_ratio(dvu, diu, 16) >
            id_ratio(dvu, diu, 16) / ID_R_BAND_TOL) {
            dv = dvu; /* the lower half steeper: its lowest level in the band */
            di = diu;
        }
        id->dv = dv;
        id->di = di;
        id->r_q16 = id_ratio(dv, di, 16);
        id->nwin = ID_R_WINDOWS;
        if (id->r_q16 > ID_R_MAX_Q16) {
            mc_id_fail(id, MC_ID_ERROR_OUT_OF_RANGE);
            return;
        }
        /* v at zero current from the top level: v0 = v_top - R i_top (sums) */
        id->v0 = id->lv[0] - (int32_t)(((int64_t)id->r_q16 * id->li[0]) >> 16);
        /* the inductances at the lowest level's current (half the top's):
         * out of the band, and room for the injection under the limit */
        c->v_d = q15_sat(id_sdiv(id->lv[2], ID_R_WINDOWS * N_));
        id_stage(id, MC_ID_STAGE_LD);
    }
}

/* ---- the spin (note 5) ---------------------------------------------------------------------- */

/* w L in Z_FS units, Q12, for a forced speed of step (2^32 a turn per
 * period) and l = L / (Ts Z_FS) in Q12: step 2 pi / 2^32 x l, as
 * floor(8 step x 2 l / 2^32) x 2 pi 2^12 / 2^16 (within a count of the
 * exact product), without a 64-bit multiply; a step past 1/8 turn a period,
 * or w L past 256 Z_FS, is held there (none is a motor this measures). */
static int32_t id_wl(const mc_id_t *id, uint32_t step)
{
    uint32_t a = (step < 0x20000000UL) ? step << 3 : 0xFFFFFFFFUL;
    uint32_t u = mc_id_mulhi(a, (uint32_t)id->l_q12 << 1);
    int32_t wl = mc_id_mac2_shr((int32_t)((u > 0x7FFFFFFFUL) ? 0x7FFFFFFFUL : u),
                                (uint16_t)ID_TWO_PI_Q12, 0, 0U, 16U);
    return (wl > ID_WL_MAX) ? ID_WL_MAX : wl;
}

/* The window's back-EMF in the frame, E = u - R i - j w L i (means), its
 * magnitude into *mag (Q15 V_FS) and the current along it (the torque
 * current) into *it (Q15 I_FS). */
static void id_emf(const mc_id_t *id, const mc_id_win_t *w, q15_t *mag, q15_t *it)
{
    q15_t id_ = id_mean(id, w->i_d), iq = id_mean(id, w->i_q);
    int32_t wl = id_wl(id, w->step);
    int32_t r = id->r_q16;
    int32_t ed = (int32_t)id_mean(id, w->u_d) - id_mul_shr(r, id_, 16U) + id_mul_shr(wl, iq, 12U);
    int32_t eq = (int32_t)id_mean(id, w->u_q) - id_mul_shr(r, iq, 16U) - id_mul_shr(wl, id_, 12U);
    uint32_t m2;
    ed = q15_sat(ed);
    eq = q15_sat(eq);
    m2 = (uint32_t)(ed * ed) + (uint32_t)(eq * eq);
    m2 = q15_isqrt_u32(m2); /* up to 46341: past Q15 where both axes are near full scale */
    *mag = q15_sat((int32_t)m2);
    /* cppcheck-suppress knownConditionTrueFalse ; it takes q15_isqrt_u32's result as 0 */
    if (*mag < 64) {
        *it = 0;
    } else {
        /* the projection of i on E: the two products of values within
         * +-32768 sum below 2^31; the quotient is below |i| < 46341, more
         * than Q15 where both axes are near full scale (and mag clamped) */
        int32_t t = id_sdiv((int32_t)id_ * ed + (int32_t)iq * eq, *mag);
        *it = q15_sat(t);
    }
}

/* The voltage the loops would ask at twice this window's speed, Q15 V_FS:
 * R i stays, the rest (back-EMF and w L i) doubles: |2 u - R i|. */
static int32_t id_volts2(const mc_id_t *id, const mc_id_win_t *w)
{
    q15_t i_d = id_mean(id, w->i_d), i_q = id_mean(id, w->i_q);
    int32_t vd = 2 * (int32_t)id_mean(id, w->u_d) - id_mul_shr(id->r_q16, i_d, 16U);
    int32_t vq = 2 * (int32_t)id_mean(id, w->u_q) - id_mul_shr(id->r_q16, i_q, 16U);
    vd = (vd > 46340) ? 46340 : (vd < -46340) ? -46340 : vd; /* squares below 2^31 */
    vq = (vq > 46340) ? 46340 : (vq < -46340) ? -46340 : vq;
    return (int32_t)q15_isqrt_u32((uint32_t)(vd * vd) + (uint32_t)(vq * vq));
}

/* One window of the J fit (note 5): the torque current against the
 * acceleration that acted over the window, in units of ID_A_UNIT per the
 * spin's acceleration, once it has eased to the full acceleration. */
static void id_j(mc_id_t *id, q15_t it)
{
    int32_t a = id_ratio(id->a_prev * ID_A_UNIT, (int32_t)id->p->accel, 0);
    if (a > -ID_A_UNIT && a < ID_A_UNIT) {
        return; /* easing: the rotor's torque lags a changing acceleration */
    }
    id->j_n++;
    id->j_a += a;
    id->j_aa += a * a;
    id->j_i += it;
    id->j_ia += (int32_t)it * a;
}

/* The damping (note 5): the rotor pulled by a current at a forced angle
 * swings about the angle its torque needs, undamped (the current loop
 * takes away the damping its back-EMF would give). Moving the forced speed
 * by -k times the swing's angle (the sine of the load angle, the torque
 * current over the current, less its low-pass) damps it at k = 2 pi
 * MC_ID_DAMP_HZ rad/s: d'' + k d' + wn^2 d = 0 for the load angle d. Where
 * the back-EMF is too small to give the angle the damping rests; it never
 * moves the forced speed by more than half. */
static void id_damp(mc_id_t *id, const mc_id_win_t *w, q15_t mag, q15_t it, bool on)
{
    int32_t i = id_mean(id, w->i_d);
    int32_t sn = (i > 0) ? id_ratio(it, i, 15) : 0; /* sin(load angle), Q15 */
    int32_t lim = (int32_t)(w->step / 2U);
    int32_t ang = 0;
    sn = q15_sat(sn);
    if (on && mag >= ID_E_MIN) {
        int32_t dev = sn * 64 - id->it_lp; /* Q15 x 64 */
        id->it_lp += dev / ID_DAMP_LP;
        ang = dev / 64;
        ang = (ang > ID_DAMP_ANGLE_MAX)    ? ID_DAMP_ANGLE_MAX
              : (ang < -ID_DAMP_ANGLE_MAX) ? -ID_DAMP_ANGLE_MAX
                                           : ang;
        id->ang_f += (ang * 16 - id->ang_f) / ID_DAMP_F;
        ang = id->ang_f / 16;
    } else {
        id->it_lp = sn * 64;
        id->ang_f = 0;
    }
    /* ang within +-ID_DAMP_ANGLE_MAX; p->damp some 2^21 */
    ang = -id_mul_shr((int32_t)id->p->damp, (int16_t)ang, 15U);
    id->damp_goal = (ang > lim) ? lim : (ang < -lim) ? -lim : ang;
}

static void id_spin(mc_id_t *id, const mc_id_win_t *w)
{
    mc_id_cmd_t *c = &id->cmd;
    q15_t mag, it;
    id_emf(id, w, &mag, &it);
    /* the loops take over from the open loop at the spin's start */
    id_damp(id, w, mag, it, id->stage != MC_ID_STAGE_SPIN1 || id->wins > ID_SPIN_START);
    switch (id->stage) {
        case MC_ID_STAGE_SPIN1:
            if (id->wins == 1U) {
                /* the dead time over the band of this motor's PWM ripple (note 7) */
                c->dt_band = mc_id_dt_band(c->dt_counts, id->vbus, id->l_q12, id->p->band_k);
            }
            if (id->wins <= ID_SPIN_START) {
                return;
            }
            /* a load angle past 45 degrees (the torque current above 0.7 of
             * the current): more current, up to the measurements' */
            if (it > (q15_t)(((int32_t)c->i_ref.d * 23170) >> 15) && c->i_ref.d < id->i_dc) {
                int32_t i = (int32_t)c->i_ref.d + c->i_ref.d / 8;
                c->i_ref.d = (q15_t)((i > id->i_dc) ? id->i_dc : i);
            }
            /* the first speed: where the back-EMF reaches ID_E1, or where
             * twice the speed would ask 0.8 of the voltage limit (v_max is
             * 0.7 of it), or half the speed limit; the first two only while
             * the rotor follows the forced angle (note 5): a swinging
             * rotor's peaks are not its speed */
            if ((mag >= ID_E1 || id_volts2(id, w) >= (int32_t)id->p->v_max * 8 / 7) &&
                id->wins > ID_SPIN_START + ID_DAMP_LP &&
                id_abs(id->ang_f) <= (int32_t)ID_SPIN_SWING_MAX * 16) {
                id->ok++;
            } else {
                id->ok = 0U;
            }
            if (id->ok >= ID_SETTLE || w->step >= id->p->step_max / 2U) {
                if (mag < ID_E_MIN) {
                    mc_id_fail(id, MC_ID_ERROR_ROTOR_LOCKED);
                    return;
                }
                id->goal = 0;
                id_stage(id, MC_ID_STAGE_HOLD1);
            } else if (id->wins > ID_SPIN_WINDOWS_MAX) {
                mc_id_fail(id, MC_ID_ERROR_TIMEOUT);
            }
            return;
        case MC_ID_STAGE_HOLD1:
        case MC_ID_STAGE_HOLD2:
            if (id->wins <= ID_HOLD_SETTLE) {
                return;
            }
            id->acc[0] += mag;
            id->acc[1]++;
            id->acc[2] += (int32_t)(w->step >> 16) * N_; /* turns x 65536 */
            id_track(id, mag);
            /* ID_HOLD_WINDOWS, and ID_HOLD_TURNS electrical turns: the rotor
             * swings about the forced angle, its mean speed over the hold is
             * the forced one within the swing's angle over the turns */
            if (id->acc[1] < ID_HOLD_WINDOWS ||
                (id->acc[2] < ID_HOLD_TURNS * 65536L && id->acc[1] < ID_HOLD_WINDOWS_MAX)) {
                return;
            }
            {
                int32_t m = id_ratio(id->acc[0], id->acc[1], 4); /* mean |E| x 16 */
                int32_t swing = (id->hi - id->lo) * 16;
                /* a light rotor on a stiff field swings about the forced angle
                 * undamped (the current loop takes the damping its back-EMF
                 * would give): still synchronous, its mean speed the forced
                 * one, so measured over the most windows, the swing's part
                 * period a small share of them */
                if (swing > m + m / 2 && swing <= 2 * m && id->acc[1] < ID_HOLD_WINDOWS_MAX) {
                    return;
                }
                /* a rotor that follows turns at the forced speed: |E| never
                 * falls to zero */
                if (swing > 2 * m || m < ID_E_MIN * 16) {
                    /* no back-EMF at the first speed: the rotor never turned */
                    mc_id_fail(id, (m < ID_E_MIN * 16 && id->stage == MC_ID_STAGE_HOLD1)
                                       ? MC_ID_ERROR_ROTOR_LOCKED
                                       : MC_ID_ERROR_NO_SYNC);
                    return;
                }
                if (id->stage == MC_ID_STAGE_HOLD1) {
                    id->m1 = m;
                    id->x1 = w->step;
                    id->goal = (int32_t)id->p->accel;
                    id_stage(id, MC_ID_STAGE_SPIN2);
                } else {
                    id->m2 = m;
                    id->x2 = w->step;
                    /* |E| / speed at both speeds must agree (note 5) */
                    /* m1 x2 / x1 from the speeds' ratio in Q13 (x2 is about
                     * 2 x1: at most 4, so 32768) */
                    int32_t k = id_ratio((int32_t)(id->x2 >> 8), (int32_t)(id->x1 >> 8), 13U);
                    k = (k > 32768) ? 32768 : k;
                    if (id_abs(mc_id_mac2_shr(id->m1, (uint16_t)k, 0, 0U, 13U) - id->m2) >
                        id->m2 / 8) {
                        mc_id_fail(id, MC_ID_ERROR_NO_SYNC);
                        return;
                    }
                    id->goal = -(int32_t)id->p->accel;
                    id_stage(id, MC_ID_STAGE_SPIN3);
                }
            }
            return;
        case MC_ID_STAGE_SPIN2:
            id_j(id, it);
            if (w->step >= 2U * id->x1 - id->x1 / 8U) { /* the rest while the acceleration eases */
                id->goal = 0;
                id_stage(id, MC_ID_STAGE_HOLD2);
            } else if (id->wins > ID_SPIN_WINDOWS_MAX) {
                mc_id_fail(id, MC_ID_ERROR_TIMEOUT);
            }
            return;
        case MC_ID_STAGE_SPIN3:
            id_j(id, it);
            if (w->step <= id->x1 + id->x1 / 8U) {
                /* J is measured: to rest at four times the rate (the
                 * stopping distance of the rest is the spin's longest) */
                id->goal = -4 * (int32_t)id->p->accel;
                id_stage(id, MC_ID_STAGE_SPIN4);
            }
            return;
        default: /* SPIN4: to rest, then done */
            if (w->step <= id->p->accel * 200U || w->step > id->x2 + id->x2 / 4) {
                c->accel = 0;
                id->goal = 0;
                c->end = true;
                id->stage = MC_ID_STAGE_DONE;
            }
            return;
    }
}

/* The spin's acceleration moves to its goal by 1/ID_JERK of the spin's a
 * window: a step of acceleration is a step of torque, and a rotor pulled
 * by a current at a forced angle swings, undamped, about the angle that
 * torque needs (note 5). */
static void id_ease(mc_id_t *id)
{
    int32_t step = (int32_t)(id->p->accel / ID_JERK) + 1;
    int32_t a = id->ramp;
    int32_t d = id_sdiv(id->damp_goal - id->damp, N_); /* the damping's offset over the window */
    a += (id->goal > a + step) ? step : (id->goal < a - step) ? -step : id->goal - a;
    id->ramp = a;
    id->damp += d * N_;
    id->cmd.accel = a + d;
}

void mc_id_window(mc_id_t *id, const mc_id_win_t *w, q15_t vbus, mc_id_cmd_t *cmd)
{
    if (id->stage == MC_ID_STAGE_R) {
        id->vbus = vbus; /* the bus the inverter's error is a share of */
    }
    if (id->stage != MC_ID_STAGE_DONE && id->stage != MC_ID_STAGE_FAILED &&
        id->stage != MC_ID_STAGE_IDLE) {
        if (id->wins < UINT16_MAX) {
            id->wins++;
        }
        switch (id->stage) {
            case MC_ID_STAGE_RAMP:
                id_ramp(id, w);
                break;
            case MC_ID_STAGE_LD:
            case MC_ID_STAGE_LQ:
                id_inductance(id, w);
                break;
            case MC_ID_STAGE_R:
                id_resistance(id, w);
                break;
            default:
                id->a_prev = id->ramp; /* what acted over this window, less the damping */
                id_spin(id, w);
                if (!id->cmd.end) {
                    id_ease(id);
                }
                break;
        }
    }
    *cmd = id->cmd;
}

/*
 * Notes
 *
 * 1. Results. R = dv / di (sums of the same number of periods, so their
 *    ratio is R in Z_FS); L (Ld, Lq) = Ts (zu - R zm / 2) / zi; the
 *    inverter's error from v0; Ke from m1, m2 at x1, x2; J from the fit
 *    of the torque current against the acceleration (j_*).
 *    mc_identify_result (mc.c) turns them into micro-ohms, nanohenries,
 *    microvolts per rpm and 1e-9 kg m^2 in 64-bit integers, once, outside
 *    the interrupts.
 *
 * 2. Inductance by correlation. Between two samples the current changes
 *    by Ts / L (u - R i - e), u the applied voltage over the interval
 *    (the two commands that act in it, weighted as mc.h note 2 says), i
 *    the mean current, e = 0 at rest. Multiplying by z (+-1, the sign of
 *    the injected square wave in the command that acts most of that
 *    interval) and summing, anything uncorrelated with z drops out: the
 *    ADC noise, the slow DC loop, a constant inverter error. So
 *    L = Ts (sum z u - R sum z i) / sum z di holds whatever z's phase; the
 *    current is a triangle in quadrature with the square wave, so sum z i
 *    is nearly 0 and R's term a small correction. The DC current keeps
 *    the injected axis's phases out of the dead-time band on d (B and C
 *    carry +-0.87 i_d); on q phase A crosses zero, whose error, a static
 *    function of a current in quadrature with z, also sums to nearly 0.
 *
 * 3. Gains. With L known the PI's Kp = L wc puts the crossover at wc
 *    whatever R; its zero at wc / 8 (R unknown) or R / L keeps the integral
 *    from winding the loop into oscillation (a pure integral loop of an RL
 *    plant is stable only slower than R / L, which spans the square of
 *    R's range).
 *
 * 4. R and the inverter's error. With the current on beta, phases B and
 *    C carry +-0.87 i, phase A none: at steady state the d voltage is
 *    R i + v0, v0 = 2 / sqrt(3) Vd, Vd the dead-time voltage of one phase
 *    (its share of the bus and the diodes' drop), when both phases' currents
 *    lie outside the band where a current smaller than its PWM ripple
 *    reverses in each period (there the error is linear in the current,
 *    an apparent resistance). Three levels tell: the lower half's slope
 *    above the upper half's by more than 1 / ID_R_BAND_TOL means the
 *    lowest level is in the band, and the upper half alone gives R.
 *
 * 5. Ke and J. Turning at a steady speed w with the current on d, the
 *    voltage the loops ask is u = R i + j w L i + E, E the back-EMF, w psi
 *    in magnitude, on the rotor's q axis; the window's |E| is w_rotor psi,
 *    and over a hold the rotor's mean speed is the forced one (it swings
 *    about it), so the mean |E| is w psi without the bias a vector mean
 *    of a swinging E would have. From two holds, psi = (m2 - m1) /
 *    (w2 - w1): the parts of R i and of the inverter's error along E,
 *    which do not change with speed, cancel. The current along E drives
 *    the rotor (torque 3/2 p psi i_t); accelerating and decelerating at the
 *    same rate over the same speeds, friction is the same both ways and
 *    2 J alpha = 3/2 p psi (i_t,up - i_t,down); fitted as a line of i_t
 *    against the acceleration over every window at the full rate.
 *    A current at a forced angle holds the rotor like a spring: it swings
 *    about the angle its torque needs, undamped, since the current loop
 *    cancels the damping its back-EMF would give (a light rotor on a
 *    stiff field kept swinging through whole holds and stopped once a
 *    swing). id_damp moves the forced speed by -k times the load angle's
 *    departure from its mean, which for the load angle d gives
 *    d'' + k d' + wn^2 d = 0; k = 2 pi MC_ID_DAMP_HZ (63 /s) damps the
 *    swings of a few Hz to some tens critically or nearly, the low-pass
 *    of ID_DAMP_F windows keeps the loop's own delay (two windows) from
 *    exciting the fast ones. The holds take |E| at the forced speed the
 *    damping leaves, their mean over many windows.
 *    The first speed is taken from the back-EMF (or the voltage) only
 *    while the rotor follows the forced angle, else the peak of a swing
 *    is taken for the speed and the holds run at a fraction of the speed
 *    meant, where a light rotor on a stiff field is not held: not before
 *    the damping has run ID_DAMP_LP windows (the rotor, let go from LQ's
 *    angle, swings hardest at the spin's start: R x3.7 L x0.34 Ke x4
 *    J x0.5 reached |E| = ID_E1 at window 24, at a thirteenth of the
 *    speed; the swing's mean, which its angle is measured from, needs
 *    that long), nor while the swing's angle is above ID_SPIN_SWING_MAX
 *    (1/8 rad; R x4.1 L x0.3 Ke x3.7 J x2.2 lurched to three times the
 *    forced speed at window 40). Over 400 drawn motors none that follows
 *    took its first speed before window 100.
 *    What limits Ke: the error of the voltage's angle (the inverter's
 *    dead time seen a few hundredths of a period off, the sample's
 *    timing) times the part of u across E, R i, which the two speeds do
 *    not cancel (it grows with the speed as E does). Small where E is
 *    large against R i; a motor whose back-EMF at the speed limit is a
 *    few times its R i reads low by a few per cent (docs/identify.md).
 *
 * 6. A cut lead. With phase B or C open the voltage on d (beta) drives
 *    the current along the two phases left, A and the other, 60 degrees
 *    off d: a q current sqrt(3) times the d current, at every level. A
 *    sound motor has a q current too, phase A's own (A carries none of
 *    the d current, so its dead-time error, a full +-Vd on the smallest
 *    current of either sign, drives alpha up to Vd / R), but one that
 *    hardly changes with the d voltage: the q current's change from the
 *    top R level to the lowest is set against the d current's, and above
 *    half of it is a cut lead. With A open d still conducts (B and C), but
 *    LQ's injection on q (alpha: phase A's current) drives nothing: where
 *    LD reached its swing, LQ at its largest amplitude and period does not
 *    reach a quarter of it. (LQ's q bias is no test: on a small R it is
 *    mostly the dead-time voltage phase A's current, in the band, does not
 *    see in full.)
 *
 * 7. The spin's dead-time band. The compensation (mc_internal.h
 *    mc_deadtime_counts) adds the full dead time for a phase current out of
 *    a band around zero and a share of it inside, where the current's PWM
 *    ripple reverses it within the period and the inverter loses only part
 *    of its dead time. The build's band (MC_DEADTIME_BAND_A) is the
 *    profile's motor's ripple; a motor of a sixth of that inductance has
 *    six times the ripple, and the band of the profile makes the
 *    compensation switch the full dead time on currents the inverter
 *    loses only a part of it on: an error of the voltage that turns with
 *    the current's phase, which the back-EMF (Ke) takes in (+10 % on a
 *    motor of R and L x0.15 on the switching inverter). Once L is known
 *    (the end of LQ) the spin's band is the ripple of that L, Vbus / (12 L
 *    fpwm) as UserParms.h sizes the build's, from the bus measured while R
 *    was: ((vbus k) >> 4) / l (mc_derived.h MC_ID_BAND_K), which at the
 *    profile's L and nominal bus is the build's band (the Hurst: 387
 *    against MC_DT_BAND_Q15 388), held above the dead time (the slope
 *    below 2^15) and at most a quarter of I_FS. It is computed in the
 *    spin's first window and acts from its second, long before the loops
 *    have settled (ID_SPIN_START): not in LQ's last window, the slow
 *    step's heaviest already. mc_id_stop puts the build's back.
 */

#else
/* UserParms.h MC_IDENTIFY 0: no sequence in this build (ISO C wants a
 * translation unit to declare something). */
extern const mc_id_params_t mc_id_absent;
#endif /* MC_IDENTIFY */
