/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* mc_contract.c - what a broken contract does on the PC (mc_contract.h). */
#include "mc_contract.h"

#if MC_CONTRACTS
#include <stdio.h>
#include <stdlib.h>

void mc_contract_fail(const char *what, const char *file, int line)
{
    (void)fprintf(stderr, "%s:%d: contract broken: %s\n", file, line, what);
    abort();
}
#else
/* the chip: no contracts (ISO C wants a translation unit to declare something) */
extern const int mc_contract_absent;
#endif
