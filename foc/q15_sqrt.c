/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* q15_sqrt.c - integer and Q15 square roots, rounded to nearest. */
#include "q15_sqrt.h"

/* round(sqrt((16 + j) 2^24)), j = 0..48: sqrt over [2^28, 2^30] in 48 steps;
 * const, so the dsPIC linker places it in flash (98 bytes). */
static const uint16_t q15_sqrt_table[49] = {
    16384U, 16888U, 17378U, 17854U, 18318U, 18770U, 19212U, 19644U, 20066U, 20480U,
    20886U, 21283U, 21674U, 22058U, 22435U, 22806U, 23170U, 23530U, 23884U, 24232U,
    24576U, 24915U, 25249U, 25580U, 25905U, 26227U, 26545U, 26859U, 27170U, 27477U,
    27780U, 28081U, 28378U, 28672U, 28963U, 29251U, 29537U, 29819U, 30099U, 30377U,
    30652U, 30924U, 31194U, 31462U, 31727U, 31991U, 32252U, 32511U, 32768U,
};

/* n > 65535.5^2 rounds to 65536, the one result outside 16 bits. */
#define Q15_ISQRT_TOP 0xFFFF0001UL

uint32_t q15_isqrt_u32(uint32_t n)
{
    uint16_t hi = (uint16_t)(n >> 16);
    uint8_t lz;
    uint32_t m;
    uint16_t y;
    uint16_t j;
    uint16_t r;
    uint32_t sq;
    if (n < 2UL) {
        return n;
    }
    if (n >= Q15_ISQRT_TOP) {
        return 65536UL;
    }
    /* m = n 4^s (s in -1..14) in [2^28, 2^30), so sqrt(m) in [2^14, 2^15):
     * a left shift by an even count, built from 16-bit shifts (a 32-bit
     * shift by a variable count is a loop on the dsPIC). */
    lz = (hi != 0U) ? q15_dsp_clz16(hi) : (uint8_t)(16U + q15_dsp_clz16((uint16_t)n));
    if (lz >= 2U) {
        uint8_t sh = (uint8_t)((lz - 2U) & ~1U); /* 0..30, even */
        uint16_t lo = (uint16_t)n;
        if (sh == 0U) {
            m = n;
        } else if (sh < 16U) {
            m = ((uint32_t)(uint16_t)((uint16_t)(hi << sh) | (uint16_t)(lo >> (16U - sh))) << 16) |
                (uint16_t)(lo << sh);
        } else {
            m = (uint32_t)(uint16_t)(lo << (sh - 16U)) << 16;
        }
    } else {
        m = n >> 2; /* n >= 2^30: the two bits dropped are restored below */
    }
    /* Seed from the table (within 5 units), then one Newton step (note 1). */
    j = (uint16_t)((m >> 24) - 16UL);
    y = (uint16_t)(q15_sqrt_table[j] +
                   (uint16_t)(((uint32_t)(uint16_t)(q15_sqrt_table[j + 1U] - q15_sqrt_table[j]) *
                               (uint32_t)((m >> 16) & 0xFFUL)) >>
                              8));
    y = (uint16_t)(((uint32_t)y + (uint32_t)q15_dsp_divud(m, y)) >> 1);
    /* Back to n's scale (y < 2^15, so 16-bit arithmetic holds it), then the
     * exact rounding: round(sqrt(n)) = r iff r^2 - r < n <= r^2 + r, with
     * 16 x 16 products (note 2). */
    if (lz >= 2U) {
        uint8_t s = (uint8_t)((lz - 2U) >> 1);
        r = y;
        if (s > 0U) {
            r = (uint16_t)((uint16_t)(y + (uint16_t)(1U << (s - 1U))) >> s);
        }
    } else {
        r = (uint16_t)(y << 1);
    }
    /* sq = r^2 from one 16 x 16 product, then stepped with r: (r +- 1)^2 =
     * r^2 +- 2r + 1 (32-bit adds, no further product). */
    sq = (uint32_t)r * r;
    while (n > sq + r) {
        sq += 2U * (uint32_t)r + 1U;
        r++;
    }
    while (sq - r >= n) {
        sq -= 2U * (uint32_t)r - 1U;
        r--;
    }
    return r;
}

q15_t q15_sqrt(q15_t x)
{
    if (x <= 0) {
        return 0;
    }
    /* sqrt(x / 2^15) * 2^15 = sqrt(x * 2^15); x 2^15 < 2^30, result <= 32767. */
    return (q15_t)q15_isqrt_u32((uint32_t)x << 15);
}

/*
 * Notes
 *
 * 1. The seed interpolates the table linearly between steps of 2^24 in m:
 *    the chord of sqrt is within 5 units of the curve (sqrt'' is largest at
 *    2^28). One Newton step y' = (y + m / y) / 2 squares the relative
 *    error (5 / 2^14 -> 5e-8) and truncates twice, so y' is within one unit
 *    of sqrt(m). m / y < 2^15 fits div.ud's 16-bit quotient.
 *
 * 2. Scaled back, the estimate is within about 2 of round(sqrt(n)); the two
 *    loops step it onto the exact answer, one or two steps at most, with
 *    r <= 65535 (n below 0xFFFF0001 stops the first loop there) so
 *    r^2 + r <= 2^32 - 2^16 fits 32 bits and r^2 - r never goes below 0
 *    (r >= 1 for n >= 2). An exact tie cannot occur: sqrt(n) = k + 1/2 has
 *    no integer n.
 */
