/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* fieldweak.c - field weakening: Id reference from a 16-point table versus speed. */
#include "fieldweak.h"

#include "q15_dsp.h"

#define FIELDWEAK_SEGMENTS 15U

void fieldweak_init(fieldweak_t *fw, const fieldweak_params_t *params)
{
    fw->p = params;
    fw->span = 0U;
    if (params->speed_nominal < 0 || params->speed_max <= params->speed_nominal) {
        return; /* disabled: Id_ref = 0 everywhere */
    }
    /* 1..32767: both speeds are in 0..32767 and max > nominal. */
    fw->span = (uint16_t)((int32_t)params->speed_max - (int32_t)params->speed_nominal);
}

q15_t fieldweak_id_ref(const fieldweak_t *fw, q15_t speed)
{
    const q15_t *t = fw->p->id_table;
    uint16_t span = fw->span;
    if (span == 0U) {
        return 0;
    }
    q15_t s = q15_abs_sat(speed);
    if (s < fw->p->speed_nominal) {
        return 0;
    }
    if (s >= fw->p->speed_max) {
        return t[FIELDWEAK_TABLE_SIZE - 1];
    }

    /* The segment and the place in it, exactly: 15 d = i span + r with d in
     * 0..span-1, so i in 0..14 and r in 0..span-1 (note 1). */
    uint16_t d = (uint16_t)(s - fw->p->speed_nominal);
    uint32_t n = (uint32_t)FIELDWEAK_SEGMENTS * d;
    uint16_t i = q15_dsp_divud(n, span);
    uint16_t r = (uint16_t)(n - (uint32_t)i * span);

    /* The fraction r / span as Q16, rounded to nearest (note 2). */
    uint16_t frac = q15_dsp_divud(((uint32_t)r << 16) + (uint32_t)(span / 2U), span);

    /* Id = t[i] + frac (t[i+1] - t[i]) / 2^16, rounded to nearest, ties up. */
    int32_t step = (int32_t)t[i + 1U] - (int32_t)t[i];
    int32_t delta;
    if (step >= 0) {
        delta = (int32_t)(((uint32_t)step * frac + 0x8000UL) >> 16);
    } else {
        delta = -(int32_t)(((uint32_t)(-step) * frac + 0x7FFFUL) >> 16);
    }
    return q15_sat((int32_t)t[i] + delta);
}

/*
 * Notes
 *
 * 1. Index. One 32 / 16 division (div.ud on the dsPIC) of 15 d < 2^19 by
 *    the span gives the segment i = floor(15 d / span) <= 14 (d < span), so
 *    t[i + 1] exists, and its remainder r. At a table point (15 d a multiple
 *    of span) r = 0 and the output is the table entry exactly.
 *
 * 2. Ranges. r <= span - 1 < 2^15, so r 2^16 + span / 2 < 2^31, and the
 *    rounded quotient stays below 2^16: it would reach 2^16 only if span / 2
 *    >= 2^16 (span - r) >= 2^16. |step| <= 65535, so |step| * frac < 2^32.
 *    The result lies between t[i] and t[i + 1]; q15_sat only documents
 *    that. Accuracy: |Id - exact| <= 0.5 LSB (rounding) + |step| / 2^17
 *    LSB (frac within half a Q16 LSB); test_fieldweak.c prints the measured
 *    figure.
 *
 * 3. Two divisions per call, both by the hardware divider (18 cycles
 *    each): no reciprocal, no 32-bit shift by a variable count (a loop on
 *    the dsPIC). AN1078 computed the divisor as Q15(a - b + 1), which
 *    overflowed 16 bits; here the span is an integer count of speed LSB and
 *    never a Q15 value.
 */
