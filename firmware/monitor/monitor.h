/* monitor.h - live data monitor: a recorder of core variables and a framed binary UART protocol. */
#ifndef MONITOR_H
#define MONITOR_H

/*
 * The diagnostics mode AN1078 gets from RTDM + DMCI, without an IDE: the host
 * (tools/scope) selects up to MONITOR_MAX_CH variables of the core, a
 * decimation N, and either streams them continuously or takes a snapshot at
 * the full rate into RAM; it can also start/stop the motor, set the speed
 * reference (replacing the pot) and change a whitelist of tuning parameters.
 * docs/monitor.md is the protocol specification.
 *
 * The parts, one job each:
 *   monitor_link.[ch]  framing: bytes <-> frames, CRC, transmit queue;
 *   monitor_vars.[ch]  the registry: one row per variable, one per gain;
 *   monitor_rec.[ch]   the recorder: sampling in the ISR, DATA frames;
 *   monitor.c          the protocol: one table row per command, and the
 *                      adapter, the only place the main loop calls the core.
 *
 * Two contexts, as on the dsPIC:
 *   ISR        monitor_sample() once per PWM period, after mc_step(): O(1),
 *              it never waits and never touches the UART (a decimation count,
 *              then at most nch variable reads and int16 stores);
 *   main loop  monitor_rx_byte() for each received byte (only while
 *              monitor_rx_ready()), monitor_tick_1ms() every millisecond (the
 *              receive timeout), monitor_poll() on every pass (queues the
 *              recorded data), monitor_tx_byte() to take bytes for the UART.
 * The control loop's timing never depends on the UART: when the host reads
 * too slowly a stream stops with the overflow flag, it is never waited for.
 *
 * Shared data (single core, the ISR preempts the main loop, never the reverse):
 * while run != 0 the ring's write count `wr` and the flags `isr_started`,
 * `isr_done`, `isr_overflow` are written only by the ISR; `rd`, the
 * configuration and `run` only by the main loop, which changes the
 * configuration and resets the ring and the ISR's flags only while run == 0
 * (the ISR then returns at once) and sets run last.
 * Every shared field is one byte or one 16-bit word (atomic on the dsPIC).
 *
 * A reply has CMD | 0x80; an error reply has CMD 0x7F and the payload
 * [request CMD, MONITOR_ERR_*]; a request that gets an error reply changed
 * nothing. Recorded data goes out as unsolicited MONITOR_CMD_DATA frames.
 */

#include <stdbool.h>
#include <stdint.h>

#include "mc.h"
#include "monitor_link.h"
#include "monitor_vars.h"

/* ---- sizes (override MONITOR_BUF_WORDS with -D) ------------------------------- */

#define MONITOR_MAX_CH 4U /* channels sampled together */
#ifndef MONITOR_BUF_WORDS
#define MONITOR_BUF_WORDS 256U /* recorder RAM, int16 words (512 bytes) */
#endif
#define MONITOR_DECIM_MAX 10000U
#define MONITOR_VERSION   1U

/* ---- commands (host -> device; the reply has CMD | 0x80) ------------------ */
#define MONITOR_CMD_INFO       0x01U /* []                 -> version, counts, sizes, f_pwm */
#define MONITOR_CMD_VAR_INFO   0x02U /* [idx]              -> idx kind fs_milli name\0unit */
#define MONITOR_CMD_PARAM_INFO 0x03U /* [idx]              -> idx value min max name */
#define MONITOR_CMD_SELECT     0x04U /* [decim:2 n ch[n]]  recorder stopped only */
#define MONITOR_CMD_START      0x05U /* [mode trig]        -> first sample's period (u32 0) */
#define MONITOR_CMD_STOP       0x06U /* []                 recorder stops, buffer dropped */
#define MONITOR_CMD_TRIGGER    0x07U /* []                 a snapshot armed with TRIG_CMD */
#define MONITOR_CMD_STATUS     0x08U /* []                 -> recorder and motor status */
#define MONITOR_CMD_MOTOR      0x10U /* [action]           MONITOR_MOTOR_* */
#define MONITOR_CMD_SET_SPEED  0x11U /* [rpm:2]            remote speed reference */
#define MONITOR_CMD_SET_PARAM  0x12U /* [idx value:2]      whitelisted tuning parameter */
#define MONITOR_CMD_DATA       0x40U /* device -> host: [flags index:2 nsets data...] */
#define MONITOR_CMD_ERROR      0x7FU /* device -> host: [request cmd, error] */
#define MONITOR_REPLY          0x80U

/* error codes */
#define MONITOR_ERR_NONE    0U /* not sent: the request succeeded */
#define MONITOR_ERR_CRC     1U /* CRC mismatch */
#define MONITOR_ERR_LENGTH  2U /* LEN above MONITOR_MAX_PAYLOAD, or wrong for the command */
#define MONITOR_ERR_UNKNOWN 3U /* no such command */
#define MONITOR_ERR_RANGE   4U /* an argument out of its range */
#define MONITOR_ERR_STATE   5U /* not now (recorder running, nothing armed...) */
#define MONITOR_ERR_TIMEOUT 6U /* truncated frame: a gap of MONITOR_RX_TIMEOUT_MS */

/* START modes and triggers */
#define MONITOR_MODE_STREAM   0U /* continuous: samples go out as the UART takes them */
#define MONITOR_MODE_SNAPSHOT 1U /* fill the buffer at full rate, then send it */
#define MONITOR_TRIG_NOW      0U
#define MONITOR_TRIG_CMD      1U /* snapshot starts at MONITOR_CMD_TRIGGER */
#define MONITOR_TRIG_STATE    2U /* snapshot starts when the motor state changes */

/* MOTOR actions */
#define MONITOR_MOTOR_STOP  0U
#define MONITOR_MOTOR_START 1U
#define MONITOR_MOTOR_POT   2U /* reference from the pot again */

/* DATA flags */
#define MONITOR_DATA_LAST     0x01U /* recording finished: this is its last frame */
#define MONITOR_DATA_OVERFLOW 0x02U /* the stream stopped: the host read too slowly */

/* recorder states (STATUS) */
#define MONITOR_REC_IDLE    0U
#define MONITOR_REC_ARMED   1U /* snapshot waiting for its trigger */
#define MONITOR_REC_RUNNING 2U /* recording (stream: and sending) */
#define MONITOR_REC_SENDING 3U /* snapshot full, being sent */

/* ---- the instance -------------------------------------------------------- */

typedef struct {
    monitor_link_t link; /* framing (monitor_link.c, main loop) */

    /* protocol counters (monitor.c, main loop), reported by STATUS */
    uint16_t rx_errors;  /* error replies sent (saturates) */
    uint16_t rx_dropped; /* frames dropped for lack of TX room (saturates) */

    /* the motor's side (monitor.c, main loop; the motor itself through motor.h) */
    bool (*may_start)(void *ctx); /* START's guard (the board's start rule), NULL: none */
    void *may_start_ctx;
    bool remote;          /* the monitor set the reference (SET_SPEED) ... */
    uint8_t ref_seq_mine; /* ... and mc_status_t.ref_seq was this after it: the status
                             reports REMOTE only while both hold (mc_reference_held) */

    /* The recorder (monitor_rec.c). Its fields are not gathered in a struct
     * of their own because tools/sim/sim_pty.c reads `wr` by this name. */
    /* configuration (main loop, only while run == 0) */
    uint16_t decim;             /* 1..MONITOR_DECIM_MAX PWM periods per sample */
    uint16_t cap;               /* sample sets the buffer holds: MONITOR_BUF_WORDS / nch */
    uint8_t nch;                /* 1..MONITOR_MAX_CH */
    uint8_t ch[MONITOR_MAX_CH]; /* variable indices */
    uint8_t mode, trig;
    /* handshake */
    volatile uint8_t run;          /* main: 1 = the ISR records */
    volatile uint8_t trig_req;     /* main: TRIGGER received */
    volatile uint8_t isr_started;  /* ISR: the snapshot trigger has fired */
    volatile uint8_t isr_done;     /* ISR: snapshot buffer full */
    volatile uint8_t isr_overflow; /* ISR: stream stopped, buffer was full */
    uint8_t last_state;            /* ISR: motor state at the previous sample */
    volatile uint16_t wr;          /* ISR: sample sets written (mod 2^16) */
    volatile uint16_t rd;          /* main: sample sets sent (mod 2^16) */
    uint16_t wi, ri;               /* ISR / main: ring slot of the next set */
    uint16_t div;                  /* ISR: periods since the last sample */
    int16_t buf[MONITOR_BUF_WORDS];
} monitor_t;

/* Everything idle, channels {speed_est}, decimation 1, no START guard. The
 * commands act on the motor through its mailbox (motor.h), the recorder on
 * the motor monitor_sample() is given. */
void monitor_init(monitor_t *m);

/* MOTOR START asks may_start(ctx) first and is refused (MONITOR_ERR_STATE)
 * when it says no: the application's rule for every START (app.c's
 * app_start_allowed: not while the fault pin holds a hardware fault). */
void monitor_set_start_guard(monitor_t *m, bool (*may_start)(void *ctx), void *ctx);

/* ISR, once per PWM period after mc_step(). Returns true when it stored a
 * sample set this period (for the simulator's truth log). */
bool monitor_sample(monitor_t *m, const mc_t *mc);

/* Main loop. */
bool monitor_rx_ready(const monitor_t *m); /* room for the longest reply */
void monitor_rx_byte(monitor_t *m, uint8_t byte);
void monitor_tick_1ms(monitor_t *m);
void monitor_poll(monitor_t *m);
bool monitor_tx_byte(monitor_t *m, uint8_t *byte); /* next byte to send, false if none */

/* Current value of parameter idx, through the mailbox (0 for idx out of
 * range). */
int16_t monitor_param_get(uint8_t idx);

#endif /* MONITOR_H */
