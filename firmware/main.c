/* main.c - the dsPIC33FJ32MC204 program: init, then the main loop forever (dsPIC only). */
#include "app.h"
#include "../hal/hal.h" /* firmware/ may include hal/hal.h (DESIGN.md layers) */

/*
 * The control loop is not here: hal_motor_start() enables the ADC
 * interrupt, whose vector (hal/dspic33f/hal_isr.c) reads each conversion
 * set, runs mc_step() and writes the duties, once per PWM period. The main
 * loop is the slow rest (app.h): buttons, pot, LEDs, UART, fault latch.
 * Built only by `make firmware` / MPLAB X; the host tests cover app.c.
 */

static app_t app;

int main(void)
{
    hal_init();
    app_init(&app);
    hal_motor_start();
    for (;;) {
        app_poll(&app);
    }
}
