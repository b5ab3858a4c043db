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
 * The UART speaks the live data monitor's protocol (firmware/monitor,
 * docs/monitor.md, host side tools/scope): its recorder observes the motor
 * from the ADC interrupt, after the duties are written. Build with
 * -DAPP_NO_MONITOR for the plain text status line of app.h instead (and
 * without the monitor's RAM, docs/board.md).
 *
 * Built only by `make firmware` / MPLAB X; the host tests cover app.c, and
 * test/hal's hostcc test links this file into the whole image.
 */

#if !defined(APP_NO_MONITOR)
#include "monitor/monitor_app.h"

static monitor_t monitor;
static app_uart_client_t monitor_client;

/* The recorder, once per PWM period in the ADC interrupt (constant time). */
static void monitor_observer(void *ctx, const mc_t *mc)
{
    (void)monitor_sample((monitor_t *)ctx, mc);
}
#endif

static app_t app;

#if !defined(APP_NO_MONITOR)
/* The monitor's START follows the board's rule (app_start_allowed). */
static bool monitor_may_start(void *ctx)
{
    return app_start_allowed((app_t *)ctx);
}
#endif

int main(void)
{
    hal_init();
    app_init(&app);
    motor_start();
#if !defined(APP_NO_MONITOR)
    monitor_init(&monitor);
    monitor_set_start_guard(&monitor, monitor_may_start, &app);
    monitor_app_client(&monitor, &monitor_client);
    app_set_uart_client(&app, &monitor_client);
    motor_observe(monitor_observer, &monitor);
#endif
    for (;;) {
        app_poll(&app);
    }
}
