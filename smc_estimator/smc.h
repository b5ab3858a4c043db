/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* smc.h - sliding-mode observer: rotor angle and speed from alpha/beta currents and voltages. */
#ifndef SMC_H
#define SMC_H

#include "frames.h"
#include "lpf.h"
#include "q15.h"

/*
 * What it computes, once per PWM period n, per axis alpha and beta
 * (AN1078's observer; "note N" below is docs/estimator.md, "Derivation",
 * note N, where each step is derived and measured):
 *
 *   i_est(n) = F i_est(n-1) + G (v(n-1) - e(n-1) - z(n-1))   motor model (note 2)
 *   z(n)     = Kslide * sat((i_est(n) - i_meas(n)) / MaxSMCError)
 *   e(n)     = e(n-1)  + K (z(n) - e(n-1))                   first stage, in the loop
 *   ef(n)    = ef(n-1) + K (e(n) - ef(n-1))                  second stage
 *   theta(n) = atan2(-ef_alpha, ef_beta) + comp(K, omega)    (+ pi when omega < 0)
 *
 * F = exp(-Ts R / L) and G = (1 - F) / R, the exact discretisation of the
 * per-phase R-L model; K = omega Ts, floored at the minimum speed's value.
 * Every irp_percalc periods the angle steps give the speed, which sets K,
 * the phase lead comp (from the observer's own transfer functions, notes
 * 3-4, not a constant 90 degrees) and the validity flag.
 *
 * Units and formats (the interface agreed with the mc core):
 *   currents   Q15 of I_FS (A), the ADC current full scale;
 *   voltages   Q15 of V_FS (V), the SVGen full scale (nominal Vbus / sqrt 3,
 *              phase peak);
 *   back-EMF   e, ef, z, Kslide and the amplitude: Q15 of E_FS =
 *              SMC_EMF_FS_RATIO V_FS (32-bit filter states: Q31 of E_FS);
 *   speed      electrical, signed (negative = reverse), Q15 of omega_fs_hz;
 *              the core picks omega_fs_hz = MC_SPEED_FULLSCALE_RPM * pole
 *              pairs / 60, so the number equals the mechanical Q15 speed;
 *   angles     angle_q15_t, electrical, one turn = 2^16.
 *
 * Timing contract (note 1): smc_update(s, i_meas, v_applied) is called once
 * per PWM period n with
 *   i_meas     the alpha/beta currents sampled at the instant s_n (offset
 *              removed), one period after s_(n-1);
 *   v_applied  the mean alpha/beta voltage the inverter applied over
 *              [s_(n-1), s_n], dead-time compensated and scaled to the bus
 *              present: the voltage the current evolved under, not the one
 *              being computed now (the core weights the commands of the two
 *              last periods by the time each acted, firmware/mc.h note 2);
 *   theta      the rotor angle at s_n, for the Park transform of i_meas
 *              (the core advances it to the middle of the period its
 *              voltage acts in, note 6).
 *
 * Two sides (note 10). Fast, in the PWM interrupt: smc_update every period
 * and smc_window_end every irp_percalc periods (a snapshot). Slow, once per
 * window in a context the interrupt pre-empts: smc_slow_step (speed, K,
 * compensation, back-EMF check), whose results the fast side takes with
 * smc_apply. Each side writes only its own fields. Cycles:
 * docs/performance.md.
 */

/* E_FS / V_FS: above the base speed the back-EMF exceeds V_FS (field
 * weakening) and the correction z must carry about 0.65 of it (note 5), so
 * the back-EMF quantities get twice the voltage scale. */
#define SMC_EMF_FS_RATIO 2.0

/* ---- parameters ---------------------------------------------------------- */

/*
 * Coefficients of magnitude >= 1 are a Q15 mantissa and a named left shift:
 * value = mant * 2^shift / 32768. Initialise with SMC_PARAMS_INIT
 * (smc_params.h), which computes and range-checks every field at compile
 * time from engineering units.
 */
typedef struct {
    q15_t f;              /* F = exp(-Ts R / L), Q15, in (0, 1) */
    q15_t g;              /* G = (1 - F)/R in I_FS per E_FS (x 2 V_FS/I_FS): mantissa, Q15 */
    uint8_t g_shift;      /* ... and its shift, 0..7 */
    q15_t kslide;         /* Kslide, Q15 of E_FS, in (0, 1) */
    q15_t max_err;        /* MaxSMCError, Q15 of I_FS, >= 1 LSB */
    q15_t kz;             /* Kslide / MaxSMCError (E_FS per I_FS): mantissa, Q15 */
    uint8_t kz_shift;     /* ... and its shift, 0..15 */
    q15_t k_per_omega;    /* x = |omega| * k_per_omega = 2 pi f Ts (rad per period), Q15 */
    q15_t k_min;          /* floor of K: 2 pi f_min Ts, Q15 */
    q15_t omega_min;      /* minimum closed-loop speed, Q15 of omega_fs */
    q15_t kspeed;         /* omega = sum of angle steps * kspeed * 2^kspeed_shift / 32768 */
    uint8_t kspeed_shift; /* ... 1 / (2 IRP Ts omega_fs) as mantissa and shift, 0..15 */
    uint16_t irp_percalc; /* PWM periods per speed calculation, 1..256 */
    q15_t k_speed_lpf;    /* speed filter coefficient at the speed-loop rate, Q15 */
    q15_t emf_gain;       /* expected |ef| (Q15 of E_FS) per unit |omega| (Q15): mantissa, */
    uint8_t emf_shift;    /* ... and shift (always 3); emf_gain 0 = no back-EMF check */
    /* The observer's transfer function (notes 3-4), Q12 unless said: */
    q15_t tf_mdc; /* constant term of the in-loop stage's denominator, per unit K */
    q15_t tf_b10; /* its u coefficient B1 = tf_b10 + K tf_b1k */
    q15_t tf_b1k;
    q15_t tf_b2;   /* its u^2 coefficient B2 = tf_b2 (1 - K), Q15 */
    q15_t tf_xadv; /* compensation term tf_xadv * x, in angle counts per Q15 rad, Q15; 0 in
                      relay mode (note 4), which also turns the lag correction off */
} smc_params_t;

/* ---- state --------------------------------------------------------------- */

/* The window end's snapshot for the slow side (smc_window_end fills it). */
typedef struct {
    int32_t dtheta_sum; /* sum of theta_raw steps over the window, angle counts */
    int32_t w_alpha;    /* model back-EMF filter states at the window end, Q31 */
    int32_t w_beta;
    int32_t ef_alpha; /* e_final states at the window end, Q31 */
    int32_t ef_beta;
    angle_q15_t theta_raw; /* at the window end */
    uint8_t epoch;         /* resets and presets so far (the run the window belongs to) */
    bool full;             /* irp_percalc periods since the last window end, reset or preset */
    bool preset;           /* the last change of epoch was smc_preset_speed ... */
    q15_t preset_omega;    /* ... to this speed */
} smc_window_t;

/* What the slow side computes from a window (smc_slow_step); the fast side
 * takes it at the next window end. */
typedef struct {
    q15_t omega;      /* filtered speed, Q15 of omega_fs, signed */
    q15_t k;          /* Kslf, Q15 */
    q15_t k_w;        /* 4 k, the gain smoothing the model back-EMF (note 8), Q15 */
    angle_q15_t comp; /* compensation added to theta_raw (incl. pi if omega < 0) */
    q15_t emf_mag;    /* |ef| (Q15 of E_FS) */
    q15_t emf_ratio;  /* |ef| / expected at |omega|, Q12 (4096 = as expected) */
    bool valid;       /* |omega| >= omega_min and emf_ratio inside the band */
    uint8_t epoch;    /* of the window it was computed from */
} smc_result_t;

/* The slow side's own state: written only by smc_slow_step (and smc_init). */
typedef struct {
    lpf_t k_lpf;     /* x = |omega| 2 pi Ts filtered again: K before its floor, Q31 */
    lpf_t omega_lpf; /* filtered speed, Q31 of omega_fs */
    q15_t omega;     /* its output */
    angle_q15_t lag; /* lag of theta_raw behind the model back-EMF at the last window end */
    bool lag_valid;  /* lag holds a measurement */
    uint8_t startup; /* windows left in the tracking phase (note 8) */
    uint8_t epoch;   /* the run this state belongs to */
} smc_slow_t;

typedef struct {
    const smc_params_t *p;
    q15_t raw_c;  /* the raw back-EMF's c = mdc - 1 + p, Q12 (note 8), from p */
    q15_t raw_np; /* ... and -p, Q15 */
    /* fast side: smc_update, every period */
    ab_q15_t i_est; /* model current, Q15 of I_FS */
    ab_q15_t z;     /* sliding-mode correction, Q15 of E_FS */
    ab_q15_t e;     /* first stage e rounded to Q15 (what the model is fed) */
    lpf_t e_alpha;  /* first stage e, Q31 of E_FS */
    lpf_t e_beta;
    lpf_t ef_alpha; /* second stage e_final, Q31 of E_FS */
    lpf_t ef_beta;
    lpf_t w_alpha; /* model back-EMF from the correction (note 8), smoothed, Q31 of E_FS */
    lpf_t w_beta;
    int32_t dtheta_sum;    /* sum of theta_raw steps this window, angle counts */
    uint16_t count;        /* periods since the last window end, reset or preset */
    angle_q15_t theta_raw; /* atan2 of ef, uncompensated */
    angle_q15_t theta;     /* compensated: the rotor angle at t_n */
    /* the slow side's results in use (smc_window_end takes them) */
    q15_t omega;
    q15_t k;
    q15_t k_w;
    angle_q15_t comp;
    q15_t emf_mag;
    q15_t emf_ratio;
    bool valid;
    /* the hand-over between the two sides */
    uint8_t epoch;       /* incremented by smc_reset and smc_preset_speed */
    bool preset_pending; /* a preset the slow side has not seen yet */
    q15_t preset_omega;
    smc_window_t win;  /* fast -> slow, written at the window end */
    smc_result_t res;  /* slow -> fast, written by smc_slow_step */
    smc_result_t rest; /* the results at rest (speed 0), computed once by smc_init */
    smc_slow_t slow;
} smc_t;

/* Band of emf_ratio (Q12) inside which the back-EMF counts as consistent
 * with the speed: 0.5 .. 2.0 of the amplitude Ke predicts (note 9). */
#define SMC_EMF_RATIO_ONE 4096
#define SMC_EMF_RATIO_LO  2048
#define SMC_EMF_RATIO_HI  8192

/* ---- API ----------------------------------------------------------------- */

/* Bind the parameters (kept by pointer: they must outlive s) and reset.
 * Computes the results at rest once (a phase lead: not for the 50 us path). */
void smc_init(smc_t *s, const smc_params_t *p);

/* Fast side. All state to zero: model currents, corrections and filters 0,
 * the results at rest (speed 0, K at its floor, not valid), theta the
 * compensation at rest; the slow side restarts from speed 0 at its next
 * window (note 10). */
void smc_reset(smc_t *s);

/* Fast side. Preset the speed (Q15 of omega_fs, signed) at a hand-off from
 * open loop: omega takes the value at once; the slow side restarts its
 * filters from it at the next window, K and the compensation follow from
 * that window's results (note 10). The back-EMF filters are left as they
 * are (the observer runs during the open-loop start-up and has already
 * converged). */
void smc_preset_speed(smc_t *s, q15_t omega);

/* Fast side, one PWM period: see the timing contract above. Scaling and
 * overflow: model and correction in 32-bit products rounded to Q15 and
 * saturated (|v - e - z| saturates at full scale before the multiply by G);
 * filters with 32-bit states (foc/lpf.h); the angle-step sum is 32 bits, so
 * no speed below the Nyquist limit (|delta theta| < pi per period) wraps.
 * One division (atan2), no float. Defined inline in smc_update.h. */
Q15_INLINE void smc_update(smc_t *s, ab_q15_t i_meas, ab_q15_t v_applied);

/* Fast side, every irp_percalc periods, after smc_update: snapshots this
 * window for the slow side (note 10). Inline (smc_update.h): it runs in the
 * window's period of the interrupt, the longest. */
Q15_INLINE void smc_window_end(smc_t *s);

/* Slow side, once after each smc_window_end and before the next one: the
 * speed (with the lag correction of note 8), K, the compensation (two
 * atan2 and about twenty products), the back-EMF amplitude and one 32 / 16
 * division for the consistency figure; the speed saturates at +-omega_fs. */
void smc_slow_step(smc_t *s);

/* Fast side, once the slow step of the last window has run: takes its
 * results (omega, K, the compensation, the back-EMF figures, valid) if they
 * belong to the present run (note 10). */
void smc_apply(smc_t *s);

/* The phase lead (angle counts) that cancels the lag of the two stages and
 * the loop delay for a positive frequency x (electrical rad per PWM period,
 * Q15, 0 <= x < 1) with stage coefficient k (Q15, >= 1): notes 2-4.
 * smc_update adds it (negated, plus pi, for reverse rotation) to theta_raw.
 * Scaling: u and D2 in Q30, D1 in Q27, from 16 x 16 products and seven
 * 32 x 16 ones; two atan2 calls. */
angle_q15_t smc_phase_lead(const smc_params_t *p, q15_t k, q15_t x);

/* Speed (Q15 of omega_fs, signed, saturated at +-32767) from a window's sum
 * of angle steps (angle counts, |sum| <= 256 * 32768): note 7. */
q15_t smc_speed_from_steps(const smc_params_t *p, int32_t sum);

/* Read-outs: the compensated angle (rotor at s_n), the uncompensated one,
 * the speed, the validity flag (|omega| >= the minimum and, with Ke given,
 * the back-EMF consistent: note 9), |ef| (Q15 of E_FS), emf_ratio (Q12,
 * 4096 = the amplitude Ke predicts at the estimated speed: a stall /
 * loss-of-sync figure) and e_final itself (Q15 of E_FS). */
static inline angle_q15_t smc_theta(const smc_t *s)
{
    return s->theta;
}
static inline angle_q15_t smc_theta_raw(const smc_t *s)
{
    return s->theta_raw;
}
static inline q15_t smc_omega(const smc_t *s)
{
    return s->omega;
}
static inline bool smc_valid(const smc_t *s)
{
    return s->valid;
}
static inline q15_t smc_emf_amplitude(const smc_t *s)
{
    return s->emf_mag;
}
static inline q15_t smc_emf_ratio(const smc_t *s)
{
    return s->emf_ratio;
}
static inline ab_q15_t smc_e_final(const smc_t *s)
{
    ab_q15_t ef;
    ef.alpha = lpf_output(&s->ef_alpha);
    ef.beta = lpf_output(&s->ef_beta);
    return ef;
}

/* The per-period step's definition (inline; smc_update above). */
#include "smc_update.h"

#endif /* SMC_H */
