/* clarke.c - amplitude-invariant Clarke transform from two phase currents. */
#include "clarke.h"

/*
 * beta = (ia + 2 ib) / sqrt(3), computed as u = ia + 2 ib (int32_t, |u| <=
 * 98,304) times 1/sqrt(3) in Q16 (37,837, an unsigned 16-bit constant: in
 * Q15 the constant would be 18,919 and its own rounding would cost up to
 * 0.73 LSB at |beta| = 1; in Q16 it costs 0.2 LSB).
 *
 * Saturation is decided on u before multiplying: beta rounds to >= 32768
 * exactly when u >= 56,756 and to < -32768 when u <= -56,757, so u is
 * clamped to [-56,756, 56,755] first. That keeps u * 37,837 + 2^15 inside
 * int32_t (max 2,147,471,703 < 2^31 - 1) and makes the clamp exactly the
 * saturation of the rounded result.
 */

Q15_STATIC_ASSERT((long long)CLARKE_U_MAX *CLARKE_INV_SQRT3_Q16 + CLARKE_ROUND <= 0x7FFFFFFFLL &&
                      (long long)CLARKE_U_MIN * CLARKE_INV_SQRT3_Q16 >= -0x7FFFFFFFLL - 1LL,
                  "clarke: u * 1/sqrt(3) must fit int32_t at the clamp");
