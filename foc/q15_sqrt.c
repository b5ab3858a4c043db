/* q15_sqrt.c - integer and Q15 square roots, rounded to nearest. */
#include "q15_sqrt.h"

uint32_t q15_isqrt_u32(uint32_t n)
{
    /* Restoring square root, two bits of n per step, a fixed 16 steps (the
     * same time for every input, which suits an ISR). Invariant:
     * rem = n_consumed - root^2 (note 1). */
    uint32_t rem = n;
    uint32_t root = 0UL;
    uint32_t bit = 0x40000000UL;
    uint8_t k;
    for (k = 0U; k < 16U; k++) {
        if (rem >= root + bit) {
            rem -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    /* root = floor(sqrt(n)), rem = n - root^2. sqrt(n) > root + 1/2 iff
     * n > root^2 + root + 1/4, i.e. rem > root for integers. */
    if (rem > root) {
        root++;
    }
    return root;
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
 * 1. The loop keeps root scaled by the current bit: after the last step it
 *    is floor(sqrt(n)). root + bit never exceeds 2^16 + 2^30, and rem only
 *    decreases, so no step can overflow 32 bits.
 */
