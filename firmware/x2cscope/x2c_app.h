/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* x2c_app.h - the X2Cscope target as the application's UART client (firmware/app.h). */
#ifndef X2C_APP_H
#define X2C_APP_H

#include "../app.h"
#include "x2c.h"

/*
 * On the dsPIC (firmware/main.c) the wiring is:
 *   static x2c_t x2c;  static app_uart_client_t client;
 *   x2c_init(&x2c);  x2c_app_client(&x2c, &client);
 *   app_set_uart_client(&app, &client);
 * and the scope samples from the ADC interrupt through motor_observe().
 */
void x2c_app_client(x2c_t *x, app_uart_client_t *client);

#endif /* X2C_APP_H */
