/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_pty.h - the X2Cscope target (firmware/x2cscope) on a pseudo-terminal and TCP, driven by
 * the simulator. */
#ifndef SIM_PTY_H
#define SIM_PTY_H

#include "sim_core.h"

/*
 * `sim --pty` runs no scenario: it opens a pseudo-terminal (raw: 0x11 and
 * 0x13 are data), prints its path ("pty: /dev/pts/N") on stdout, with
 * --tcp also listens on 127.0.0.1:PORT ("tcp: 127.0.0.1:PORT"; one client
 * at a time, the same frames), and steps the core and the simulated motor
 * period after period, with the X2Cscope target wired as on the dsPIC:
 *   every PWM period (the ISR): simcore_step() (mc_step inside), then
 *     x2c_sample();
 *   every millisecond of simulated time (the main loop): received bytes into
 *     x2c_rx_byte() while x2c_rx_ready(), and the reply's bytes out of
 *     x2c_tx_byte() at the UART's rate (baud / 10 bytes per simulated
 *     second, 8N1), to the transport the request came on.
 * The target presents its variables in a 16-bit window (x2c.h); the map
 * of it is built from this program's ELF (sim_x2c_map.h).
 * Time is paced against the wall clock (`speed` x real time; 0 = as fast as
 * the CPU goes), so a host program sees the motor as it would the board.
 */

typedef struct {
    double speed;           /* simulated seconds per wall second; 0 = free-running */
    long baud;              /* emulated UART rate (8N1) */
    int tcp_port;           /* > 0: also serve 127.0.0.1:tcp_port */
    double duration_s;      /* stop after this much simulated time; <= 0 = until killed */
    const char *truth_path; /* NULL, or a CSV of the true speed at every stored dataset */
} sim_pty_cfg_t;

void sim_pty_cfg_default(sim_pty_cfg_t *cfg);

/* Runs until duration_s, SIGINT or SIGTERM. Returns 0, or 2 when the pty
 * or the TCP port cannot be opened. */
int sim_pty_run(simcore_t *s, const sim_pty_cfg_t *cfg);

#endif /* SIM_PTY_H */
