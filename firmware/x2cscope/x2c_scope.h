/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* x2c_scope.h - the X2Cscope scope: channels sampled in the ADC interrupt, an edge trigger. */
#ifndef X2C_SCOPE_H
#define X2C_SCOPE_H

/*
 * The recorder X2Cscope clients configure with "save parameter 1" and poll
 * with "load parameter 1" (docs/x2cscope.md, "Scope"). It knows nothing of
 * addresses: the target (x2c.c) resolves every channel and the trigger
 * source against its whitelist and hands this module plain pointers.
 *
 * Sampling. x2c_scope_sample() runs once per PWM period in the ADC
 * interrupt, after the duties are written. Every call evaluates the
 * trigger; every (prescaler + 1)th call stores one dataset: each channel's
 * bytes, in channel order, little-endian as in memory. The buffer is a ring
 * of `used` bytes (the largest whole number of datasets that fits).
 *
 * Modes (the state the client writes):
 *   2  sample until full: datasets 0.. from the start of the buffer, the
 *      trigger ignored, trigger position 0;
 *   1  wait for the trigger, then:
 *      delay >= 0 (bytes, whole datasets): keeps `delay` bytes recorded
 *        before the trigger; the trigger is armed once they are in the
 *        ring; the dataset stored at or after the edge is at `trig_pos`,
 *        and the ring is full when `used - delay` bytes from it are in;
 *        the oldest dataset is then at trig_pos - delay (mod used), where
 *        the client rotates to;
 *      delay < 0: waits -delay bytes' worth of datasets (prescaled) after
 *        the edge, then records from the start of the buffer like mode 2.
 *   trigger mode 0 (auto) fires on the first call the edge could.
 * Done, the state returns to 0 (idle); the client reads the buffer.
 *
 * Edge: rising, the previous value below the level and this one at or
 * above it; falling, the previous above and this one at or below. Values
 * are compared as unsigned keys (x2c_scope_key): signed integers with the
 * sign bit flipped, IEEE float32 by sign and magnitude, so one unsigned
 * compare serves every type and no float arithmetic runs in the interrupt.
 *
 * Sharing: the configuration is written by the main loop only while the
 * state is 0 (the interrupt then does nothing), and the state last; the
 * `run` part is the interrupt's; the main loop reads it only masked.
 */

#include <stdbool.h>
#include <stdint.h>

/* X2C_SCOPE: the scope (1, the default). 0 leaves it out, with its RAM: the
 * target then answers no load or save parameter service (the commissioning
 * image, make firmware IMAGE=identify, whose client only reads and writes
 * variables). */
#ifndef X2C_SCOPE
#define X2C_SCOPE 1
#endif

#ifndef X2C_SCOPE_BYTES
/* The sample buffer, bytes. 360 = 2^3 x 3^2 x 5: whole datasets of 2, 4, 6,
 * 8, 10, 12, 18, 20 and 24 bytes fill it exactly. docs/x2cscope.md, "RAM",
 * says why not more on the 2 KB dsPIC33FJ32MC204. */
#define X2C_SCOPE_BYTES 360U
#endif
#define X2C_SCOPE_CHANNELS 8U     /* most channels one dataset holds */
#define X2C_SCOPE_WAIT_MAX 65535L /* longest negative delay, datasets (3.3 s at 20 kHz) */
#define X2C_SCOPE_VERSION  0x82U  /* the scope's layout version (load parameter) */

/* Scope states (the protocol's numbers). */
#define X2C_SCOPE_IDLE      0U
#define X2C_SCOPE_WAIT_TRIG 1U /* ring recording, waiting for the edge */
#define X2C_SCOPE_SAMPLE    2U /* sampling until the buffer is full */
#define X2C_SCOPE_POST_TRIG 7U /* the edge came: the rest of the ring */
#define X2C_SCOPE_DELAY     8U /* the edge came: waiting the negative delay */

/* Trigger data type flags (the dtype byte of the configuration). */
#define X2C_TRIG_FLOAT  0x40U
#define X2C_TRIG_SIGNED 0x20U
#define X2C_TRIG_SIZE   0x0FU

typedef struct {
    uint8_t state;     /* X2C_SCOPE_*: the interrupt's, the main loop's only while idle */
    uint16_t wr;       /* next byte of the ring to write */
    uint16_t trig_pos; /* where the dataset at or after the edge was stored, bytes */
    uint16_t left;     /* SAMPLE, POST_TRIG: bytes still to record; WAIT_TRIG: history missing */
    uint32_t wait;     /* DELAY: datasets still to wait */
    uint16_t div;      /* calls since the last dataset */
    uint32_t prev;     /* the trigger source's key at the last call */
    bool primed;       /* prev holds a value */
} x2c_scope_run_t;

/* What the scope keeps of a configuration (x2c_scope_start copies it). */
typedef struct {
    uint8_t nch; /* 1..X2C_SCOPE_CHANNELS */
    uint16_t prescaler;
    uint8_t size[X2C_SCOPE_CHANNELS]; /* 1, 2 or 4, aligned to it */
    /* the trigger (WAIT_TRIG) */
    const volatile uint8_t *trig_src; /* NULL: auto (fires without an edge) */
    uint8_t trig_dtype;               /* X2C_TRIG_* flags | size */
    uint32_t trig_level;              /* as a key (x2c_scope_key) */
    bool rising;
    int32_t delay; /* bytes, whole datasets: > 0 history, < 0 wait */
} x2c_scope_set_t;

/* One configuration, as the target resolved it: the settings, and what
 * only the start reads (the state, then run.state; the channels'
 * pointers, then the copy list x2c_scope_t.word), which the RAM does not
 * keep twice. */
typedef struct {
    x2c_scope_set_t set;
    uint8_t state; /* X2C_SCOPE_SAMPLE or X2C_SCOPE_WAIT_TRIG (X2C_SCOPE_IDLE: stop) */
    const volatile uint8_t *src[X2C_SCOPE_CHANNELS];
} x2c_scope_cfg_t;

typedef struct {
    x2c_scope_set_t cfg;
    uint8_t dataset; /* bytes per dataset */
    uint16_t used;   /* bytes of whole datasets the buffer holds */
    /* What the interrupt copies: with every channel 2 or 4 bytes (nwords
     * > 0), the dataset's nwords words from word[0..nwords-1], word-aligned
     * at both ends; otherwise channel i's size[i] bytes from word[i]. */
    uint8_t nwords;
    const volatile void *word[2U * X2C_SCOPE_CHANNELS];
    x2c_scope_run_t run;
    uint8_t buf[X2C_SCOPE_BYTES];
} x2c_scope_t;

/* Idle, no channel. */
void x2c_scope_init(x2c_scope_t *s);

/* Checks a configuration: 0, or the X2Cscope error code of its fault
 * (X2C_ERR_*: x2c.h). Channels and source are taken as resolved. */
uint8_t x2c_scope_check(const x2c_scope_cfg_t *cfg);

/* Stops the scope, takes a checked configuration and starts it (the
 * caller masks the interrupt or knows it does not run). */
void x2c_scope_start(x2c_scope_t *s, const x2c_scope_cfg_t *cfg);

/* Stops the scope (atomic: one byte). */
void x2c_scope_stop(x2c_scope_t *s);

/* The ADC interrupt, once per period. True when it stored a dataset this
 * call (at byte *at of the buffer, when at is not NULL). */
bool x2c_scope_sample(x2c_scope_t *s, uint16_t *at);

/* An n-byte value (little-endian raw bytes, n = 1, 2 or 4) as an unsigned
 * key that orders like the value of the given type. */
uint32_t x2c_scope_key(uint32_t raw, uint8_t dtype);

#endif /* X2C_SCOPE_H */
