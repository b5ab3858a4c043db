/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* app.h - the main loop of the dsPIC application: buttons, pot, LEDs, UART, fault latch. */
#ifndef APP_H
#define APP_H

/*
 * Everything time-critical is in the ADC interrupt (hal/dspic33f/hal_isr.c);
 * this is the slow rest, one app_poll() per main-loop pass, talking to the
 * motor only through its mailbox (motor.h). It uses nothing but hal.h and
 * motor.h, so the host tests run it against mocks of both.
 *
 * Once per millisecond (hal_tick_1ms):
 *   - S2 and S3 are debounced (APP_DEBOUNCE_MS of steady level);
 *     S2 pressed: MC_REQUEST_START_STOP; if the FLTA latch is set, it is
 *     cleared first, and the press is ignored while the pin is still asserted;
 *     S3 pressed: AN1078's "double speed" toggle (speed mode only): the
 *     reference becomes twice what the pot gives, clamped to
 *     SPEED_REF_MAX_RPM; pressing again returns the reference to the pot
 *     (MC_REQUEST_REF_POT);
 *   - the FLTA latch is reported to the core once (MC_REQUEST_HW_FAULT);
 *   - every APP_STATUS_PERIOD_MS: the status snapshot is taken, the LEDs
 *     are set from it, and in double-speed mode the pot is read into the
 *     reference (motor_set_reference);
 *   - with the text protocol (APP_TEXT_UART), every APP_TELEMETRY_PERIOD_MS
 *     one status line is queued for the UART.
 * On every pass: queued bytes go out while the UART takes them, received
 * bytes are commands.
 *
 * LEDs: RUN off when stopped or faulted, blinking at 4 Hz during start-up
 * (CALIBRATE, LOCK, OPEN_LOOP), on in CLOSED_LOOP. FAULT shows the fault
 * code: code n = n blinks (APP_BLINK_MS on, APP_BLINK_MS off), then
 * APP_FAULT_PAUSE_MS dark, repeating; off when there is no fault.
 *
 * UART (8N1, HAL_UART_BAUD), the text protocol: every 100 ms the line
 *   "S<state> F<fault> R<speed_ref> W<speed_est> A<ia> D<0|1>\r\n"
 * (decimal; state = mc_state_t, speeds in Q15 of MC_SPEED_FULLSCALE_RPM,
 * ia offset-corrected in Q15 of BOARD_I_FULLSCALE_A, D = double-speed mode). Commands, one byte
 * each: 'g' MC_REQUEST_START, 's' MC_REQUEST_STOP, 'p' MC_REQUEST_REF_POT (and double speed off).
 *
 * A UART client (app_set_uart_client, e.g. the X2Cscope target of
 * firmware/x2cscope, docs/x2cscope.md) takes the UART over: the status line and
 * the one-byte commands stop (in the X2Cscope image they are not compiled:
 * APP_TEXT_UART 0, and the UART is idle until the client is set); received bytes go to the client
 * while it is ready for them (a byte it is not ready for stays in the UART), bytes it queues go out
 * as the UART takes them, and it gets a tick every 1 ms.
 */

#include <stdbool.h>
#include <stdint.h>

#include "../hal/hal.h" /* firmware/ may include hal/hal.h (docs/architecture.md) */
#include "motor.h"

#define APP_DEBOUNCE_MS         20U
#define APP_STATUS_PERIOD_MS    10U
#define APP_TELEMETRY_PERIOD_MS 100U
#define APP_RUN_BLINK_MS        125U /* start-up blink: 125 ms on, 125 ms off */
#define APP_BLINK_MS            250U
#define APP_FAULT_PAUSE_MS      1500U
#define APP_TX_QUEUE_SIZE       64U /* power of two, up to 256: one status line (< 48) */

/* APP_TEXT_UART: the plain text protocol on the UART (a status line every
 * APP_TELEMETRY_PERIOD_MS, the commands g, s, p) while no client owns it.
 * 1 in a build without the X2Cscope target (APP_NO_X2CSCOPE), whose main.c
 * sets no client; 0 otherwise, and then neither its code nor its queue is
 * in the image. */
#ifndef APP_TEXT_UART
#if defined(APP_NO_X2CSCOPE)
#define APP_TEXT_UART 1
#else
#define APP_TEXT_UART 0
#endif
#endif

typedef struct {
    bool level;     /* debounced: true = held down */
    uint8_t steady; /* ms the raw level has differed from `level` */
} app_button_t;

/* A protocol that owns the UART (all callbacks required, ctx passed back). */
typedef struct {
    void *ctx;
    bool (*rx_ready)(void *ctx);               /* true: rx_byte may be called */
    void (*rx_byte)(void *ctx, uint8_t byte);  /* one received byte */
    bool (*tx_byte)(void *ctx, uint8_t *byte); /* next byte to send; false: none */
    void (*tick_1ms)(void *ctx);               /* once per elapsed millisecond */
    void (*poll)(void *ctx);                   /* once per main-loop pass */
} app_uart_client_t;

typedef struct {
    app_button_t s2, s3;
    bool double_speed;    /* S3 mode: the board owns the reference (app.c note) */
    uint8_t ref_seq_mine; /* mc_status_t.ref_seq after the app's own last reference */
    bool fault_reported;  /* the current FLTA latch was posted to the core */
    uint16_t status_ms;   /* counts to APP_STATUS_PERIOD_MS */
    uint16_t run_phase;   /* ms into the RUN blink */
    uint16_t fault_phase; /* ms into the FAULT pattern */
    uint16_t fault_shown; /* fault code the pattern is showing */
    mc_status_t status;   /* last snapshot */
#if APP_TEXT_UART
    uint16_t telemetry_ms; /* counts to APP_TELEMETRY_PERIOD_MS */
    uint8_t tx[APP_TX_QUEUE_SIZE];
    uint8_t tx_head, tx_tail; /* head: next free, tail: next to send */
#endif
    const app_uart_client_t *uart_client; /* NULL: the text protocol above (APP_TEXT_UART) */
    bool client_tx_held;                  /* client_tx holds a byte the UART refused */
    uint8_t client_tx;
} app_t;

/* Everything to rest: buttons released, normal speed, LEDs off. */
void app_init(app_t *app);

/* Hands the UART to a client (NULL: back to the text protocol, or idle without it). */
void app_set_uart_client(app_t *app, const app_uart_client_t *client);

/* May the motor start? The rule S2 and every other START source share: a
 * latched hardware fault is cleared first, and while the fault pin still
 * holds it nothing starts (false). */
bool app_start_allowed(app_t *app);

/* One main-loop pass: the 1 ms work if a tick elapsed, then the UART. */
void app_poll(app_t *app);

/* The pieces of app_poll(), for the tests. */
void app_tick_1ms(app_t *app);
void app_service_uart(app_t *app);

/* Speed reference for a pot reading (0..32767), Q15 of MC_SPEED_FULLSCALE_RPM:
 * the core's map (mc_pot_to_speed), times 2 when doubled, never above
 * SPEED_REF_MAX_RPM. */
int16_t app_speed_from_pot(int16_t pot, bool doubled);

/* LED levels for a state / fault code at a pattern phase (ms). */
bool app_led_run_on(mc_state_t state, uint16_t phase_ms);
bool app_led_fault_on(uint16_t fault, uint16_t phase_ms);
/* Length of the fault pattern of code n: n blinks plus the pause (ms). */
uint16_t app_fault_pattern_ms(uint16_t fault);

#endif /* APP_H */
