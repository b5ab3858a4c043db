/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* vec_x2c.c - 16-bit check vectors for the X2Cscope target: services, whitelist, tunables, scope.
 */
/* (tools/check16/run reads the first directive line only: kept whole) */
/* clang-format off */
/* check16-requires: firmware/mc.c firmware/mc_state.c firmware/mc_slow.c firmware/mc_sensor.c firmware/mc_dtm.c firmware/mc_api.c firmware/mc_contract.c firmware/mc_id_isr.c firmware/mc_id_units.c firmware/mc_id.c smc_estimator/smc.c firmware/x2cscope/lnet.c firmware/x2cscope/x2c.c firmware/x2cscope/x2c_scope.c tools/sim/sim_mailbox.c */
/* clang-format on */
#include "emit.h"

#include <stddef.h>

#include "mc.h"
#include "x2cscope/x2c.h"
#include "../sim/sim_mailbox.h"

/* the client's side: a receiver for any frame (the target's takes X2C_RX_BYTES) */
static uint8_t rx_buf[LNET_MAX_DATA];

/*
 * The wire addresses are each platform's own (the AVR's and the dsPIC's
 * real ones, the PC's window) and so are some variables' widths (an enum
 * is 2 bytes on the 16-bit targets, 4 on the PC): a request names a row and
 * an offset from it, and a read's reply is emitted as its value, not its
 * bytes. Sections:
 *   x2c_tables    every row's object and flags (its size is the platform's);
 *   x2c_protocol  3000 requests (reads, writes, scope configurations, the
 *                 other services), valid or mutated (address, width, count,
 *                 value, length, checksum): the reply's error and value, and
 *                 the state a request may change (tunables, mailbox, scope);
 *   x2c_scope     captures of three channels (int16, uint32, bool) with
 *                 triggers and delays over a core fed random frames: the
 *                 trigger position and a checksum of the buffer.
 */

static mc_t mc;   /* static: off the AVR stack */
static x2c_t x2c; /* static: off the AVR stack */

static uint16_t row_addr(uint8_t r)
{
    const x2c_row_t *row = &x2c_rows[r];
    return (uint16_t)(x2c_wire(&x2c, (x2c_obj_t)row->obj) + row->offset);
}

static void vec_tables(void)
{
    uint8_t i;
    emit_section("x2c_tables");
    for (i = 0; i < X2C_ROWS; i++) {
        emit_u8(i);
        emit_sep();
        emit_u8(x2c_rows[i].obj);
        emit_u8(x2c_rows[i].flags);
        emit_end();
    }
}

/* A frame for node 1 from its data, fed byte by byte; the reply collected. */
static uint8_t reply[LNET_MAX_DATA];
static uint8_t reply_n;

static void transact(const uint8_t *d, uint8_t n, bool corrupt)
{
    uint8_t sum = 0x55U, b, i;
    lnet_rx_t rx;
    x2c_rx_byte(&x2c, 0x55U);
    for (i = 0; i < (uint8_t)(n + 2U); i++) {
        b = (i == 0U) ? n : (i == 1U) ? 1U : d[i - 2U];
        x2c_rx_byte(&x2c, b);
        sum = (uint8_t)(sum + b);
        if (b == 0x55U || b == 0x02U) {
            x2c_rx_byte(&x2c, 0x00U);
        }
    }
    b = lnet_crc_byte(sum);
    x2c_rx_byte(&x2c, corrupt ? (uint8_t)(b == 0x54U ? 0x53U : b ^ 0x01U) : b);
    lnet_rx_init(&rx, rx_buf, (uint8_t)LNET_MAX_DATA);
    reply_n = 0;
    while (x2c_tx_byte(&x2c, &b)) {
        if (lnet_rx_byte(&rx, b) == LNET_RX_FRAME) {
            reply_n = rx.size;
            for (i = 0; i < rx.size; i++) {
                reply[i] = rx.data[i];
            }
        }
    }
}

static void emit_state(void)
{
    uint8_t k;
    emit_i16(x2c.tune.cur_kp);
    emit_i16(x2c.tune.cur_ki);
    emit_i16(x2c.tune.spd_kp);
    emit_i16(x2c.tune.spd_ki);
    emit_i16(x2c.tune.speed_ref_rpm);
    emit_i16(x2c.tune.run);
    for (k = 0; k < (uint8_t)MC_REQUEST_COUNT; k++) {
        emit_u8(mc.mbox.req_posted[k]);
    }
    emit_i16(mc.mbox.ref_remote);
    emit_i16(mc.pi_d.p.kp);
    emit_i16(mc.pi_q.p.ki);
    emit_i16(mc.spd_kp_base);
    emit_i16(mc.spd_ki_base);
    emit_u8(x2c.scope.run.state);
    emit_u8(x2c.scope.cfg.nch);
    emit_u16(x2c.scope.cfg.prescaler);
    emit_i32(x2c.scope.cfg.delay);
    emit_u32(x2c.scope.cfg.trig_level);
}

/* The reply as values: error, then a read's value or a reply's bytes
 * with the platform's addresses left out. */
static void emit_reply(uint8_t service)
{
    uint8_t i;
    emit_u8(reply_n > 0U ? reply[0] : 0xFFU);
    emit_u8(reply_n > 1U ? reply[1] : 0xFFU);
    if (reply_n <= 2U) {
        return;
    }
    if (service == X2C_SVC_GET_RAM) {
        uint32_t v = 0;
        for (i = 0; i < (uint8_t)(reply_n - 2U) && i < 4U; i++) {
            v |= (uint32_t)reply[2U + i] << (8U * i);
        }
        emit_u32(v);
        return;
    }
    for (i = 2; i < reply_n; i++) {
        if (service == X2C_SVC_LOAD_PARAM && i >= 10U && i < 14U) {
            continue; /* the buffer's address */
        }
        emit_u8(reply[i]);
    }
}

/* A row whose size is the same on every platform: all but the state (an
 * enum: 2 bytes on the 16-bit targets, 4 on the PC). */
static uint8_t some_row(uint8_t rows)
{
    return (uint8_t)(1U + vec_rand_u16() % (uint16_t)(rows - 1U));
}

/* A width every platform refuses, now and then; else 1 (aligned anywhere). */
static uint8_t some_width(void)
{
    static const uint8_t bad[] = {0, 3, 5};
    return (vec_rand_u16() % 8U == 0U) ? bad[vec_rand_u16() % 3U] : 1U;
}

static uint8_t build(uint8_t *d)
{
    uint8_t n = 0, r = some_row((uint8_t)X2C_ROWS);
    uint16_t size = x2c_rows[r].size;
    /* inside the row now and then: the same on every platform */
    uint16_t delta = (size > 1U && vec_rand_u16() % 4U == 0U) ? vec_rand_u16() % size : 0U;
    uint16_t a = (uint16_t)(row_addr(r) + delta);
    switch (vec_rand_u16() % 8U) {
        case 0:
        case 1:
        case 2: /* read */
            d[0] = X2C_SVC_GET_RAM;
            d[1] = (uint8_t)a;
            d[2] = (uint8_t)(a >> 8);
            d[3] = (uint8_t)((r == X2C_ROWS - 1U) ? vec_rand_u16() % 256U
                                                  : (uint16_t)(size - delta) +
                                                        ((vec_rand_u16() % 8U == 0U) ? 1U : 0U));
            d[4] = some_width();
            n = 5;
            break;
        case 3:
        case 4: { /* write a tunable, mostly */
            uint8_t t = (uint8_t)(X2C_MOTOR_ROWS + vec_rand_u16() % X2C_TUNE_ROWS);
            int16_t v = (vec_rand_u16() % 2U) ? vec_rand_between(-2, 2000) : vec_rand_i16();
            a = (vec_rand_u16() % 4U == 0U) ? a : row_addr(t);
            d[0] = X2C_SVC_PUT_RAM;
            d[1] = (uint8_t)a;
            d[2] = (uint8_t)(a >> 8);
            d[3] = some_width();
            d[4] = (uint8_t)((uint16_t)v & 0xFFU);
            d[5] = (uint8_t)((uint16_t)v >> 8);
            n = 6;
            break;
        }
        case 5: { /* a scope configuration */
            uint8_t tr = some_row((uint8_t)X2C_MOTOR_ROWS);
            uint16_t ta = row_addr(tr);
            uint8_t tw = (uint8_t)x2c_rows[tr].size;
            uint8_t nch = (uint8_t)(1U + vec_rand_u16() % 9U), k;
            d[0] = X2C_SVC_SAVE_PARAM;
            d[1] = 1;
            d[2] = 0;
            d[3] = (uint8_t)(1U + vec_rand_u16() % 2U);
            d[4] = nch;
            d[5] = (uint8_t)(vec_rand_u16() % 3U);
            d[6] = 0;
            n = 7;
            for (k = 0; k < nch; k++) {
                uint8_t cr = some_row((uint8_t)X2C_MOTOR_ROWS);
                uint16_t ca = row_addr(cr);
                d[n++] = 0;
                d[n++] = (uint8_t)ca;
                d[n++] = (uint8_t)(ca >> 8);
                d[n++] = 0;
                d[n++] = 0;
                d[n++] = (uint8_t)x2c_rows[cr].size;
            }
            d[n++] = (uint8_t)(0x80U | 0x20U | tw);
            d[n++] = 0;
            d[n++] = (uint8_t)ta;
            d[n++] = (uint8_t)(ta >> 8);
            d[n++] = 0;
            d[n++] = 0;
            for (k = 0; k < tw; k++) {
                d[n++] = (uint8_t)vec_rand_u16();
            }
            {
                int16_t delay = (int16_t)(vec_rand_between(-8, 8) * 6);
                d[n++] = (uint8_t)((uint16_t)delay & 0xFFU);
                d[n++] = (uint8_t)((uint16_t)delay >> 8);
                d[n++] = delay < 0 ? 0xFFU : 0U;
                d[n++] = delay < 0 ? 0xFFU : 0U;
            }
            d[n++] = (uint8_t)(vec_rand_u16() % 2U);
            d[n++] = (uint8_t)(vec_rand_u16() % 2U);
            break;
        }
        case 6:
            d[0] = X2C_SVC_LOAD_PARAM;
            d[1] = (uint8_t)(1U + vec_rand_u16() % 8U / 7U);
            d[2] = 0;
            n = 3;
            break;
        default: {
            static const uint8_t other[] = {0x00, 0x01, 0x02, 0x19, 0x33};
            d[0] = other[vec_rand_u16() % (uint16_t)sizeof other];
            n = 1;
            break;
        }
    }
    if (vec_rand_u16() % 10U == 0U) {
        n = (uint8_t)(vec_rand_u16() % (uint16_t)(n + 1U)); /* cut short */
    }
    return n;
}

static void vec_protocol(void)
{
    uint8_t d[LNET_MAX_DATA];
    uint16_t k;
    emit_section("x2c_protocol");
    vec_seed(0x3073U);
    mc_init(&mc);
    sim_mailbox_attach(&mc);
    x2c_init(&x2c);
    for (k = 0; k < 3000U; k++) {
        uint8_t n = build(d);
        bool corrupt = vec_rand_u16() % 16U == 0U;
        emit_u16(k);
        emit_u8(n);
        emit_u8(n > 0U ? d[0] : 0U);
        emit_bool(corrupt);
        emit_sep();
        transact(d, n, corrupt);
        emit_reply(n > 0U ? d[0] : 0U);
        emit_state();
        emit_end();
        if ((k & 7U) == 0U) {
            (void)x2c_sample(&x2c, NULL);
        }
    }
}

static void run_periods(uint16_t n)
{
    uint16_t k;
    for (k = 0; k < n; k++) {
        mc_adc_frame_t in;
        mc_pwm_out_t out;
        in.ia = vec_rand_between(-200, 200);
        in.ib = vec_rand_between(-200, 200);
        in.vbus = vec_rand_between(14000, 16000);
        in.pot = vec_rand_between(0, 32767);
        mc_step(&mc, &in, &out);
        mc_slow_step(&mc);
        (void)x2c_sample(&x2c, NULL);
    }
}

static void vec_scope(void)
{
    static const int8_t delays[] = {0, 10, -10, 40};
    uint8_t i;
    emit_section("x2c_scope");
    vec_seed(0x3074U);
    mc_init(&mc);
    sim_mailbox_attach(&mc);
    x2c_init(&x2c);
    mc_request(&mc, MC_REQUEST_START);
    for (i = 0; i < sizeof delays; i++) {
        x2c_scope_cfg_t c;
        uint16_t j, sum = 0;
        c.state = (i == 0U) ? X2C_SCOPE_SAMPLE : X2C_SCOPE_WAIT_TRIG;
        c.set.nch = 3;
        c.set.prescaler = i;
        c.src[0] = (const volatile uint8_t *)&mc.i_dq.q;
        c.set.size[0] = 2;
        c.src[1] = (const volatile uint8_t *)&mc.ol_angle;
        c.set.size[1] = 4;
        c.src[2] = (const volatile uint8_t *)&mc.smc.valid;
        c.set.size[2] = 1;
        for (j = 3; j < X2C_SCOPE_CHANNELS; j++) {
            c.src[j] = NULL;
            c.set.size[j] = 0;
        }
        c.set.trig_src = (const volatile uint8_t *)&mc.i_dq.q;
        c.set.trig_dtype = 0xA2;
        c.set.trig_level = x2c_scope_key(0U, c.set.trig_dtype);
        c.set.rising = (i & 1U) == 0U;
        c.set.delay = (int32_t)delays[i] * 7;
        emit_u8(i);
        emit_u8(x2c_scope_check(&c));
        emit_sep();
        x2c_scope_start(&x2c.scope, &c);
        run_periods(1500U);
        for (j = 0; j < X2C_SCOPE_BYTES; j++) {
            sum = (uint16_t)(sum * 31U + x2c.scope.buf[j]);
        }
        emit_u8(x2c.scope.run.state);
        emit_u16(x2c.scope.run.wr);
        emit_u16(x2c.scope.run.trig_pos);
        emit_u16(sum);
        emit_end();
    }
}

void vec_x2c(void)
{
    vec_tables();
    vec_protocol();
    vec_scope();
}
