/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* lnet.h - the LNet frame layer X2Cscope clients speak: a byte-at-a-time receiver and sender. */
#ifndef LNET_H
#define LNET_H

/*
 * A frame is SYN SIZE NODE DATA[SIZE] CRC (docs/x2cscope.md, "Frame"):
 *   SYN   0x55, never escaped;
 *   SIZE  the number of DATA bytes, 0..255;
 *   NODE  the client sends 1, the target answers with its own id (1);
 *   CRC   (SYN + SIZE + NODE + DATA) mod 256 over the unescaped values,
 *         sent inverted when it equals 0x55 or 0x02, never escaped.
 * 0x55 and 0x02 are reserved inside a frame: wherever SIZE, NODE or a DATA
 * byte equals one of them, a 0x00 fill byte follows, which is neither
 * counted in SIZE nor summed. A 0x55 followed by anything but the fill is
 * a new SYN, so a receiver that lost its place finds the next frame; out
 * of a frame, 0x55 0x00 is such a data byte of a frame it missed, not a SYN.
 * Errors are reported only for a frame whose NODE was received and is this
 * target's: noise and other nodes' frames get no answer.
 *
 * The receiver unescapes into a buffer its owner sizes: a target's for the
 * largest request it takes, not for the largest frame (a longer one is
 * received to its checksum and reported, without its data). The sender
 * escapes as it hands out one byte at a time, from a head (built in the
 * request's buffer) and a body (read where it lies, e.g. the scope's
 * buffer), so a reply of up to 255 data bytes needs no buffer of its own
 * and no second, escaped copy (up to 514 bytes for node 1).
 */

#include <stdbool.h>
#include <stdint.h>

#define LNET_SYN      0x55U
#define LNET_RESERVED 0x02U /* the other byte that takes a fill */
#define LNET_FILL     0x00U
#define LNET_MAX_DATA 255U /* SIZE is one byte: the largest frame a client sends */
#define LNET_NODE     1U   /* this target's id, and the one clients address */

/* ---- receiving ------------------------------------------------------------- */

typedef enum {
    LNET_RX_NONE,       /* nothing complete yet */
    LNET_RX_FRAME,      /* a frame for this node: rx->data[0 .. rx->size - 1] */
    LNET_RX_BAD_CRC,    /* a whole frame whose checksum did not match: dropped */
    LNET_RX_BAD_FORMAT, /* a reserved byte without its fill: dropped */
    LNET_RX_TOO_LONG    /* a whole, valid frame for this node of more data bytes than
                           the buffer holds: rx->size says how many, rx->data the first */
} lnet_rx_event_t;

typedef struct {
    uint8_t state;   /* where in the frame the next byte belongs (lnet.c) */
    uint8_t size;    /* SIZE of the frame being received */
    uint8_t node;    /* its NODE */
    uint8_t n;       /* DATA bytes received so far (the first cap of them stored) */
    uint8_t sum;     /* running checksum, mod 256 */
    uint8_t pending; /* the reserved byte whose fill is due next, 0: none */
    uint8_t cap;     /* bytes of data */
    uint8_t *data;   /* the owner's buffer */
} lnet_rx_t;

/* Idle, receiving into cap bytes of data (at most LNET_MAX_DATA are used). */
void lnet_rx_init(lnet_rx_t *rx, uint8_t *data, uint8_t cap);

/* One received byte. A frame addressed to another node, and any error of
 * one, is dropped without an event. After LNET_RX_FRAME the data stay valid
 * until the next byte is fed. */
lnet_rx_event_t lnet_rx_byte(lnet_rx_t *rx, uint8_t byte);

/* The line has been silent longer than a client leaves between the bytes
 * of a frame (the owner's timeout): a partial frame is dropped, so a client
 * that left in the middle of one leaves nothing for the next. True when
 * one was. */
bool lnet_rx_gap(lnet_rx_t *rx);

/* ---- sending ------------------------------------------------------------------ */

typedef struct {
    const uint8_t *data;          /* the DATA's head, unescaped; must stay until it is sent */
    const volatile uint8_t *body; /* its body, read as it is sent (NULL: none) */
    uint8_t head;                 /* bytes of the head */
    uint8_t size;                 /* of head and body */
    uint8_t node;
    uint8_t state; /* the next field to send (lnet.c) */
    uint8_t n;     /* DATA bytes sent */
    uint8_t sum;
    bool fill; /* the byte just sent was reserved: its fill is next */
} lnet_tx_t;

/* Nothing to send. */
void lnet_tx_init(lnet_tx_t *tx);

/* Start sending one frame from node: its DATA are head bytes of data, then
 * size - head bytes of body (each read when it is sent), head <= size. */
void lnet_tx_start(lnet_tx_t *tx, uint8_t node, const uint8_t *data, uint8_t head,
                   const volatile uint8_t *body, uint8_t size);

/* The next byte of the frame into *byte; false once the frame is all sent
 * (or none was started). */
bool lnet_tx_next(lnet_tx_t *tx, uint8_t *byte);

/* True while a frame is being sent. */
bool lnet_tx_busy(const lnet_tx_t *tx);

/* The checksum byte as sent for the unescaped sum of a frame: inverted when
 * it would read as a reserved byte. */
uint8_t lnet_crc_byte(uint8_t sum);

#endif /* LNET_H */
