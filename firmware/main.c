/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* main.c - the dsPIC33FJ32MC204 program: init, then the main loop forever (dsPIC only). */
#include "app.h"
#include "../hal/hal.h" /* firmware/ may include hal/hal.h (docs/architecture.md) */
#include "motor.h"

/*
 * The control loop is not here: motor_start() (motor.c) enables the ADC
 * interrupt, whose vector (hal/dspic33f/hal_isr.c) reads each conversion
 * set and hands it to motor.c's hooks, which run the core and hand the
 * duties back, once per PWM period. The main loop is the slow rest
 * (app.h): buttons, pot, LEDs, UART, fault latch.
 *
 * The UART speaks X2Cscope (firmware/x2cscope, docs/x2cscope.md): MPLAB X's
 * X2CScope plugin, MPLAB Data Visualizer, pyx2cscope and tools/scope watch
 * and tune the firmware through it; its scope samples the motor from the
 * ADC interrupt, after the duties are written. Build with
 * -DAPP_NO_X2CSCOPE for the plain text status line of app.h instead (and
 * without the target's RAM, docs/board.md).
 *
 * Built only by `make firmware` / MPLAB X; the host tests cover app.c, and
 * test/hal's hostcc test links this file into the whole image.
 */

#if !defined(APP_NO_X2CSCOPE)
#include <stddef.h>

#include "x2cscope/x2c_app.h"

/* The target. Its name is part of the interface: clients find the
 * tunables as x2c.tune.<name> in this program's ELF (x2c_vars.h). */
x2c_t x2c;
static app_uart_client_t x2c_client;

/* The scope, once per PWM period in the ADC interrupt (constant time). */
static void x2c_observer(void *ctx, const mc_t *mc)
{
    (void)mc; /* the channels were resolved to addresses when configured */
    (void)x2c_sample((x2c_t *)ctx, NULL);
}
#endif

static app_t app;

#if !defined(APP_NO_X2CSCOPE)
/* run = 1 follows the board's rule (app_start_allowed). */
static bool x2c_may_start(void *ctx)
{
    return app_start_allowed((app_t *)ctx);
}
#endif

int main(void)
{
    hal_init();
    app_init(&app);
    motor_start();
#if !defined(APP_NO_X2CSCOPE)
    x2c_init(&x2c);
    x2c_set_start_guard(&x2c, x2c_may_start, &app);
    x2c_app_client(&x2c, &x2c_client);
    app_set_uart_client(&app, &x2c_client);
    if (X2C_SCOPE) {
        motor_observe(x2c_observer, &x2c); /* the scope's sampling */
    }
#endif
    for (;;) {
        app_poll(&app);
    }
}
