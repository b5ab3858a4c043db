/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* x2c_util.h - the X2Cscope target's tests: one request in, one reply out, and state snapshots. */
#ifndef X2C_UTIL_H
#define X2C_UTIL_H

#include "test_support.h"

#include <stddef.h>
#include <string.h>

#include "lnet.h"
#include "sim_mailbox.h"
#include "x2c.h"

/* the client's side: a receiver for any frame (the target's takes X2C_RX_BYTES) */
static uint8_t rx_buf[LNET_MAX_DATA];

/* The motor the target's mailbox acts on, and the target. */
typedef struct {
    mc_t mc;
    x2c_t x;
    unsigned crc_inverted; /* reply checksums sent inverted (0x55 / 0x02 sums) */
} rig_t;

static inline void rig_init(rig_t *r)
{
    memset(r, 0, sizeof *r);
    mc_init(&r->mc);
    sim_mailbox_attach(&r->mc);
    x2c_init(&r->x);
}

/* A frame for node 1, written here independently of lnet.c's sender:
 * SYN SIZE NODE DATA CRC, 0x00 after every 0x55 / 0x02 of SIZE, NODE, DATA. */
static inline size_t rig_frame(const uint8_t *data, uint8_t n, uint8_t *out)
{
    size_t k = 0;
    unsigned sum = 0x55U, i;
    uint8_t hdr[2];
    hdr[0] = n;
    hdr[1] = 1U;
    out[k++] = 0x55U;
    for (i = 0; i < 2U + n; i++) {
        uint8_t b = (i < 2U) ? hdr[i] : data[i - 2U];
        out[k++] = b;
        sum += b;
        if (b == 0x55U || b == 0x02U) {
            out[k++] = 0x00U;
        }
    }
    sum &= 0xFFU;
    out[k++] = (uint8_t)((sum == 0x55U || sum == 0x02U) ? (~sum & 0xFFU) : sum);
    return k;
}

/* Feeds the bytes; collects the whole reply into reply[] (unescaped DATA);
 * returns its length, or -1 when no reply came. */
static inline int rig_bytes(rig_t *r, const uint8_t *bytes, size_t n, uint8_t *reply)
{
    lnet_rx_t rx;
    uint8_t b;
    int len = -1;
    size_t k;
    for (k = 0; k < n; k++) {
        assert_true(x2c_rx_ready(&r->x));
        x2c_rx_byte(&r->x, bytes[k]);
    }
    lnet_rx_init(&rx, rx_buf, (uint8_t)LNET_MAX_DATA);
    while (x2c_tx_byte(&r->x, &b)) {
        lnet_rx_event_t e = lnet_rx_byte(&rx, b);
        if (e == LNET_RX_FRAME) {
            len = rx.size;
            memcpy(reply, rx.data, rx.size);
            unsigned sum = 0x55U + rx.size + 1U, i;
            for (i = 0; i < rx.size; i++) {
                sum += rx.data[i];
            }
            sum &= 0xFFU;
            if (sum == 0x55U || sum == 0x02U) {
                r->crc_inverted++; /* and lnet_rx accepted it: it was sent inverted */
            }
        } else {
            assert_int_equal(e, LNET_RX_NONE);
        }
    }
    assert_true(x2c_rx_ready(&r->x));
    return len;
}

/* One request (data[0] the service); the reply in reply[], its length. */
static inline int rig_req(rig_t *r, const uint8_t *data, uint8_t n, uint8_t *reply)
{
    uint8_t frame[2U * 258U];
    size_t k = rig_frame(data, n, frame);
    return rig_bytes(r, frame, k, reply);
}

/* The error byte of a request's reply (the reply must be for its service). */
static inline uint8_t rig_err(rig_t *r, const uint8_t *data, uint8_t n)
{
    uint8_t reply[LNET_MAX_DATA];
    int len = rig_req(r, data, n, reply);
    assert_cmp(len, >=, 2);
    assert_int_equal(reply[0], data[0]);
    return reply[1];
}

/* What a refused request must leave as it was: the motor and the target's
 * state (its frame buffers and reply counters aside). */
typedef struct {
    mc_t mc;
    uint8_t x[offsetof(x2c_t, answered) - offsetof(x2c_t, tune)];
} rig_snap_t;

static inline void rig_snap(const rig_t *r, rig_snap_t *s)
{
    memcpy(&s->mc, &r->mc, sizeof s->mc);
    memcpy(s->x, (const uint8_t *)&r->x + offsetof(x2c_t, tune), sizeof s->x);
}

static inline bool rig_same(const rig_t *r, const rig_snap_t *s)
{
    rig_snap_t now;
    rig_snap(r, &now);
    return memcmp(&now.mc, &s->mc, sizeof now.mc) == 0 && memcmp(now.x, s->x, sizeof now.x) == 0;
}

/* Wire addresses of a motor field and of a tunable. */
#define RIG_MOTOR(r, field) ((uint16_t)(x2c_wire(&(r)->x, X2C_OBJ_MOTOR) + offsetof(mc_t, field)))
#define RIG_TUNE(r, field)                                                                         \
    ((uint16_t)(x2c_wire(&(r)->x, X2C_OBJ_TUNE) + offsetof(x2c_tune_t, field)))
#define RIG_SCOPE(r) (x2c_wire(&(r)->x, X2C_OBJ_SCOPE))
#define RIG_ID(r, field)                                                                           \
    ((uint16_t)(x2c_wire(&(r)->x, X2C_OBJ_ID) + offsetof(mc_id_result_t, field)))

#endif /* X2C_UTIL_H */
