/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* config_bits.c - the dsPIC33FJ32MC204 configuration words, all in this one file. */

/*
 * Values from the Microchip MCLV / 32MC204 examples (docs/hardware.md 1.3) [SRC];
 * the setting and value NAMES are those of the XC16 `#pragma config` syntax
 * for this device family [MEM: check with MPLAB X, Window > Target Memory
 * Views > Configuration Bits, which lists the exact names]. Settings not
 * listed keep their erased value (all ones): no code protection, no boot or
 * secure segment, write protection off.
 *
 *   FNOSC = FRC       start on the internal FRC; hal_init() switches to the
 *                     crystal through the PLL (hence FCKSM must allow it)
 *   FCKSM = CSECMD    clock switching enabled, fail-safe monitor off
 *   POSCMD = XT       8 MHz crystal on the MCLV
 *   IOL1WAY = OFF     the peripheral pin select may be unlocked more than once
 *   FWDTEN = OFF      no watchdog
 *   FPWRT = PWR128    128 ms power-up timer
 *   PWMPIN = ON       PWM pins are tri-stated port pins after reset, until
 *                     hal_init() hands them to MCPWM1 (with the override off)
 *   HPOL = ON, LPOL = ON   high and low sides active high
 *   ICS = PGD3        program/debug on PGC3/PGD3, the MCLV PIM's ICSP pins
 *   JTAGEN = OFF      JTAG off (its pins are port pins)
 *
 * Only XC16 sees the pragmas; on the PC this file is an empty unit, and
 * test/hal/test_hal_config.c checks this text holds each setting above.
 */

#if defined(__XC16__)

#pragma config FNOSC = FRC
#pragma config FCKSM = CSECMD
#pragma config POSCMD = XT
#pragma config IOL1WAY = OFF
#pragma config FWDTEN = OFF
#pragma config FPWRT = PWR128
#pragma config PWMPIN = ON
#pragma config HPOL = ON
#pragma config LPOL = ON
#pragma config ICS = PGD3
#pragma config JTAGEN = OFF

#else

/* ISO C wants at least one declaration in a translation unit. */
typedef int config_bits_host_unit_t;

#endif
