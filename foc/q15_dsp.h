/* q15_dsp.h - the multiply/divide primitives, XC16 built-ins on the dsPIC, bit-identical C
 * elsewhere. */
#ifndef Q15_DSP_H
#define Q15_DSP_H

#include <stdint.h>

/*
 * This is the only place the core touches a compiler intrinsic. Every
 * function has two bodies that must return the same bits for every input:
 *
 *   q15_dsp_mulss(a, b)  16 x 16 -> 32 signed product, exact (mul.ss).
 *                        |result| <= 2^30, cannot overflow.
 *   q15_dsp_divsd(n, d)  32 / 16 -> 16 signed quotient, truncated toward
 *                        zero (div.sd). The caller guarantees d != 0 and
 *                        that the quotient fits in int16_t: the dsPIC
 *                        traps on d == 0 and returns garbage on overflow.
 *                        The portable twin has the same contract and does
 *                        not check it (outside it, e.g. d == 0, the host
 *                        build is undefined, which UBSan reports in tests);
 *                        every caller documents how it keeps to it.
 *
 * The portable bodies widen before multiplying, which is what makes them
 * correct where int is 16 bits (avr-gcc, XC16): `a * b` of two int16_t is a
 * 16-bit product there.
 */

#if defined(__XC16__)

static inline int32_t q15_dsp_mulss(int16_t a, int16_t b)
{
    return __builtin_mulss(a, b);
}

static inline int16_t q15_dsp_divsd(int32_t num, int16_t den)
{
    return __builtin_divsd(num, den);
}

#else

static inline int32_t q15_dsp_mulss(int16_t a, int16_t b)
{
    return (int32_t)a * (int32_t)b;
}

static inline int16_t q15_dsp_divsd(int32_t num, int16_t den)
{
    /* C99 division truncates toward zero, as div.sd does. */
    return (int16_t)(num / (int32_t)den);
}

#endif

#endif /* Q15_DSP_H */
