/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* x2c_scope.c - the X2Cscope scope (see x2c_scope.h). */
#include "x2c_scope.h"

#include <stddef.h>
#include <string.h>

#if X2C_SCOPE /* else the target has no scope (x2c_scope.h) */

#include "q15_dsp.h"
#include "x2c.h"

/* A compiler barrier: no store is moved across it (gcc, clang, XC16's gcc). The
 * interrupt samples while the main loop configures: the state is its only
 * signal, so the settings are stored after the stop and before the start. */
#define X2C_BARRIER() __asm__ __volatile__("" ::: "memory")

void x2c_scope_init(x2c_scope_t *s)
{
    /* idle (X2C_SCOPE_IDLE is 0), no channel (NULL), an empty buffer; then what is not zero */
    memset(s, 0, sizeof *s);
    s->cfg.rising = true;
    s->dataset = 1;
    s->used = X2C_SCOPE_BYTES;
}

static uint8_t dataset_of(const x2c_scope_cfg_t *cfg)
{
    uint8_t i, n = 0;
    for (i = 0; i < cfg->set.nch; i++) {
        n = (uint8_t)(n + cfg->set.size[i]);
    }
    return n;
}

/* |v| as unsigned (|INT32_MIN| included). */
static uint32_t mag_of(int32_t v)
{
    return (v < 0) ? (uint32_t)0U - (uint32_t)v : (uint32_t)v;
}

/* |v| mod d for d in 1..255, by two 32 / 16 divisions (each quotient fits
 * 16 bits: the high half's is below 2^16, the second's dividend below
 * d 2^16), so no 32-bit division helper is linked. */
static uint16_t mag_rem(int32_t v, uint8_t d)
{
    uint32_t m = mag_of(v);
    uint16_t hi = (uint16_t)(m >> 16);
    uint16_t r = (uint16_t)(hi - (uint16_t)(q15_dsp_divud(hi, d) * d));
    uint32_t lo = ((uint32_t)r << 16) | (uint16_t)m;
    return (uint16_t)(lo - (uint32_t)q15_dsp_divud(lo, d) * d);
}

static bool width_ok(uint8_t n)
{
    return n == 1U || n == 2U || n == 4U;
}

uint8_t x2c_scope_check(const x2c_scope_cfg_t *cfg)
{
    uint8_t i, dataset;
    uint16_t used;
    if (cfg->state == X2C_SCOPE_IDLE) {
        return X2C_ERR_OK; /* a stop */
    }
    if (cfg->state != X2C_SCOPE_SAMPLE && cfg->state != X2C_SCOPE_WAIT_TRIG) {
        return X2C_ERR_FORMAT;
    }
    if (cfg->set.nch < 1U || cfg->set.nch > X2C_SCOPE_CHANNELS) {
        return X2C_ERR_LIMIT;
    }
    for (i = 0; i < cfg->set.nch; i++) {
        if (cfg->src[i] == NULL || !width_ok(cfg->set.size[i])) {
            return X2C_ERR_FORMAT;
        }
    }
    dataset = dataset_of(cfg);
    used = (uint16_t)(X2C_SCOPE_BYTES - X2C_SCOPE_BYTES % dataset);
    if (cfg->state == X2C_SCOPE_WAIT_TRIG) {
        uint8_t n = (uint8_t)(cfg->set.trig_dtype & X2C_TRIG_SIZE);
        if (!width_ok(n) || ((cfg->set.trig_dtype & X2C_TRIG_FLOAT) != 0U && n != 4U)) {
            return X2C_ERR_FORMAT;
        }
        if (mag_rem(cfg->set.delay, dataset) != 0U) {
            return X2C_ERR_FORMAT; /* the client sends whole datasets */
        }
        if (cfg->set.delay >= (int32_t)used) {
            return X2C_ERR_LIMIT; /* more history than the ring holds */
        }
        if (cfg->set.delay < -(int32_t)X2C_SCOPE_WAIT_MAX * (int32_t)dataset) {
            return X2C_ERR_LIMIT; /* a wait of hours, or an overflow */
        }
    }
    return X2C_ERR_OK;
}

/* The interrupt's copy list (x2c_scope_t.word): the words of every
 * channel when all are 2 or 4 bytes (their sources aligned: the target
 * checked), returning their count; else each channel's start, returning 0. */
static uint8_t words_of(const x2c_scope_cfg_t *cfg, const volatile void **word)
{
    uint8_t i, n = 0;
    for (i = 0; i < cfg->set.nch; i++) {
        if (cfg->set.size[i] == 1U) {
            break;
        }
    }
    if (i < cfg->set.nch) {
        for (i = 0; i < cfg->set.nch; i++) {
            word[i] = cfg->src[i];
        }
        return 0;
    }
    for (i = 0; i < cfg->set.nch; i++) {
        word[n++] = cfg->src[i];
        if (cfg->set.size[i] == 4U) {
            word[n++] = cfg->src[i] + 2;
        }
    }
    return n;
}

void x2c_scope_stop(x2c_scope_t *s)
{
    s->run.state = X2C_SCOPE_IDLE;
}

void x2c_scope_start(x2c_scope_t *s, const x2c_scope_cfg_t *cfg)
{
    x2c_scope_stop(s);
    X2C_BARRIER();
    s->cfg = cfg->set;
    if (cfg->state == X2C_SCOPE_IDLE) {
        return;
    }
    s->dataset = dataset_of(cfg);
    s->used = (uint16_t)(X2C_SCOPE_BYTES - X2C_SCOPE_BYTES % s->dataset);
    s->nwords = words_of(cfg, s->word);
    s->run.wr = 0;
    s->run.trig_pos = 0;
    if (cfg->state == X2C_SCOPE_SAMPLE) {
        s->run.left = s->used;
    } else {
        s->run.left = (cfg->set.delay > 0) ? (uint16_t)cfg->set.delay : 0U;
    }
    /* the negative delay in datasets, divided here, not in the interrupt;
     * x2c_scope_check bounds it by X2C_SCOPE_WAIT_MAX datasets, so the
     * quotient fits the 32 / 16 divider's 16 bits */
    s->run.wait = (cfg->set.delay < 0) ? (uint32_t)q15_dsp_divud(mag_of(cfg->set.delay), s->dataset)
                                       : (uint32_t)0;
    s->run.div = 0;
    s->run.prev = 0;
    s->run.primed = false;
    X2C_BARRIER(); /* the state last: the interrupt reads the settings once it sees it */
    s->run.state = cfg->state;
}

uint32_t x2c_scope_key(uint32_t raw, uint8_t dtype)
{
    uint8_t n = (uint8_t)(dtype & X2C_TRIG_SIZE);
    if ((dtype & X2C_TRIG_FLOAT) != 0U) {
        /* sign and magnitude: negatives reversed below the positives */
        return ((raw & 0x80000000UL) != 0UL) ? ~raw : (raw | 0x80000000UL);
    }
    if ((dtype & X2C_TRIG_SIGNED) != 0U) {
        return raw ^ ((uint32_t)1 << (8U * n - 1U)); /* two's complement, sign flipped */
    }
    return raw;
}

/* Did the source cross the level this call? The key (x2c_scope_key) is
 * built from 16-bit halves: no 32-bit shift in the interrupt. */
static bool edge(x2c_scope_t *s)
{
    const x2c_scope_set_t *c = &s->cfg;
    const volatile uint8_t *p = c->trig_src;
    uint32_t key, prev, level;
    bool was;
    if (p == NULL) {
        return true; /* auto */
    }
    switch (c->trig_dtype & (X2C_TRIG_SIZE | X2C_TRIG_FLOAT | X2C_TRIG_SIGNED)) {
        case 1U:
            key = *p;
            break;
        case 1U | X2C_TRIG_SIGNED:
            key = (uint8_t)(*p ^ 0x80U);
            break;
        case 2U:
            key = *(const volatile uint16_t *)(const volatile void *)p;
            break;
        case 2U | X2C_TRIG_SIGNED:
            key = (uint16_t)(*(const volatile uint16_t *)(const volatile void *)p ^ 0x8000U);
            break;
        default: { /* 4 bytes: two aligned words */
            uint16_t lo = *(const volatile uint16_t *)(const volatile void *)p;
            uint16_t hi = *(const volatile uint16_t *)(const volatile void *)(p + 2);
            if ((c->trig_dtype & X2C_TRIG_FLOAT) != 0U) {
                if ((hi & 0x8000U) != 0U) { /* negative: the magnitude reversed */
                    hi = (uint16_t)~hi;
                    lo = (uint16_t)~lo;
                } else {
                    hi |= 0x8000U;
                }
            } else if ((c->trig_dtype & X2C_TRIG_SIGNED) != 0U) {
                hi ^= 0x8000U;
            }
            key = ((uint32_t)hi << 16) | lo;
            break;
        }
    }
    prev = s->run.prev;
    was = s->run.primed;
    s->run.prev = key;
    s->run.primed = true;
    level = c->trig_level;
    if (c->rising) {
        return was && prev < level && key >= level;
    }
    return was && prev > level && key <= level;
}

bool x2c_scope_sample(x2c_scope_t *s, uint16_t *at)
{
    x2c_scope_run_t *r = &s->run;
    uint8_t state = r->state;

    if (state == X2C_SCOPE_IDLE) {
        return false;
    }
    if (state == X2C_SCOPE_WAIT_TRIG) {
        /* evaluated on every call, so the previous value is always the last call's */
        bool fired = edge(s);
        if (fired && r->left == 0U) { /* armed: the history is in */
            if (s->cfg.delay < 0) {
                state = X2C_SCOPE_DELAY; /* r->wait was set by x2c_scope_start */
            } else {
                state = X2C_SCOPE_POST_TRIG;
                r->trig_pos = r->wr;
                r->left = (uint16_t)(s->used - (uint16_t)s->cfg.delay);
            }
            r->state = state;
        }
    }

    /* the prescaler: one dataset every prescaler + 1 calls */
    if (r->div != 0U) {
        r->div--;
        return false;
    }
    r->div = s->cfg.prescaler;

    if (state == X2C_SCOPE_DELAY) {
        if (r->wait != 0UL) {
            r->wait--; /* this slot is one of the delay's */
            return false;
        }
        state = X2C_SCOPE_SAMPLE;
        r->wr = 0;
        r->trig_pos = 0;
        r->left = s->used;
        r->state = state;
    }

    /* one dataset */
    if (s->nwords != 0U) {
        /* every channel 2 or 4 bytes: the dataset is even, so is wr; one
         * load and one store a word, unrolled (docs/x2cscope.md "Cycles") */
        volatile uint16_t *d = (volatile uint16_t *)(volatile void *)&s->buf[r->wr];
        const volatile void *const *w = s->word;
        switch (s->nwords) {
            case 16:
                *d++ = *(const volatile uint16_t *)*w++;
                /* fall through */
            case 15:
                *d++ = *(const volatile uint16_t *)*w++;
                /* fall through */
            case 14:
                *d++ = *(const volatile uint16_t *)*w++;
                /* fall through */
            case 13:
                *d++ = *(const volatile uint16_t *)*w++;
                /* fall through */
            case 12:
                *d++ = *(const volatile uint16_t *)*w++;
                /* fall through */
            case 11:
                *d++ = *(const volatile uint16_t *)*w++;
                /* fall through */
            case 10:
                *d++ = *(const volatile uint16_t *)*w++;
                /* fall through */
            case 9:
                *d++ = *(const volatile uint16_t *)*w++;
                /* fall through */
            case 8:
                *d++ = *(const volatile uint16_t *)*w++;
                /* fall through */
            case 7:
                *d++ = *(const volatile uint16_t *)*w++;
                /* fall through */
            case 6:
                *d++ = *(const volatile uint16_t *)*w++;
                /* fall through */
            case 5:
                *d++ = *(const volatile uint16_t *)*w++;
                /* fall through */
            case 4:
                *d++ = *(const volatile uint16_t *)*w++;
                /* fall through */
            case 3:
                *d++ = *(const volatile uint16_t *)*w++;
                /* fall through */
            case 2:
                *d++ = *(const volatile uint16_t *)*w++;
                /* fall through */
            case 1:
                *d++ = *(const volatile uint16_t *)*w++;
                /* fall through */
            default:
                break;
        }
    } else {
        /* a 1-byte channel among them: byte by byte */
        uint8_t *d = &s->buf[r->wr];
        uint8_t i;
        for (i = 0; i < s->cfg.nch; i++) {
            const volatile uint8_t *p = (const volatile uint8_t *)s->word[i];
            switch (s->cfg.size[i]) {
                case 4:
                    d[3] = p[3];
                    d[2] = p[2];
                    /* fall through */
                case 2:
                    d[1] = p[1];
                    /* fall through */
                default:
                    d[0] = p[0];
                    break;
            }
            d += s->cfg.size[i];
        }
    }
    if (at != NULL) {
        *at = r->wr;
    }
    /* `left` counts the bytes still to record (SAMPLE, POST_TRIG) or the
     * history still missing (WAIT_TRIG) */
    r->wr = (uint16_t)(r->wr + s->dataset);
    if (state == X2C_SCOPE_WAIT_TRIG) {
        if (r->wr >= s->used) {
            r->wr = 0; /* the ring */
        }
        if (r->left != 0U) {
            r->left = (r->left > s->dataset) ? (uint16_t)(r->left - s->dataset) : 0U;
        }
        return true;
    }
    r->left = (uint16_t)(r->left - s->dataset);
    if (r->left == 0U) {
        r->wr = s->used; /* done: the pointer says full */
        r->state = X2C_SCOPE_IDLE;
    } else if (r->wr >= s->used) {
        r->wr = 0; /* POST_TRIG wraps round the ring */
    }
    return true;
}

#endif /* X2C_SCOPE */
