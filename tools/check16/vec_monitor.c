/* vec_monitor.c - 16-bit check vectors for the live data monitor: parser, replies, recorder. */
/* (tools/check16/run reads the first directive line only: kept whole) */
/* clang-format off */
/* check16-requires: firmware/mc.c smc_estimator/smc.c firmware/monitor/monitor.c firmware/monitor/monitor_link.c firmware/monitor/monitor_rec.c firmware/monitor/monitor_vars.c tools/sim/sim_mailbox.c */
/* clang-format on */
#include "emit.h"

#include <stddef.h>

#include "mc.h"
#include "monitor/monitor.h"
#include "../sim/sim_mailbox.h"

/*
 * Sections:
 *   monitor_tables    the variable full scales and the parameter ranges,
 *                     as each compiler folded them (a 32-bit double on the AVR);
 *   monitor_protocol  3000 requests, valid or mutated (bit flips, truncation,
 *                     a wrong length, a changed command), fed byte by byte,
 *                     each followed by the receive timeout: the length and
 *                     CRC of every byte the device queued, and the state the
 *                     request may change (recorder configuration, mailbox,
 *                     remote reference, gains);
 *   monitor_recorder  a 4-channel stream at decimation 3 and a snapshot over
 *                     2000 periods of a stopped core fed a varying bus: every
 *                     DATA frame's length and CRC.
 */

static mc_t mc;       /* static: off the AVR stack */
static monitor_t mon; /* static: off the AVR stack */

static uint16_t crc_bytes(const uint8_t *p, uint8_t n)
{
    uint16_t c = 0xFFFFU;
    uint8_t i;
    for (i = 0; i < n; i++) {
        c = monitor_crc16(c, p[i]);
    }
    return c;
}

/* Takes every queued byte: emits how many and their CRC. */
static void emit_tx(void)
{
    uint16_t c = 0xFFFFU, n = 0;
    uint8_t b;
    while (monitor_tx_byte(&mon, &b)) {
        c = monitor_crc16(c, b);
        n++;
    }
    emit_u16(n);
    emit_u16(c);
}

static void emit_state(void)
{
    uint8_t k;
    emit_u16(mon.decim);
    emit_u8(mon.nch);
    for (k = 0; k < MONITOR_MAX_CH; k++) {
        emit_u8(mon.ch[k]);
    }
    emit_u8(mon.mode);
    emit_u8(mon.trig);
    emit_u8(mon.run);
    emit_u16(mon.rx_errors);
    for (k = 0; k < (uint8_t)MC_REQUEST_COUNT; k++) {
        emit_u8(mc.req_posted[k]);
    }
    emit_i16(mc.ref_remote);
    emit_i16(mc.pi_d.p.kp);
    emit_i16(mc.pi_q.p.ki);
    emit_i16(mc.spd_kp_base);
    emit_i16(mc.spd_ki_base);
}

static void vec_tables(void)
{
    uint8_t i;
    emit_section("monitor_tables");
    for (i = 0; i < MONITOR_NUM_VARS; i++) {
        emit_u8(i);
        emit_sep();
        emit_u8(monitor_vars[i].kind);
        emit_i32(monitor_vars[i].fs_milli);
        emit_end();
    }
    for (i = 0; i < MONITOR_NUM_PARAMS; i++) {
        emit_u8(i);
        emit_sep();
        emit_i16(monitor_params[i].min);
        emit_i16(monitor_params[i].max);
        emit_i16(monitor_param_get(i));
        emit_end();
    }
}

static uint8_t build_request(uint8_t *f)
{
    static const uint8_t cmds[] = {
        MONITOR_CMD_INFO,  MONITOR_CMD_VAR_INFO,  MONITOR_CMD_PARAM_INFO, MONITOR_CMD_SELECT,
        MONITOR_CMD_START, MONITOR_CMD_STOP,      MONITOR_CMD_TRIGGER,    MONITOR_CMD_STATUS,
        MONITOR_CMD_MOTOR, MONITOR_CMD_SET_SPEED, MONITOR_CMD_SET_PARAM,  0x33U};
    uint8_t cmd = cmds[vec_rand_u16() % (uint16_t)sizeof cmds];
    uint8_t len = (uint8_t)(vec_rand_u16() % 8U);
    uint8_t i, n;
    uint16_t c;
    if ((vec_rand_u16() & 3U) != 0U) { /* mostly the command's own length */
        if (cmd == MONITOR_CMD_VAR_INFO || cmd == MONITOR_CMD_PARAM_INFO ||
            cmd == MONITOR_CMD_MOTOR) {
            len = 1U;
        } else if (cmd == MONITOR_CMD_START || cmd == MONITOR_CMD_SET_SPEED) {
            len = 2U;
        } else if (cmd == MONITOR_CMD_SET_PARAM) {
            len = 3U;
        } else {
            len = 0U;
        }
    }
    if (cmd == MONITOR_CMD_SELECT) {
        len = (uint8_t)(3U + vec_rand_u16() % 5U);
    }

    f[0] = MONITOR_SOF;
    f[1] = len;
    f[2] = cmd;
    for (i = 0; i < len; i++) {
        f[3 + i] = (uint8_t)(vec_rand_u16() % 24U);
    }
    if (cmd == MONITOR_CMD_SELECT) {
        f[5] = (uint8_t)(len - 3U); /* mostly consistent */
    }
    if (cmd == MONITOR_CMD_MOTOR || cmd == MONITOR_CMD_START) {
        f[3] = (uint8_t)(vec_rand_u16() % 4U);
        f[4] = (uint8_t)(vec_rand_u16() % 4U);
    }
    if (cmd == MONITOR_CMD_SET_SPEED || cmd == MONITOR_CMD_SET_PARAM) {
        uint16_t v = vec_rand_u16();
        f[len >= 3U ? 4 : 3] = (uint8_t)(v & 0xFFU);
        f[len >= 3U ? 5 : 4] = (uint8_t)((v >> 8) & 0x1FU);
    }
    c = crc_bytes(&f[1], (uint8_t)(len + 2U));
    f[3 + len] = (uint8_t)(c & 0xFFU);
    f[4 + len] = (uint8_t)(c >> 8);
    n = (uint8_t)(len + 5U);
    switch (vec_rand_u16() % 6U) {
        case 0: {
            /* Two draws, sequenced: inside one expression their order would be
             * unspecified (gcc on the PC and XC16 pick different orders). */
            uint8_t at = (uint8_t)(vec_rand_u16() % n);
            f[at] ^= (uint8_t)(1U << (vec_rand_u16() % 8U));
            break;
        }
        case 1:
            n = (uint8_t)(vec_rand_u16() % n);
            break;
        case 2:
            f[1] = (uint8_t)vec_rand_u16();
            break;
        default: /* valid */
            break;
    }
    return n;
}

static void vec_protocol(void)
{
    uint8_t f[64];
    uint32_t k;
    uint8_t i, t;
    emit_section("monitor_protocol");
    vec_seed(0x3071U);
    mc_init(&mc);
    sim_mailbox_attach(&mc);
    monitor_init(&mon);
    for (k = 0; k < 3000UL; k++) {
        uint8_t n = build_request(f);
        emit_u8(n);
        emit_u8(n > 2U ? f[2] : 0U);
        emit_u16(crc_bytes(f, n));
        emit_sep();
        for (i = 0; i < n; i++) {
            monitor_rx_byte(&mon, f[i]);
        }
        for (t = 0; t < MONITOR_RX_TIMEOUT_MS; t++) {
            monitor_tick_1ms(&mon);
        }
        emit_tx();
        emit_state();
        emit_end();
        if ((k & 15U) == 0U) {
            (void)monitor_sample(&mon, &mc);
            monitor_poll(&mon);
            while (monitor_tx_byte(&mon, &i)) {
            }
        }
    }
}

static void feed(uint8_t cmd, const uint8_t *p, uint8_t len)
{
    uint8_t i;
    uint16_t c = 0xFFFFU;
    monitor_rx_byte(&mon, MONITOR_SOF);
    monitor_rx_byte(&mon, len);
    c = monitor_crc16(c, len);
    monitor_rx_byte(&mon, cmd);
    c = monitor_crc16(c, cmd);
    for (i = 0; i < len; i++) {
        monitor_rx_byte(&mon, p[i]);
        c = monitor_crc16(c, p[i]);
    }
    monitor_rx_byte(&mon, (uint8_t)(c & 0xFFU));
    monitor_rx_byte(&mon, (uint8_t)(c >> 8));
}

static void run_periods(uint32_t n)
{
    uint32_t k;
    for (k = 0; k < n; k++) {
        mc_adc_frame_t in;
        mc_pwm_out_t out;
        in.ia = vec_rand_between(-200, 200);
        in.ib = vec_rand_between(-200, 200);
        in.vbus = vec_rand_between(14000, 16000);
        in.pot = vec_rand_between(0, 32767);
        mc_step(&mc, &in, &out);
        mc_slow_step(&mc);
        (void)monitor_sample(&mon, &mc);
        if ((k % 20U) == 19U) {
            monitor_tick_1ms(&mon);
            monitor_poll(&mon);
            emit_u32(k);
            emit_sep();
            emit_tx();
            emit_end();
        }
    }
}

static void vec_recorder(void)
{
    const uint8_t sel4[7] = {3, 0, 4, 16, 11, 12, 0};
    const uint8_t sel1[4] = {1, 0, 1, 16};
    const uint8_t stream[2] = {MONITOR_MODE_STREAM, MONITOR_TRIG_NOW};
    const uint8_t snap[2] = {MONITOR_MODE_SNAPSHOT, MONITOR_TRIG_NOW};
    emit_section("monitor_recorder");
    vec_seed(0x3072U);
    mc_init(&mc);
    sim_mailbox_attach(&mc);
    monitor_init(&mon);
    feed(MONITOR_CMD_SELECT, sel4, 7);
    feed(MONITOR_CMD_START, stream, 2);
    run_periods(1000UL);
    feed(MONITOR_CMD_STOP, NULL, 0);
    feed(MONITOR_CMD_SELECT, sel1, 4);
    feed(MONITOR_CMD_START, snap, 2);
    run_periods(1000UL);
}

void vec_monitor(void)
{
    mc_init(&mc);
    sim_mailbox_attach(&mc); /* the monitor's commands act on mc */
    vec_tables();
    vec_protocol();
    vec_recorder();
}
