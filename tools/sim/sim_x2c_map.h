/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_x2c_map.h - the simulator's X2Cscope variable map, kept in its ELF for the map generator. */
#ifndef SIM_X2C_MAP_H
#define SIM_X2C_MAP_H

/*
 * On the PC the X2Cscope target presents its variables in a 16-bit window
 * (x2c.h, X2C_WINDOW_*), which the host ELF's own symbols cannot describe
 * (64-bit addresses, 32-bit int). This table describes the window instead:
 * one row per whitelisted variable (firmware/x2cscope/x2c_vars.h), with the
 * name a client knows from the board's ELF, its kind and width (from
 * which the generator names its XC16 type: pyx2cscope reads widths by
 * XC16's rules), its window address and its engineering scale. The rows hold no pointers, so the
 * table's bytes in the ELF's read-only data are final: `an1078-x2cmap` (tools/scope) reads them
 * from the symbol `sim_x2c_map` and writes the map clients import (pyx2cscope's import_variables
 * YAML). The layout is fixed (80 bytes a row, little-endian); tools/scope/ x2cmap.py reads the same
 * layout.
 */

#include <stdint.h>

typedef struct {
    char name[48];     /* "motor.i_dq.d", NUL-padded */
    char unit[8];      /* of full_scale; "" for a code */
    double full_scale; /* engineering value of 32768 raw counts; 0: the raw value is the value */
    int32_t min, max;  /* a tunable's range (0, 0 for the read-only) */
    uint16_t address;  /* in the window */
    uint16_t size;     /* bytes */
    uint8_t tunable;   /* 1: writable */
    uint8_t kind;      /* 'S' signed, 'U' unsigned, 'B' bool */
    uint8_t pad[2];
} sim_x2c_map_row_t;

extern const sim_x2c_map_row_t sim_x2c_map[];
extern const uint16_t sim_x2c_map_rows;

#endif /* SIM_X2C_MAP_H */
