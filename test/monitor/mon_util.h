/* mon_util.h - host-side frame encoder/decoder for the monitor tests (written apart from
 * monitor.c). */
#ifndef MON_UTIL_H
#define MON_UTIL_H

#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "monitor.h"

/* Reference CRC-16/CCITT-FALSE, table-free, written independently of
 * monitor_crc16 (MSB-first long division over the whole message). */
static inline uint16_t mon_ref_crc(const uint8_t *p, size_t n)
{
    uint32_t crc = 0xFFFFU;
    size_t i;
    int b;
    for (i = 0; i < n; i++) {
        for (b = 7; b >= 0; b--) {
            uint32_t bit = ((uint32_t)p[i] >> (unsigned)b) & 1U;
            uint32_t top = (crc >> 15) & 1U;
            crc = (crc << 1) & 0xFFFFU;
            if ((top ^ bit) != 0U) {
                crc ^= 0x1021U;
            }
        }
    }
    return (uint16_t)crc;
}

/* Encodes a frame into out (room for len + 5); returns its length. */
static inline size_t mon_encode(uint8_t *out, uint8_t cmd, const uint8_t *payload, uint8_t len)
{
    uint16_t crc;
    out[0] = MONITOR_SOF;
    out[1] = len;
    out[2] = cmd;
    if (len > 0U) {
        memcpy(&out[3], payload, len);
    }
    crc = mon_ref_crc(&out[1], (size_t)len + 2U);
    out[3 + len] = (uint8_t)(crc & 0xFFU);
    out[4 + len] = (uint8_t)(crc >> 8);
    return (size_t)len + 5U;
}

static inline void mon_feed(monitor_t *m, const uint8_t *p, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) {
        monitor_rx_byte(m, p[i]);
    }
}

static inline void mon_send(monitor_t *m, uint8_t cmd, const uint8_t *payload, uint8_t len)
{
    uint8_t f[300];
    size_t n = mon_encode(f, cmd, payload, len);
    mon_feed(m, f, n);
}

typedef struct {
    uint8_t cmd, len;
    uint8_t payload[256];
} mon_frame_t;

/* Takes every queued TX byte into buf; returns the count. */
static inline size_t mon_drain(monitor_t *m, uint8_t *buf, size_t cap)
{
    size_t n = 0;
    uint8_t b;
    while (n < cap && monitor_tx_byte(m, &b)) {
        buf[n++] = b;
    }
    return n;
}

/* Decodes frames from buf[0..n) into out[]; returns how many, or -1 on a
 * malformed device frame (the device must never send one). */
static inline int mon_decode_all(const uint8_t *buf, size_t n, mon_frame_t *out, int max)
{
    size_t i = 0;
    int k = 0;
    while (i < n) {
        uint8_t len;
        uint16_t crc;
        if (buf[i] != MONITOR_SOF || i + 5U > n) {
            return -1;
        }
        len = buf[i + 1];
        if (len > MONITOR_MAX_PAYLOAD || i + 5U + len > n || k >= max) {
            return -1;
        }
        crc = mon_ref_crc(&buf[i + 1], (size_t)len + 2U);
        if (buf[i + 3 + len] != (uint8_t)(crc & 0xFFU) || buf[i + 4 + len] != (uint8_t)(crc >> 8)) {
            return -1;
        }
        out[k].cmd = buf[i + 2];
        out[k].len = len;
        memcpy(out[k].payload, &buf[i + 3], len);
        k++;
        i += 5U + len;
    }
    return k;
}

static inline uint16_t mon_u16(const uint8_t *p)
{
    return (uint16_t)(p[0] | (p[1] << 8));
}

static inline int16_t mon_i16(const uint8_t *p)
{
    return (int16_t)mon_u16(p);
}

static inline uint32_t mon_u32(const uint8_t *p)
{
    return (uint32_t)mon_u16(p) | ((uint32_t)mon_u16(p + 2) << 16);
}

#endif /* MON_UTIL_H */
