/* monitor_app.c - the monitor as the application's UART client (see monitor_app.h). */
#include "monitor_app.h"

static bool cb_rx_ready(void *ctx)
{
    return monitor_rx_ready((const monitor_t *)ctx);
}

static void cb_rx_byte(void *ctx, uint8_t byte)
{
    monitor_rx_byte((monitor_t *)ctx, byte);
}

static bool cb_tx_byte(void *ctx, uint8_t *byte)
{
    return monitor_tx_byte((monitor_t *)ctx, byte);
}

static void cb_tick_1ms(void *ctx)
{
    monitor_tick_1ms((monitor_t *)ctx);
}

static void cb_poll(void *ctx)
{
    monitor_poll((monitor_t *)ctx);
}

void monitor_app_client(monitor_t *m, app_uart_client_t *client)
{
    client->ctx = m;
    client->rx_ready = cb_rx_ready;
    client->rx_byte = cb_rx_byte;
    client->tx_byte = cb_tx_byte;
    client->tick_1ms = cb_tick_1ms;
    client->poll = cb_poll;
}
