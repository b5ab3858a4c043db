/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* x2c.h - the X2Cscope target: the LNet services MPLAB X's X2CScope, Data Visualizer and pyx2cscope
 * use. */
#ifndef X2C_H
#define X2C_H

/*
 * What a client can do (docs/x2cscope.md, "Our target"):
 *   0x00 device info       a generic dsPIC (processor id 0x8210): 16-bit addresses;
 *   0x01 get target state  the DSP state byte of device info;
 *   0x09 read RAM          inside one whitelisted variable (x2c_vars.h) or the scope buffer;
 *   0x0A write RAM         one whole tunable, in its range, applied through the mailbox;
 *   0x11 load parameter 1  the scope's state (29 bytes);
 *   0x12 save parameter 1  configure and start the scope (channels and trigger whitelisted).
 * Everything else (reboot, flash, blocks, set target state, other
 * parameters) is refused. Each refusal is an error reply with the
 * protocol's code and changes nothing.
 *
 * Two contexts, as on the dsPIC:
 *   ISR        x2c_sample() once per PWM period, after the duties are
 *              written: the scope (x2c_scope.h), constant time;
 *   main loop  x2c_rx_byte() for each received byte while x2c_rx_ready(),
 *              x2c_tx_byte() for the bytes of the reply. The reply's head
 *              is built in the request's own buffer and a read of the
 *              scope's buffer is sent from where it lies, so no byte is
 *              taken while one is being sent (the client waits for it
 *              anyway: LNet is strictly request / response). The request
 *              buffer holds X2C_RX_BYTES: a longer frame is answered 0x15
 *              under service 0, the protocol's "too large for the target".
 * The motor is reached only through its mailbox (motor.h), masked; a read
 * of a motor variable is a masked copy of at most 4 bytes.
 */

#include <stdbool.h>
#include <stdint.h>

#include "lnet.h"
#include "version.h"
#include "x2c_scope.h"
#include "x2c_vars.h"

/* Error ids (the response's second byte). */
#define X2C_ERR_OK       0x00U
#define X2C_ERR_CHECKSUM 0x13U /* the frame's checksum did not match */
#define X2C_ERR_FORMAT   0x14U /* malformed, misaligned, or outside the whitelist */
#define X2C_ERR_SIZE     0x15U /* the reply would not fit a frame */
#define X2C_ERR_SERVICE  0x21U /* no such service here */
#define X2C_ERR_STATE    0x22U /* valid, but not now (the start guard, torque mode) */
#define X2C_ERR_PARAM    0x40U /* no such parameter id */
#define X2C_ERR_LIMIT    0x42U /* a value outside its range */

/* Services. */
#define X2C_SVC_DEVICE_INFO 0x00U
#define X2C_SVC_GET_STATE   0x01U
#define X2C_SVC_GET_RAM     0x09U
#define X2C_SVC_PUT_RAM     0x0AU
#define X2C_SVC_LOAD_PARAM  0x11U
#define X2C_SVC_SAVE_PARAM  0x12U

#define X2C_PARAM_SCOPE  1U      /* the one parameter id: the scope */
#define X2C_PROCESSOR_ID 0x8210U /* generic dsPIC: clients use 16-bit addresses */
#define X2C_MONITOR_VER  5U
#define X2C_APP_VER      AN1078_VERSION_U16   /* VERSION, as 0xMMmp (version.h) */
#define X2C_READ_MAX     (LNET_MAX_DATA - 2U) /* 253: a reply is service, error, data */
/* The largest request taken: save parameter with 8 channels and a 4-byte
 * trigger level, 3 + 4 + 8 x 6 + 16 bytes (also without the scope, whose
 * services then answer "not available", not "too large"). The request
 * buffer holds it, and the largest head built over it (device info's 2 + 44). */
#define X2C_REQUEST_MAX 71U
#define X2C_RX_BYTES                                                                               \
    ((X2C_REQUEST_MAX > 2U + X2C_INFO_BYTES) ? X2C_REQUEST_MAX : 2U + X2C_INFO_BYTES)
#define X2C_INFO_BYTES        44U
#define X2C_SCOPE_STATE_BYTES 29U

/* The dates device info reports, "MmmDDYYYY" and "HHMM": the target's
 * release, fixed so that a build is reproducible (-D to override). */
#ifndef X2C_BUILD_DATE
#define X2C_BUILD_DATE "Nov252026"
#endif
#ifndef X2C_BUILD_TIME
#define X2C_BUILD_TIME "0000"
#endif

/* DSP states (device info, get target state). */
#define X2C_DSP_POWER_OFF 0x04U /* the application runs, outputs off */
#define X2C_DSP_POWER_ON  0x05U /* the application runs, outputs switching */

/* Where the objects appear on the wire. On the dsPIC (and any 16-bit
 * target) an address is the object's own, as the ELF gives it; a PC's
 * 64-bit addresses are presented in this 16-bit window instead. */
#define X2C_WINDOW_TUNE  0x0800U
#define X2C_WINDOW_ID    0x0880U
#define X2C_WINDOW_SCOPE 0x0900U
#define X2C_WINDOW_MOTOR 0x1000U

typedef struct {
    /* the motor's side, as the board's controls have it (first: no buffer ends next to
     * a function pointer) */
    bool (*may_start)(void *ctx); /* run = 1's guard (the board's start rule), NULL: none */
    void *may_start_ctx;
    lnet_rx_t rx; /* the request, and then the reply's head built over it */
    lnet_tx_t tx;
    uint8_t rx_buf[X2C_RX_BYTES];
    const volatile uint8_t *body; /* the reply's data read where they lie (the scope's), or NULL */
    x2c_tune_t tune;
    mc_id_result_t id; /* the identification's result as last read (X2C_ID_VARS) */
#if X2C_SCOPE
    x2c_scope_t scope;
#endif
    bool remote;          /* speed_ref_rpm set the reference ... */
    uint8_t ref_seq_mine; /* ... and this was its choice (mc_reference_held) */
    uint8_t quiet_ms;     /* ms since the last byte taken, saturating (X2C_RX_GAP_MS) */
    /* counters, saturating */
    uint16_t answered; /* replies sent without an error */
    uint16_t refused;  /* error replies */
} x2c_t;

/* Silence, ms, after which a partial request is dropped (x2c_tick_1ms): a
 * client sends a request in one go (at 115200 Bd a byte is 87 us, a
 * USB-serial bridge passes the host's bytes within its 1 ms frames), so a
 * gap this long is a client that left, and the next one must not find its
 * bytes; below pyx2cscope's 50 ms reply timeout, so a client that lost a
 * byte and sends its request again is read afresh. */
#ifndef X2C_RX_GAP_MS
#define X2C_RX_GAP_MS 20U
#endif

/* Idle scope, the tunables read from the motor, no start guard. */
void x2c_init(x2c_t *x);

/* run = 1 asks may_start(ctx) first and is refused (X2C_ERR_STATE) when it
 * says no: the application's rule for every START (app_start_allowed). */
void x2c_set_start_guard(x2c_t *x, bool (*may_start)(void *ctx), void *ctx);

/* Main loop. */
bool x2c_rx_ready(const x2c_t *x); /* no reply being sent */
void x2c_rx_byte(x2c_t *x, uint8_t byte);
bool x2c_tx_byte(x2c_t *x, uint8_t *byte); /* the next byte to send, false if none */
void x2c_tick_1ms(x2c_t *x);               /* once per ms: the inter-byte timeout */

/* ISR, once per PWM period after the core's step. True when the scope
 * stored a dataset (at byte *at of its buffer, when at is not NULL). */
static inline bool x2c_sample(x2c_t *x, uint16_t *at)
{
#if X2C_SCOPE
    /* idle, the common case, without the call */
    return x->scope.run.state != X2C_SCOPE_IDLE && x2c_scope_sample(&x->scope, at);
#else
    (void)x;
    (void)at;
    return false;
#endif
}

/* The wire address of an object (x2c_obj_t). */
uint16_t x2c_wire(const x2c_t *x, x2c_obj_t obj);

#endif /* X2C_H */
