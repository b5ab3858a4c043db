/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* fieldweak.h - field weakening: Id reference from a 16-point table versus speed. */
#ifndef FIELDWEAK_H
#define FIELDWEAK_H

#include "q15.h"

/*
 * AN1078 "Field Weakening": below the nominal speed no field weakening is
 * done; above it the d-axis current reference is read from a 16-point
 * table (AN1078's dqKfw0..dqKfw15) by linear interpolation.
 *
 *   s = |speed|                          (|-32768| = 32767)
 *   s <  speed_nominal:                  Id_ref = 0
 *   s >= speed_max:                      Id_ref = id_table[15]
 *   otherwise, with the 16 points equally spaced from nominal (entry 0) to
 *   max (entry 15), 15 segments:
 *     pos    = 15 (s - speed_nominal) / (speed_max - speed_nominal)
 *     i      = floor(pos), f = pos - i
 *     Id_ref = id_table[i] + f (id_table[i + 1] - id_table[i])
 * Choose id_table[0] = 0 for a continuous reference at the nominal speed.
 * speed_max <= speed_nominal (AN1078: set them equal) or speed_nominal < 0
 * disables field weakening: Id_ref = 0 at every speed.
 *
 * The segment width is never computed in Q15 (AN1078's Q15(a - b + 1)
 * overflowed 16 bits): fieldweak_init takes the span D = max - nominal
 * (1..32767 counts). fieldweak_id_ref divides 15 (s - nominal) by D for the
 * segment index i and the remainder r = 15 (s - nominal) - i D, both exact,
 * and r 2^16 by D for the fraction f = r / D as a Q16 value, rounded: two
 * 32 / 16 divisions (the dsPIC's div.ud).
 *
 * Scaling and overflow: speeds Q15 in the caller's speed units, currents
 * Q15 of the current full scale. All intermediates are unsigned 32-bit
 * (fieldweak.c note 2); the interpolation
 * step (up to 65535 LSB between adjacent entries) is applied in 32 bits
 * and rounded once (nearest, ties up). The result lies between the two
 * bracketing table entries, so it cannot overflow.
 * Accuracy: |Id_ref - exact interpolation| <= 0.5 LSB + |step| / 131072 LSB
 * (step = difference of the bracketing entries); at table points, below
 * nominal and above max exact. test/foc/test_fieldweak.c checks it over
 * every speed -32768..32767 for an AN1078-like falling table (0 to -0.7)
 * on 12 spans and for tables alternating between +-full scale (step
 * 65535), and prints the measured figures (docs/foc_control_blocks.md,
 * "Measured accuracy").
 */
#define FIELDWEAK_TABLE_SIZE 16

typedef struct {
    q15_t speed_nominal;                  /* Q15 speed, >= 0: start of weakening */
    q15_t speed_max;                      /* Q15 speed, > speed_nominal: table end */
    q15_t id_table[FIELDWEAK_TABLE_SIZE]; /* Q15 Id reference at the 16 points */
} fieldweak_params_t;

typedef struct {
    const fieldweak_params_t *p; /* the parameters (constant: kept, not copied) */
    uint16_t span;               /* speed_max - speed_nominal, counts; 0 = disabled */
} fieldweak_t;

/* Keep params (which must outlive fw: a constant table, 36 bytes not copied
 * into RAM) and the span. */
void fieldweak_init(fieldweak_t *fw, const fieldweak_params_t *params);

/* Id reference (Q15 current) for a speed (Q15, either sign). */
q15_t fieldweak_id_ref(const fieldweak_t *fw, q15_t speed);

#endif /* FIELDWEAK_H */
