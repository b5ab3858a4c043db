/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* fieldweak.c - field weakening: Id reference from a 16-point table versus speed. */
#include "fieldweak.h"

#define FIELDWEAK_SEGMENTS 15U

void fieldweak_init(fieldweak_t *fw, const fieldweak_params_t *params)
{
    fw->p = params;
    fw->span = 0U;
    fw->recip = 0UL;
    fw->shift = 0U;
    if (params->speed_nominal < 0 || params->speed_max <= params->speed_nominal) {
        return; /* disabled: Id_ref = 0 everywhere */
    }
    /* 1..32767: both speeds are in 0..32767 and max > nominal. */
    uint16_t span = (uint16_t)((int32_t)params->speed_max - (int32_t)params->speed_nominal);
    uint8_t shift = 0U;
    while (((uint32_t)1UL << shift) < (uint32_t)span) {
        shift++;
    }
    /* 2^shift in [span, 2 span), so 2^(16 + shift) / span is in [2^16, 2^17);
     * rounded, it stays below 2^17 (note 2). */
    fw->recip = (((uint32_t)1UL << (16U + shift)) + (uint32_t)(span / 2U)) / (uint32_t)span;
    fw->shift = shift;
    fw->span = span;
}

q15_t fieldweak_id_ref(const fieldweak_t *fw, q15_t speed)
{
    const q15_t *t = fw->p->id_table;
    if (fw->span == 0U) {
        return 0;
    }
    q15_t s = q15_abs_sat(speed);
    if (s < fw->p->speed_nominal) {
        return 0;
    }
    if (s >= fw->p->speed_max) {
        return t[FIELDWEAK_TABLE_SIZE - 1];
    }

    /* d in 0..span-1. f ~ d / span as a Q16 fraction of the whole table,
     * within 1.5 Q16 LSB; it only seeds the segment index. */
    uint32_t span = fw->span;
    uint32_t d = (uint32_t)((int32_t)s - (int32_t)fw->p->speed_nominal);
    uint32_t f = (d * fw->recip) >> fw->shift;
    uint32_t i = (f * FIELDWEAK_SEGMENTS) >> 16;

    /* Exact integer index and remainder of 15 d / span (note 1). */
    int32_t r = (int32_t)(FIELDWEAK_SEGMENTS * d) - (int32_t)(i * span);
    if (r < 0) {
        i--;
        r += (int32_t)span;
    } else if (r >= (int32_t)span) {
        i++;
        r -= (int32_t)span;
    }

    /* Fraction within the segment, r / span as Q16, rounded: < 1 Q16 LSB
     * of error, <= 65534 (note 2). */
    uint32_t round_add = (fw->shift > 0U) ? ((uint32_t)1U << (fw->shift - 1U)) : (uint32_t)0U;
    uint32_t frac = ((uint32_t)r * fw->recip + round_add) >> fw->shift;

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
 * 1. Index. With recip = 2^(16 + shift) / span + e, |e| <= 1/2, and
 *    2^shift >= span, f differs from d 2^16 / span by less than 1.5, so
 *    i = floor(15 f / 2^16) is the true floor(15 d / span) or one off near a
 *    segment boundary; the exact remainder r = 15 d - i span (|.| < 2^20)
 *    detects and fixes that. d < span gives i <= 14, so t[i + 1] exists.
 *    At a table point (15 d a multiple of span) r = 0 and the output is the
 *    table entry exactly.
 *
 * 2. Ranges. d * recip < 2^15 * 2^17 = 2^32. r <= span - 1, so r * recip <
 *    span * recip <= 2^(16 + shift) + span / 2 <= 2^31 + 2^14, and frac <=
 *    65536 - 65536 / span + 1 <= 65534 for span >= 2 (for span = 1, r = 0).
 *    |step| <= 65535, so |step| * frac < 2^32. The result lies between
 *    t[i] and t[i + 1]; q15_sat only documents that.
 *    Accuracy: |Id - exact| <= 0.5 LSB (rounding) + |step| / 65536 LSB
 *    (frac error < 1 Q16 LSB); test_fieldweak.c prints the measured figure.
 *
 * 3. No division at run time: the only one is in fieldweak_init. AN1078
 *    computed the divisor as Q15(a - b + 1), which overflowed 16 bits; here
 *    the span is an integer count of speed LSB and never a Q15 value.
 */
