/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* vec_canary.c - a deliberate int-width dependence: tools/check16/selftest expects the check to
 * fail here. */
/* check16-requires: foc/q15.h */
#include "emit.h"

/*
 * unsigned arithmetic is defined on both compilers, but `unsigned` is 16 bits
 * on the AVR and 32 on the PC: the product below wraps at 2^16 on the AVR
 * only. This is the bug class check-16bit exists for (an unwidened product).
 */
void vec_canary(void)
{
    uint16_t k;
    emit_section("canary");
    for (k = 0U; k < 4U; k++) {
        unsigned a = 300U + k;
        unsigned b = 300U;
        emit_u16((uint16_t)k);
        emit_sep();
        emit_u32((uint32_t)(a * b));
        emit_end();
    }
}
