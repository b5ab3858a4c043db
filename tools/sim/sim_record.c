/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_record.c - the period record's writer (sim_record.h). */
#include "sim_record.h"

#include <string.h>

static uint8_t *put16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)(v & 0xFFU);
    p[1] = (uint8_t)(v >> 8);
    return p + 2;
}

int sim_record_header(FILE *f, uint16_t slow_periods, uint32_t pwm_hz)
{
    uint8_t h[16];
    uint8_t *p = h + 8;
    memcpy(h, SIM_RECORD_MAGIC, 8);
    p = put16(p, 1U);
    p = put16(p, (uint16_t)SIM_RECORD_BYTES);
    p = put16(p, slow_periods);
    (void)put16(p, (uint16_t)(pwm_hz / 10U));
    return fwrite(h, sizeof h, 1, f) == 1 ? 0 : -1;
}

int sim_record_period(FILE *f, uint16_t requests, const hal_adc_frame_t *in,
                      const hal_pwm_out_t *out, uint16_t state)
{
    uint8_t r[SIM_RECORD_BYTES];
    uint8_t *p = r;
    p = put16(p, requests);
    p = put16(p, (uint16_t)in->ia);
    p = put16(p, (uint16_t)in->ib);
    p = put16(p, (uint16_t)in->vbus);
    p = put16(p, (uint16_t)in->pot);
    p = put16(p, out->duty[0]);
    p = put16(p, out->duty[1]);
    p = put16(p, out->duty[2]);
    *p++ = out->outputs_on ? 1U : 0U;
    *p++ = 0U;
    (void)put16(p, state);
    return fwrite(r, sizeof r, 1, f) == 1 ? 0 : -1;
}
