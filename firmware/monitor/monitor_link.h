/* monitor_link.h - the monitor's framing: received bytes -> frames, frames -> bytes to send. */
#ifndef MONITOR_LINK_H
#define MONITOR_LINK_H

/*
 * One job: the frame layout of docs/monitor.md "Protocol" and nothing about
 * what a command means. Frame, both directions, multi-byte fields
 * little-endian:
 *   0xA5 | LEN | CMD | PAYLOAD[LEN] | CRC16 lo | CRC16 hi
 * LEN <= MONITOR_MAX_PAYLOAD; CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF,
 * no reflection, no final xor) over LEN, CMD and PAYLOAD. Bytes between
 * frames are skipped until the next 0xA5.
 * Main loop only: nothing here is touched by the ISR.
 */

#include <stdbool.h>
#include <stdint.h>

/* ---- sizes (override MONITOR_TX_SIZE with -D) ------------------------------- */
#define MONITOR_MAX_PAYLOAD 40U /* longest payload accepted or sent, bytes */
#ifndef MONITOR_TX_SIZE
#define MONITOR_TX_SIZE 128U /* transmit queue, bytes, power of two <= 256 */
#endif
#define MONITOR_FRAME_OVERHEAD 5U /* SOF LEN CMD CRC CRC */
#define MONITOR_REPLY_MAX      (MONITOR_MAX_PAYLOAD + MONITOR_FRAME_OVERHEAD) /* 45 bytes */
#define MONITOR_RX_TIMEOUT_MS  20U /* a frame with a longer gap between bytes is dropped */
#define MONITOR_SOF            0xA5U

typedef enum {
    MONITOR_RX_SOF,
    MONITOR_RX_LEN,
    MONITOR_RX_CMD,
    MONITOR_RX_PAYLOAD,
    MONITOR_RX_CRC0,
    MONITOR_RX_CRC1
} monitor_rx_state_t;

/* What a received byte completed. */
typedef enum {
    MONITOR_LINK_NONE,    /* nothing yet */
    MONITOR_LINK_FRAME,   /* a whole frame, CRC good: rx_cmd, rx_len, rx_buf hold it */
    MONITOR_LINK_BAD_CRC, /* a whole frame, CRC wrong: rx_cmd holds its CMD byte */
    MONITOR_LINK_TOO_LONG /* LEN above MONITOR_MAX_PAYLOAD: the frame is dropped */
} monitor_link_event_t;

typedef struct {
    /* receiver */
    monitor_rx_state_t rx_state;
    uint8_t rx_len, rx_cmd, rx_pos;
    uint16_t rx_crc; /* running CRC of LEN CMD PAYLOAD */
    uint8_t rx_crc_lo;
    uint8_t rx_idle_ms; /* ms since the last byte of a partial frame */
    uint8_t rx_buf[MONITOR_MAX_PAYLOAD];
    /* transmitter: a ring, head written by the senders, tail by monitor_link_tx_byte */
    uint8_t tx[MONITOR_TX_SIZE];
    uint8_t tx_head, tx_tail;
} monitor_link_t;

/* Receiver waiting for a frame, transmit queue empty. */
void monitor_link_init(monitor_link_t *l);

/* Feeds one received byte; says what it completed. A frame's contents stay
 * in rx_cmd, rx_len, rx_buf until the next byte. */
monitor_link_event_t monitor_link_rx_byte(monitor_link_t *l, uint8_t byte);

/* Every millisecond. True when a partial frame had no byte for
 * MONITOR_RX_TIMEOUT_MS: it is dropped and the receiver waits for 0xA5. */
bool monitor_link_tick_1ms(monitor_link_t *l);

/* Free room in the transmit queue, bytes. */
unsigned monitor_link_tx_free(const monitor_link_t *l);

/* Queues one frame of len payload bytes. The caller has checked the room
 * (len + MONITOR_FRAME_OVERHEAD). */
void monitor_link_send(monitor_link_t *l, uint8_t cmd, const uint8_t *payload, uint8_t len);

/* Next byte for the UART; false when the queue is empty. */
bool monitor_link_tx_byte(monitor_link_t *l, uint8_t *byte);

/* CRC-16/CCITT-FALSE update of crc with one byte. */
uint16_t monitor_crc16(uint16_t crc, uint8_t byte);

/* Little-endian fields of a payload. */
static inline void monitor_put16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)(v & 0xFFU);
    p[1] = (uint8_t)(v >> 8);
}

static inline void monitor_put32(uint8_t *p, uint32_t v)
{
    monitor_put16(p, (uint16_t)(v & 0xFFFFU));
    monitor_put16(p + 2, (uint16_t)(v >> 16));
}

static inline uint16_t monitor_get16(const uint8_t *p)
{
    return (uint16_t)((uint16_t)p[0] | (uint16_t)((uint16_t)p[1] << 8));
}

#endif /* MONITOR_LINK_H */
