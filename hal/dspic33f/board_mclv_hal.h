/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* board_mclv_hal.h - HAL-side facts of the dsPICDEM MCLV with the dsPIC33FJ32MC204 PIM. */
#ifndef BOARD_MCLV_HAL_H
#define BOARD_MCLV_HAL_H

/*
 * What the HAL needs beyond the core's board profile (boards/
 * board_mclv.h): the pins docs/hardware.md could not name. Each may be overridden with -D.
 */

/* The current amplifiers' sign is a board fact: BOARD_I_SIGN in the core's
 * board profile (boards/board_mclv.h, with its provenance).
 * -DHAL_BOARD_I_SIGN=... still overrides it for the HAL alone. */
#ifndef HAL_BOARD_I_SIGN
#define HAL_BOARD_I_SIGN BOARD_I_SIGN
#endif

/* LEDs: port (HAL_PORT_A/B/C, or HAL_PORT_NONE) and bit.
 * [NOT FOUND] which MCLV LEDs the 32MC204 PIM reaches (docs/hardware.md 1.8), so
 * no pin is driven until these are set (e.g. -DHAL_LED_RUN_PORT=HAL_PORT_B
 * -DHAL_LED_RUN_BIT=9). Driving a guessed pin could fight another driver. */
#ifndef HAL_LED_RUN_PORT
#define HAL_LED_RUN_PORT HAL_PORT_NONE
#define HAL_LED_RUN_BIT  0u
#endif
#ifndef HAL_LED_FAULT_PORT
#define HAL_LED_FAULT_PORT HAL_PORT_NONE
#define HAL_LED_FAULT_BIT  0u
#endif

/* UART1 on remappable pins: RPn numbers, or HAL_RP_NONE.
 * [NOT FOUND] the MCLV's UART pins for the 32MC204 PIM (docs/hardware.md 1.8):
 * UART1 runs but is not routed to a pin until these are set. */
#ifndef HAL_UART_RX_RP
#define HAL_UART_RX_RP HAL_RP_NONE
#endif
#ifndef HAL_UART_TX_RP
#define HAL_UART_TX_RP HAL_RP_NONE
#endif

/* Timing pin, for the bench (optional; port HAL_PORT_A/B/C and bit, or
 * HAL_PORT_NONE): high from the ADC interrupt's first statement to its
 * last. On a scope against a PWM output it shows when the interrupt starts
 * (the conversion ends 4.8 us after the trigger, which sits
 * PWM_ADC_TRIGGER_TCY after the PWM midpoint) and how long it runs, the
 * figure docs/performance.md gives in cycles. Off by default: it must be a
 * free pin of your PIM (e.g. -DHAL_TIMING_PIN_PORT=HAL_PORT_C
 * -DHAL_TIMING_PIN_BIT=5u). */
#ifndef HAL_TIMING_PIN_PORT
#define HAL_TIMING_PIN_PORT HAL_PORT_NONE
#define HAL_TIMING_PIN_BIT  0u
#endif

#endif /* BOARD_MCLV_HAL_H */
