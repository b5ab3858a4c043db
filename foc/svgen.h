/* svgen.h - space-vector modulation with AN1078's modified inverse Clarke. */
#ifndef SVGEN_H
#define SVGEN_H

#include "frames.h"

/*
 * Voltage scale: |v| = 1.0 (Q15 full scale) is the largest vector of the
 * linear region, the circle inscribed in the SVM hexagon, i.e. a phase
 * voltage amplitude of Vbus / sqrt(3) (a line-to-line amplitude of Vbus).
 *
 * CalcRef (modified inverse Clarke, alpha and beta swapped):
 *   r1 = beta
 *   r2 = ( sqrt(3) alpha - beta) / 2
 *   r3 = (-sqrt(3) alpha - beta) / 2
 * On this scale r1, r2, r3 are exactly the requested line-to-line voltages
 * v_bc, v_ab, v_ca in units of Vbus. The signs of r1..r3 give the sector;
 * the two components bounding it are the active-vector on-times T1 and T2
 * as fractions of the period. Duties are centred: the lowest phase gets
 * (period - T1 - T2) / 2, the middle one T2 more, the highest T1 more, so
 * (max duty + min duty) = period within 1 count in the linear region.
 *
 * Sectors (angle of v from the alpha axis; on a boundary either neighbour
 * gives the same duties):
 *   1: [0, 60)  2: [60, 120)  3: [120, 180)  4: [180, 240)  5: [240, 300)
 *   6: [300, 360) degrees. The zero vector reports sector 1.
 *
 * Output: duty[k] in 0..period counts for a centre-aligned PWM whose duty
 * register spans 0..period for 0..100 % (PDCx units on the dsPIC: phase k's
 * mean voltage vs the negative rail = duty[k] / period * Vbus).
 * Over-modulation (T1 + T2 > 1, the vector outside the hexagon) scales T1
 * and T2 down in proportion so that T1 + T2 = period: the vector keeps its
 * angle and lands on the hexagon; clamped is set. Never wrapped.
 *
 * Scaling and overflow: alpha, beta Q15 (any value, including -32768 on
 * both); the r's are formed exactly in 32 bits (Q30, sqrt(3)/2 as
 * Q15 28378), T1 and T2 are rounded once to counts; the over-modulation
 * ratio uses one q15_dsp_divsd whose quotient is <= period by construction.
 * No intermediate can overflow for any input.
 * Accuracy (svgen.c note 1, measured in test/foc/test_svgen.c): the
 * line-to-line voltages rebuilt from the duties are within 1 + 2.5e-6 period
 * counts of the requested ones (measured 1.003 counts at period 2000, 1.000
 * at 1000, 1.06 at 32767, mean 0.28); a clamped vector's angle is within
 * 0.02 deg at period 2000 (0.04 at 1000, 0.005 at 32767).
 */
typedef struct {
    uint16_t duty[3]; /* phases a, b, c: 0..period */
    uint8_t sector;   /* 1..6, sector of the requested vector (table above) */
    bool clamped;     /* true when the vector was outside the hexagon */
} svgen_out_t;

/* period: duty counts for 100 %, 1..32767 (larger values are treated as
 * 32767; 0 gives all duties 0). */
void svgen_update(ab_q15_t v, uint16_t period, svgen_out_t *out);

#endif /* SVGEN_H */
