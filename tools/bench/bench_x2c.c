/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* bench_x2c.c - instruction count of the X2Cscope target: the ISR's scope and the main loop's
 * services. */
/* bench-requires: firmware/mc.c firmware/x2cscope/x2c.c tools/sim/sim_mailbox.c */
/* bench-symbols: x2c_init x2c_scope_sample x2c_rx_byte x2c_tx_byte */
#include "bench.h"

#include <stddef.h>

#include "mc.h"
#include "x2c.h"
#include "../sim/sim_mailbox.h"

/*
 * The ISR side: x2c_scope_sample() once per PWM period, after the core.
 *   idle            the cost every period while nothing records;
 *   8ch_int16       eight 2-byte channels stored every period (the word path);
 *   8ch_trigger     the same, waiting for an int16 edge that never comes
 *                   (the ring: the trigger evaluated and a dataset stored);
 *   1byte_mix       a bool among seven int16 (the byte path).
 * The main-loop side: x2c_rx_byte() per received byte of read requests
 * (each completes a frame: the service, the whitelist, the copy) and
 * x2c_tx_byte() per reply byte of 253-byte scope-buffer reads.
 * The dsPIC's own cycles are in docs/x2cscope.md, measured with XC16.
 */

static mc_t mc;
static x2c_t x2c;

/* Feeds one frame; returns the bytes it fed. */
static uint32_t frame(const uint8_t *d, uint8_t n)
{
    uint8_t sum = 0x55U, i;
    uint32_t fed = 2U; /* SYN and CRC */
    x2c_rx_byte(&x2c, 0x55U);
    for (i = 0; i < (uint8_t)(n + 2U); i++) {
        uint8_t b = (i == 0U) ? n : (i == 1U) ? 1U : d[i - 2U];
        x2c_rx_byte(&x2c, b);
        sum = (uint8_t)(sum + b);
        fed++;
        if (b == 0x55U || b == 0x02U) {
            x2c_rx_byte(&x2c, 0x00U);
            fed++;
        }
    }
    x2c_rx_byte(&x2c, lnet_crc_byte(sum));
    return fed;
}

static void drain(void);

static void drain(void)
{
    uint8_t b;
    while (x2c_tx_byte(&x2c, &b)) {
        bench_sink += b;
    }
}

/* The configuration setup() started, for run() to restart. */
static x2c_scope_cfg_t c;

static void setup(uint8_t state, bool with_bool)
{
    static const volatile void *const src[8] = {&mc.ia,     &mc.ib,     &mc.i_dq.d, &mc.i_dq.q,
                                                &mc.v_dq.d, &mc.v_dq.q, &mc.theta,  &mc.vbus};
    uint8_t i;
    mc_init(&mc);
    sim_mailbox_attach(&mc);
    x2c_init(&x2c);
    c.state = state;
    c.set.nch = 8;
    c.set.prescaler = 0;
    for (i = 0; i < 8U; i++) {
        c.src[i] = (const volatile uint8_t *)src[i];
        c.set.size[i] = 2;
    }
    if (with_bool) {
        c.src[7] = (const volatile uint8_t *)&mc.outputs_on;
        c.set.size[7] = 1;
    }
    c.set.trig_src = (const volatile uint8_t *)&mc.ia;
    c.set.trig_dtype = 0xA2;
    c.set.trig_level = x2c_scope_key(30000U, 0xA2);
    c.set.rising = true;
    c.set.delay = 0;
    x2c_scope_start(&x2c.scope, &c);
}

static void run(uint32_t n)
{
    uint32_t k;
    for (k = 0U; k < n; k++) {
        if (x2c.scope.run.state == X2C_SCOPE_IDLE) {
            x2c_scope_start(&x2c.scope, &c); /* keep it recording */
        }
        bench_sink += x2c_scope_sample(&x2c.scope, NULL) ? 1 : 0;
    }
}

static void run_idle(uint32_t n)
{
    setup(X2C_SCOPE_IDLE, false);
    for (uint32_t k = 0U; k < n; k++) {
        bench_sink += x2c_scope_sample(&x2c.scope, NULL) ? 1 : 0;
    }
}

static void run_8ch(uint32_t n)
{
    setup(X2C_SCOPE_SAMPLE, false);
    run(n);
}

static void run_8ch_trigger(uint32_t n)
{
    setup(X2C_SCOPE_WAIT_TRIG, false);
    run(n);
}

static void run_mix(uint32_t n)
{
    setup(X2C_SCOPE_SAMPLE, true);
    run(n);
}

static void run_rx(uint32_t n)
{
    uint16_t a = (uint16_t)(x2c_wire(&x2c, X2C_OBJ_MOTOR) + offsetof(mc_t, i_dq.q));
    const uint8_t rd[5] = {X2C_SVC_GET_RAM, (uint8_t)a, (uint8_t)(a >> 8), 2, 2};
    uint32_t k = 0;
    setup(X2C_SCOPE_IDLE, false);
    while (k + 16U <= n) { /* each byte one measured call */
        k += frame(rd, 5U);
        drain();
    }
    for (; k < n; k++) {
        x2c_rx_byte(&x2c, 0x00U); /* between frames: skipped */
    }
}

static void run_tx(uint32_t n)
{
    uint16_t a = x2c_wire(&x2c, X2C_OBJ_SCOPE);
    const uint8_t rd[5] = {X2C_SVC_GET_RAM, (uint8_t)a, (uint8_t)(a >> 8), X2C_READ_MAX, 1};
    uint32_t k = 0;
    uint8_t b;
    setup(X2C_SCOPE_IDLE, false);
    while (k < n) { /* every call measured, the one that finds the reply sent too */
        k++;
        if (x2c_tx_byte(&x2c, &b)) {
            bench_sink += b;
        } else {
            (void)frame(rd, 5U);
        }
    }
}

void bench_x2c(void)
{
    bench_add("x2c_scope_sample/idle", "x2c_scope_sample", 2000U, run_idle);
    bench_add("x2c_scope_sample/8ch_int16", "x2c_scope_sample", 2000U, run_8ch);
    bench_add("x2c_scope_sample/8ch_trigger", "x2c_scope_sample", 2000U, run_8ch_trigger);
    bench_add("x2c_scope_sample/1byte_mix", "x2c_scope_sample", 2000U, run_mix);
    bench_add("x2c_rx_byte/read_frames", "x2c_rx_byte", 1800U, run_rx);
    bench_add("x2c_tx_byte/253_byte_reads", "x2c_tx_byte", 2000U, run_tx);
}
