/* board_mchv_hal.h - HAL-side facts of the dsPICDEM MCHV (PIM not confirmed). */
#ifndef BOARD_MCHV_HAL_H
#define BOARD_MCHV_HAL_H

/*
 * The MCHV's PIM and its pin map were not found (hardware.md 2.3); this file
 * assumes the same dsPIC33FJ32MC204 PIM wiring as the MCLV, so it takes the
 * MCLV's HAL facts (every one #ifndef-guarded): a pin confirmed for the MCHV
 * is defined here, above the include. The current sign differs, but it is
 * the core profile's BOARD_I_SIGN (firmware/boards/board_mchv.h, -1, with its
 * provenance), which HAL_BOARD_I_SIGN follows on either board.
 */

#include "board_mclv_hal.h"

#endif /* BOARD_MCHV_HAL_H */
