/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* lnet.c - the LNet frame layer: receiver and sender, one byte at a time (lnet.h). */
#include "lnet.h"

#include <stddef.h>

/* Receiver states: the field the next byte belongs to. RX_SYN: a 0x55 out of
 * a frame, which the next byte makes a SYN (anything but the fill) or
 * escaped data of a frame missed (the fill). */
enum { RX_IDLE, RX_SYN, RX_SIZE, RX_NODE, RX_DATA, RX_CRC };

/* Sender states. */
enum { TX_IDLE, TX_SYN, TX_SIZE, TX_NODE, TX_DATA, TX_CRC };

static bool lnet_reserved(uint8_t b)
{
    return b == LNET_SYN || b == LNET_RESERVED;
}

uint8_t lnet_crc_byte(uint8_t sum)
{
    return lnet_reserved(sum) ? (uint8_t)~sum : sum;
}

void lnet_rx_init(lnet_rx_t *rx, uint8_t *data, uint8_t cap)
{
    rx->data = data;
    rx->cap = cap;
    rx->state = RX_IDLE;
    rx->size = 0U;
    rx->node = 0U;
    rx->n = 0U;
    rx->sum = 0U;
    rx->pending = 0U;
}

/* A SYN: a new frame starts, whatever came before. */
static void rx_syn(lnet_rx_t *rx)
{
    rx->state = RX_SIZE;
    rx->sum = (uint8_t)LNET_SYN;
    rx->n = 0U;
    rx->pending = 0U;
}

/* The field after one that is complete (its fill, if any, taken). */
static void rx_advance(lnet_rx_t *rx)
{
    if (rx->state == RX_SIZE) {
        rx->state = RX_NODE;
    } else if (rx->state == RX_NODE || rx->n == rx->size) {
        rx->state = (rx->size == 0U || rx->n == rx->size) ? RX_CRC : RX_DATA;
    }
}

/* A SIZE, NODE or DATA byte, unescaped: stored and summed. */
static void rx_field(lnet_rx_t *rx, uint8_t b)
{
    if (rx->state == RX_SIZE) {
        rx->size = b;
    } else if (rx->state == RX_NODE) {
        rx->node = b;
    } else {
        if (rx->n < rx->cap) {
            rx->data[rx->n] = b;
        }
        rx->n++; /* <= rx->size <= 255 */
    }
    rx->sum = (uint8_t)(rx->sum + b);
    if (lnet_reserved(b)) {
        rx->pending = b; /* its fill comes first */
    } else {
        rx_advance(rx);
    }
}

/* The frame's node is known and is another's: its errors are not ours to
 * answer (a corrupted byte may have made it so: the client times out). */
static bool rx_not_ours(const lnet_rx_t *rx)
{
    return rx->state > RX_NODE && rx->node != LNET_NODE;
}

lnet_rx_event_t lnet_rx_byte(lnet_rx_t *rx, uint8_t b)
{
    if (rx->state == RX_IDLE) {
        if (b == LNET_SYN) {
            rx->state = RX_SYN;
        }
        return LNET_RX_NONE;
    }
    if (rx->state == RX_SYN) {
        if (b == LNET_FILL) {
            rx->state = RX_IDLE; /* 55 00: a data byte 0x55 of a frame we were not in */
            return LNET_RX_NONE;
        }
        rx_syn(rx);
        rx_field(rx, b); /* the SIZE (0x55: its fill, or a new SYN, decides next) */
        return LNET_RX_NONE;
    }
    if (rx->pending != 0U) {
        uint8_t was = rx->pending;
        rx->pending = 0U;
        if (b == LNET_FILL) {
            rx_advance(rx);
            return LNET_RX_NONE;
        }
        if (was == LNET_SYN) {
            /* the 0x55 was a SYN: b is the new frame's SIZE */
            rx_syn(rx);
            rx_field(rx, b);
            return LNET_RX_NONE;
        }
        /* a 0x02 without its fill: answered only in a frame known to be ours */
        bool answer = rx->state > RX_NODE && !rx_not_ours(rx);
        rx->state = (b == LNET_SYN) ? RX_SYN : RX_IDLE;
        return answer ? LNET_RX_BAD_FORMAT : LNET_RX_NONE;
    }
    if (rx->state == RX_CRC) {
        bool ours = !rx_not_ours(rx);
        rx->state = RX_IDLE;
        if (b != lnet_crc_byte(rx->sum)) {
            if (b == LNET_SYN) {
                rx->state = RX_SYN; /* no checksum reads 0x55: a new frame */
            }
            return ours ? LNET_RX_BAD_CRC : LNET_RX_NONE;
        }
        if (rx->node != LNET_NODE) {
            return LNET_RX_NONE;
        }
        return (rx->size > rx->cap) ? LNET_RX_TOO_LONG : LNET_RX_FRAME;
    }
    rx_field(rx, b);
    return LNET_RX_NONE;
}

bool lnet_rx_gap(lnet_rx_t *rx)
{
    bool partial = rx->state != RX_IDLE;
    rx->state = RX_IDLE;
    rx->pending = 0U;
    return partial;
}

void lnet_tx_init(lnet_tx_t *tx)
{
    lnet_tx_start(tx, LNET_NODE, NULL, 0U, NULL, 0U);
    tx->state = TX_IDLE;
}

void lnet_tx_start(lnet_tx_t *tx, uint8_t node, const uint8_t *data, uint8_t head,
                   const volatile uint8_t *body, uint8_t size)
{
    tx->data = data;
    tx->body = body;
    tx->head = head;
    tx->size = size;
    tx->node = node;
    tx->state = TX_SYN;
    tx->n = 0U;
    tx->sum = 0U;
    tx->fill = false;
}

bool lnet_tx_busy(const lnet_tx_t *tx)
{
    return tx->state != TX_IDLE;
}

/* A SIZE, NODE or DATA byte: summed, and its fill due if it is reserved. */
static uint8_t tx_field(lnet_tx_t *tx, uint8_t b, uint8_t next)
{
    tx->sum = (uint8_t)(tx->sum + b);
    tx->fill = lnet_reserved(b);
    tx->state = next;
    return b;
}

bool lnet_tx_next(lnet_tx_t *tx, uint8_t *byte)
{
    if (tx->state == TX_IDLE) {
        return false;
    }
    if (tx->fill) {
        tx->fill = false;
        *byte = LNET_FILL;
        return true;
    }
    switch (tx->state) {
        case TX_SYN:
            tx->sum = (uint8_t)LNET_SYN;
            tx->state = TX_SIZE;
            *byte = LNET_SYN;
            break;
        case TX_SIZE:
            *byte = tx_field(tx, tx->size, TX_NODE);
            break;
        case TX_NODE:
            *byte = tx_field(tx, tx->node, (tx->size == 0U) ? TX_CRC : TX_DATA);
            break;
        case TX_DATA: {
            uint8_t b = (tx->n < tx->head) ? tx->data[tx->n] : tx->body[tx->n - tx->head];
            tx->n++;
            *byte = tx_field(tx, b, (tx->n == tx->size) ? TX_CRC : TX_DATA);
            break;
        }
        default: /* TX_CRC */
            *byte = lnet_crc_byte(tx->sum);
            tx->state = TX_IDLE;
            break;
    }
    return true;
}
