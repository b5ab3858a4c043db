/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_x2c_app.c - the board's main loop (firmware/app.c) with the X2Cscope target as its UART
 * client, over a fake UART. */
#include "../x2c_util.h"

#include "app.h"
#include "x2c_app.h"

/* the client's side: a receiver for any frame (the target's takes X2C_RX_BYTES) */
static uint8_t rx_buf[LNET_MAX_DATA];

/*
 * A fake board around a real mc_t: the motor_* mailbox calls the core,
 * the UART is two byte queues with a transmitter that takes at most
 * uart_room bytes per pass (like the dsPIC's 4-deep FIFO), and "the ISR" is
 * mc_step() followed by x2c_sample(), 20 periods per millisecond.
 */

static mc_t motor;
static x2c_t x2c;
static app_t app;
static app_uart_client_t client;
static uint8_t rx_q[4096], tx_q[65536];
static size_t rx_head, rx_tail, tx_n;
static unsigned uart_room, uart_room_per_pass = 4;
static bool tick;

bool hal_button_pressed(hal_button_t b)
{
    (void)b;
    return false;
}
bool hal_fault_latched(void)
{
    return false;
}
bool hal_fault_clear(void)
{
    return true;
}
int16_t hal_pot_read(void)
{
    return 0;
}
void hal_led_set(hal_led_t led, bool on)
{
    (void)led;
    (void)on;
}
bool hal_uart_put(uint8_t byte)
{
    if (uart_room == 0U || tx_n >= sizeof tx_q) {
        return false;
    }
    uart_room--;
    tx_q[tx_n++] = byte;
    return true;
}
bool hal_uart_get(uint8_t *byte)
{
    if (rx_tail == rx_head) {
        return false;
    }
    *byte = rx_q[rx_tail++];
    return true;
}
bool hal_tick_1ms(void)
{
    bool t = tick;
    tick = false;
    return t;
}

static int setup(void **state)
{
    (void)state;
    mc_init(&motor);
    app_init(&app);
    sim_mailbox_attach(&motor);
    x2c_init(&x2c);
    x2c_app_client(&x2c, &client);
    app_set_uart_client(&app, &client);
    rx_head = rx_tail = tx_n = 0;
    uart_room_per_pass = 4;
    return 0;
}

static void host_send(const uint8_t *data, uint8_t n)
{
    rx_head += rig_frame(data, n, &rx_q[rx_head]);
}

/* One millisecond: 20 ISR periods with a 24 V bus, then a few main-loop passes. */
static void run_ms(unsigned ms)
{
    unsigned i, k;
    for (i = 0; i < ms; i++) {
        for (k = 0; k < 20U; k++) {
            mc_adc_frame_t in = {0, 0, Q15(0.4545), 0};
            mc_pwm_out_t out;
            mc_step(&motor, &in, &out);
            mc_slow_step(&motor);
            (void)x2c_sample(&x2c, NULL);
        }
        tick = true;
        for (k = 0; k < 4U; k++) {
            uart_room = uart_room_per_pass;
            app_poll(&app);
        }
    }
}

/* The replies the host received so far, each into its slot of reply[]. */
static unsigned host_replies(uint8_t reply[][LNET_MAX_DATA], uint8_t *len, unsigned max)
{
    lnet_rx_t rx;
    unsigned k = 0;
    lnet_rx_init(&rx, rx_buf, (uint8_t)LNET_MAX_DATA);
    for (size_t i = 0; i < tx_n && k < max; i++) {
        lnet_rx_event_t e = lnet_rx_byte(&rx, tx_q[i]);
        assert_true(e == LNET_RX_NONE || e == LNET_RX_FRAME);
        if (e == LNET_RX_FRAME) {
            memcpy(reply[k], rx.data, rx.size);
            len[k++] = rx.size;
        }
    }
    return k;
}

static uint8_t rep[64][LNET_MAX_DATA];
static uint8_t rep_len[64];

static void test_the_app_should_hand_the_uart_to_the_target_and_send_no_status_line(void **state)
{
    static const uint8_t info[1] = {X2C_SVC_DEVICE_INFO};
    (void)state;
    run_ms(500);
    assert_int_equal(tx_n, 0); /* no text telemetry */
    host_send(info, 1U);
    run_ms(20);
    assert_int_equal(host_replies(rep, rep_len, 64), 1U);
    assert_int_equal(rep_len[0], 2U + X2C_INFO_BYTES);
    assert_int_equal(rep[0][1], X2C_ERR_OK);
}

/* Two requests back to back: the second waits in the UART while the first
 * reply goes out, as a client that did not wait would have it. */
static void test_a_start_at_2000_rpm_over_the_uart_should_reach_the_core(void **state)
{
    uint16_t a_ref = (uint16_t)(X2C_WINDOW_TUNE + offsetof(x2c_tune_t, speed_ref_rpm));
    uint16_t a_run = (uint16_t)(X2C_WINDOW_TUNE + offsetof(x2c_tune_t, run));
    uint8_t speed[6] = {X2C_SVC_PUT_RAM, (uint8_t)a_ref, (uint8_t)(a_ref >> 8), 2, 0xD0, 0x07};
    uint8_t go[6] = {X2C_SVC_PUT_RAM, (uint8_t)a_run, (uint8_t)(a_run >> 8), 2, 1, 0};
    mc_status_t st;
    (void)state;
    if (sizeof(void *) <= 2U) {
        skip(); /* the window is the PC's */
    }
    host_send(speed, 6U);
    host_send(go, 6U);
    run_ms(50);
    assert_int_equal(host_replies(rep, rep_len, 64), 2U);
    assert_int_equal(rep[0][1], X2C_ERR_OK);
    assert_int_equal(rep[1][1], X2C_ERR_OK);
    mc_status(&motor, &st);
    assert_int_not_equal(st.state, MC_STATE_STOPPED);
    assert_int_equal(st.speed_target, (int16_t)(2000.0 * 32768.0 / MC_SPEED_FULLSCALE_RPM + 0.5));
}

/* A full-rate capture, polled and read through a slow UART, arrives whole. */
static void test_a_full_rate_capture_through_a_slow_uart_should_arrive_whole(void **state)
{
    uint16_t a_vbus = (uint16_t)(X2C_WINDOW_MOTOR + offsetof(mc_t, vbus));
    uint8_t cfg[] = {X2C_SVC_SAVE_PARAM,
                     1,
                     0,
                     X2C_SCOPE_SAMPLE,
                     1,
                     0,
                     0,
                     0,
                     (uint8_t)a_vbus,
                     (uint8_t)(a_vbus >> 8),
                     0,
                     0,
                     2,
                     0x82,
                     0,
                     0,
                     0,
                     0,
                     0,
                     0,
                     0,
                     0,
                     0,
                     0,
                     0,
                     1,
                     0};
    uint8_t load[3] = {X2C_SVC_LOAD_PARAM, 1, 0};
    uint8_t got[X2C_SCOPE_BYTES];
    unsigned polls = 0, k;
    uint16_t at = 0;
    (void)state;
    if (sizeof(void *) <= 2U) {
        skip();
    }
    uart_room_per_pass = 1; /* 4 bytes per ms: slower than 38400 Bd */
    host_send(cfg, (uint8_t)sizeof cfg);
    run_ms(30);
    for (;;) {
        tx_n = 0;
        host_send(load, 3U);
        run_ms(30);
        assert_int_equal(host_replies(rep, rep_len, 64), 1U);
        polls++;
        if (rep[0][2] == X2C_SCOPE_IDLE) {
            break;
        }
        assert_cmp(polls, <, 50U);
    }
    while (at < X2C_SCOPE_BYTES) {
        uint16_t a = (uint16_t)(X2C_WINDOW_SCOPE + at);
        uint8_t n =
            (uint8_t)(X2C_SCOPE_BYTES - at > X2C_READ_MAX ? X2C_READ_MAX : X2C_SCOPE_BYTES - at);
        uint8_t rd[5] = {X2C_SVC_GET_RAM, (uint8_t)a, (uint8_t)(a >> 8), n, 1};
        tx_n = 0;
        host_send(rd, 5U);
        run_ms(200); /* 255 bytes at 4 a millisecond */
        assert_int_equal(host_replies(rep, rep_len, 64), 1U);
        assert_int_equal(rep_len[0], 2U + n);
        memcpy(&got[at], &rep[0][2], n);
        at = (uint16_t)(at + n);
    }
    assert_memory_equal(got, x2c.scope.buf, X2C_SCOPE_BYTES);
    for (k = 0; k < X2C_SCOPE_BYTES / 2U; k++) {
        assert_int_equal(got[2U * k] | (got[2U * k + 1U] << 8), (uint16_t)motor.vbus);
    }
}

/* The X2Cscope image has no text protocol (APP_TEXT_UART 0): with the
 * client removed the UART stays idle, no status line comes back. */
static void test_removing_the_client_should_leave_the_uart_idle(void **state)
{
    (void)state;
    tx_n = 0;
    app_set_uart_client(&app, NULL);
    run_ms(250);
    assert_int_equal(tx_n, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(
            test_the_app_should_hand_the_uart_to_the_target_and_send_no_status_line, setup),
        cmocka_unit_test_setup(test_a_start_at_2000_rpm_over_the_uart_should_reach_the_core, setup),
        cmocka_unit_test_setup(test_a_full_rate_capture_through_a_slow_uart_should_arrive_whole,
                               setup),
        cmocka_unit_test_setup(test_removing_the_client_should_leave_the_uart_idle, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
