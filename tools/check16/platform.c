/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* platform.c - where the 16-bit check's programs write: USART0 under simavr, stdout on the PC. */
#include <stdint.h>

#include "emit.h"

#if defined(__AVR__)

#include <avr/interrupt.h>
#include <avr/io.h>
#include <avr/sleep.h>

_Static_assert(sizeof(int) == 2, "the point of this build is a 16-bit int");

void platform_init(void)
{
    /* USART0 at 2 Mbaud (U2X, UBRR = 0 at 16 MHz); simavr logs every line
     * written to UDR0 on its stderr. */
    UCSR0A = (uint8_t)(1U << U2X0);
    UBRR0 = 0U;
    UCSR0B = (uint8_t)(1U << TXEN0);
}

void emit_putc(char c)
{
    while ((UCSR0A & (1U << UDRE0)) == 0U) {
    }
    UDR0 = (uint8_t)c;
}

void platform_exit(void)
{
    /* Let the last character leave the shift register, then sleep with
     * interrupts off: simavr ends the simulation cleanly on that. */
    while ((UCSR0A & (1U << UDRE0)) == 0U) {
    }
    cli();
    /* Power-down, sleep enable (set_sleep_mode() trips -Wconversion). */
    SMCR = (uint8_t)((1U << SM1) | (1U << SE));
    sleep_cpu();
    for (;;) {
    }
}

#else

#include <stdio.h>
#include <stdlib.h>

void platform_init(void)
{
}

void emit_putc(char c)
{
    (void)putchar(c);
}

void platform_exit(void)
{
    (void)fflush(stdout);
    exit(0);
}

#endif
