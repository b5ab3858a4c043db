/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_app.c - the main-loop body (firmware/app.c) against cmocka mocks of hal.h. */
#include "test_support.h"

#include <stdio.h>
#include <string.h>

#include "app.h"

/*
 * Outputs the app must not emit unasked (core requests, references) are
 * strict cmocka mocks: an unexpected call fails the test. Inputs are a small
 * fake board (buttons, latch, pot, status, UART) the tests set directly.
 */

static bool fake_button[2];
static bool fake_latched;
static int16_t fake_pot;
static mc_status_t fake_status;
static bool fake_led[2];
static unsigned fake_status_calls;
static char fake_tx[512];
static size_t fake_tx_n;
static bool fake_tx_accept;
static const char *fake_rx;

bool hal_button_pressed(hal_button_t b)
{
    return fake_button[b == HAL_BUTTON_S2 ? 0 : 1];
}
bool hal_fault_latched(void)
{
    return fake_latched;
}
bool hal_fault_clear(void)
{
    return (bool)mock();
}
int16_t hal_pot_read(void)
{
    return fake_pot;
}
void hal_led_set(hal_led_t led, bool on)
{
    fake_led[led == HAL_LED_RUN ? 0 : 1] = on;
}
/* The reference's owner as the core's status shows it (mc_status_t
 * ref_remote, ref_seq): set references count, the pot request clears. */
void motor_request(mc_request_t request)
{
    int r = (int)request;
    check_expected(r);
    if (request == MC_REQUEST_REF_POT) {
        fake_status.ref_remote = false;
    }
}
static bool fake_ref_free; /* references counted, not checked against expectations */
static unsigned fake_ref_calls;
uint8_t motor_set_reference(int16_t ref)
{
    int value = ref;
    fake_ref_calls++;
    if (!fake_ref_free) {
        check_expected(value);
    }
    fake_status.ref_seq = (uint8_t)(fake_status.ref_seq + 1U);
    fake_status.ref_remote = true;
    return fake_status.ref_seq;
}
void motor_status(mc_status_t *st)
{
    fake_status_calls++;
    *st = fake_status;
}
bool hal_uart_put(uint8_t byte)
{
    if (!fake_tx_accept || fake_tx_n >= sizeof fake_tx - 1) {
        return false;
    }
    fake_tx[fake_tx_n++] = (char)byte;
    fake_tx[fake_tx_n] = '\0';
    return true;
}
bool hal_uart_get(uint8_t *byte)
{
    if (fake_rx == NULL || *fake_rx == '\0') {
        return false;
    }
    *byte = (uint8_t)*fake_rx++;
    return true;
}
bool hal_tick_1ms(void)
{
    return (bool)mock();
}

static app_t app;

static int setup(void **state)
{
    (void)state;
    memset(fake_button, 0, sizeof fake_button);
    fake_latched = false;
    fake_ref_free = false;
    fake_ref_calls = 0;
    fake_pot = 0;
    memset(&fake_status, 0, sizeof fake_status);
    fake_status.state = MC_STATE_STOPPED;
    fake_led[0] = fake_led[1] = true; /* app_init must turn them off */
    fake_status_calls = 0;
    fake_tx_n = 0;
    fake_tx[0] = '\0';
    fake_tx_accept = true;
    fake_rx = NULL;
    app_init(&app);
    assert_false(fake_led[0] || fake_led[1]);
    return 0;
}

static void ticks(unsigned n)
{
    while (n--) {
        app_tick_1ms(&app);
    }
}

/* ---- buttons ------------------------------------------------------------------ */

static void test_s2_press_should_request_start_stop_once_after_the_debounce_time(void **state)
{
    (void)state;
    fake_button[0] = true;
    ticks(APP_DEBOUNCE_MS - 1U); /* not yet: a strict mock would fail on a call */
    expect_value(motor_request, r, MC_REQUEST_START_STOP);
    ticks(1);
    ticks(500); /* held: no repeat */
    fake_button[0] = false;
    ticks(100); /* release: no event */
    expect_value(motor_request, r, MC_REQUEST_START_STOP);
    fake_button[0] = true;
    ticks(APP_DEBOUNCE_MS);
}

static void test_s2_bouncing_faster_than_the_debounce_time_should_request_nothing(void **state)
{
    (void)state;
    unsigned i;
    for (i = 0; i < 400U; i++) {
        fake_button[0] = (i / (APP_DEBOUNCE_MS / 2U)) % 2U == 0U;
        ticks(1);
    }
}

static void test_s2_with_the_fault_latched_should_clear_it_then_request_start_stop(void **state)
{
    (void)state;
    fake_latched = true;
    expect_value(motor_request, r, MC_REQUEST_HW_FAULT);
    ticks(1);
    fake_button[0] = true;
    will_return(hal_fault_clear, true);
    expect_value(motor_request, r, MC_REQUEST_START_STOP);
    ticks(APP_DEBOUNCE_MS);
}

static void test_s2_while_the_fault_pin_is_still_asserted_should_start_nothing(void **state)
{
    (void)state;
    fake_latched = true;
    expect_value(motor_request, r, MC_REQUEST_HW_FAULT);
    ticks(1);
    fake_button[0] = true;
    will_return(hal_fault_clear, false);
    ticks(APP_DEBOUNCE_MS + 100U);
}

static void test_fault_latch_should_be_reported_to_the_core_once_per_latch(void **state)
{
    (void)state;
    fake_latched = true;
    expect_value(motor_request, r, MC_REQUEST_HW_FAULT);
    ticks(300);
    fake_latched = false;
    ticks(10);
    fake_latched = true;
    expect_value(motor_request, r, MC_REQUEST_HW_FAULT);
    ticks(300);
}

static void test_s3_should_double_the_pot_reference_until_pressed_again(void **state)
{
    (void)state;
    int16_t doubled;
    unsigned i;

    fake_pot = 8000;
    doubled = app_speed_from_pot(8000, true);
    fake_button[1] = true;
    /* On the press edge (tick 20), and by the status period of that tick. */
    expect_value_count(motor_set_reference, value, doubled, 2);
    for (i = 0; i < APP_DEBOUNCE_MS; i++) {
        ticks(1);
    }
    fake_pot = 16000; /* the pot keeps feeding the reference */
    doubled = app_speed_from_pot(16000, true);
    expect_value_count(motor_set_reference, value, doubled, 5);
    ticks(5U * APP_STATUS_PERIOD_MS);
    fake_button[1] = false;
    expect_value_count(motor_set_reference, value, doubled, 5);
    ticks(5U * APP_STATUS_PERIOD_MS);
    fake_button[1] = true;
    expect_value(motor_request, r, MC_REQUEST_REF_POT);
    expect_value_count(motor_set_reference, value, doubled, 1); /* before the edge */
    ticks(APP_DEBOUNCE_MS);
    ticks(10U * APP_STATUS_PERIOD_MS); /* back on the pot: no more references */
}

/* ---- pot -> reference ---------------------------------------------------------- */

static void test_speed_from_pot_should_map_linearly_and_clamp_when_doubled(void **state)
{
    (void)state;
    err_stats_t e1, e2;
    int32_t pot;
    const double lo = MC_SPEED_REF_MIN_Q15, hi = MC_SPEED_REF_MAX_Q15;

    err_stats_init(&e1);
    err_stats_init(&e2);
    for (pot = 0; pot <= 32767; pot++) {
        double ref = lo + (hi - lo) * (double)pot / 32768.0; /* mc.h: the core's map */
        double ref2 = 2.0 * ref > hi ? hi : 2.0 * ref;
        err_stats_add(&e1, app_speed_from_pot((int16_t)pot, false) - ref, (double)pot);
        err_stats_add(&e2, app_speed_from_pot((int16_t)pot, true) - ref2, (double)pot);
    }
    err_stats_print("app_speed_from_pot vs linear map", &e1, "LSB");
    err_stats_print("app_speed_from_pot doubled vs min(2 map, max)", &e2, "LSB");
    assert_cmp(e1.max_abs, <, 1.0); /* the core's floor: under one count */
    assert_cmp(e2.max_abs, <, 2.0);
    /* one map: the core's, everywhere (the two used to differ on 25,395 readings) */
    for (pot = 0; pot <= 32767; pot++) {
        assert_int_equal(app_speed_from_pot((int16_t)pot, false), mc_pot_to_speed((int16_t)pot));
    }
    assert_int_equal(app_speed_from_pot(0, false), MC_SPEED_REF_MIN_Q15);
    assert_int_equal(app_speed_from_pot(32767, true), MC_SPEED_REF_MAX_Q15);
    assert_int_equal(app_speed_from_pot(-5, false), MC_SPEED_REF_MIN_Q15);
}

/* ---- LEDs ------------------------------------------------------------------------- */

static unsigned count_on_ms(unsigned led, unsigned ms)
{
    unsigned on = 0;
    while (ms--) {
        ticks(1);
        on += fake_led[led] ? 1U : 0U;
    }
    return on;
}

static void
test_run_led_should_be_off_stopped_blinking_in_start_up_and_on_in_closed_loop(void **state)
{
    (void)state;
    unsigned on;

    on = count_on_ms(0, 1000);
    assert_int_equal(on, 0);
    fake_status.state = MC_STATE_LOCK;
    ticks(APP_STATUS_PERIOD_MS);
    on = count_on_ms(0, 1000);
    printf("measured: RUN LED in LOCK on %u of 1000 ms\n", on);
    assert_in_range(on, 400, 600);
    fake_status.state = MC_STATE_CLOSED_LOOP;
    ticks(APP_STATUS_PERIOD_MS);
    assert_int_equal(count_on_ms(0, 1000), 1000);
    fake_status.state = MC_STATE_FAULT;
    ticks(APP_STATUS_PERIOD_MS);
    assert_int_equal(count_on_ms(0, 1000), 0);
}

static void test_fault_led_should_blink_the_fault_code_then_pause(void **state)
{
    (void)state;
    uint16_t code;
    for (code = 1; code <= 9U; code++) {
        unsigned period = app_fault_pattern_ms(code), blinks = 0, ms;
        bool prev = false;
        setup(NULL);
        fake_status.state = MC_STATE_FAULT;
        fake_status.fault = code;
        ticks(APP_STATUS_PERIOD_MS); /* the snapshot that starts the pattern */
        prev = fake_led[1];
        blinks = prev ? 1U : 0U;
        for (ms = 1; ms < period; ms++) {
            ticks(1);
            if (fake_led[1] && !prev) {
                blinks++;
            }
            prev = fake_led[1];
        }
        printf("measured: fault code %u -> %u blinks in a %u ms pattern\n", code, blinks, period);
        assert_int_equal(blinks, code);
        assert_int_equal(period, code * 2U * APP_BLINK_MS + APP_FAULT_PAUSE_MS);
    }
    fake_status.fault = MC_FAULT_NONE;
    ticks(APP_STATUS_PERIOD_MS);
    assert_int_equal(count_on_ms(1, 5000), 0);
}

/* ---- UART -------------------------------------------------------------------------- */

#if APP_TEXT_UART
static void test_telemetry_should_send_one_status_line_every_100ms(void **state)
{
    (void)state;
    fake_status.state = MC_STATE_CLOSED_LOOP;
    fake_status.fault = 0;
    fake_status.speed_ref = 1234;
    fake_status.speed_est = -56;
    fake_status.ia = -7;
    ticks(APP_TELEMETRY_PERIOD_MS - 1U);
    app_service_uart(&app);
    assert_int_equal(fake_tx_n, 0);
    ticks(1);
    app_service_uart(&app);
    printf("measured: line \"%.*s\"\n", (int)(fake_tx_n - 2), fake_tx);
    assert_string_equal(fake_tx, "S4 F0 R1234 W-56 A-7 D0\r\n");
    fake_tx_n = 0;
    fake_status.fault = MC_FAULT_OFFSET;
    fake_status.state = MC_STATE_FAULT;
    fake_status.speed_ref = -32768;
    fake_status.speed_est = 32767;
    fake_status.ia = -32768;
    ticks(APP_TELEMETRY_PERIOD_MS);
    app_service_uart(&app);
    {
        char want[48];
        snprintf(want, sizeof want, "S%d F9 R-32768 W32767 A-32768 D0\r\n", (int)MC_STATE_FAULT);
        assert_string_equal(fake_tx, want); /* the state's number, as mc.h lists it */
    }
}

static void
test_uart_should_keep_bytes_while_the_transmitter_is_full_and_drop_whole_lines(void **state)
{
    (void)state;
    unsigned i;
    fake_tx_accept = false;
    for (i = 0; i < 10U; i++) { /* 10 lines offered, the queue holds 3 */
        ticks(APP_TELEMETRY_PERIOD_MS);
        app_service_uart(&app);
    }
    assert_int_equal(fake_tx_n, 0);
    fake_tx_accept = true;
    app_service_uart(&app);
    printf("measured: %zu bytes queued while blocked (queue %u)\n", fake_tx_n, APP_TX_QUEUE_SIZE);
    /* 63 usable bytes hold three 19-byte lines; the other seven were dropped whole. */
    {
        const char *line = "S0 F0 R0 W0 A0 D0\r\n";
        unsigned k;
        assert_int_equal(fake_tx_n, 3U * strlen(line));
        for (k = 0; k < 3U; k++) {
            assert_memory_equal(fake_tx + k * strlen(line), line, strlen(line));
        }
    }
}

static void test_uart_commands_should_post_start_stop_and_return_to_the_pot(void **state)
{
    (void)state;
    fake_rx = "gxsp";
    expect_value(motor_request, r, MC_REQUEST_START);
    expect_value(motor_request, r, MC_REQUEST_STOP);
    expect_value(motor_request, r, MC_REQUEST_REF_POT);
    app_service_uart(&app);
}

static void test_uart_start_should_follow_the_s2_rule_while_the_fault_pin_holds(void **state)
{
    (void)state;
    fake_latched = true;
    fake_rx = "g";
    will_return(hal_fault_clear, false); /* the pin still asserted: no START */
    app_service_uart(&app);
    fake_rx = "g";
    will_return(hal_fault_clear, true); /* cleared: START */
    expect_value(motor_request, r, MC_REQUEST_START);
    app_service_uart(&app);
}
#else
/* Without the text protocol (the X2Cscope image) and before the client is
 * set, the UART stays idle: no status line, and received bytes are left
 * for the client (the strict mocks fail on any request). */
static void test_uart_without_the_text_protocol_should_stay_idle_until_a_client(void **state)
{
    (void)state;
    fake_rx = "gsp";
    ticks(3U * APP_TELEMETRY_PERIOD_MS);
    app_service_uart(&app);
    assert_int_equal(fake_tx_n, 0);
    assert_int_equal(strlen(fake_rx), 3); /* nothing read */
}
#endif

static void test_s3_should_yield_the_reference_to_another_side_that_sets_it(void **state)
{
    (void)state;
    unsigned i;
    unsigned n;
    fake_pot = 8000;
    fake_ref_free = true;
    fake_ref_calls = 0;
    fake_button[1] = true;
    for (i = 0; i < APP_DEBOUNCE_MS; i++) {
        ticks(1);
    }
    assert_true(app.double_speed);
    assert_cmp(fake_ref_calls, >=, 1U);
    /* X2Cscope sets a speed: S3's mode ends, no more board references */
    fake_status.ref_seq = (uint8_t)(fake_status.ref_seq + 1U);
    n = fake_ref_calls;
    ticks(5U * APP_STATUS_PERIOD_MS);
    assert_false(app.double_speed);
    assert_int_equal(fake_ref_calls, n);
    /* S3 again takes it back for the board, and keeps it */
    fake_button[1] = false;
    ticks(APP_DEBOUNCE_MS);
    fake_button[1] = true;
    ticks(APP_DEBOUNCE_MS);
    assert_true(app.double_speed);
    n = fake_ref_calls;
    ticks(5U * APP_STATUS_PERIOD_MS);
    assert_true(app.double_speed);
    assert_int_equal(fake_ref_calls, n + 5U);
    /* the pot taken back by another side (REF_POT): the mode ends too */
    fake_status.ref_remote = false;
    ticks(5U * APP_STATUS_PERIOD_MS);
    assert_false(app.double_speed);
    assert_int_equal(fake_ref_calls, n + 5U);
    fake_ref_free = false;
}

static void test_poll_should_do_the_1ms_work_only_when_a_tick_elapsed(void **state)
{
    (void)state;
    unsigned i;
    will_return_count(hal_tick_1ms, false, 50);
    for (i = 0; i < 50U; i++) {
        app_poll(&app);
    }
    assert_int_equal(fake_status_calls, 0);
    will_return_count(hal_tick_1ms, true, (int)APP_STATUS_PERIOD_MS);
    for (i = 0; i < APP_STATUS_PERIOD_MS; i++) {
        app_poll(&app);
    }
    assert_int_equal(fake_status_calls, 1);
}

int main(void)
{
    const struct CMUnitTest tests[] =
    { cmocka_unit_test_setup(test_s2_press_should_request_start_stop_once_after_the_debounce_time,
                             setup),
      cmocka_unit_test_setup(test_s2_bouncing_faster_than_the_debounce_time_should_request_nothing,
                             setup),
      cmocka_unit_test_setup(test_s2_with_the_fault_latched_should_clear_it_then_request_start_stop,
                             setup),
      cmocka_unit_test_setup(test_s2_while_the_fault_pin_is_still_asserted_should_start_nothing,
                             setup),
      cmocka_unit_test_setup(test_fault_latch_should_be_reported_to_the_core_once_per_latch, setup),
      cmocka_unit_test_setup(test_s3_should_double_the_pot_reference_until_pressed_again, setup),
      cmocka_unit_test_setup(test_speed_from_pot_should_map_linearly_and_clamp_when_doubled, setup),
      cmocka_unit_test_setup(
          test_run_led_should_be_off_stopped_blinking_in_start_up_and_on_in_closed_loop, setup),
      cmocka_unit_test_setup(test_fault_led_should_blink_the_fault_code_then_pause, setup),
#if APP_TEXT_UART
      cmocka_unit_test_setup(test_telemetry_should_send_one_status_line_every_100ms, setup),
      cmocka_unit_test_setup(
          test_uart_should_keep_bytes_while_the_transmitter_is_full_and_drop_whole_lines, setup),
      cmocka_unit_test_setup(test_uart_commands_should_post_start_stop_and_return_to_the_pot,
                             setup),
      cmocka_unit_test_setup(test_uart_start_should_follow_the_s2_rule_while_the_fault_pin_holds,
                             setup),
#else
      cmocka_unit_test_setup(test_uart_without_the_text_protocol_should_stay_idle_until_a_client,
                             setup),
#endif
      cmocka_unit_test_setup(test_poll_should_do_the_1ms_work_only_when_a_tick_elapsed, setup),
      cmocka_unit_test_setup(test_s3_should_yield_the_reference_to_another_side_that_sets_it,
                             setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
