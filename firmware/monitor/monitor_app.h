/* monitor_app.h - the monitor as the application's UART client (firmware/app.h). */
#ifndef MONITOR_APP_H
#define MONITOR_APP_H

#include "../app.h"
#include "monitor.h"

/*
 * On the dsPIC (firmware/main.c), the wiring is:
 *   static monitor_t mon;  static app_uart_client_t client;
 *   monitor_init(&mon, <the mc_t the ADC interrupt steps>);
 *   monitor_app_client(&mon, &client);
 *   app_set_uart_client(&app, &client);
 * and in the ADC interrupt, after mc_step(): monitor_sample(&mon, &motor).
 */
void monitor_app_client(monitor_t *m, app_uart_client_t *client);

#endif /* MONITOR_APP_H */
