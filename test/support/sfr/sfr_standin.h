/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sfr_standin.h - test-side control of the SFR stand-in: reset values and the built-in call log. */
#ifndef SFR_STANDIN_H
#define SFR_STANDIN_H

#include <stdint.h>

#include "xc.h"

/* Every register to its power-on value as the stand-in models it: 0, except
 * TRISx = 0xFFFF (all inputs), U1STA.TRMT = 1 (transmitter empty), CORCON =
 * 0x0024 (SATDW as after reset, PSV as left by the XC16 start-up code) [MEM],
 * OSCCON.COSC = NOSC = 0 (FRC, per the FNOSC = FRC configuration). Clears
 * the call log. */
void sfr_standin_reset(void);

/* One call of __builtin_write_OSCCONH/L, with the registers as they were. */
typedef struct {
    char which;      /* 'H' or 'L' */
    uint8_t value;   /* the byte written */
    uint16_t pllfbd; /* PLLFBD at the time of the call */
    uint16_t clkdiv; /* CLKDIV at the time of the call */
} sfr_osccon_write_t;

#define SFR_OSCCON_LOG_MAX 16
extern sfr_osccon_write_t sfr_osccon_log[SFR_OSCCON_LOG_MAX];
extern unsigned sfr_osccon_log_n;

/* Accesses of P1DC1..3 (reads and writes alike) while sfr_pdc_log_on: how
 * many, and how many of them with PWM1CON2.UDIS = 0 (a duty that could load
 * at a period boundary apart from the others). */
extern unsigned sfr_pdc_log_on;
extern unsigned sfr_pdc_accesses;
extern unsigned sfr_pdc_accesses_udis0;

#endif /* SFR_STANDIN_H */
