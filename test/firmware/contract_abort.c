/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* contract_abort.c - a broken contract on the PC stops the program with one line naming it
 * (mc_contract.h): the library's own handler, which no test replaces here. */
#include "mc.h"

static mc_t mc;

int main(void)
{
    mc_init(&mc);
    mc_request(&mc, MC_REQUEST_COUNT); /* not a request: aborts */
    return 0;
}
