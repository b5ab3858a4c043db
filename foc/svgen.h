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
 * The signs of r1..r3 give the sector; the two bounding components are the
 * on-times T1 and T2 as fractions of the period. Duties are centred:
 * the third phase gets (period - T1 - T2) / 2 and the others add T1, T2.
 *
 * Output: duty[k] in 0..period counts for a centre-aligned PWM whose duty
 * register spans 0..period for 0..100 % (PDCx units on the dsPIC).
 * Over-modulation (T1 + T2 > 1) scales T1 and T2 down in proportion, so the
 * vector keeps its angle and lands on the hexagon: clamped, never wrapped.
 */
typedef struct {
    uint16_t duty[3]; /* phases a, b, c: 0..period */
    uint8_t sector;   /* 1..6, sector of the requested vector */
    bool clamped;     /* true when the vector was outside the hexagon */
} svgen_out_t;

/* period: duty counts for 100 %, 1..32767. */
void svgen_update(ab_q15_t v, uint16_t period, svgen_out_t *out);

#endif /* SVGEN_H */
