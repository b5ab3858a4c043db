/* smc.h - sliding-mode observer: rotor angle and speed from alpha/beta currents and voltages. */
#ifndef SMC_H
#define SMC_H

#include "frames.h"
#include "lpf.h"
#include "q15.h"

/*
 * What it computes, once per PWM period n (the equations of AN1078's
 * "Sensorless FOC for PMSM", per axis alpha and beta):
 *
 *   i_est(n) = F i_est(n-1) + G (v(n-1) - e(n-1) - z(n-1))   digitised motor model
 *   err(n)   = i_est(n) - i_meas(n)
 *   z(n)     = Kslide * sat(err(n) / MaxSMCError)            linear in the band,
 *                                                            +-Kslide outside it
 *   e(n)     = e(n-1)  + K (z(n) - e(n-1))                   first stage (in the loop)
 *   ef(n)    = ef(n-1) + K (e(n) - ef(n-1))                  second stage (plain)
 *   theta_raw(n) = atan2(-ef_alpha, ef_beta)                 foc/atan2.h
 *   theta(n) = theta_raw(n) + comp(omega) (+ pi when omega < 0)
 *
 * with F = exp(-Ts R / L) and G = (1 - F) / R (per-phase R and L; AN1078's
 * 1 - Ts R / L and Ts / L are their first-order truncations, note 2),
 * K = Kslf = omega Ts (the cut-off at the electrical frequency), floored at
 * the value of the minimum closed-loop speed. Every IRP_PERCALC periods the
 * angle steps of theta_raw (plus the lag correction of note 8) are summed in
 * 32 bits, scaled to a speed and filtered, and the new speed sets K (note
 * 7), the compensation comp (derived in notes 3-4 from the observer's
 * discrete transfer functions and the loop delay) and the validity flag.
 *
 * Units and formats (the interface agreed with the mc core):
 *   currents   Q15 of I_FS (A), the ADC current full scale
 *              (BOARD_I_FULLSCALE_A = 4.4 A on the MCLV);
 *   voltages   Q15 of V_FS (V), the SVGen full scale (nominal Vbus / sqrt(3),
 *              phase peak);
 *   back-EMF   e, ef, z, Kslide and the amplitude: Q15 of E_FS = 2 V_FS
 *              (SMC_EMF_FS_RATIO; 32-bit filter states, Q31 of E_FS), so G
 *              is (1 - F)/R * E_FS/I_FS in these units;
 *   speed      electrical, signed (negative = reverse rotation), Q15 of
 *              omega_fs_hz (the core sets omega_fs_hz = MC_SPEED_FULLSCALE_RPM
 *              * pole pairs / 60, so the Q15 speed equals the mechanical speed
 *              in Q15 of MC_SPEED_FULLSCALE_RPM);
 *   angles     angle_q15_t, electrical, one turn = 2^16.
 *
 * Timing contract (note 1): smc_update(s, i_meas, v_applied) is called once
 * per PWM period n with
 *   i_meas     the alpha/beta currents sampled once per period at the
 *              instant s_n (offset removed), one period after s_(n-1);
 *   v_applied  the mean alpha/beta voltage the inverter applied over
 *              [s_(n-1), s_n], the one the current evolved under between
 *              the previous sample and this one: on the dsPIC (sample at
 *              0.54 of the period, duties loaded at the boundary) the core
 *              passes the commands of the two last periods weighted by the
 *              time each acted (firmware/mc.h note 2), each after dead-time
 *              compensation and scaled to the bus actually present: the
 *              estimator must be fed the voltage that was applied, not the
 *              one being computed now.
 *   theta      estimates the rotor electrical angle at s_n, the instant
 *              i_meas was sampled (use it for Park of i_meas). The core
 *              advances it to the middle of the period its voltage will act
 *              in for the inverse Park (note 6; 0.96 omega Ts on the dsPIC).
 *
 * Two sides (note 10). The fast side runs in the PWM interrupt:
 * smc_update every period (2 model steps, 2 switches, 6 first-order updates
 * with 32-bit states, one atan2) and smc_window_end every irp_percalc
 * periods (a snapshot). The slow side, smc_slow_step, runs once per window
 * in a context the interrupt pre-empts: the speed, K, the compensation and
 * the back-EMF check; its results reach the fast side at the next window
 * end, one window later. Cycle figures: docs/performance.md.
 */

/* The back-EMF quantities (z, e, e_final, Kslide, the amplitude) are Q15 of
 * E_FS = SMC_EMF_FS_RATIO * V_FS: above the base speed the back-EMF exceeds
 * the inverter's V_FS (field weakening), and the correction must carry
 * about 0.65 of it (note 5). */
#define SMC_EMF_FS_RATIO 2.0

/* ---- parameters ---------------------------------------------------------- */

/*
 * Coefficients of magnitude >= 1 are a Q15 mantissa and a named left shift:
 * value = mant * 2^shift / 32768. Initialise with SMC_PARAMS_INIT (below),
 * which computes and range-checks everything at compile time.
 */
typedef struct {
    q15_t f;              /* F = exp(-Ts R / L), Q15, in (0, 1) (note 2) */
    q15_t g;              /* G = (1 - F)/R * 2 V_FS/I_FS (I_FS per E_FS): mantissa, Q15 */
    uint8_t g_shift;      /* ... and its shift, 0..7 */
    q15_t kslide;         /* Kslide, Q15 of E_FS = 2 V_FS, in (0, 1) */
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
    q15_t tf_xadv; /* compensation term tf_xadv * x, in angle counts per Q15 rad, Q15 */
} smc_params_t;

/* ---- compile-time parameter computation ---------------------------------- */

/* Smallest shift s in 0..15 with x < 2^s, for 0 <= x < 32768 (a larger x
 * gives 15, and the callers' range checks reject it): q15.h's 0..7
 * convention (Q15_SHIFT7_OF, Q15_MANT7_OF) extended by 8 for x >= 128
 * (x / 256 is exact in any binary double). */
#define SMC_SHIFT_OF(x) ((x) < 128.0 ? Q15_SHIFT7_OF(x) : 8 + Q15_SHIFT7_OF((x) / 256.0))

/* Mantissa of x for the shift SMC_SHIFT_OF(x). */
#define SMC_MANT_OF(x) Q15((double)(x) / (double)(1L << SMC_SHIFT_OF(x)))

/* Q12 constant (range [-8, 8)), rounded half away from zero. */
#define SMC_Q12(x) ((q15_t)((x)*4096.0 + ((x) >= 0.0 ? 0.5 : -0.5)))

/* exp(-y) for 0 < y <= 1 as a constant expression: the (3,3) Pade
 * approximant, relative error 1.03e-5 at y = 1 (0.12 LSB of F in Q15) and
 * < 1e-13 at y = 0.07 (the Hurst motor); it keeps the macro expansion small
 * (y appears 6 times). */
#define SMC_EXPNEG_(y)                                                                             \
    ((1.0 - (y) * (0.5 - (y) * (0.1 - (y) / 120.0))) /                                             \
     (1.0 + (y) * (0.5 + (y) * (0.1 + (y) / 120.0))))

/* The derived quantities, in double (engineering units in, ratios out). */
#define SMC_Y_(r, l, ts) ((double)(ts) * (double)(r) / (double)(l))
#define SMC_F_(r, l, ts) SMC_EXPNEG_(SMC_Y_(r, l, ts))
#define SMC_G_(r, l, ts, vfs, ifs)                                                                 \
    ((1.0 - SMC_F_(r, l, ts)) / (double)(r) * (double)(vfs) / (double)(ifs))
/* G and Kslide in the internal back-EMF scale E_FS = SMC_EMF_FS_RATIO * V_FS. */
#define SMC_GE_(r, l, ts, vfs, ifs) (SMC_G_(r, l, ts, vfs, ifs) * SMC_EMF_FS_RATIO)
#define SMC_KSE_(ks)                ((double)(ks) / SMC_EMF_FS_RATIO)
#define SMC_KZ_(kslide, maxerr)     (SMC_KSE_(kslide) / (double)(maxerr))
#define SMC_KPW_(ts, wfs)           (6.283185307179586 * (double)(wfs) * (double)(ts))
#define SMC_KSPEED_(ts, wfs, irp)   (1.0 / (2.0 * (double)(irp) * (double)(ts) * (double)(wfs)))
#define SMC_KSLPF_(ts, irp, fc)     (6.283185307179586 * (double)(fc) * (double)(irp) * (double)(ts))
/* Loop gain c = G Kz of the linear band and the pole p = F - c (note 3).
 * Linear when |p| < 1 (c < 1 + F); otherwise the band is unstable as a
 * linear loop and the observer chatters (relay mode, note 4). */
#define SMC_C_(r, l, ts, vfs, ifs, ks, me) (SMC_GE_(r, l, ts, vfs, ifs) * SMC_KZ_(ks, me))
#define SMC_LIN_(r, l, ts, vfs, ifs, ks, me)                                                       \
    (SMC_C_(r, l, ts, vfs, ifs, ks, me) < 1.0 + SMC_F_(r, l, ts))
#define SMC_P_(r, l, ts, vfs, ifs, ks, me) (SMC_F_(r, l, ts) - SMC_C_(r, l, ts, vfs, ifs, ks, me))
#define SMC_MDC_(r, l, ts, vfs, ifs, ks, me)                                                       \
    (SMC_LIN_(r, l, ts, vfs, ifs, ks, me)                                                          \
         ? 1.0 + 2.0 * SMC_C_(r, l, ts, vfs, ifs, ks, me) - SMC_F_(r, l, ts)                       \
         : 2.0)
#define SMC_B10_(r, l, ts, vfs, ifs, ks, me)                                                       \
    (SMC_LIN_(r, l, ts, vfs, ifs, ks, me)                                                          \
         ? 1.0 - SMC_F_(r, l, ts) + SMC_C_(r, l, ts, vfs, ifs, ks, me)                             \
         : 1.0)
#define SMC_B1K_(r, l, ts, vfs, ifs, ks, me)                                                       \
    (SMC_LIN_(r, l, ts, vfs, ifs, ks, me)                                                          \
         ? 2.0 * SMC_F_(r, l, ts) - 1.0 - 3.0 * SMC_C_(r, l, ts, vfs, ifs, ks, me)                 \
         : -1.0)
#define SMC_B2_(r, l, ts, vfs, ifs, ks, me)                                                        \
    (SMC_LIN_(r, l, ts, vfs, ifs, ks, me) ? SMC_P_(r, l, ts, vfs, ifs, ks, me) : 0.0)
#define SMC_XADV_(r, l, ts, vfs, ifs, ks, me)                                                      \
    (SMC_LIN_(r, l, ts, vfs, ifs, ks, me) ? 0.5 / 3.141592653589793 : 0.0)
/* Low-speed gain |ef| / |E| of the two stages (note 5): about 0.30 with the
 * dead-beat band (c = F), 0.32 in relay mode, 0.30..0.41 for c in 0.5..F;
 * one constant is enough for a 0.5 .. 2 consistency band. */
#define SMC_STAGE_GAIN 0.31
#define SMC_EMFG_(ke, wfs, vfs)                                                                    \
    ((double)(ke) * (double)(wfs) / ((double)(vfs)*SMC_EMF_FS_RATIO) * SMC_STAGE_GAIN)

/* MaxSMCError (fraction of I_FS) that makes the linear band dead-beat
 * (c = F, p = 0; note 3): the recommended choice. */
#define SMC_MAXERR_DEADBEAT(r, l, ts, vfs, ifs, kslide)                                            \
    ((double)(kslide)*SMC_G_(r, l, ts, vfs, ifs) / SMC_F_(r, l, ts))

/*
 * SMC_PARAMS_INIT(r_ohm, l_h, ts_s, v_fs_v, i_fs_a, kslide_frac, maxerr_frac,
 *                 omega_fs_hz, min_speed_hz, irp_percalc, speed_lpf_hz,
 *                 ke_v_per_hz)
 * An initialiser for a `static const smc_params_t`:
 *   r_ohm, l_h     per-phase resistance and inductance (half the
 *                  line-to-line meter reading);
 *   ts_s           PWM period (s);
 *   v_fs_v, i_fs_a the voltage and current full scales (above);
 *   kslide_frac    Kslide as a fraction of V_FS, (0, 2); it must exceed the
 *                  part of the back-EMF the correction carries (about half
 *                  the largest back-EMF, note 5);
 *   maxerr_frac    MaxSMCError as a fraction of I_FS, > 0; recommended:
 *                  SMC_MAXERR_DEADBEAT(...) (note 3);
 *   omega_fs_hz    electrical frequency of Q15 full-scale speed (Hz);
 *   min_speed_hz   minimum closed-loop electrical speed (Hz): the K floor
 *                  and the validity threshold;
 *   irp_percalc    PWM periods per speed calculation, 1..256;
 *   speed_lpf_hz   cut-off of the speed filter (Hz, at the speed-loop rate);
 *   ke_v_per_hz    back-EMF, phase peak volts per electrical Hz (0 = no
 *                  back-EMF consistency check; valid then only tests speed).
 * Each range is checked; a failure names the quantity in the compiler's
 * first error, a bit-field 'smc_...' of negative width (q15.h). The core
 * (firmware/mc_derived.h) checks the parameters these come from first, so
 * that its builds name the parameter instead.
 */
#define SMC_PARAMS_INIT(r, l, ts, vfs, ifs, ks, me, wfs, fmin, irp, fspd, ke)                      \
    {                                                                                              \
        /* f */ (q15_t)(Q15_CHECK_EXPR(smc_Ts_R_over_L_must_be_in_0_1,                             \
                                       SMC_Y_(r, l, ts) > 0.0 && SMC_Y_(r, l, ts) <= 1.0) +        \
                        Q15(SMC_F_(r, l, ts))), /* g */                                            \
            (q15_t)(Q15_CHECK_EXPR(smc_G_Ts_over_L_times_2Vfs_over_Ifs_must_be_in_1e_4_to_128,     \
                                   SMC_GE_(r, l, ts, vfs, ifs) >= 1e-4 &&                          \
                                       SMC_GE_(r, l, ts, vfs, ifs) < 128.0) +                      \
                    Q15_MANT7_OF(SMC_GE_(r, l, ts, vfs, ifs))),                                    \
            /* g_shift */ (uint8_t)Q15_SHIFT7_OF(SMC_GE_(r, l, ts, vfs, ifs)), /* kslide */        \
            (q15_t)(Q15_CHECK_EXPR(smc_Kslide_must_be_in_0_2_of_V_FS, (ks) > 0.0 && (ks) < 2.0) +  \
                    Q15(SMC_KSE_(ks))), /* max_err */                                              \
            (q15_t)(Q15_CHECK_EXPR(smc_MaxSMCError_must_be_in_1_LSB_to_1,                          \
                                   (me) >= 1.0 / 32768.0 && (me) < 1.0) +                          \
                    Q15(me)), /* kz */                                                             \
            (q15_t)(Q15_CHECK_EXPR(smc_Kslide_over_MaxSMCError_must_be_below_32768,                \
                                   SMC_KZ_(ks, me) < 32768.0) +                                    \
                    SMC_MANT_OF(SMC_KZ_(ks, me))),                                                 \
            /* kz_shift */ (uint8_t)SMC_SHIFT_OF(SMC_KZ_(ks, me)), /* k_per_omega */               \
            (q15_t)(Q15_CHECK_EXPR(smc_2pi_omega_fs_Ts_must_be_below_1, SMC_KPW_(ts, wfs) < 1.0) + \
                    Q15(SMC_KPW_(ts, wfs))), /* k_min */                                           \
            (q15_t)(Q15_CHECK_EXPR(smc_min_speed_must_be_in_0_omega_fs,                            \
                                   (fmin) > 0.0 && (fmin) < (wfs) &&                               \
                                       SMC_KPW_(ts, fmin) >= 1.0 / 32768.0) +                      \
                    Q15(SMC_KPW_(ts, fmin))),                                                      \
            /* omega_min */ Q15((double)(fmin) / (double)(wfs)), /* kspeed */                      \
            (q15_t)(Q15_CHECK_EXPR(smc_speed_scale_1_over_2_IRP_Ts_omega_fs_must_be_below_32768,   \
                                   SMC_KSPEED_(ts, wfs, irp) < 32768.0) +                          \
                    SMC_MANT_OF(SMC_KSPEED_(ts, wfs, irp))),                                       \
            /* kspeed_shift */ (uint8_t)SMC_SHIFT_OF(SMC_KSPEED_(ts, wfs, irp)), /* irp_percalc */ \
            (uint16_t)(Q15_CHECK_EXPR(smc_IRP_PERCALC_must_be_in_1_256,                            \
                                      (irp) >= 1 && (irp) <= 256) +                                \
                       (irp)), /* k_speed_lpf */                                                   \
            (q15_t)(Q15_CHECK_EXPR(smc_speed_lpf_2pi_fc_IRP_Ts_must_be_in_0_1,                     \
                                   SMC_KSLPF_(ts, irp, fspd) > 0.0 &&                              \
                                       SMC_KSLPF_(ts, irp, fspd) < 1.0) +                          \
                    Q15(SMC_KSLPF_(ts, irp, fspd))), /* emf_gain */                                \
            (q15_t)(Q15_CHECK_EXPR(smc_Ke_omega_fs_over_Vfs_gain_must_be_in_0_8,                   \
                                   SMC_EMFG_(ke, wfs, vfs) >= 0.0 &&                               \
                                       SMC_EMFG_(ke, wfs, vfs) < 8.0) +                            \
                    Q15(SMC_EMFG_(ke, wfs, vfs) / 8.0)),                                           \
            /* emf_shift */ (uint8_t)3,                                                            \
            /* tf_mdc */ SMC_Q12(SMC_MDC_(r, l, ts, vfs, ifs, ks, me)),                            \
            /* tf_b10 */ SMC_Q12(SMC_B10_(r, l, ts, vfs, ifs, ks, me)),                            \
            /* tf_b1k */ SMC_Q12(SMC_B1K_(r, l, ts, vfs, ifs, ks, me)),                            \
            /* tf_b2 */ Q15(SMC_B2_(r, l, ts, vfs, ifs, ks, me)),                                  \
            /* tf_xadv */ Q15(SMC_XADV_(r, l, ts, vfs, ifs, ks, me))                               \
    }

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
    uint8_t startup; /* windows left in the start-up phase (note 8) */
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

/* Fixed design constants of the speed path (notes 7-8). */
#define SMC_LAG_DEADZONE      1024 /* settled: lag steps below 5.6 deg per window are noise */
#define SMC_LAG_TRANSIENT     5461 /* a lag step above 30 deg starts a tracking phase */
#define SMC_STARTUP_WINDOWS   32U  /* tracking phase after reset, preset or a transient */
#define SMC_K_LPF_SHIFT       2U   /* settled: K follows the speed 4 times slower */
#define SMC_K_LPF_SHIFT_START 1U   /* tracking: 2 times slower */
#define SMC_EMF_RAW_K_SHIFT   2    /* the model back-EMF is smoothed with 4 K */

/* Band of emf_ratio (Q12) inside which the back-EMF counts as consistent
 * with the speed: 0.5 .. 2.0 of the expected amplitude. */
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
 * window for the slow side (note 10). */
void smc_window_end(smc_t *s);

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
 * Scaling: Q27 arithmetic with 16 x 16 products only; two atan2 calls. */
angle_q15_t smc_phase_lead(const smc_params_t *p, q15_t k, q15_t x);

/* Speed (Q15 of omega_fs, signed, saturated at +-32767) from a window's sum
 * of angle steps (angle counts, |sum| <= 256 * 32768): note 7. */
q15_t smc_speed_from_steps(const smc_params_t *p, int32_t sum);

/* Read-outs. */
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

/*
 * Notes
 *
 * 1. Timing and indices. Samples are one period apart, at s_n. The mean
 *    voltage over [s_(n-1), s_n] is what carried the current from
 *    i(s_(n-1)) to i(s_n) (which commands make it up is the core's
 *    business, firmware/mc.h note 2). The model step in smc_update(n)
 *    therefore uses v_applied with e and z from call n-1, and compares the
 *    result with i_meas(n). The outputs of call n refer to s_n.
 *
 * 2. Discretisation and scales. With the voltage constant over a period the
 *    exact (zero-order-hold) solution of L di/dt = v - R i - e is
 *    i(n) = F i(n-1) + G (v(n-1) - Ebar(n-1)), F = exp(-Ts R/L),
 *    G = (1 - F)/R, where Ebar(m) is the back-EMF weighted over [t_m,
 *    t_(m+1)]. AN1078's F = 1 - Ts R/L, G = Ts/L truncate both series; for
 *    the Hurst motor (Ts R/L = 0.0695) that makes G 3.5 % too large, which
 *    a double-precision run shows as a constant +0.25 degree bias; the exact
 *    values cost nothing (compile time) and remove it. Above the base speed
 *    (field weakening) the back-EMF exceeds the inverter's V_FS (22 V peak
 *    at 5300 rpm against V_FS = 13.9 V on 24 V), and the correction z must
 *    carry about 0.65 of it (note 5), so z, e, e_final and Kslide use
 *    E_FS = 2 V_FS; G is scaled to match (G E_FS / I_FS).
 *
 * 3. The observer's transfer function (linear band, |err| < MaxSMCError).
 *    Write Ebar(m) = E(t_m) exp(j x / 2) with x = omega Ts: for a rotating
 *    back-EMF the ZOH weighting is the value at mid-period to within
 *    0.05 degree (up to omega L / R = 2). With eps = i_est - i, c = G Kz
 *    (Kz = Kslide / MaxSMCError) and p = F - c:
 *      eps(n) = F eps(n-1) + G (Ebar(n-1) - e(n-1) - z(n-1)), z(n) = Kz eps(n)
 *      =>  z = D (Ebar - e),  D = c q^-1 / (1 - p q^-1)
 *    The first stage e = Lk z, Lk = K / (1 - (1 - K) q^-1), is inside this
 *    loop, so e = H1 Ebar with
 *      H1 = Lk D / (1 + Lk D) = K c q^-1 / [(1 - (1-K) q^-1)(1 - p q^-1) + K c q^-1]
 *    and the second stage is plain: H2 = Lk. At q^-1 = exp(-j x), with
 *    u = 1 - exp(-j x) = (1 - cos x) + j sin x, the denominators are
 *      D1 = K (1 + c - p) + B1 u + B2 u^2,   B1 = 1 - p - K (1 + c - 2p),
 *                                            B2 = p (1 - K)
 *      D2 = K + (1 - K) u
 *    (this form has no cancellation: its constant term is exactly the DC
 *    value, so coefficients in Q12/Q15 are enough). Hence
 *      e_final(n) = H1 H2 exp(j x / 2) E(t_n),
 *      arg = -x (the q^-1 of D) + x / 2 (ZOH) - arg D1 - arg D2,
 *    and the lead that puts theta on the rotor at t_n is
 *      comp(K, x) = arg D1 + arg D2 + x / 2.
 *    The constants mdc = 1 + c - p, B1 = b10 + K b1k, p and the x / 2 term
 *    are computed by SMC_PARAMS_INIT; smc_phase_lead evaluates the rest once
 *    per speed window (1 - cos x and sin x by their Taylor series in Q27,
 *    two atan2 arctangents). Measured: smc_phase_lead is within 0.017
 *    degree of the formula in double, and the formula within 0.05 degree of
 *    the lag of a double-precision copy of the observer run on the exact
 *    plant (test_smc.c). For the Hurst settings (dead-beat band, note 5) the
 *    lag is 71.5 degrees at 500 rpm and 63.1 at 5300 rpm: a constant 90
 *    would over-compensate by 18 to 27 degrees. The plain-filter reading of
 *    the first stage (45 degrees per stage) is wrong because e is fed back
 *    into the model: it only has to absorb what z does not carry.
 *    With K floored (below the minimum speed) the same formula holds with
 *    K > x, so theta stays defined there; for reverse rotation the stages'
 *    response is the complex conjugate, so the lead is negated (and pi added,
 *    note 6).
 *
 * 4. Relay mode. When c >= 1 + F the linear band is unstable as a linear
 *    loop (|p| >= 1): the correction chatters between +-Kslide (AN1078's
 *    published gains, Kslide 0.85 and MaxSMCError 0.005 of full scale, are
 *    in this mode). Only the average of z is then defined, by the ideal
 *    sliding condition z = Ebar - e, which gives D1 = 2K + (1 - K) u, B2 = 0
 *    and no q^-1 or ZOH term (the relay's switching lag and the ZOH half
 *    period cancel to within about a degree in simulation). The chatter
 *    leaves 2 to 13 degrees of ripple and bias (test_smc.c); the lag
 *    correction of note 8 is off in this mode.
 *
 * 5. Choosing Kslide and MaxSMCError. Recommended: MaxSMCError =
 *    SMC_MAXERR_DEADBEAT(...) = Kslide G / F, which makes c = F and p = 0:
 *    the model error is corrected in one period (dead-beat), z(n) =
 *    F (Ebar(n-1) - e(n-1)), and the loop is linear and ripple-free. In
 *    steady state |e| is about 0.48 |E| and |z| about 0.65 |E|; to recover
 *    from any state (e near 0 while the motor turns) Kslide must exceed the
 *    largest back-EMF: 1.8 V_FS for the Hurst up to 5300 rpm on 24 V. The
 *    low-speed gain |e_final / E| of the two stages is then about 0.30
 *    (c / |mdc + j b10| / sqrt 2); SMC_STAGE_GAIN (0.31) turns Ke into the
 *    expected amplitude for the consistency figure emf_ratio.
 *
 * 6. Angles. theta_raw = atan2(-ef_alpha, ef_beta) (the back-EMF leads the
 *    rotor flux by 90 degrees); for omega < 0 the back-EMF is reversed, so pi
 *    is added. theta estimates the rotor angle at s_n, the sample; for the
 *    inverse Park the core adds the delay to the middle of the period its
 *    voltage acts in (firmware/mc.h note 2; the output side is the core's).
 *
 * 7. Speed. The angle steps (angle_sub, each in [-pi, pi)) are summed in an
 *    int32 over IRP_PERCALC <= 256 periods, so the sum (at most 2^23) cannot
 *    overflow at any speed below the Nyquist limit (a 16-bit sum over 1 ms
 *    wraps above 30,000 electrical rpm; 17,000 rpm with 2 pole pairs is
 *    34,000). omega = sum / (2 IRP Ts omega_fs) in Q15, computed as two
 *    16 x 16 products and saturated at +-32767, then a first-order filter
 *    (speed_lpf_hz, at the speed-loop rate). The stages' lag depends on
 *    x / K: a speed error changes K, which turns theta_raw, which the next
 *    window reads as speed (a positive loop of gain about 0.9 at the stages'
 *    time constant). K therefore follows |omega| through a further filter
 *    4 times slower (SMC_K_LPF_SHIFT; 2 times in the tracking phase of note
 *    8); since comp uses the actual K and the estimated x separately, a
 *    lagging K costs no steady accuracy.
 *
 * 8. Lag correction of the speed. In the linear band the correction gives
 *    the back-EMF without any filter: z(n) - p z(n-1) + c e(n-1) =
 *    c Ebar(n-1) (note 3). It is smoothed with 4 K (SMC_EMF_RAW_K_SHIFT)
 *    and at each window end its angle minus theta_raw is the lag the stages
 *    have at that moment, transients included. The change of that lag over
 *    the window is added to the window's angle sum, which removes the
 *    stages' transients (a wrong initial state, K moving) from the speed.
 *    Its noise is that of an unfiltered back-EMF, so it is used in full only
 *    in a tracking phase of SMC_STARTUP_WINDOWS windows, started by
 *    smc_reset, smc_preset_speed or a lag step above SMC_LAG_TRANSIENT
 *    (30 degrees), during which K also follows the speed faster
 *    (SMC_K_LPF_SHIFT_START). Settled, only the part beyond a dead zone of
 *    SMC_LAG_DEADZONE (5.6 degrees, above the noise of a 10-bit ADC) is
 *    added, and the speed keeps the smoothness of theta_raw. Measured
 *    (Hurst, worst of 24 initial states): 24.6 ms to 2 degrees at 500 rpm,
 *    15.1 ms at 1000 rpm; without the correction (trial run) 56 and 35 ms.
 *
 * 9. Validity. valid = |omega| >= omega_min and, when Ke is given,
 *    0.5 <= emf_ratio <= 2. Below the minimum speed K stays at its floor,
 *    the speed and the angle keep being computed (saturating, never
 *    wrapping) but valid is false; a stalled rotor with a speed estimate
 *    left over drops the flag through the speed and the ratio.
 *
 * 10. Fast and slow sides. Everything that changes only once per window
 *    (the speed, K, k_w, the compensation, the back-EMF figures, valid) is
 *    computed by smc_slow_step from a snapshot (win) that smc_window_end
 *    takes, and handed back in res, which smc_apply takes over at a fixed
 *    period after the window end (the caller's choice). So the slow side
 *    may run at any time in between (on the dsPIC, in a lower-priority
 *    interrupt), the outcome does not depend on when, and each side writes
 *    only its own fields: win and the fast state belong to the fast side,
 *    res and slow to the slow side. The price is that delay: K and the
 *    compensation follow the speed a fraction of a window later than they
 *    would in one context, which the stages' own time constant (about
 *    1 / K, 12 ms at the lowest speed) dwarfs. A reset or
 *    preset changes the epoch; the slow side restarts its filters when it
 *    sees the new epoch in a window, and results of an older epoch are
 *    dropped. A window a reset or preset cut short measures no speed (its
 *    angle sum spans fewer periods than the scaling assumes).
 */

/* The per-period step's definition (inline; smc_update above). */
#include "smc_update.h"

#endif /* SMC_H */
