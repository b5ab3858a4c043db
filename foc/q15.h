/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* q15.h - Q15 fixed-point types, constant macros and saturating primitives. */
#ifndef Q15_H
#define Q15_H

#include <stdbool.h>
#include <stdint.h>

#include "q15_dsp.h"

/*
 * Definitions, written once (see note 1 at the end of this file):
 *
 *  q15_t        int16_t, value = raw / 32768, range [-1, 1 - 2^-15].
 *               "1.0" is represented by 0x7FFF; -1 * -1 saturates to 0x7FFF.
 *  q31_t        int32_t, value = raw / 2^31 (the dsPIC accumulator's 1.31).
 *  angle_q15_t  int16_t binary angle: one electrical turn = 2^16 counts,
 *               -32768..32767 = -pi..pi. Angle sums wrap modulo 2^16 on
 *               purpose; the wrap is done in uint16_t (angle_add/angle_sub)
 *               so it is never signed overflow.
 *
 *  Rounding rule: every rounded result rounds to nearest with ties toward
 *  +infinity (add half an LSB, then arithmetic shift right). This is what
 *  the dsPIC DSP engine does with CORCON.RND = 1 (conventional rounding).
 *  Functions named *_trunc round toward -infinity (plain arithmetic shift).
 *
 *  Signed right shift of a negative value is arithmetic on every compiler
 *  this project supports (gcc, avr-gcc, XC16: all document it as
 *  implementation-defined and arithmetic). The code relies on it.
 *
 *  Left shifts are done on unsigned types (a left shift of a negative
 *  signed value is undefined in C99) after the range has been checked.
 */

typedef int16_t q15_t;
typedef int32_t q31_t;
typedef int16_t angle_q15_t;

#define Q15_MAX ((q15_t)0x7FFF)
#define Q15_MIN ((q15_t)(-0x7FFF - 1))
#define Q31_MAX ((q31_t)0x7FFFFFFFL)
#define Q31_MIN ((q31_t)(-0x7FFFFFFFL - 1L))

/* ---- compile-time checks ------------------------------------------------ */

/* Every compile-time check is a bit-field whose width is 1 when the
 * condition holds and -1 (illegal) when it does not, inside a sizeof. Why
 * not _Static_assert or an array size: the conditions compare floating
 * constants (volts, amps, seconds), and C99 and C11 admit no floating
 * operand in an integer constant expression, so each compiler decides for
 * itself. Every supported one (gcc, clang, avr-gcc, XC16's gcc 4.5) folds
 * such a condition to a constant where a bit-field width is read (clang's
 * -Wgnu-folding-constant, a warning outside -Wall/-Wextra). _Static_assert
 * is not portable here: clang refuses a floating condition even when it
 * holds ("not an integral constant expression"), gcc 4.5 has none, and
 * glibc's <sys/cdefs.h> redefines it in C99 mode. An array size would be a
 * variable-length array to clang and gcc 4.5. The bit-field is C89 syntax
 * and fails alike in C99 and C11 mode, the field's name in the first error
 * line:
 *   gcc, avr-gcc, XC16:  error: negative width in bit-field 'NAME'
 *   clang:               error: bit-field 'NAME' has negative width (-1)
 * The (int) cast makes a floating condition an integer one. */
#define Q15_CHECK_WIDTH_(cond) (((int)(cond)) ? 1 : -1)

/* An expression that is 0 when cond holds and stops the build naming
 * `name` when it does not. Usable inside constant expressions (static
 * initializers included), at file scope and in functions. */
#define Q15_CHECK_EXPR(name, cond)                                                                 \
    ((int)(0 * sizeof(struct { unsigned name : Q15_CHECK_WIDTH_(cond); })))

/* The same as a declaration, at file or block scope: one more declaration
 * of the array q15_check_[1] (C allows any number of compatible extern
 * declarations), so nothing needs a unique tag or name (no __COUNTER__) and
 * nothing is defined. */
#define Q15_CHECK_DECL(name, cond) extern char q15_check_[1 + Q15_CHECK_EXPR(name, cond)]

/* Q15_STATIC_ASSERT(cond, "why"), at file or block scope: the build stops
 * at this line, whose message says why, with "... bit-field
 * 'static_assertion_failed' ...". */
#define Q15_STATIC_ASSERT(cond, msg) Q15_CHECK_DECL(static_assertion_failed, cond)

/* 0 when x is inside [lo, hi]; outside, the build stops ("negative width in
 * bit-field 'q15_constant_out_of_range'"). */
#define Q15_RANGE_CHECK(x, lo, hi)                                                                 \
    Q15_CHECK_EXPR(q15_constant_out_of_range, (x) >= (lo) && (x) <= (hi))

/* Raw value of x * 32768 rounded half away from zero, 1.0 saturating to
 * 32767; only for x already range-checked. Unlike Q15() it also works on a
 * value known only at run time (the tests sweep it). */
#define Q15_ROUND_(x)                                                                              \
    ((x)*32768.0 >= 32767.5 ? 32767L : (long)((x)*32768.0 + ((x) >= 0 ? 0.5 : -0.5)))

/* Q15(x): a compile-time Q15 constant from a real number in [-1, 1].
 * Scales symmetrically by 32768 and rounds to nearest; 1.0 (and anything
 * that rounds to 32768) gives 0x7FFF. Outside [-1, 1] the build fails. */
#define Q15(x) ((q15_t)(Q15_RANGE_CHECK((x), -1.0, 1.0) + Q15_ROUND_(x)))

/* Q15 of x / fullscale, e.g. Q15_SCALED(1.5, 4.4) for 1.5 A on a 4.4 A scale. */
#define Q15_SCALED(x, fullscale) Q15((double)(x) / (double)(fullscale))

/* A coefficient x >= 1 is kept as a Q15 mantissa and a named left shift,
 * value = mant * 2^shift / 32768, with shift in 0..7 (a dsPIC accumulator's
 * guard bits): Q15_SHIFT7_OF(x) is the smallest shift with x < 2^shift, and
 * Q15_MANT7_OF(x) the mantissa for it. Constant expressions, for x in
 * [0, 128); a larger x fails in Q15_MANT7_OF's range check. */
#define Q15_SHIFT7_OF(x)                                                                           \
    ((x) < 1.0    ? 0                                                                              \
     : (x) < 2.0  ? 1                                                                              \
     : (x) < 4.0  ? 2                                                                              \
     : (x) < 8.0  ? 3                                                                              \
     : (x) < 16.0 ? 4                                                                              \
     : (x) < 32.0 ? 5                                                                              \
     : (x) < 64.0 ? 6                                                                              \
                  : 7)
#define Q15_MANT7_OF(x) Q15((double)(x) / (double)(1L << Q15_SHIFT7_OF(x)))

/* Binary angle of a value in degrees, any real (wraps). 180 -> -32768. */
#define ANGLE_Q15_DEG(deg)                                                                         \
    ((angle_q15_t)(int16_t)(uint16_t)((unsigned long)((long)((deg)*65536.0 / 360.0 +               \
                                                             ((deg) >= 0 ? 0.5 : -0.5))) &         \
                                      0xFFFFUL))

/* ---- saturation --------------------------------------------------------- */

/* Clamp a 32-bit value into q15. */
Q15_INLINE q15_t q15_sat(int32_t x)
{
    if (x > (int32_t)Q15_MAX) {
        return Q15_MAX;
    }
    if (x < (int32_t)Q15_MIN) {
        return Q15_MIN;
    }
    return (q15_t)x;
}

/* Clamp x into [lo, hi]; lo <= hi is the caller's contract. */
Q15_INLINE q15_t q15_clamp(q15_t x, q15_t lo, q15_t hi)
{
    if (x > hi) {
        return hi;
    }
    if (x < lo) {
        return lo;
    }
    return x;
}

/* ---- add, subtract, negate, absolute value (all saturating) ------------- */

/* a + b, saturated to [-32768, 32767]. Exact inside the range. (lac, lac,
 * add, sac on the dsPIC.) */
Q15_INLINE q15_t q15_add_sat(q15_t a, q15_t b)
{
    return q15_dsp_add_sat(a, b);
}

/* a - b, saturated. */
Q15_INLINE q15_t q15_sub_sat(q15_t a, q15_t b)
{
    return q15_dsp_sub_sat(a, b);
}

/* -a, saturated: -(-32768) gives 32767. */
Q15_INLINE q15_t q15_neg_sat(q15_t a)
{
    return q15_dsp_neg_sat(a);
}

/* |a|, saturated: |-32768| gives 32767. */
Q15_INLINE q15_t q15_abs_sat(q15_t a)
{
    return (a < 0) ? q15_neg_sat(a) : a;
}

/* ---- multiply ----------------------------------------------------------- */

/* a * b in Q15, rounded to nearest (ties up). Max error 0.5 LSB.
 * Saturates only for -1 * -1 -> 0x7FFF. (mpy + sac.r on the dsPIC.) */
Q15_INLINE q15_t q15_mul(q15_t a, q15_t b)
{
    return q15_dsp_mpy_r(a, b);
}

/* a * b in Q15, truncated toward -infinity. Error in (-1, 0] LSB.
 * Saturates only for -1 * -1 -> 0x7FFF. */
Q15_INLINE q15_t q15_mul_trunc(q15_t a, q15_t b)
{
    return q15_sat(q15_dsp_mulss(a, b) >> 15);
}

/* ---- shifts ------------------------------------------------------------- */

/* a * 2^n for n in 0..15, saturated. */
Q15_INLINE q15_t q15_shl_sat(q15_t a, uint8_t n)
{
    int32_t wide = (int32_t)a;
    int32_t lim = (int32_t)(0x7FFFL >> n);
    if (wide > lim) {
        return Q15_MAX;
    }
    if (wide < -lim - 1) {
        return Q15_MIN;
    }
    return (q15_t)(int16_t)(uint16_t)((uint16_t)a << n);
}

/* a / 2^n for n in 0..15, truncated toward -infinity (arithmetic shift). */
Q15_INLINE q15_t q15_shr(q15_t a, uint8_t n)
{
    return (q15_t)(a >> n);
}

/* a / 2^n for n in 1..15, rounded to nearest (ties up). Cannot overflow. */
Q15_INLINE q15_t q15_shr_round(q15_t a, uint8_t n)
{
    return (q15_t)(((int32_t)a + (int32_t)(1L << (n - 1U))) >> n);
}

/* ---- 32-bit accumulator helpers (Q31, the dsPIC's 1.31 accumulator) ------ */

/* a + b, saturated to the 32-bit range (the accumulator with SATA = 1,
 * ACCSAT = 0). Computed without signed overflow. */
Q15_INLINE q31_t q31_add_sat(q31_t a, q31_t b)
{
    uint32_t sum = (uint32_t)a + (uint32_t)b;
    /* Overflow iff a and b share a sign and the sum's sign differs. */
    if (((~((uint32_t)a ^ (uint32_t)b)) & ((uint32_t)a ^ sum) & 0x80000000UL) != 0U) {
        return (a < 0) ? Q31_MIN : Q31_MAX;
    }
    return (q31_t)sum;
}

/* a - b, saturated to the 32-bit range. */
Q15_INLINE q31_t q31_sub_sat(q31_t a, q31_t b)
{
    uint32_t diff = (uint32_t)a - (uint32_t)b;
    /* Overflow iff a and b differ in sign and the result's sign differs from a. */
    if ((((uint32_t)a ^ (uint32_t)b) & ((uint32_t)a ^ diff) & 0x80000000UL) != 0U) {
        return (a < 0) ? Q31_MIN : Q31_MAX;
    }
    return (q31_t)diff;
}

/* Q15 -> Q31, exact (x * 2^16). */
Q15_INLINE q31_t q31_from_q15(q15_t x)
{
    return (q31_t)((uint32_t)(int32_t)x << 16);
}

/* a * b as a Q31 (the fractional product, mulss << 1). Exact except that
 * -1 * -1 saturates to Q31_MAX. */
Q15_INLINE q31_t q31_mul_q15(q15_t a, q15_t b)
{
    int32_t p = q15_dsp_mulss(a, b);
    if (p == 0x40000000L) {
        return Q31_MAX;
    }
    return (q31_t)((uint32_t)p << 1);
}

/* acc + a * b in Q31, saturated (one MAC with SATA = 1). */
Q15_INLINE q31_t q31_mac_sat(q31_t acc, q15_t a, q15_t b)
{
    return q31_add_sat(acc, q31_mul_q15(a, b));
}

/* Q31 -> Q15, rounded to nearest (ties up), saturated (sacr). */
Q15_INLINE q15_t q15_from_q31(q31_t x)
{
    if (x >= (int32_t)0x7FFF8000L) {
        return Q15_MAX;
    }
    return (q15_t)((x + 0x8000L) >> 16);
}

/* Q31 -> Q15, truncated toward -infinity (sac). */
Q15_INLINE q15_t q15_from_q31_trunc(q31_t x)
{
    return (q15_t)(x >> 16);
}

/* ---- binary angles ------------------------------------------------------ */

/* a + b modulo one turn. */
Q15_INLINE angle_q15_t angle_add(angle_q15_t a, angle_q15_t b)
{
    return (angle_q15_t)(int16_t)(uint16_t)((uint16_t)a + (uint16_t)b);
}

/* a - b modulo one turn, in [-pi, pi): the shortest signed difference. */
Q15_INLINE angle_q15_t angle_sub(angle_q15_t a, angle_q15_t b)
{
    return (angle_q15_t)(int16_t)(uint16_t)((uint16_t)a - (uint16_t)b);
}

/* -a modulo one turn (-pi stays -pi). */
Q15_INLINE angle_q15_t angle_neg(angle_q15_t a)
{
    return (angle_q15_t)(int16_t)(uint16_t)(0U - (uint16_t)a);
}

/*
 * Notes
 *
 * 1. Why one rounding rule. AN1078's assembly stored its 40-bit accumulators
 *    with rounding; the later C ports truncated with ">> 15" and added in
 *    plain int16 that can wrap. Mixing the two makes results depend on which
 *    block ran, so the core rounds to nearest everywhere a value leaves an
 *    accumulator, and truncates only where a function says *_trunc and why.
 *
 * 2. Conversions from unsigned to signed types (e.g. (int16_t)(uint16_t)x
 *    for x >= 2^15) are implementation-defined in C99; gcc, avr-gcc and XC16
 *    all define them as reduction modulo 2^N, which the angle code uses.
 *
 * 3. Q15() computes in double at compile time. avr-gcc and XC16 (without
 *    -fno-short-double) have a 32-bit double; a 24-bit mantissa still holds
 *    every 16-bit raw value exactly, but long derivations of constants can
 *    round differently there. Derived constants are therefore checked for
 *    equality between the host and the 16-bit build (make check-16bit).
 */

#endif /* Q15_H */
