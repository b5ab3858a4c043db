/* board_mchv_hal.h - HAL-side facts of the dsPICDEM MCHV (PIM not confirmed). */
#ifndef BOARD_MCHV_HAL_H
#define BOARD_MCHV_HAL_H

/*
 * The MCHV's PIM and its pin map were not found (hardware.md 2.3); this file
 * assumes the same dsPIC33FJ32MC204 PIM wiring as the MCLV (the current
 * sign differs: BOARD_I_SIGN in the board profile).
 */

/* The current amplifiers' sign is a board fact: BOARD_I_SIGN in the core's
 * board profile (firmware/boards/board_mchv.h, -1, with its provenance).
 * -DHAL_BOARD_I_SIGN=... still overrides it for the HAL alone. */
#ifndef HAL_BOARD_I_SIGN
#define HAL_BOARD_I_SIGN BOARD_I_SIGN
#endif

/* [NOT FOUND] as on the MCLV: nothing driven until set. */
#ifndef HAL_LED_RUN_PORT
#define HAL_LED_RUN_PORT HAL_PORT_NONE
#define HAL_LED_RUN_BIT  0u
#endif
#ifndef HAL_LED_FAULT_PORT
#define HAL_LED_FAULT_PORT HAL_PORT_NONE
#define HAL_LED_FAULT_BIT  0u
#endif
#ifndef HAL_UART_RX_RP
#define HAL_UART_RX_RP HAL_RP_NONE
#endif
#ifndef HAL_UART_TX_RP
#define HAL_UART_TX_RP HAL_RP_NONE
#endif

#endif /* BOARD_MCHV_HAL_H */
