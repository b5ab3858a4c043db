/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* mc_contract.h - run-time contracts of the core's API: checked on the PC, empty on the chip. */
#ifndef MC_CONTRACT_H
#define MC_CONTRACT_H

/*
 * MC_REQUIRE(cond): a caller's obligation the function cannot check by its
 * type, such as a request code from the enum. On the dsPIC and the AVR
 * (the 16-bit check) it compiles to nothing, so the image pays no flash or
 * cycle; the function still does something safe there (mc_request ignores
 * an unknown request). On the PC a false condition calls
 * mc_contract_fail, which prints one line and aborts (mc_contract.c), so a
 * host test that breaks a contract fails; a test that means to break one
 * links its own mc_contract_fail (the library's is then not linked).
 */
#if defined(__XC16__) || defined(__AVR__)
#define MC_CONTRACTS 0
#else
#define MC_CONTRACTS 1
#endif

#if MC_CONTRACTS
void mc_contract_fail(const char *what, const char *file, int line);
#define MC_REQUIRE(cond) ((cond) ? (void)0 : mc_contract_fail(#cond, __FILE__, __LINE__))
#else
#define MC_REQUIRE(cond) ((void)0)
#endif

#endif /* MC_CONTRACT_H */
