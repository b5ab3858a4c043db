/* test_monitor_app.c - the board's main loop (firmware/app.c) with the monitor as its UART client,
 * over a fake UART. */
#include "test_support.h"

#include <string.h>

#include "../mon_util.h"
#include "app.h"
#include "monitor.h"
#include "monitor_app.h"
#include "sim_mailbox.h"

/*
 * A fake board around a real mc_t: the motor_* mailbox calls the core,
 * the UART is two byte queues with a transmitter that takes at most
 * uart_room bytes per pass (like the dsPIC's 4-deep FIFO), and "the ISR" is
 * mc_step() followed by monitor_sample(), 20 periods per millisecond.
 */

static mc_t motor;
static monitor_t mon;
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
    monitor_init(&mon);
    monitor_app_client(&mon, &client);
    app_set_uart_client(&app, &client);
    rx_head = rx_tail = tx_n = 0;
    uart_room_per_pass = 4;
    return 0;
}

static void host_send(uint8_t cmd, const uint8_t *p, uint8_t len)
{
    rx_head += mon_encode(&rx_q[rx_head], cmd, p, len);
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
            (void)monitor_sample(&mon, &motor);
        }
        tick = true;
        for (k = 0; k < 4U; k++) {
            uart_room = uart_room_per_pass;
            app_poll(&app);
        }
    }
}

static void test_the_app_should_hand_the_uart_to_the_monitor_and_send_no_status_line(void **state)
{
    static mon_frame_t fr[64];
    int k;
    (void)state;
    run_ms(500);
    assert_int_equal(tx_n, 0); /* no text telemetry */
    host_send(MONITOR_CMD_INFO, NULL, 0);
    run_ms(20);
    k = mon_decode_all(tx_q, tx_n, fr, 64);
    assert_int_equal(k, 1);
    assert_int_equal(fr[0].cmd, MONITOR_CMD_INFO | MONITOR_REPLY);
}

static void test_a_start_at_2000_rpm_over_the_uart_should_reach_the_core(void **state)
{
    static mon_frame_t fr[64];
    uint8_t p[2] = {(uint8_t)(2000 & 0xFF), (uint8_t)(2000 >> 8)};
    uint8_t go = MONITOR_MOTOR_START;
    mc_status_t st;
    int k;
    (void)state;
    host_send(MONITOR_CMD_SET_SPEED, p, 2);
    host_send(MONITOR_CMD_MOTOR, &go, 1);
    run_ms(50);
    k = mon_decode_all(tx_q, tx_n, fr, 64);
    assert_int_equal(k, 2);
    assert_int_equal(fr[0].cmd, MONITOR_CMD_SET_SPEED | MONITOR_REPLY);
    assert_int_equal(fr[1].cmd, MONITOR_CMD_MOTOR | MONITOR_REPLY);
    mc_status(&motor, &st);
    assert_int_not_equal(st.state, MC_STATE_STOPPED);
    assert_int_equal(st.speed_target, (int16_t)(2000.0 * 32768.0 / MC_SPEED_FULLSCALE_RPM + 0.5));
}

static void
test_a_full_rate_snapshot_through_a_slow_uart_should_arrive_whole_and_in_order(void **state)
{
    static mon_frame_t fr[2048];
    uint8_t sel[4] = {1, 0, 1, 16}; /* decim 1 (full rate), one channel: vbus */
    uint8_t st[2] = {MONITOR_MODE_SNAPSHOT, MONITOR_TRIG_NOW};
    int k, i, sets = 0;
    uint16_t next = 0;
    (void)state;
    uart_room_per_pass = 1; /* 4 bytes per ms: ~ 38400 Bd */
    host_send(MONITOR_CMD_SELECT, sel, 4);
    host_send(MONITOR_CMD_START, st, 2);
    run_ms(1000);
    k = mon_decode_all(tx_q, tx_n, fr, 2048);
    assert_cmp(k, >, 2);
    assert_int_equal(fr[0].cmd, MONITOR_CMD_SELECT | MONITOR_REPLY);
    assert_int_equal(fr[1].cmd, MONITOR_CMD_START | MONITOR_REPLY);
    for (i = 2; i < k; i++) {
        assert_int_equal(fr[i].cmd, MONITOR_CMD_DATA);
        assert_int_equal(mon_u16(&fr[i].payload[1]), next);
        next = (uint16_t)(next + fr[i].payload[3]);
        sets += fr[i].payload[3];
    }
    assert_int_equal(sets, MONITOR_BUF_WORDS);
    assert_int_equal(fr[k - 1].payload[0], MONITOR_DATA_LAST);
}

static void test_the_text_protocol_should_return_when_the_client_is_removed(void **state)
{
    (void)state;
    app_set_uart_client(&app, NULL);
    run_ms(250);
    assert_cmp(tx_n, >, 10);
    assert_int_equal(tx_q[0], 'S');
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(
            test_the_app_should_hand_the_uart_to_the_monitor_and_send_no_status_line, setup),
        cmocka_unit_test_setup(test_a_start_at_2000_rpm_over_the_uart_should_reach_the_core, setup),
        cmocka_unit_test_setup(
            test_a_full_rate_snapshot_through_a_slow_uart_should_arrive_whole_and_in_order, setup),
        cmocka_unit_test_setup(test_the_text_protocol_should_return_when_the_client_is_removed,
                               setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
