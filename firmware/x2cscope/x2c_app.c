/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* x2c_app.c - the X2Cscope target as the application's UART client (see x2c_app.h). */
#include "x2c_app.h"

static bool cb_rx_ready(void *ctx)
{
    return x2c_rx_ready((const x2c_t *)ctx);
}

static void cb_rx_byte(void *ctx, uint8_t byte)
{
    x2c_rx_byte((x2c_t *)ctx, byte);
}

static bool cb_tx_byte(void *ctx, uint8_t *byte)
{
    return x2c_tx_byte((x2c_t *)ctx, byte);
}

/* The inter-byte timeout (X2C_RX_GAP_MS). */
static void cb_tick_1ms(void *ctx)
{
    x2c_tick_1ms((x2c_t *)ctx);
}

/* Nothing is queued: the main loop's poll has no work. */
static void cb_idle(void *ctx)
{
    (void)ctx;
}

void x2c_app_client(x2c_t *x, app_uart_client_t *client)
{
    client->ctx = x;
    client->rx_ready = cb_rx_ready;
    client->rx_byte = cb_rx_byte;
    client->tx_byte = cb_tx_byte;
    client->tick_1ms = cb_tick_1ms;
    client->poll = cb_idle;
}
