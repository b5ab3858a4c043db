/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* board_mchv_hal.h - HAL-side facts of the dsPICDEM MCHV (PIM not confirmed). */
#ifndef BOARD_MCHV_HAL_H
#define BOARD_MCHV_HAL_H

/*
 * The MCHV's PIM and its pin map were not found (docs/hardware.md 2.3); this file
 * assumes the same dsPIC33FJ32MC204 PIM wiring as the MCLV, so it takes the
 * MCLV's HAL facts (every one #ifndef-guarded): a pin confirmed for the MCHV
 * is defined here, above the include. The current sign differs, but it is
 * the core profile's BOARD_I_SIGN (boards/board_mchv.h, -1, with its
 * provenance), which HAL_BOARD_I_SIGN follows on either board.
 */

/* Pin conflict, unresolved [GUESS on the PIM]: a 2012 Microchip sample
 * "updated to MCHV" reads push-button S3 on RB8, the pin this HAL makes the
 * latched fault input FLTA1 (HAL_FLTA1_RP = RP8). On a PIM wired that way a
 * press of S3 trips the fault, and the fault pin would not be where the
 * HAL expects it. The one constant to settle: HAL_MCHV_PINS_CONFIRMED.
 * Check on the MCHV PIM's schematic (or with a meter, board unpowered)
 * which pins S3 and the inverter's fault output reach; if S3 is not on
 * RB8 and the fault is, build with -DHAL_MCHV_PINS_CONFIRMED=1 (XC16_CFLAGS);
 * otherwise move HAL_FLTA1_RP / HAL_S3_PORTB_BIT to the confirmed pins
 * first. Until then the MCHV image is refused. */
#ifndef HAL_MCHV_PINS_CONFIRMED
#define HAL_MCHV_PINS_CONFIRMED 0
#endif
#if !HAL_MCHV_PINS_CONFIRMED
#error                                                                                             \
    "MCHV build refused: push-button S3 may share RB8 with the fault input FLTA1; check the MCHV PIM pin map (docs/board.md, 'MCHV pin map'), then build with -DHAL_MCHV_PINS_CONFIRMED=1"
#endif

#include "board_mclv_hal.h"

#endif /* BOARD_MCHV_HAL_H */
