/* smc.h - sliding-mode current observer: rotor angle and speed from alpha/beta currents and
 * voltages. */
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
 *   theta_raw(n) = atan2(-ef_alpha, ef_beta)                 CORDIC, foc/cordic.h
 *   theta(n) = theta_raw(n) + comp(omega) (+ pi when omega < 0)
 *
 * with F = 1 - Ts R / L and G = Ts / L (per-phase R and L), K = Kslf =
 * omega Ts (the cut-off at the electrical frequency), floored at the value of
 * the minimum closed-loop speed. Every IRP_PERCALC periods the angle steps
 * of theta_raw are summed in 32 bits, scaled to a speed, filtered, and the
 * new speed sets K, the compensation comp (derived in notes 2-5 from the
 * observer's discrete transfer functions and the loop delay) and the
 * validity flag.
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
 *   i_meas     the alpha/beta currents sampled at the start of period n
 *              (instant t_n), offset removed;
 *   v_applied  the alpha/beta voltage the inverter applied during the
 *              previous period [t_(n-1), t_n], i.e. the one the current
 *              evolved under between the previous sample and this one. The
 *              core passes the command it computed in period n-2 (applied in
 *              period n-1), after dead-time compensation, scaled to the bus
 *              actually present: the estimator must be fed the voltage that
 *              was applied, not the one being computed now.
 *   theta      estimates the rotor electrical angle at t_n, the instant
 *              i_meas was sampled (use it for Park of i_meas). A voltage
 *              computed now is applied over [t_(n+1), t_(n+2)]; the core may
 *              advance theta by 1.5 omega Ts for the inverse Park (note 6).
 *
 * Cost (make bench, host callgrind; dsPIC: no division and no float in the
 * per-period path): see smc.c. Once every IRP_PERCALC periods the speed
 * update adds one 32 x 16 scaling, two CORDIC arctangents (the compensation)
 * and one 32 / 16 division (the back-EMF consistency figure).
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

/* An expression that is 0, and fails to compile with the error
 * "negative width in bit-field '<name>'" when cond is false. */
#define SMC_CHECK(name, cond) ((int)(0 * sizeof(struct { unsigned name : ((cond) ? 1 : -1); })))

/* Smallest shift s in 0..15 with |x| < 2^s (x >= 2^15 gives 16, which the
 * callers reject). */
#define SMC_SHIFT_OF(x)                                                                            \
    ((x) < 1.0       ? 0                                                                           \
     : (x) < 2.0     ? 1                                                                           \
     : (x) < 4.0     ? 2                                                                           \
     : (x) < 8.0     ? 3                                                                           \
     : (x) < 16.0    ? 4                                                                           \
     : (x) < 32.0    ? 5                                                                           \
     : (x) < 64.0    ? 6                                                                           \
     : (x) < 128.0   ? 7                                                                           \
     : (x) < 256.0   ? 8                                                                           \
     : (x) < 512.0   ? 9                                                                           \
     : (x) < 1024.0  ? 10                                                                          \
     : (x) < 2048.0  ? 11                                                                          \
     : (x) < 4096.0  ? 12                                                                          \
     : (x) < 8192.0  ? 13                                                                          \
     : (x) < 16384.0 ? 14                                                                          \
     : (x) < 32768.0 ? 15                                                                          \
                     : 16)

/* The same for 0 <= x < 128 only (8 comparisons: keeps the expansion small). */
#define SMC_SHIFT7_OF(x)                                                                           \
    ((x) < 1.0    ? 0                                                                              \
     : (x) < 2.0  ? 1                                                                              \
     : (x) < 4.0  ? 2                                                                              \
     : (x) < 8.0  ? 3                                                                              \
     : (x) < 16.0 ? 4                                                                              \
     : (x) < 32.0 ? 5                                                                              \
     : (x) < 64.0 ? 6                                                                              \
                  : 7)
#define SMC_MANT7_OF(x) Q15((double)(x) / (double)(1L << SMC_SHIFT7_OF(x)))

/* Mantissa of x for the shift SMC_SHIFT_OF(x). */
#define SMC_MANT_OF(x) Q15((double)(x) / (double)(1L << SMC_SHIFT_OF(x)))

/* Q12 constant (range [-8, 8)), rounded half away from zero. */
#define SMC_Q12(x) ((q15_t)((x)*4096.0 + ((x) >= 0.0 ? 0.5 : -0.5)))

/* exp(-y) for 0 <= y <= 1 as a constant expression (Taylor, 13 terms,
 * error < 2e-11). */
/* exp(-y) for 0 < y <= 1 as a constant expression: the (3,3) Pade
 * approximant, relative error < 3e-7 at y = 1 and < 1e-13 at y = 0.07 (the
 * Hurst motor); it keeps the macro expansion small (y appears 6 times). */
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
 * "negative width in bit-field 'smc_...'" error.
 */
#define SMC_PARAMS_INIT(r, l, ts, vfs, ifs, ks, me, wfs, fmin, irp, fspd, ke)                      \
    {                                                                                              \
        /* f */ (q15_t)(SMC_CHECK(smc_Ts_R_over_L_must_be_in_0_1,                                  \
                                  SMC_Y_(r, l, ts) > 0.0 && SMC_Y_(r, l, ts) <= 1.0) +             \
                        Q15(SMC_F_(r, l, ts))), /* g */                                            \
            (q15_t)(SMC_CHECK(smc_G_Ts_over_L_times_2Vfs_over_Ifs_must_be_in_1e_4_to_128,          \
                              SMC_GE_(r, l, ts, vfs, ifs) >= 1e-4 &&                               \
                                  SMC_GE_(r, l, ts, vfs, ifs) < 128.0) +                           \
                    SMC_MANT7_OF(SMC_GE_(r, l, ts, vfs, ifs))),                                    \
            /* g_shift */ (uint8_t)SMC_SHIFT7_OF(SMC_GE_(r, l, ts, vfs, ifs)), /* kslide */        \
            (q15_t)(SMC_CHECK(smc_Kslide_must_be_in_0_2_of_V_FS, (ks) > 0.0 && (ks) < 2.0) +       \
                    Q15(SMC_KSE_(ks))), /* max_err */                                              \
            (q15_t)(SMC_CHECK(smc_MaxSMCError_must_be_in_1_LSB_to_1,                               \
                              (me) >= 1.0 / 32768.0 && (me) < 1.0) +                               \
                    Q15(me)), /* kz */                                                             \
            (q15_t)(SMC_CHECK(smc_Kslide_over_MaxSMCError_must_be_below_32768,                     \
                              SMC_KZ_(ks, me) < 32768.0) +                                         \
                    SMC_MANT_OF(SMC_KZ_(ks, me))),                                                 \
            /* kz_shift */ (uint8_t)SMC_SHIFT_OF(SMC_KZ_(ks, me)), /* k_per_omega */               \
            (q15_t)(SMC_CHECK(smc_2pi_omega_fs_Ts_must_be_below_1, SMC_KPW_(ts, wfs) < 1.0) +      \
                    Q15(SMC_KPW_(ts, wfs))), /* k_min */                                           \
            (q15_t)(SMC_CHECK(smc_min_speed_must_be_in_0_omega_fs,                                 \
                              (fmin) > 0.0 && (fmin) < (wfs) &&                                    \
                                  SMC_KPW_(ts, fmin) >= 1.0 / 32768.0) +                           \
                    Q15(SMC_KPW_(ts, fmin))),                                                      \
            /* omega_min */ Q15((double)(fmin) / (double)(wfs)), /* kspeed */                      \
            (q15_t)(SMC_CHECK(smc_speed_scale_1_over_2_IRP_Ts_omega_fs_must_be_below_32768,        \
                              SMC_KSPEED_(ts, wfs, irp) < 32768.0) +                               \
                    SMC_MANT_OF(SMC_KSPEED_(ts, wfs, irp))),                                       \
            /* kspeed_shift */ (uint8_t)SMC_SHIFT_OF(SMC_KSPEED_(ts, wfs, irp)), /* irp_percalc */ \
            (uint16_t)(SMC_CHECK(smc_IRP_PERCALC_must_be_in_1_256, (irp) >= 1 && (irp) <= 256) +   \
                       (irp)), /* k_speed_lpf */                                                   \
            (q15_t)(SMC_CHECK(smc_speed_lpf_2pi_fc_IRP_Ts_must_be_in_0_1,                          \
                              SMC_KSLPF_(ts, irp, fspd) > 0.0 &&                                   \
                                  SMC_KSLPF_(ts, irp, fspd) < 1.0) +                               \
                    Q15(SMC_KSLPF_(ts, irp, fspd))), /* emf_gain */                                \
            (q15_t)(SMC_CHECK(smc_Ke_omega_fs_over_Vfs_gain_must_be_in_0_8,                        \
                              SMC_EMFG_(ke, wfs, vfs) >= 0.0 && SMC_EMFG_(ke, wfs, vfs) < 8.0) +   \
                    Q15(SMC_EMFG_(ke, wfs, vfs) / 8.0)),                                           \
            /* emf_shift */ (uint8_t)3,                                                            \
            /* tf_mdc */ SMC_Q12(SMC_MDC_(r, l, ts, vfs, ifs, ks, me)),                            \
            /* tf_b10 */ SMC_Q12(SMC_B10_(r, l, ts, vfs, ifs, ks, me)),                            \
            /* tf_b1k */ SMC_Q12(SMC_B1K_(r, l, ts, vfs, ifs, ks, me)),                            \
            /* tf_b2 */ Q15(SMC_B2_(r, l, ts, vfs, ifs, ks, me)),                                  \
            /* tf_xadv */ Q15(SMC_XADV_(r, l, ts, vfs, ifs, ks, me))                               \
    }

/* ---- state --------------------------------------------------------------- */

typedef struct {
    const smc_params_t *p;
    ab_q15_t i_est; /* model current, Q15 of I_FS */
    ab_q15_t z;     /* sliding-mode correction, Q15 of E_FS */
    ab_q15_t e;     /* first stage e rounded to Q15 (what the model is fed) */
    lpf_t e_alpha;  /* first stage e, Q31 of E_FS */
    lpf_t e_beta;
    lpf_t ef_alpha; /* second stage e_final, Q31 of E_FS */
    lpf_t ef_beta;
    lpf_t w_alpha; /* model back-EMF from the correction (note 8), smoothed, Q31 of E_FS */
    lpf_t w_beta;
    lpf_t k_lpf;           /* x = |omega| 2 pi Ts filtered again: K before its floor, Q31 */
    lpf_t omega_lpf;       /* filtered speed, Q31 of omega_fs */
    int32_t dtheta_sum;    /* sum of theta_raw steps this window, angle counts */
    uint16_t count;        /* periods in this window, 0..irp_percalc-1 */
    angle_q15_t theta_raw; /* atan2 of ef, uncompensated */
    angle_q15_t theta;     /* compensated: the rotor angle at t_n */
    angle_q15_t comp;      /* compensation added to theta_raw (incl. pi if omega < 0) */
    angle_q15_t lag;       /* lag of theta_raw behind the model back-EMF at the last window end */
    q15_t omega_raw;       /* last unfiltered window speed, Q15 of omega_fs */
    q15_t omega;           /* filtered speed, Q15 of omega_fs, signed */
    q15_t k;               /* Kslf in use, Q15 */
    q15_t emf_mag;         /* |ef| (Q15 of E_FS), refreshed every window */
    q15_t emf_ratio;       /* |ef| / expected at |omega|, Q12 (4096 = as expected) */
    bool valid;            /* |omega| >= omega_min and emf_ratio inside the band */
    bool lag_valid;        /* lag holds a measurement (false until the first window end) */
} smc_t;

/* Fixed design constants of the speed path (notes 7-8). */
#define SMC_LAG_DEADZONE    1024 /* lag steps below 1024 counts (5.6 deg) per window are noise */
#define SMC_K_LPF_SHIFT     2    /* K follows the speed through a filter 4 times slower */
#define SMC_EMF_RAW_K_SHIFT 2    /* the model back-EMF is smoothed with 4 K */

/* Band of emf_ratio (Q12) inside which the back-EMF counts as consistent
 * with the speed: 0.5 .. 2.0 of the expected amplitude. */
#define SMC_EMF_RATIO_ONE 4096
#define SMC_EMF_RATIO_LO  2048
#define SMC_EMF_RATIO_HI  8192

/* ---- API ----------------------------------------------------------------- */

/* Bind the parameters (kept by pointer: they must outlive s) and reset. */
void smc_init(smc_t *s, const smc_params_t *p);

/* All state to zero: model currents, corrections and filters 0, speed 0
 * (so K starts at its floor), window empty, theta 0, not valid. */
void smc_reset(smc_t *s);

/* Preset the speed (Q15 of omega_fs, signed) at a hand-off from open loop:
 * the speed filter, K and the compensation take the value at once; the
 * window restarts. The back-EMF filters are left as they are (the observer
 * runs during the open-loop start-up and has already converged). */
void smc_preset_speed(smc_t *s, q15_t omega);

/* One PWM period: see the timing contract above. Scaling and overflow:
 * model and correction in 32-bit products rounded to Q15 and saturated
 * (|v - e - z| saturates at full scale before the multiply by G); filters
 * with 32-bit states (foc/lpf.h); the angle-step sum is 32 bits, so no
 * speed below the Nyquist limit (|delta theta| < pi per period) wraps; the
 * speed saturates at +-omega_fs. No division in the per-period path. */
void smc_update(smc_t *s, ab_q15_t i_meas, ab_q15_t v_applied);

/* The phase lead (angle counts) that cancels the lag of the two stages and
 * the loop delay for a positive frequency x (electrical rad per PWM period,
 * Q15, 0 <= x < 1) with stage coefficient k (Q15, >= 1): notes 2-4.
 * smc_update adds it (negated, plus pi, for reverse rotation) to theta_raw.
 * Scaling: Q27 arithmetic with 16 x 16 products only; two CORDIC calls. */
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
 * 1. Timing. (to be completed: the derivation of the compensation.)
 */

#endif /* SMC_H */
