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
 *   q15_dsp_divud(n, d)  32 / 16 -> 16 unsigned quotient, truncated
 *                        (div.ud); same contract: d != 0, quotient < 2^16.
 *   q15_dsp_clz16(v)     leading zeros of a non-zero 16-bit value, 0..15
 *                        (ff1l - 1); v == 0 is outside the contract.
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

static inline uint16_t q15_dsp_divud(uint32_t num, uint16_t den)
{
    return __builtin_divud(num, den);
}

static inline uint8_t q15_dsp_clz16(uint16_t v)
{
    return (uint8_t)(__builtin_ff1l(v) - 1U);
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

static inline uint16_t q15_dsp_divud(uint32_t num, uint16_t den)
{
    return (uint16_t)(num / (uint32_t)den);
}

static inline uint8_t q15_dsp_clz16(uint16_t v)
{
    uint8_t n = 0U;
    if (v < 0x0100U) {
        v = (uint16_t)(v << 8);
        n = 8U;
    }
    if (v < 0x1000U) {
        v = (uint16_t)(v << 4);
        n = (uint8_t)(n + 4U);
    }
    if (v < 0x4000U) {
        v = (uint16_t)(v << 2);
        n = (uint8_t)(n + 2U);
    }
    if (v < 0x8000U) {
        n = (uint8_t)(n + 1U);
    }
    return n;
}

#endif

#endif /* Q15_DSP_H */
