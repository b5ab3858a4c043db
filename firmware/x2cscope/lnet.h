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
 * a new SYN, so a receiver that lost its place finds the next frame.
 *
 * Neither side needs more than the one 255-byte data buffer: the receiver
 * unescapes into it, and the sender escapes from it as it hands out one
 * byte at a time, so a reply can be built in the request's buffer and sent
 * from the main loop without a second, escaped copy (up to 514 bytes for node 1).
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
    LNET_RX_NONE,      /* nothing complete yet */
    LNET_RX_FRAME,     /* a frame for this node: rx->data[0 .. rx->size - 1] */
    LNET_RX_BAD_CRC,   /* a whole frame whose checksum did not match: dropped */
    LNET_RX_BAD_FORMAT /* a reserved byte without its fill: dropped */
} lnet_rx_event_t;

typedef struct {
    uint8_t state;   /* where in the frame the next byte belongs (lnet.c) */
    uint8_t size;    /* SIZE of the frame being received */
    uint8_t node;    /* its NODE */
    uint8_t n;       /* DATA bytes received so far */
    uint8_t sum;     /* running checksum, mod 256 */
    uint8_t pending; /* the reserved byte whose fill is due next, 0: none */
    uint8_t data[LNET_MAX_DATA];
} lnet_rx_t;

void lnet_rx_init(lnet_rx_t *rx);

/* One received byte. A frame addressed to another node is dropped without
 * an event. After LNET_RX_FRAME the data stay valid until the next byte is
 * fed. */
lnet_rx_event_t lnet_rx_byte(lnet_rx_t *rx, uint8_t byte);

/* ---- sending ------------------------------------------------------------------ */

typedef struct {
    const uint8_t *data; /* the frame's DATA, unescaped; must stay until it is sent */
    uint8_t size;
    uint8_t node;
    uint8_t state; /* the next field to send (lnet.c) */
    uint8_t n;     /* DATA bytes sent */
    uint8_t sum;
    bool fill; /* the byte just sent was reserved: its fill is next */
} lnet_tx_t;

/* Nothing to send. */
void lnet_tx_init(lnet_tx_t *tx);

/* Start sending one frame of size bytes of data from node. */
void lnet_tx_start(lnet_tx_t *tx, uint8_t node, const uint8_t *data, uint8_t size);

/* The next byte of the frame into *byte; false once the frame is all sent
 * (or none was started). */
bool lnet_tx_next(lnet_tx_t *tx, uint8_t *byte);

/* True while a frame is being sent. */
bool lnet_tx_busy(const lnet_tx_t *tx);

/* The checksum byte as sent for the unescaped sum of a frame: inverted when
 * it would read as a reserved byte. */
uint8_t lnet_crc_byte(uint8_t sum);

#endif /* LNET_H */
