/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* app.c - the main loop of the dsPIC application (see app.h). */
#include "app.h"

#include <stddef.h>

#include "q15.h"

Q15_STATIC_ASSERT((APP_TX_QUEUE_SIZE & (APP_TX_QUEUE_SIZE - 1U)) == 0U && APP_TX_QUEUE_SIZE <= 256U,
                  "APP_TX_QUEUE_SIZE must be a power of two up to 256");
Q15_STATIC_ASSERT(APP_TEXT_UART == 0 || APP_TEXT_UART == 1, "APP_TEXT_UART must be 0 or 1");
Q15_STATIC_ASSERT(MC_SPEED_REF_MIN_Q15 >= 0 && MC_SPEED_REF_MAX_Q15 >= MC_SPEED_REF_MIN_Q15,
                  "app_speed_from_pot assumes 0 <= SPEED_REF_MIN_RPM <= SPEED_REF_MAX_RPM");
Q15_STATIC_ASSERT(APP_DEBOUNCE_MS < 255U, "APP_DEBOUNCE_MS must fit the uint8_t counter");

void app_init(app_t *app)
{
    app->s2.level = false;
    app->s2.steady = 0;
    app->s3 = app->s2;
    app->double_speed = false;
    app->ref_seq_mine = 0;
    app->fault_reported = false;
    app->status_ms = 0;
    app->run_phase = 0;
    app->fault_phase = 0;
    app->fault_shown = MC_FAULT_NONE;
    app->status.state = MC_STATE_STOPPED;
    app->status.fault = MC_FAULT_NONE;
    app->status.speed_ref = 0;
    app->status.speed_est = 0;
#if APP_TEXT_UART
    app->telemetry_ms = 0;
    app->tx_head = 0;
    app->tx_tail = 0;
#endif
    app->uart_client = NULL;
    app->client_tx_held = false;
    app->client_tx = 0;
    hal_led_set(HAL_LED_RUN, false);
    hal_led_set(HAL_LED_FAULT, false);
}

/* ---- pure pieces ----------------------------------------------------------- */

int16_t app_speed_from_pot(int16_t pot, bool doubled)
{
    /* the core's map (mc.h), doubled within the pot's range: 0 <= min <= max
     * < 2^15 (the check above), so twice it fits in 17 bits */
    int32_t ref = mc_pot_to_speed(pot);
    if (doubled) {
        ref *= 2;
    }
    return (int16_t)(ref > MC_SPEED_REF_MAX_Q15 ? MC_SPEED_REF_MAX_Q15 : ref);
}

bool app_led_run_on(mc_state_t state, uint16_t phase_ms)
{
    switch (state) {
        case MC_STATE_CALIBRATE:
        case MC_STATE_LOCK:
        case MC_STATE_OPEN_LOOP:
            return phase_ms < APP_RUN_BLINK_MS;
        case MC_STATE_CLOSED_LOOP:
            return true;
        default:
            return false;
    }
}

uint16_t app_fault_pattern_ms(uint16_t fault)
{
    uint16_t n = fault > 20U ? 20U : fault; /* codes are small; keep the sum in range */
    return (uint16_t)(n * 2U * APP_BLINK_MS + APP_FAULT_PAUSE_MS);
}

bool app_led_fault_on(uint16_t fault, uint16_t phase_ms)
{
    if (fault == MC_FAULT_NONE) {
        return false;
    }
    uint16_t n = fault > 20U ? 20U : fault;
    if (phase_ms >= n * 2U * APP_BLINK_MS) {
        return false;
    }
    return (phase_ms % (2U * APP_BLINK_MS)) < APP_BLINK_MS;
}

/* ---- buttons ---------------------------------------------------------------- */

/* True on the debounced press edge. */
static bool button_pressed_edge(app_button_t *b, bool raw)
{
    if (raw == b->level) {
        b->steady = 0;
        return false;
    }
    b->steady++;
    if (b->steady < APP_DEBOUNCE_MS) {
        return false;
    }
    b->level = raw;
    b->steady = 0;
    return raw;
}

bool app_start_allowed(app_t *app)
{
    if (hal_fault_latched()) {
        if (!hal_fault_clear()) {
            return false; /* the fault pin is still asserted: nothing may start */
        }
        app->fault_reported = false;
    }
    return true;
}

static void on_s2(app_t *app)
{
    if (app_start_allowed(app)) {
        motor_request(MC_REQUEST_START_STOP);
    }
}

/*
 * The speed reference has one owner at a time: the pot, the board (S3's
 * doubled pot) or whoever else calls mc_set_reference (X2Cscope). The
 * last explicit choice wins and the core's status shows it to every side:
 * ref_remote (a set reference, not the pot) and ref_seq (counts the set
 * references). S3 takes the reference for the board; while doubling, the
 * app writes the doubled pot every status period, but only while the
 * status still shows its own last write (mc_reference_held): otherwise
 * another side has taken the reference (or handed it back to the pot) and
 * S3's mode ends.
 */
static void board_reference(app_t *app)
{
    app->ref_seq_mine = motor_set_reference(app_speed_from_pot(hal_pot_read(), true));
}

static void on_s3(app_t *app)
{
    if (MC_TORQUE_MODE) {
        return; /* no speed reference to double */
    }
    app->double_speed = !app->double_speed;
    if (app->double_speed) {
        board_reference(app);
    } else {
        motor_request(MC_REQUEST_REF_POT);
    }
}

/* ---- UART -------------------------------------------------------------------- */

#if APP_TEXT_UART
static uint8_t tx_used(const app_t *app)
{
    return (uint8_t)(((unsigned)app->tx_head - (unsigned)app->tx_tail) & (APP_TX_QUEUE_SIZE - 1U));
}

static void tx_byte(app_t *app, uint8_t c)
{
    app->tx[app->tx_head] = c;
    app->tx_head = (uint8_t)((app->tx_head + 1U) & (APP_TX_QUEUE_SIZE - 1U));
}

/* Appends "<tag><decimal>" to buf at *n. */
static void fmt_field(uint8_t *buf, uint8_t *n, char tag, int32_t v)
{
    char digits[6];
    uint8_t k = 0;
    uint32_t u = v < 0 ? 0U - (uint32_t)v : (uint32_t)v;
    buf[(*n)++] = (uint8_t)tag;
    if (v < 0) {
        buf[(*n)++] = '-';
    }
    do {
        digits[k++] = (char)('0' + (char)(u % 10U));
        u /= 10U;
    } while (u != 0U && k < sizeof digits);
    while (k > 0U) {
        buf[(*n)++] = (uint8_t)digits[--k];
    }
}

/* Queues the status line whole, or not at all when it does not fit. */
static void queue_telemetry(app_t *app)
{
    /* Longest line 38 bytes: S, F up to 5 digits, R W A signed 5 digits, D,
     * 5 spaces, CR LF. */
    uint8_t line[48];
    uint8_t n = 0;
    uint8_t i;
    fmt_field(line, &n, 'S', (int32_t)app->status.state);
    line[n++] = ' ';
    fmt_field(line, &n, 'F', (int32_t)app->status.fault);
    line[n++] = ' ';
    fmt_field(line, &n, 'R', app->status.speed_ref);
    line[n++] = ' ';
    fmt_field(line, &n, 'W', app->status.speed_est);
    line[n++] = ' ';
    fmt_field(line, &n, 'A', app->status.ia);
    line[n++] = ' ';
    fmt_field(line, &n, 'D', app->double_speed ? 1 : 0);
    line[n++] = '\r';
    line[n++] = '\n';
    if ((unsigned)tx_used(app) + n > APP_TX_QUEUE_SIZE - 1U) {
        return;
    }
    for (i = 0; i < n; i++) {
        tx_byte(app, line[i]);
    }
}

/* The text protocol's bytes out, its commands in. */
static void service_text(app_t *app)
{
    uint8_t c;
    while (app->tx_tail != app->tx_head && hal_uart_put(app->tx[app->tx_tail])) {
        app->tx_tail = (uint8_t)((app->tx_tail + 1U) & (APP_TX_QUEUE_SIZE - 1U));
    }
    while (hal_uart_get(&c)) {
        if (c == 'g') {
            if (app_start_allowed(app)) {
                motor_request(MC_REQUEST_START);
            }
        } else if (c == 's') {
            motor_request(MC_REQUEST_STOP);
        } else if (c == 'p') {
            app->double_speed = false;
            motor_request(MC_REQUEST_REF_POT);
        }
    }
}

/* The status line every APP_TELEMETRY_PERIOD_MS. */
static void tick_text(app_t *app)
{
    app->telemetry_ms = (uint16_t)(app->telemetry_ms + 1U);
    if (app->telemetry_ms >= APP_TELEMETRY_PERIOD_MS) {
        app->telemetry_ms = 0;
        queue_telemetry(app);
    }
}
#endif /* APP_TEXT_UART */

void app_set_uart_client(app_t *app, const app_uart_client_t *client)
{
    app->uart_client = client;
    app->client_tx_held = false;
}

/* The UART belongs to the client: its bytes out, received bytes in while it
 * can answer them, then its main-loop work. */
static void service_client(app_t *app, const app_uart_client_t *cl)
{
    uint8_t c;
    for (;;) {
        if (!app->client_tx_held) {
            if (!cl->tx_byte(cl->ctx, &app->client_tx)) {
                break;
            }
            app->client_tx_held = true;
        }
        if (!hal_uart_put(app->client_tx)) {
            break;
        }
        app->client_tx_held = false;
    }
    while (cl->rx_ready(cl->ctx) && hal_uart_get(&c)) {
        cl->rx_byte(cl->ctx, c);
    }
    cl->poll(cl->ctx);
}

void app_service_uart(app_t *app)
{
    if (app->uart_client != NULL) {
        service_client(app, app->uart_client);
        return;
    }
#if APP_TEXT_UART
    service_text(app);
#endif
}

/* ---- the 1 ms work ---------------------------------------------------------- */

static void update_leds(app_t *app)
{
    if (app->status.fault != app->fault_shown) {
        app->fault_shown = app->status.fault;
        app->fault_phase = 0;
    }
    hal_led_set(HAL_LED_RUN, app_led_run_on(app->status.state, app->run_phase));
    hal_led_set(HAL_LED_FAULT, app_led_fault_on(app->fault_shown, app->fault_phase));
}

void app_tick_1ms(app_t *app)
{
    /* Phases of the LED patterns. */
    app->run_phase = (uint16_t)(app->run_phase + 1U);
    if (app->run_phase >= 2U * APP_RUN_BLINK_MS) {
        app->run_phase = 0;
    }
    app->fault_phase = (uint16_t)(app->fault_phase + 1U);
    if (app->fault_phase >= app_fault_pattern_ms(app->fault_shown)) {
        app->fault_phase = 0;
    }

    /* The fault latch, once per latch. */
    if (hal_fault_latched()) {
        if (!app->fault_reported) {
            motor_request(MC_REQUEST_HW_FAULT);
            app->fault_reported = true;
        }
    } else {
        app->fault_reported = false;
    }

    if (button_pressed_edge(&app->s2, hal_button_pressed(HAL_BUTTON_S2))) {
        on_s2(app);
    }
    if (button_pressed_edge(&app->s3, hal_button_pressed(HAL_BUTTON_S3))) {
        on_s3(app);
    }

    app->status_ms = (uint16_t)(app->status_ms + 1U);
    if (app->status_ms >= APP_STATUS_PERIOD_MS) {
        app->status_ms = 0;
        motor_status(&app->status);
        update_leds(app);
        if (!MC_TORQUE_MODE && app->double_speed) {
            if (mc_reference_held(&app->status, app->ref_seq_mine)) {
                board_reference(app);
            } else {
                app->double_speed = false; /* another side took the reference */
            }
        }
    }

    if (app->uart_client != NULL) {
        app->uart_client->tick_1ms(app->uart_client->ctx);
        return;
    }
#if APP_TEXT_UART
    tick_text(app);
#endif
}

void app_poll(app_t *app)
{
    if (hal_tick_1ms()) {
        app_tick_1ms(app);
    }
    app_service_uart(app);
}
