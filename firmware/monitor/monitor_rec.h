/* monitor_rec.h - the monitor's recorder, as the protocol (monitor.c) drives it. */
#ifndef MONITOR_REC_H
#define MONITOR_REC_H

/*
 * The recorder's half of monitor_t: configuration, the ISR handshake and the
 * sample ring (monitor.h "Shared data"). monitor_sample() (ISR) and
 * monitor_poll() (main loop, DATA frames) are the public entry points; the
 * calls below are the protocol's. Each returns MONITOR_ERR_NONE or the error
 * code of the refusal, having changed nothing when it refuses.
 */

#include <stdint.h>

#include "monitor.h"

/* Stopped, empty, channels {speed_est}, decimation 1, stream now. */
void monitor_rec_init(monitor_t *m);

/* SELECT: decimation (PWM periods per sample) and n channels ch[0..n-1]. */
uint8_t monitor_rec_select(monitor_t *m, uint16_t decim, uint8_t n, const uint8_t *ch);

/* START: MONITOR_MODE_*, MONITOR_TRIG_*; motor_state is the core's state now
 * (the state-change trigger compares against it). */
uint8_t monitor_rec_start(monitor_t *m, uint8_t mode, uint8_t trig, uint8_t motor_state);

/* STOP: the ISR stops recording, unsent data is dropped. */
void monitor_rec_stop(monitor_t *m);

/* TRIGGER: fires a snapshot armed with MONITOR_TRIG_CMD. */
uint8_t monitor_rec_trigger(monitor_t *m);

/* The recorder's part of the STATUS reply, bytes 0..13 of docs/monitor.md's
 * layout (rec state, mode, decim:2, nch, ch[4], written:2, buffered:2,
 * overflow); returns 14. */
uint8_t monitor_rec_status(const monitor_t *m, uint8_t *p);

#endif /* MONITOR_REC_H */
