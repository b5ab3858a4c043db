/* monitor_link.c - the monitor's framing (see monitor_link.h). */
#include "monitor_link.h"

#include "q15.h"

Q15_STATIC_ASSERT((MONITOR_TX_SIZE & (MONITOR_TX_SIZE - 1U)) == 0U && MONITOR_TX_SIZE <= 256U,
                  "MONITOR_TX_SIZE must be a power of two up to 256");
Q15_STATIC_ASSERT(MONITOR_TX_SIZE >= 2U * MONITOR_REPLY_MAX + 1U,
                  "the TX queue must hold a data frame and a reply");
Q15_STATIC_ASSERT(MONITOR_MAX_PAYLOAD >= 36U && MONITOR_MAX_PAYLOAD <= 250U,
                  "MONITOR_MAX_PAYLOAD out of range");

uint16_t monitor_crc16(uint16_t crc, uint8_t byte)
{
    uint8_t i;
    crc = (uint16_t)(crc ^ (uint16_t)((uint16_t)byte << 8));
    for (i = 0; i < 8U; i++) {
        if ((crc & 0x8000U) != 0U) {
            crc = (uint16_t)((uint16_t)(crc << 1) ^ 0x1021U);
        } else {
            crc = (uint16_t)(crc << 1);
        }
    }
    return crc;
}

void monitor_link_init(monitor_link_t *l)
{
    uint16_t i;
    l->rx_state = MONITOR_RX_SOF;
    l->rx_len = 0;
    l->rx_cmd = 0;
    l->rx_pos = 0;
    l->rx_crc = 0xFFFFU;
    l->rx_crc_lo = 0;
    l->rx_idle_ms = 0;
    for (i = 0; i < MONITOR_MAX_PAYLOAD; i++) {
        l->rx_buf[i] = 0;
    }
    for (i = 0; i < MONITOR_TX_SIZE; i++) {
        l->tx[i] = 0;
    }
    l->tx_head = 0;
    l->tx_tail = 0;
}

/* ---- receiver ---------------------------------------------------------------- */

monitor_link_event_t monitor_link_rx_byte(monitor_link_t *l, uint8_t byte)
{
    l->rx_idle_ms = 0;
    switch (l->rx_state) {
        case MONITOR_RX_SOF:
            if (byte == MONITOR_SOF) {
                l->rx_state = MONITOR_RX_LEN;
                l->rx_crc = 0xFFFFU;
            }
            return MONITOR_LINK_NONE; /* anything else between frames is noise: skipped */
        case MONITOR_RX_LEN:
            if (byte > MONITOR_MAX_PAYLOAD) {
                l->rx_state = MONITOR_RX_SOF;
                return MONITOR_LINK_TOO_LONG;
            }
            l->rx_len = byte;
            l->rx_crc = monitor_crc16(l->rx_crc, byte);
            l->rx_state = MONITOR_RX_CMD;
            return MONITOR_LINK_NONE;
        case MONITOR_RX_CMD:
            l->rx_cmd = byte;
            l->rx_crc = monitor_crc16(l->rx_crc, byte);
            l->rx_pos = 0;
            l->rx_state = (l->rx_len == 0U) ? MONITOR_RX_CRC0 : MONITOR_RX_PAYLOAD;
            return MONITOR_LINK_NONE;
        case MONITOR_RX_PAYLOAD:
            l->rx_buf[l->rx_pos++] = byte;
            l->rx_crc = monitor_crc16(l->rx_crc, byte);
            if (l->rx_pos >= l->rx_len) {
                l->rx_state = MONITOR_RX_CRC0;
            }
            return MONITOR_LINK_NONE;
        case MONITOR_RX_CRC0:
            l->rx_crc_lo = byte;
            l->rx_state = MONITOR_RX_CRC1;
            return MONITOR_LINK_NONE;
        default: /* MONITOR_RX_CRC1 */
            l->rx_state = MONITOR_RX_SOF;
            if (l->rx_crc_lo != (uint8_t)(l->rx_crc & 0xFFU) || byte != (uint8_t)(l->rx_crc >> 8)) {
                return MONITOR_LINK_BAD_CRC;
            }
            return MONITOR_LINK_FRAME;
    }
}

bool monitor_link_tick_1ms(monitor_link_t *l)
{
    if (l->rx_state == MONITOR_RX_SOF) {
        return false;
    }
    l->rx_idle_ms++;
    if (l->rx_idle_ms < MONITOR_RX_TIMEOUT_MS) {
        return false;
    }
    l->rx_state = MONITOR_RX_SOF;
    l->rx_idle_ms = 0;
    return true;
}

/* ---- transmitter ---------------------------------------------------------------- */

unsigned monitor_link_tx_free(const monitor_link_t *l)
{
    unsigned used = ((unsigned)l->tx_head - (unsigned)l->tx_tail) & (MONITOR_TX_SIZE - 1U);
    return MONITOR_TX_SIZE - 1U - used;
}

static void tx_put(monitor_link_t *l, uint8_t b)
{
    l->tx[l->tx_head] = b;
    l->tx_head = (uint8_t)((l->tx_head + 1U) & (MONITOR_TX_SIZE - 1U));
}

void monitor_link_send(monitor_link_t *l, uint8_t cmd, const uint8_t *payload, uint8_t len)
{
    uint16_t crc = 0xFFFFU;
    uint8_t i;
    tx_put(l, (uint8_t)MONITOR_SOF);
    tx_put(l, len);
    crc = monitor_crc16(crc, len);
    tx_put(l, cmd);
    crc = monitor_crc16(crc, cmd);
    for (i = 0; i < len; i++) {
        tx_put(l, payload[i]);
        crc = monitor_crc16(crc, payload[i]);
    }
    tx_put(l, (uint8_t)(crc & 0xFFU));
    tx_put(l, (uint8_t)(crc >> 8));
}

bool monitor_link_tx_byte(monitor_link_t *l, uint8_t *byte)
{
    if (l->tx_tail == l->tx_head) {
        return false;
    }
    *byte = l->tx[l->tx_tail];
    l->tx_tail = (uint8_t)((l->tx_tail + 1U) & (MONITOR_TX_SIZE - 1U));
    return true;
}
