/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* smc_params.h - the observer's parameters (smc_params_t) from motor and board data, at compile
 * time. */
#ifndef SMC_PARAMS_H
#define SMC_PARAMS_H

#include "q15.h"
#include "smc.h"

/*
 * SMC_PARAMS_INIT(r_ohm, l_h, ts_s, v_fs_v, i_fs_a, kslide_frac, maxerr_frac,
 *                 omega_fs_hz, min_speed_hz, irp_percalc, speed_lpf_hz,
 *                 ke_v_per_hz)
 * An initialiser for a `static const smc_params_t`:
 *   r_ohm, l_h     per-phase resistance and inductance (half the
 *                  line-to-line meter reading);
 *   ts_s           PWM period (s);
 *   v_fs_v, i_fs_a the voltage and current full scales (smc.h);
 *   kslide_frac    Kslide as a fraction of V_FS, (0, 2); it must exceed the
 *                  part of the back-EMF the correction carries (about half
 *                  the largest back-EMF, note 5);
 *   maxerr_frac    MaxSMCError as a fraction of I_FS, [1 LSB, 1); recommended:
 *                  SMC_MAXERR_DEADBEAT(...) (note 3);
 *   omega_fs_hz    electrical frequency of Q15 full-scale speed (Hz);
 *   min_speed_hz   minimum closed-loop electrical speed (Hz): the K floor
 *                  and the validity threshold;
 *   irp_percalc    PWM periods per speed calculation, 1..256;
 *   speed_lpf_hz   cut-off of the speed filter (Hz, at the speed-loop rate);
 *   ke_v_per_hz    back-EMF, phase peak volts per electrical Hz (0 = no
 *                  back-EMF consistency check; valid then only tests speed).
 * Every field is computed in double and range-checked at compile time; a
 * failure names the quantity in the compiler's first error, a bit-field
 * 'smc_...' of negative width (q15.h). The core (firmware/mc_derived.h)
 * checks the parameters these come from first, so that its builds name the
 * parameter instead. How each field follows from the motor model (notes
 * 2-5, 7): docs/estimator.md, "Derivation".
 *
 * The macros below are constant expressions and C has no way to name an
 * intermediate value, so every use of a quantity writes it out again: the
 * expansion grows with the product of the nesting depths. Each field is
 * therefore written so that its arguments appear as few times as the
 * rounding allows (a rounding step that needs its argument once, the mode
 * test moved in front of the rounding), always with the same floating-point
 * operations, so the integers are those of the plain formulas.
 */

/* ---- the derived quantities, in double (engineering units in, ratios out) --- */

/* exp(-y) for 0 < y <= 1 as a constant expression: the (3,3) Pade
 * approximant (y appears 6 times; accuracy: docs/estimator.md). */
#define SMC_EXPNEG_(y)                                                                             \
    ((1.0 - (y) * (0.5 - (y) * (0.1 - (y) / 120.0))) /                                             \
     (1.0 + (y) * (0.5 + (y) * (0.1 + (y) / 120.0))))

/* y = Ts R / L; the model's F = exp(-y) and G = (1 - F) / R, in I_FS per V_FS. */
#define SMC_Y_(r, l, ts) ((double)(ts) * (double)(r) / (double)(l))
#define SMC_F_(r, l, ts) SMC_EXPNEG_(SMC_Y_(r, l, ts))
#define SMC_G_(r, l, ts, vfs, ifs)                                                                 \
    ((1.0 - SMC_F_(r, l, ts)) / (double)(r) * (double)(vfs) / (double)(ifs))
/* G and Kslide in the back-EMF scale E_FS = SMC_EMF_FS_RATIO * V_FS. */
#define SMC_GE_(r, l, ts, vfs, ifs) (SMC_G_(r, l, ts, vfs, ifs) * SMC_EMF_FS_RATIO)
#define SMC_KSE_(ks)                ((double)(ks) / SMC_EMF_FS_RATIO)
/* Kz = Kslide / MaxSMCError (E_FS per I_FS). */
#define SMC_KZ_(kslide, maxerr) (SMC_KSE_(kslide) / (double)(maxerr))
/* x per unit Q15 speed: 2 pi omega_fs Ts (rad per period). */
#define SMC_KPW_(ts, wfs) (6.283185307179586 * (double)(wfs) * (double)(ts))
/* Q15 speed per angle count summed over a window: 1 / (2 IRP Ts omega_fs). */
#define SMC_KSPEED_(ts, wfs, irp) (1.0 / (2.0 * (double)(irp) * (double)(ts) * (double)(wfs)))
/* Speed filter coefficient at the window rate: 2 pi fc IRP Ts. */
#define SMC_KSLPF_(ts, irp, fc) (6.283185307179586 * (double)(fc) * (double)(irp) * (double)(ts))

/* The linear band's loop gain c = G Kz and pole p = F - c (note 3). The
 * band is a linear loop when |p| < 1, i.e. c < 1 + F; otherwise the
 * observer chatters (relay mode, note 4) and the transfer-function
 * constants take their relay values. */
#define SMC_C_(r, l, ts, vfs, ifs, ks, me) (SMC_GE_(r, l, ts, vfs, ifs) * SMC_KZ_(ks, me))
#define SMC_LIN_(r, l, ts, vfs, ifs, ks, me)                                                       \
    (SMC_C_(r, l, ts, vfs, ifs, ks, me) < 1.0 + SMC_F_(r, l, ts))
#define SMC_P_(r, l, ts, vfs, ifs, ks, me) (SMC_F_(r, l, ts) - SMC_C_(r, l, ts, vfs, ifs, ks, me))
/* The transfer-function constants of the linear band (note 3): the
 * constant term mdc = 1 + c - p of the in-loop stage's denominator and B1 =
 * b10 + K b1k; in relay mode mdc = 2, b10 = 1, b1k = -1, B2 = 0, no
 * x / 2 advance (note 4). */
#define SMC_MDC_LIN_(r, l, ts, vfs, ifs, ks, me)                                                   \
    (1.0 + 2.0 * SMC_C_(r, l, ts, vfs, ifs, ks, me) - SMC_F_(r, l, ts))
#define SMC_B10_LIN_(r, l, ts, vfs, ifs, ks, me)                                                   \
    (1.0 - SMC_F_(r, l, ts) + SMC_C_(r, l, ts, vfs, ifs, ks, me))
#define SMC_B1K_LIN_(r, l, ts, vfs, ifs, ks, me)                                                   \
    (2.0 * SMC_F_(r, l, ts) - 1.0 - 3.0 * SMC_C_(r, l, ts, vfs, ifs, ks, me))
#define SMC_XADV_LIN (0.5 / 3.141592653589793) /* x / 2 in angle counts per Q15 rad */

/* Low-speed gain |ef| / |E| of the two stages (note 5): one constant for a
 * 0.5 .. 2 consistency band (figures: docs/estimator.md). */
#define SMC_STAGE_GAIN 0.31
/* The expected |ef| (fraction of E_FS) per unit Q15 speed. */
#define SMC_EMFG_(ke, wfs, vfs)                                                                    \
    ((double)(ke) * (double)(wfs) / ((double)(vfs)*SMC_EMF_FS_RATIO) * SMC_STAGE_GAIN)

/* MaxSMCError (fraction of I_FS) that makes the linear band dead-beat
 * (c = F, p = 0; note 3): the recommended choice. */
#define SMC_MAXERR_DEADBEAT(r, l, ts, vfs, ifs, kslide)                                            \
    ((double)(kslide)*SMC_G_(r, l, ts, vfs, ifs) / SMC_F_(r, l, ts))

/* ---- rounding to the stored formats ------------------------------------------- */

/* Raw Q15 of v for 0 <= v <= 1, with v written once: rounded half up, and
 * v >= 1 - 2^-16 saturates to 32767 by an integer step ((L + 1) 32767 /
 * 32768 is L for 0 <= L <= 32767 and 32767 for L = 32768). For such v it
 * is the integer Q15(v) gives (q15.h). */
#define SMC_Q15U_(v) ((q15_t)(((long)((v)*32768.0 + 0.5) + 1L) * 32767L / 32768L))

/* Raw Q15 of v for -1 < v <= 1 (v written three times), = Q15(v). */
#define SMC_Q15S_(v) ((v) >= 0.0 ? SMC_Q15U_(v) : (q15_t)(long)((v)*32768.0 - 0.5))

/* Q12 constant, range [-8, 8), rounded half away from zero; SMC_Q12U_ for
 * x >= 0 only (x written once). Converted through long: the same integer
 * in range, and no float-to-int16 overflow for an analyser to find in the
 * relay-mode initialiser's linear branch, which is never taken. */
#define SMC_Q12(x)   ((q15_t)(long)((x)*4096.0 + ((x) >= 0.0 ? 0.5 : -0.5)))
#define SMC_Q12U_(x) ((q15_t)(long)((x)*4096.0 + 0.5))

/* Smallest shift s in 0..15 with x < 2^s, for 0 <= x < 32768 (a larger x
 * gives 15, and the callers' range checks reject it): q15.h's 0..7
 * convention (Q15_SHIFT7_OF) extended by 8 for x >= 128 (x / 256 is exact
 * in any binary double). */
#define SMC_SHIFT_OF(x) ((x) < 128.0 ? Q15_SHIFT7_OF(x) : 8 + Q15_SHIFT7_OF((x) / 256.0))

/* Mantissas for the shifts Q15_SHIFT7_OF(x) (0 <= x < 128) and
 * SMC_SHIFT_OF(x) (0 <= x < 32768): x / 2^shift in [0, 1), the integers of
 * Q15_MANT7_OF and Q15(x / 2^shift). */
#define SMC_MANT7_OF(x) SMC_Q15U_((double)(x) / (double)(1L << Q15_SHIFT7_OF(x)))
#define SMC_MANT_OF(x)  SMC_Q15U_((double)(x) / (double)(1L << SMC_SHIFT_OF(x)))

/* ---- the initialiser ------------------------------------------------------------ */

/* The checks come first in each field; every value they admit lies where
 * the rounding step used for it is exact (SMC_Q15U_ for [0, 1], SMC_Q12U_
 * for >= 0): f in (0, 1] (0 < y <= 1), G in [1e-4, 128), Kslide / 2 and
 * MaxSMCError in (0, 1), Kz and the speed scale in (0, 32768), the
 * positive Ts and omega_fs that the minimum-speed check implies, mdc and
 * b10 >= 0 (c > 0, F <= 1), p in (-1, 1) in the linear band. */
#define SMC_PARAMS_INIT(r, l, ts, vfs, ifs, ks, me, wfs, fmin, irp, fspd, ke)                      \
    {                                                                                              \
        /* f */                                                                                    \
        (q15_t)(Q15_CHECK_EXPR(smc_Ts_R_over_L_must_be_in_0_1,                                     \
                               SMC_Y_(r, l, ts) > 0.0 && SMC_Y_(r, l, ts) <= 1.0) +                \
                SMC_Q15U_(SMC_F_(r, l, ts))), /* g */                                              \
            (q15_t)(Q15_CHECK_EXPR(smc_G_Ts_over_L_times_2Vfs_over_Ifs_must_be_in_1e_4_to_128,     \
                                   SMC_GE_(r, l, ts, vfs, ifs) >= 1e-4 &&                          \
                                       SMC_GE_(r, l, ts, vfs, ifs) < 128.0) +                      \
                    SMC_MANT7_OF(SMC_GE_(r, l, ts, vfs, ifs))),                                    \
            /* g_shift */ (uint8_t)Q15_SHIFT7_OF(SMC_GE_(r, l, ts, vfs, ifs)), /* kslide */        \
            (q15_t)(Q15_CHECK_EXPR(smc_Kslide_must_be_in_0_2_of_V_FS, (ks) > 0.0 && (ks) < 2.0) +  \
                    SMC_Q15U_(SMC_KSE_(ks))), /* max_err */                                        \
            (q15_t)(Q15_CHECK_EXPR(smc_MaxSMCError_must_be_in_1_LSB_to_1,                          \
                                   (me) >= 1.0 / 32768.0 && (me) < 1.0) +                          \
                    SMC_Q15U_(me)), /* kz */                                                       \
            (q15_t)(Q15_CHECK_EXPR(smc_Kslide_over_MaxSMCError_must_be_below_32768,                \
                                   SMC_KZ_(ks, me) < 32768.0) +                                    \
                    SMC_MANT_OF(SMC_KZ_(ks, me))),                                                 \
            /* kz_shift */ (uint8_t)SMC_SHIFT_OF(SMC_KZ_(ks, me)), /* k_per_omega */               \
            (q15_t)(Q15_CHECK_EXPR(smc_2pi_omega_fs_Ts_must_be_below_1, SMC_KPW_(ts, wfs) < 1.0) + \
                    SMC_Q15U_(SMC_KPW_(ts, wfs))), /* k_min */                                     \
            (q15_t)(Q15_CHECK_EXPR(smc_min_speed_must_be_in_0_omega_fs,                            \
                                   (fmin) > 0.0 && (fmin) < (wfs) &&                               \
                                       SMC_KPW_(ts, fmin) >= 1.0 / 32768.0) +                      \
                    SMC_Q15U_(SMC_KPW_(ts, fmin))),                                                \
            /* omega_min */ SMC_Q15U_((double)(fmin) / (double)(wfs)), /* kspeed */                \
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
                    SMC_Q15U_(SMC_KSLPF_(ts, irp, fspd))), /* emf_gain */                          \
            (q15_t)(Q15_CHECK_EXPR(smc_Ke_omega_fs_over_Vfs_gain_must_be_in_0_8,                   \
                                   SMC_EMFG_(ke, wfs, vfs) >= 0.0 &&                               \
                                       SMC_EMFG_(ke, wfs, vfs) < 8.0) +                            \
                    SMC_Q15U_(SMC_EMFG_(ke, wfs, vfs) / 8.0)),                                     \
            /* emf_shift */ (uint8_t)3, /* tf_mdc */                                               \
            (SMC_LIN_(r, l, ts, vfs, ifs, ks, me)                                                  \
                 ? SMC_Q12U_(SMC_MDC_LIN_(r, l, ts, vfs, ifs, ks, me))                             \
                 : (q15_t)8192), /* tf_b10 */                                                      \
            (SMC_LIN_(r, l, ts, vfs, ifs, ks, me)                                                  \
                 ? SMC_Q12U_(SMC_B10_LIN_(r, l, ts, vfs, ifs, ks, me))                             \
                 : (q15_t)4096), /* tf_b1k */                                                      \
            (SMC_LIN_(r, l, ts, vfs, ifs, ks, me)                                                  \
                 ? SMC_Q12(SMC_B1K_LIN_(r, l, ts, vfs, ifs, ks, me))                               \
                 : (q15_t)(-4096)), /* tf_b2 */                                                    \
            (SMC_LIN_(r, l, ts, vfs, ifs, ks, me) ? SMC_Q15S_(SMC_P_(r, l, ts, vfs, ifs, ks, me))  \
                                                  : (q15_t)0), /* tf_xadv */                       \
            (SMC_LIN_(r, l, ts, vfs, ifs, ks, me) ? SMC_Q15U_(SMC_XADV_LIN) : (q15_t)0)            \
    }

#endif /* SMC_PARAMS_H */
