/* sim_pty.h - the live data monitor (firmware/monitor) on a pseudo-terminal, driven by the
 * simulator. */
#ifndef SIM_PTY_H
#define SIM_PTY_H

#include "sim_core.h"

/*
 * `sim --pty` runs no scenario: it opens a pseudo-terminal, prints its path
 * ("pty: /dev/pts/N") on stdout, and steps the core and the simulated motor
 * period after period, with the monitor wired as on the dsPIC:
 *   every PWM period (the ISR): simcore_step() (mc_step inside), then
 *     monitor_sample();
 *   every millisecond of simulated time (the main loop): received bytes into
 *     monitor_rx_byte() while monitor_rx_ready(), monitor_tick_1ms(),
 *     monitor_poll(), and bytes out of monitor_tx_byte() at the UART's rate
 *     (baud / 10 bytes per simulated second, 8N1).
 * Time is paced against the wall clock (`speed` x real time; 0 = as fast as
 * the CPU goes), so a host program sees the motor as it would the board.
 */

typedef struct {
    double speed;           /* simulated seconds per wall second; 0 = free-running */
    long baud;              /* emulated UART rate (8N1) */
    double duration_s;      /* stop after this much simulated time; <= 0 = until killed */
    const char *truth_path; /* NULL, or a CSV of the true speed at every recorded sample */
} sim_pty_cfg_t;

void sim_pty_cfg_default(sim_pty_cfg_t *cfg);

/* Runs until duration_s, SIGINT or SIGTERM. Returns 0, or 2 when the pty
 * cannot be opened. */
int sim_pty_run(simcore_t *s, const sim_pty_cfg_t *cfg);

#endif /* SIM_PTY_H */
