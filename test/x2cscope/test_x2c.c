/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_x2c.c - the X2Cscope target's services: every service, the whitelist, every refusal. */
#include "x2c_util.h"

#include <stdio.h>
#include <stdlib.h>

static rig_t rig;

static int setup(void **state)
{
    (void)state;
    rig_init(&rig);
    return 0;
}

static void put16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)(v & 0xFFU);
    p[1] = (uint8_t)(v >> 8);
}

static void put32(uint8_t *p, uint32_t v)
{
    put16(p, (uint16_t)(v & 0xFFFFU));
    put16(p + 2, (uint16_t)(v >> 16));
}

static uint32_t get32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

/* read RAM: reply length, data into out */
static int read_ram(uint16_t addr, uint8_t n, uint8_t width, uint8_t *out, uint8_t *err)
{
    uint8_t req[5] = {X2C_SVC_GET_RAM, 0, 0, n, width};
    uint8_t reply[LNET_MAX_DATA];
    int len;
    put16(&req[1], addr);
    len = rig_req(&rig, req, 5U, reply);
    assert_cmp(len, >=, 2);
    assert_int_equal(reply[0], X2C_SVC_GET_RAM);
    *err = reply[1];
    if (out != NULL && len > 2) {
        memcpy(out, &reply[2], (size_t)len - 2U);
    }
    return len - 2;
}

static uint8_t write_ram(uint16_t addr, uint8_t width, const uint8_t *data, uint8_t n)
{
    uint8_t req[LNET_MAX_DATA] = {X2C_SVC_PUT_RAM, 0, 0, width};
    put16(&req[1], addr);
    memcpy(&req[4], data, n);
    return rig_err(&rig, req, (uint8_t)(4U + n));
}

static uint8_t write_i16(uint16_t addr, int16_t v)
{
    uint8_t d[2];
    put16(d, (uint16_t)v);
    return write_ram(addr, 2U, d, 2U);
}

static int16_t read_i16(uint16_t addr)
{
    uint8_t d[2], err;
    assert_int_equal(read_ram(addr, 2U, 2U, d, &err), 2);
    assert_int_equal(err, X2C_ERR_OK);
    return (int16_t)(uint16_t)((uint16_t)d[0] | (uint16_t)((uint16_t)d[1] << 8));
}

/* ---- device info, target state, unknown services ---------------------------------------- */

static void test_device_info_should_present_a_generic_dspic_with_255_byte_frames(void **state)
{
    (void)state;
    uint8_t req[1] = {X2C_SVC_DEVICE_INFO};
    uint8_t reply[LNET_MAX_DATA];
    const uint8_t *r = &reply[2];
    assert_int_equal(rig_req(&rig, req, 1U, reply), 2 + (int)X2C_INFO_BYTES);
    assert_int_equal(reply[0], 0x00);
    assert_int_equal(reply[1], X2C_ERR_OK);
    assert_int_equal(r[0] | (r[1] << 8), X2C_MONITOR_VER);
    assert_int_equal(r[4], 255);
    assert_int_equal(r[5] | (r[6] << 8), 0x8210);
    assert_memory_equal(&r[7],
                        "Nov252026"
                        "0000",
                        13);
    assert_memory_equal(&r[20],
                        "Nov252026"
                        "0000",
                        13);
    assert_int_equal(r[33], X2C_DSP_POWER_OFF);
}

static void test_target_state_should_follow_the_outputs(void **state)
{
    (void)state;
    uint8_t req[1] = {X2C_SVC_GET_STATE};
    uint8_t reply[LNET_MAX_DATA];
    assert_int_equal(rig_req(&rig, req, 1U, reply), 3);
    assert_int_equal(reply[2], X2C_DSP_POWER_OFF);
    rig.mc.state = MC_STATE_CLOSED_LOOP; /* as the core would be, running */
    assert_int_equal(rig_req(&rig, req, 1U, reply), 3);
    assert_int_equal(reply[2], X2C_DSP_POWER_ON);
}

static void test_services_the_target_does_not_offer_should_be_refused(void **state)
{
    (void)state;
    /* reboot, set target state, flash and block services, and every other id */
    for (unsigned id = 0; id < 256U; id++) {
        uint8_t req[4] = {(uint8_t)id, 0x01, 0x00, 0x00};
        rig_snap_t before;
        if (id == 0x00U || id == 0x01U || id == 0x09U || id == 0x0AU || id == 0x11U ||
            id == 0x12U) {
            continue;
        }
        rig_snap(&rig, &before);
        assert_int_equal(rig_err(&rig, req, 4U), X2C_ERR_SERVICE);
        assert_true(rig_same(&rig, &before));
    }
}

static void test_frame_errors_should_be_answered_with_their_codes(void **state)
{
    (void)state;
    uint8_t reply[LNET_MAX_DATA];
    uint8_t frame[16];
    uint8_t data[1] = {X2C_SVC_DEVICE_INFO};
    size_t n = rig_frame(data, 1U, frame);
    frame[n - 1] ^= 0x01U; /* the checksum */
    assert_int_equal(rig_bytes(&rig, frame, n, reply), 2);
    assert_int_equal(reply[1], X2C_ERR_CHECKSUM);
    /* an empty frame is no frame: after a SYN a SIZE of 0 is an escaped 0x55's fill, as the
     * clients read it; nothing answers it */
    n = rig_frame(data, 0U, frame);
    assert_int_equal(rig_bytes(&rig, frame, n, reply), -1);
    /* a reserved byte without its fill: in a frame for node 1 answered; in its SIZE, before
     * the node is known, noise (no answer) */
    {
        static const uint8_t bad[] = {0x55, 0x03, 0x01, 0x02, 0x09}; /* DATA 0x02, then no fill */
        assert_int_equal(rig_bytes(&rig, bad, sizeof bad, reply), 2);
        assert_int_equal(reply[1], X2C_ERR_FORMAT);
        static const uint8_t noise[] = {0x55, 0x02, 0x01}; /* the 0x01 where SIZE's fill belongs */
        assert_int_equal(rig_bytes(&rig, noise, sizeof noise, reply), -1);
    }
    /* wrong lengths for fixed-size services */
    {
        uint8_t info[2] = {X2C_SVC_DEVICE_INFO, 0};
        uint8_t rd[6] = {X2C_SVC_GET_RAM, 0, 0x08, 2, 2, 0};
        uint8_t ld[4] = {X2C_SVC_LOAD_PARAM, 1, 0, 0};
        uint8_t st[2] = {X2C_SVC_GET_STATE, 0};
        assert_int_equal(rig_err(&rig, info, 2U), X2C_ERR_FORMAT);
        assert_int_equal(rig_err(&rig, rd, 6U), X2C_ERR_FORMAT);
        assert_int_equal(rig_err(&rig, rd, 4U), X2C_ERR_FORMAT);
        assert_int_equal(rig_err(&rig, ld, 4U), X2C_ERR_FORMAT);
        assert_int_equal(rig_err(&rig, st, 2U), X2C_ERR_FORMAT);
    }
}

/* ---- reads --------------------------------------------------------------------------------- */

/* Every whitelisted row reads back its bytes, whole and byte by byte. */
static void test_every_row_should_read_back_what_memory_holds(void **state)
{
    (void)state;
    unsigned i, rows = 0;
    for (i = 0; i < sizeof rig.mc; i++) {
        ((uint8_t *)&rig.mc)[i] = (uint8_t)(i * 7U + 3U); /* a known pattern */
    }
    rig.mc.smc.p = NULL;
    for (i = 0; i < X2C_MOTOR_ROWS; i++) {
        const x2c_row_t *row = &x2c_rows[i];
        uint16_t addr = (uint16_t)(x2c_wire(&rig.x, X2C_OBJ_MOTOR) + row->offset);
        uint8_t got[4], err;
        uint8_t w = (row->size == 1U || (addr & 1U) != 0U) ? 1U : (row->size == 2U ? 2U : 4U);
        assert_int_equal(read_ram(addr, (uint8_t)row->size, w, got, &err), row->size);
        assert_int_equal(err, X2C_ERR_OK);
        assert_memory_equal(got, (const uint8_t *)&rig.mc + row->offset, row->size);
        assert_int_equal(read_ram(addr, 1U, 1U, got, &err), 1);
        assert_int_equal(got[0], ((const uint8_t *)&rig.mc)[row->offset]);
        rows++;
    }
    printf("measured: %u motor variables read back\n", rows);
    assert_int_equal(rows, X2C_MOTOR_ROWS);
}

static void test_the_scope_buffer_should_read_in_253_byte_chunks(void **state)
{
    (void)state;
    uint8_t got[X2C_READ_MAX], err;
    uint16_t at = 0;
    for (unsigned i = 0; i < X2C_SCOPE_BYTES; i++) {
        rig.x.scope.buf[i] = (uint8_t)(i ^ 0x55U);
    }
    while (at < X2C_SCOPE_BYTES) {
        uint8_t n =
            (uint8_t)((X2C_SCOPE_BYTES - at > X2C_READ_MAX) ? X2C_READ_MAX : X2C_SCOPE_BYTES - at);
        assert_int_equal(read_ram((uint16_t)(RIG_SCOPE(&rig) + at), n, 1U, got, &err), n);
        assert_int_equal(err, X2C_ERR_OK);
        assert_memory_equal(got, &rig.x.scope.buf[at], n);
        at = (uint16_t)(at + n);
    }
    /* 254 bytes would not fit a reply */
    assert_int_equal(read_ram(RIG_SCOPE(&rig), 254U, 1U, NULL, &err), 0);
    assert_int_equal(err, X2C_ERR_SIZE);
}

static void test_reads_outside_the_whitelist_or_misaligned_should_be_refused(void **state)
{
    (void)state;
    struct {
        uint16_t addr;
        uint8_t n, width, err;
    } cases[] = {
        {0, 2, 2, X2C_ERR_FORMAT},                                          /* below everything */
        {0xFFFE, 2, 2, X2C_ERR_FORMAT},                                     /* above everything */
        {RIG_MOTOR(&rig, mbox.req_posted[0]), 1, 1, X2C_ERR_FORMAT},        /* not exported */
        {RIG_MOTOR(&rig, i_dq.d), 4, 2, X2C_ERR_FORMAT},                    /* straddles two rows */
        {(uint16_t)(RIG_MOTOR(&rig, i_dq.d) + 1U), 2, 2, X2C_ERR_FORMAT},   /* odd, word */
        {(uint16_t)(RIG_MOTOR(&rig, ol_angle) + 1U), 4, 4, X2C_ERR_FORMAT}, /* odd, long */
        {RIG_MOTOR(&rig, i_dq.d), 3, 3, X2C_ERR_FORMAT},                    /* width 3 */
        {RIG_MOTOR(&rig, i_dq.d), 2, 0, X2C_ERR_FORMAT},                    /* width 0 */
        {RIG_MOTOR(&rig, ol_angle), 3, 2, X2C_ERR_FORMAT},                  /* not whole words */
        {RIG_MOTOR(&rig, i_dq.d), 0, 1, X2C_ERR_FORMAT},                    /* nothing */
        {(uint16_t)(RIG_SCOPE(&rig) + X2C_SCOPE_BYTES - 1U), 2, 1, X2C_ERR_FORMAT}, /* past end */
        {RIG_SCOPE(&rig), 255, 1, X2C_ERR_SIZE},
    };
    for (unsigned i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        rig_snap_t before;
        uint8_t err;
        rig_snap(&rig, &before);
        assert_int_equal(read_ram(cases[i].addr, cases[i].n, cases[i].width, NULL, &err), 0);
        assert_int_equal(err, cases[i].err);
        assert_true(rig_same(&rig, &before));
    }
}

/* ---- writes --------------------------------------------------------------------------------- */

static void test_gains_should_be_applied_through_the_mailbox_and_read_back(void **state)
{
    (void)state;
    static const struct {
        uint16_t off;
        mc_gain_t gain;
        int16_t build;
        int16_t min;
    } g[] = {
        {offsetof(x2c_tune_t, cur_kp), MC_GAIN_CUR_KP, MC_CUR_KP,
         X2C_GAIN_MIN(MC_CUR_KP, MC_GAIN_CUR_KP_MIN8)},
        {offsetof(x2c_tune_t, cur_ki), MC_GAIN_CUR_KI, MC_CUR_KI,
         X2C_GAIN_MIN(MC_CUR_KI, MC_GAIN_CUR_KI_MIN8)},
        {offsetof(x2c_tune_t, spd_kp), MC_GAIN_SPD_KP, MC_SPD_KP,
         X2C_GAIN_MIN(MC_SPD_KP, MC_GAIN_SPD_KP_MIN8)},
        {offsetof(x2c_tune_t, spd_ki), MC_GAIN_SPD_KI, MC_SPD_KI,
         X2C_GAIN_MIN(MC_SPD_KI, MC_GAIN_SPD_KI_MIN8)},
    };
    for (unsigned i = 0; i < 4U; i++) {
        uint16_t addr = (uint16_t)(x2c_wire(&rig.x, X2C_OBJ_TUNE) + g[i].off);
        int16_t v = (int16_t)(g[i].build + g[i].build / 4); /* inside every bound */
        assert_int_equal(read_i16(addr), g[i].build);
        assert_int_equal(write_i16(addr, v), X2C_ERR_OK);
        assert_int_equal(mc_get_gain(&rig.mc, g[i].gain), v);
        assert_int_equal(read_i16(addr), v);
        /* outside the range: refused, nothing changed */
        {
            rig_snap_t before;
            rig_snap(&rig, &before);
            assert_int_equal(write_i16(addr, X2C_GAIN_MAX(g[i].build) + 1 > 32767
                                                 ? 0
                                                 : (int16_t)(X2C_GAIN_MAX(g[i].build) + 1)),
                             X2C_ERR_LIMIT);
            assert_int_equal(write_i16(addr, (int16_t)(g[i].min - 1)), X2C_ERR_LIMIT);
            assert_true(rig_same(&rig, &before));
            assert_int_equal(read_i16(addr), v);
        }
    }
}

static void test_speed_reference_should_be_remote_until_zero_gives_the_pot_back(void **state)
{
    (void)state;
#if !MC_TORQUE_MODE
    uint16_t addr = RIG_TUNE(&rig, speed_ref_rpm);
    mc_status_t st;
    assert_int_equal(write_i16(addr, X2C_RPM_MIN + 100), X2C_ERR_OK);
    mc_status(&rig.mc, &st);
    assert_true(mc_reference_held(&st, rig.x.ref_seq_mine));
    assert_int_equal(read_i16(addr), X2C_RPM_MIN + 100);
    assert_int_equal(write_i16(addr, 0), X2C_ERR_OK);
    assert_int_equal(read_i16(addr), 0);
    /* below the pot's range, above it: refused, nothing changed */
    {
        rig_snap_t before;
        rig_snap(&rig, &before);
        assert_int_equal(write_i16(addr, X2C_RPM_MIN - 1), X2C_ERR_LIMIT);
        assert_int_equal(write_i16(addr, X2C_RPM_MAX + 1), X2C_ERR_LIMIT);
        assert_int_equal(write_i16(addr, -1), X2C_ERR_LIMIT);
        assert_true(rig_same(&rig, &before));
    }
    /* the pot taking the reference back reads as 0 */
    assert_int_equal(write_i16(addr, X2C_RPM_MAX), X2C_ERR_OK);
    mc_request(&rig.mc, MC_REQUEST_REF_POT);
    assert_int_equal(read_i16(addr), 0);
#endif
}

static bool guard_says;
static bool guard(void *ctx)
{
    (void)ctx;
    return guard_says;
}

static void test_run_should_start_and_stop_like_s2_and_follow_its_guard(void **state)
{
    (void)state;
    uint16_t addr = RIG_TUNE(&rig, run);
    uint8_t seq = rig.mc.mbox.req_seq;
    x2c_set_start_guard(&rig.x, guard, NULL);
    guard_says = false;
    {
        rig_snap_t before;
        rig_snap(&rig, &before);
        assert_int_equal(write_i16(addr, 1), X2C_ERR_STATE);
        assert_int_equal(write_i16(addr, 2), X2C_ERR_LIMIT);
        assert_true(rig_same(&rig, &before));
    }
    guard_says = true;
    assert_int_equal(write_i16(addr, 1), X2C_ERR_OK);
    assert_int_equal(rig.mc.mbox.req_posted[MC_REQUEST_START], 1U);
    assert_int_not_equal(rig.mc.mbox.req_seq, seq);
    assert_int_equal(write_i16(addr, 0), X2C_ERR_OK);
    assert_int_equal(rig.mc.mbox.req_posted[MC_REQUEST_STOP], 1U);
}

/* identify: 1 from STOPPED only (and under the start guard), 0 stops a
 * measurement going on and nothing else; it reads 1 while one runs. */
static void test_identify_should_request_a_measurement_from_stopped_only(void **state)
{
    (void)state;
    uint16_t addr = RIG_TUNE(&rig, identify);
    x2c_set_start_guard(&rig.x, guard, NULL);
    guard_says = true;
    {
        rig_snap_t before;
        rig.mc.state = MC_STATE_CLOSED_LOOP; /* running: refused */
        rig_snap(&rig, &before);
        assert_int_equal(write_i16(addr, 1), X2C_ERR_STATE);
        assert_int_equal(write_i16(addr, 2), X2C_ERR_LIMIT);
        assert_true(rig_same(&rig, &before));
        assert_int_equal(write_i16(addr, 0), X2C_ERR_OK); /* not measuring: nothing to stop */
        assert_int_equal(rig.mc.mbox.req_posted[MC_REQUEST_STOP], 0U);
        rig.mc.state = MC_STATE_STOPPED;
        guard_says = false; /* the fault pin still set */
        rig_snap(&rig, &before);
        assert_int_equal(write_i16(addr, 1), X2C_ERR_STATE);
        assert_true(rig_same(&rig, &before));
    }
    guard_says = true;
    assert_int_equal(write_i16(addr, 1), X2C_ERR_OK);
    assert_int_equal(rig.mc.mbox.req_posted[MC_REQUEST_IDENTIFY], 1U);
    assert_int_equal(rig.mc.mbox.req_posted[MC_REQUEST_START], 0U);
    rig.mc.state = MC_STATE_IDENTIFY; /* as the core would be, measuring */
    rig.mc.id_status = MC_ID_RUNNING;
    assert_int_equal(read_i16(addr), 1);
    assert_int_equal(write_i16(addr, 0), X2C_ERR_OK);
    assert_int_equal(rig.mc.mbox.req_posted[MC_REQUEST_STOP], 1U);
    rig.mc.state = MC_STATE_STOPPED;
    rig.mc.id_status = MC_ID_FAILED;
    assert_int_equal(read_i16(addr), 0);
}

/* Every row of the result reads what mc_identify_result gives at that
 * moment: a failure's code, then a finished run's values. */
static void test_the_identification_result_should_read_as_the_core_reports_it(void **state)
{
    (void)state;
    for (unsigned pass = 0; pass < 2U; pass++) {
        mc_id_result_t want;
        unsigned i, rows = 0;
        if (pass == 0U) {
            rig.mc.id_status = MC_ID_FAILED;
            rig.mc.id_error = MC_ID_ERROR_ROTOR_LOCKED;
        } else {
            rig.mc.id_status = MC_ID_DONE;
            rig.mc.id_error = MC_ID_ERROR_NONE;
            rig.mc.id.dv = 123456; /* R = dv / di Z_FS */
            rig.mc.id.di = 654321;
            rig.mc.id.x1 = 1000000UL; /* Ke from m1, m2 at x1, x2 */
            rig.mc.id.x2 = 2000000UL;
            rig.mc.id.m1 = 50000;
            rig.mc.id.m2 = 100000;
        }
        mc_identify_result(&rig.mc, &want);
        for (i = 0; i < X2C_ID_ROWS; i++) {
            const x2c_row_t *row = &x2c_rows[X2C_MOTOR_ROWS + X2C_TUNE_ROWS + 1U + i];
            uint16_t addr = (uint16_t)(x2c_wire(&rig.x, X2C_OBJ_ID) + row->offset);
            uint8_t got[4], err;
            uint8_t w = (row->size == 1U) ? 1U : (row->size == 2U ? 2U : 4U);
            assert_int_equal(row->obj, X2C_OBJ_ID);
            assert_int_equal(read_ram(addr, (uint8_t)row->size, w, got, &err), row->size);
            assert_int_equal(err, X2C_ERR_OK);
            assert_memory_equal(got, (const uint8_t *)&want + row->offset, row->size);
            rows++;
        }
        assert_int_equal(rows, X2C_ID_ROWS);
        if (pass == 0U) {
            assert_int_equal(want.status, MC_ID_FAILED);
            assert_int_equal(want.error, MC_ID_ERROR_ROTOR_LOCKED);
        } else {
            assert_int_equal(want.status, MC_ID_DONE);
            assert_true(want.rs_uohm > 0U && want.ke_uv_per_rpm > 0U);
        }
        assert_int_equal(want.pole_pairs, MOTOR_POLE_PAIRS);
    }
}

static void test_writes_other_than_a_whole_tunable_should_be_refused(void **state)
{
    (void)state;
    uint8_t two[2] = {0x10, 0x00}, four[4] = {0, 0, 0, 0};
    struct {
        uint16_t addr;
        uint8_t width;
        const uint8_t *data;
        uint8_t n;
    } cases[] = {
        {RIG_MOTOR(&rig, i_ref.q), 2, two, 2},                  /* read-only */
        {RIG_MOTOR(&rig, state), 2, two, 2},                    /* read-only */
        {RIG_MOTOR(&rig, mbox.req_posted[0]), 1, two, 1},       /* not exported */
        {RIG_TUNE(&rig, cur_kp), 1, two, 1},                    /* half of it */
        {(uint16_t)(RIG_TUNE(&rig, cur_kp) + 1U), 1, two, 1},   /* its other half */
        {RIG_TUNE(&rig, cur_kp), 2, four, 4},                   /* two tunables */
        {(uint16_t)(RIG_TUNE(&rig, cur_kp) + 1U), 2, two, 2},   /* odd address */
        {RIG_TUNE(&rig, cur_kp), 3, four, 3},                   /* width 3 */
        {RIG_TUNE(&rig, cur_kp), 4, two, 2},                    /* not whole longs */
        {RIG_SCOPE(&rig), 1, two, 1},                           /* the scope's buffer */
        {(uint16_t)(RIG_TUNE(&rig, identify) + 2U), 2, two, 2}, /* past the tunables */
        {RIG_ID(&rig, status), 1, two, 1},                      /* the result: read-only */
        {RIG_ID(&rig, rs_uohm), 4, four, 4},                    /* the result: read-only */
    };
    for (unsigned i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        rig_snap_t before;
        rig_snap(&rig, &before);
        assert_int_equal(write_ram(cases[i].addr, cases[i].width, cases[i].data, cases[i].n),
                         X2C_ERR_FORMAT);
        assert_true(rig_same(&rig, &before));
    }
    {
        uint8_t req[4] = {X2C_SVC_PUT_RAM, 0x00, 0x08, 2}; /* no data */
        assert_int_equal(rig_err(&rig, req, 4U), X2C_ERR_FORMAT);
    }
}

/* ---- the scope ------------------------------------------------------------------------------ */

typedef struct {
    uint8_t b[LNET_MAX_DATA];
    uint8_t n;
} cfg_buf_t;

static void cfg_begin(cfg_buf_t *c, uint8_t state, uint8_t nch, uint16_t prescaler)
{
    c->b[0] = X2C_SVC_SAVE_PARAM;
    c->b[1] = X2C_PARAM_SCOPE;
    c->b[2] = 0;
    c->b[3] = state;
    c->b[4] = nch;
    put16(&c->b[5], prescaler);
    c->n = 7;
}

static void cfg_channel(cfg_buf_t *c, uint32_t addr, uint8_t size)
{
    c->b[c->n++] = 0;
    put32(&c->b[c->n], addr);
    c->n = (uint8_t)(c->n + 4U);
    c->b[c->n++] = size;
}

static void cfg_trigger(cfg_buf_t *c, uint8_t dtype, uint32_t addr, uint32_t level, int32_t delay,
                        uint8_t edge, int mode)
{
    uint8_t lsize = (uint8_t)(dtype & 0x0FU);
    c->b[c->n++] = dtype;
    c->b[c->n++] = 0;
    put32(&c->b[c->n], addr);
    c->n = (uint8_t)(c->n + 4U);
    for (uint8_t i = 0; i < lsize; i++) {
        c->b[c->n++] = (uint8_t)(level >> (8U * i));
    }
    put32(&c->b[c->n], (uint32_t)delay);
    c->n = (uint8_t)(c->n + 4U);
    c->b[c->n++] = edge;
    if (mode >= 0) {
        c->b[c->n++] = (uint8_t)mode;
    }
}

static void load_state(uint8_t *r29)
{
    uint8_t req[3] = {X2C_SVC_LOAD_PARAM, X2C_PARAM_SCOPE, 0};
    uint8_t reply[LNET_MAX_DATA];
    assert_int_equal(rig_req(&rig, req, 3U, reply), 2 + (int)X2C_SCOPE_STATE_BYTES);
    assert_int_equal(reply[1], X2C_ERR_OK);
    memcpy(r29, &reply[2], X2C_SCOPE_STATE_BYTES);
}

static void test_scope_should_sample_until_full_and_report_its_state(void **state)
{
    (void)state;
    cfg_buf_t c;
    uint8_t st[X2C_SCOPE_STATE_BYTES];
    unsigned k = 0;
    cfg_begin(&c, X2C_SCOPE_SAMPLE, 2, 1); /* every 2nd call */
    cfg_channel(&c, RIG_MOTOR(&rig, i_dq.q), 2);
    cfg_channel(&c, RIG_MOTOR(&rig, ol_angle), 4);
    cfg_trigger(&c, 0x82, 0, 0, 0, 1, 0); /* what pyx2cscope sends with no trigger */
    assert_int_equal(rig_err(&rig, c.b, c.n), X2C_ERR_OK);
    load_state(st);
    assert_int_equal(st[0], X2C_SCOPE_SAMPLE);
    assert_int_equal(st[1], 2);
    assert_int_equal(st[2] | (st[3] << 8), 1);
    assert_int_equal(get32(&st[8]), RIG_SCOPE(&rig));
    assert_int_equal(get32(&st[20]), X2C_SCOPE_BYTES / 6U * 6U); /* whole datasets of 6 */
    assert_int_equal(get32(&st[24]), X2C_SCOPE_BYTES);
    assert_int_equal(st[28], 0x82);
    while (rig.x.scope.run.state != X2C_SCOPE_IDLE) {
        rig.mc.i_dq.q = (int16_t)k;
        rig.mc.ol_angle = 0x01020304UL * k;
        (void)x2c_sample(&rig.x, NULL);
        k++;
        assert_cmp(k, <, 1000U);
    }
    assert_int_equal(k,
                     2U * (X2C_SCOPE_BYTES / 6U) - 1U); /* the first call stores, then every 2nd */
    load_state(st);
    assert_int_equal(st[0], 0);
    assert_int_equal(get32(&st[4]), X2C_SCOPE_BYTES / 6U * 6U); /* the pointer at the used length */
    assert_int_equal(get32(&st[16]), 0U);                       /* no rotation */
    for (unsigned d = 0; d < X2C_SCOPE_BYTES / 6U; d++) {
        const uint8_t *ds = &rig.x.scope.buf[6U * d];
        uint32_t call = 2U * d;
        assert_int_equal(ds[0] | (ds[1] << 8), (uint16_t)call);
        assert_int_equal(get32(&ds[2]), 0x01020304UL * call);
    }
}

static void test_scope_configurations_outside_the_rules_should_be_refused(void **state)
{
    (void)state;
    cfg_buf_t c;
    uint16_t iq = RIG_MOTOR(&rig, i_dq.q);
    rig_snap_t before;
    /* a scope running, to see that a refusal leaves it running */
    cfg_begin(&c, X2C_SCOPE_SAMPLE, 1, 0);
    cfg_channel(&c, iq, 2);
    cfg_trigger(&c, 0x82, 0, 0, 0, 1, 0);
    assert_int_equal(rig_err(&rig, c.b, c.n), X2C_ERR_OK);
    rig_snap(&rig, &before);

    cfg_begin(&c, X2C_SCOPE_SAMPLE, 9, 0); /* 9 channels asked, one given */
    cfg_channel(&c, iq, 2);
    cfg_trigger(&c, 0x82, 0, 0, 0, 1, 0);
    assert_int_equal(rig_err(&rig, c.b, c.n), X2C_ERR_LIMIT);
    assert_true(rig_same(&rig, &before));

    /* 9 channels given: 77 bytes, longer than any request the target takes
     * (X2C_REQUEST_MAX): the frame is refused whole, 0x15 under service 0 */
    cfg_begin(&c, X2C_SCOPE_SAMPLE, 9, 0);
    for (int i = 0; i < 9; i++) {
        cfg_channel(&c, iq, 2);
    }
    cfg_trigger(&c, 0x82, 0, 0, 0, 1, 0);
    assert_cmp(c.n, >, X2C_RX_BYTES);
    {
        uint8_t reply[LNET_MAX_DATA];
        assert_int_equal(rig_req(&rig, c.b, c.n, reply), 2);
        assert_int_equal(reply[0], 0);
        assert_int_equal(reply[1], X2C_ERR_SIZE);
    }

    {
        static const struct {
            uint32_t addr;
            uint8_t size;
        } bad[] = {{0x0000, 2}, {0x10000UL + 0x1000U, 2}, {1, 2}, {0, 3}};
        for (unsigned i = 0; i < sizeof bad / sizeof bad[0]; i++) {
            cfg_begin(&c, X2C_SCOPE_SAMPLE, 1, 0);
            cfg_channel(&c, bad[i].addr == 0 && bad[i].size == 3 ? iq : bad[i].addr, bad[i].size);
            cfg_trigger(&c, 0x82, 0, 0, 0, 1, 0);
            assert_int_equal(rig_err(&rig, c.b, c.n), X2C_ERR_FORMAT);
        }
    }
    cfg_begin(&c, X2C_SCOPE_SAMPLE, 1, 0); /* a channel not exported */
    cfg_channel(&c, RIG_MOTOR(&rig, mbox.req_seq), 1);
    cfg_trigger(&c, 0x82, 0, 0, 0, 1, 0);
    assert_int_equal(rig_err(&rig, c.b, c.n), X2C_ERR_FORMAT);
    cfg_begin(&c, X2C_SCOPE_SAMPLE, 1, 0); /* a channel's source type other than an address */
    cfg_channel(&c, iq, 2);
    c.b[7] = 1;
    cfg_trigger(&c, 0x82, 0, 0, 0, 1, 0);
    assert_int_equal(rig_err(&rig, c.b, c.n), X2C_ERR_FORMAT);
    cfg_begin(&c, X2C_SCOPE_WAIT_TRIG, 1, 0); /* a trigger source not exported */
    cfg_channel(&c, iq, 2);
    cfg_trigger(&c, 0xA2, RIG_MOTOR(&rig, offset_a), 0, 0, 1, 1);
    assert_int_equal(rig_err(&rig, c.b, c.n), X2C_ERR_FORMAT);
    cfg_begin(&c, X2C_SCOPE_WAIT_TRIG, 1, 0); /* a trigger source of the wrong width */
    cfg_channel(&c, iq, 2);
    cfg_trigger(&c, 0xA4, iq, 0, 0, 1, 1);
    assert_int_equal(rig_err(&rig, c.b, c.n), X2C_ERR_FORMAT);
    cfg_begin(&c, X2C_SCOPE_WAIT_TRIG, 1, 0); /* more history than the ring */
    cfg_channel(&c, iq, 2);
    cfg_trigger(&c, 0xA2, iq, 0, X2C_SCOPE_BYTES, 1, 1);
    assert_int_equal(rig_err(&rig, c.b, c.n), X2C_ERR_LIMIT);
    cfg_begin(&c, X2C_SCOPE_WAIT_TRIG, 1, 0); /* a delay of half a dataset */
    cfg_channel(&c, iq, 2);
    cfg_trigger(&c, 0xA2, iq, 0, 3, 1, 1);
    assert_int_equal(rig_err(&rig, c.b, c.n), X2C_ERR_FORMAT);
    cfg_begin(&c, X2C_SCOPE_WAIT_TRIG, 1, 0); /* an edge that is neither */
    cfg_channel(&c, iq, 2);
    cfg_trigger(&c, 0xA2, iq, 0, 0, 2, 1);
    assert_int_equal(rig_err(&rig, c.b, c.n), X2C_ERR_FORMAT);
    cfg_begin(&c, X2C_SCOPE_WAIT_TRIG, 1, 0); /* a float of two bytes */
    cfg_channel(&c, iq, 2);
    cfg_trigger(&c, 0xC2, iq, 0, 0, 1, 1);
    assert_int_equal(rig_err(&rig, c.b, c.n), X2C_ERR_FORMAT);
    cfg_begin(&c, 3, 1, 0); /* a state a client does not send */
    cfg_channel(&c, iq, 2);
    cfg_trigger(&c, 0x82, 0, 0, 0, 1, 0);
    assert_int_equal(rig_err(&rig, c.b, c.n), X2C_ERR_FORMAT);
    cfg_begin(&c, X2C_SCOPE_SAMPLE, 1, 0); /* cut short */
    cfg_channel(&c, iq, 2);
    assert_int_equal(rig_err(&rig, c.b, c.n), X2C_ERR_FORMAT);
    {
        uint8_t ld[3] = {X2C_SVC_LOAD_PARAM, 2, 0}, sv[3] = {X2C_SVC_SAVE_PARAM, 1, 1};
        assert_int_equal(rig_err(&rig, ld, 3U), X2C_ERR_PARAM);
        assert_int_equal(rig_err(&rig, sv, 3U), X2C_ERR_PARAM);
    }
    assert_true(rig_same(&rig, &before));
    assert_int_equal(rig.x.scope.run.state, X2C_SCOPE_SAMPLE);
    /* no configuration at all: a stop */
    {
        uint8_t sv[3] = {X2C_SVC_SAVE_PARAM, 1, 0};
        assert_int_equal(rig_err(&rig, sv, 3U), X2C_ERR_OK);
        assert_int_equal(rig.x.scope.run.state, X2C_SCOPE_IDLE);
    }
}

/* A trigger on a motor variable, positive delay: the client's rotation
 * (trigger position / dataset - delay) puts the crossing at the delay. */
static void test_scope_trigger_should_place_the_edge_where_the_client_rotates_to(void **state)
{
    (void)state;
    for (int delay = -20; delay <= 60; delay += 20) {
        cfg_buf_t c;
        uint8_t st[X2C_SCOPE_STATE_BYTES];
        uint16_t iq = RIG_MOTOR(&rig, i_dq.q);
        unsigned k = 0, n = X2C_SCOPE_BYTES / 2U; /* datasets of 2 bytes */
        int16_t rot[X2C_SCOPE_BYTES / 2U];
        rig.mc.i_dq.q = -1000;
        cfg_begin(&c, X2C_SCOPE_WAIT_TRIG, 1, 0);
        cfg_channel(&c, iq, 2);
        cfg_trigger(&c, 0xA2, iq, 100, delay * 2, 1, 1); /* int16, rising past 100 */
        assert_int_equal(rig_err(&rig, c.b, c.n), X2C_ERR_OK);
        while (rig.x.scope.run.state != X2C_SCOPE_IDLE) {
            /* a ramp that crosses 100 at call 700 */
            rig.mc.i_dq.q = (int16_t)((int)k - 600);
            (void)x2c_sample(&rig.x, NULL);
            k++;
            assert_cmp(k, <, 5000U);
        }
        load_state(st);
        {
            int32_t pos = (int32_t)get32(&st[16]) / 2;
            int32_t start = delay >= 0 ? pos - delay : 0;
            for (unsigned i = 0; i < n; i++) {
                unsigned j = (unsigned)(((int32_t)i + start + (int32_t)n) % (int32_t)n);
                rot[i] = (int16_t)(uint16_t)(rig.x.scope.buf[2U * j] |
                                             (rig.x.scope.buf[2U * j + 1U] << 8));
            }
        }
        if (delay >= 0) {
            /* the edge is at index `delay`, the history before it */
            assert_int_equal(rot[delay], 100);
            assert_int_equal(rot[0], 100 - delay);
            assert_int_equal(rot[n - 1U], 100 - delay + (int)n - 1);
        } else {
            /* the record starts -delay datasets after the edge */
            assert_int_equal(rot[0], 100 - delay);
            assert_int_equal(rot[n - 1U], 100 - delay + (int)n - 1);
        }
    }
}

/* A client that leaves with only the checksum missing: after X2C_RX_GAP_MS
 * of silence the next client's request is answered as its own, with no
 * reply to the one that left; with less silence its SYN would be read as
 * the missing checksum (the stale reply a client then reads one behind). */
static void test_a_request_left_unfinished_should_not_answer_the_next_client(void **state)
{
    (void)state;
    rig_t *r = malloc(sizeof *r);
    assert_non_null(r);
    rig_init(r);
    static const uint8_t info[] = {X2C_SVC_DEVICE_INFO};
    uint8_t frame[16], reply[LNET_MAX_DATA];
    size_t n = rig_frame(info, 1U, frame);
    for (size_t k = 0; k + 1U < n; k++) {
        x2c_rx_byte(&r->x, frame[k]); /* all but the checksum */
    }
    for (unsigned ms = 0; ms < X2C_RX_GAP_MS; ms++) {
        x2c_tick_1ms(&r->x);
    }
    uint8_t b;
    assert_false(x2c_tx_byte(&r->x, &b)); /* nothing was answered */
    static const uint8_t state_req[] = {X2C_SVC_GET_STATE};
    int len = rig_req(r, state_req, 1U, reply);
    assert_int_equal(len, 3);
    assert_int_equal(reply[0], X2C_SVC_GET_STATE);
    assert_int_equal(reply[1], X2C_ERR_OK);
    assert_int_equal(r->x.refused, 0U);
    free(r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_device_info_should_present_a_generic_dspic_with_255_byte_frames,
                               setup),
        cmocka_unit_test_setup(test_target_state_should_follow_the_outputs, setup),
        cmocka_unit_test_setup(test_services_the_target_does_not_offer_should_be_refused, setup),
        cmocka_unit_test_setup(test_frame_errors_should_be_answered_with_their_codes, setup),
        cmocka_unit_test_setup(test_every_row_should_read_back_what_memory_holds, setup),
        cmocka_unit_test_setup(test_the_scope_buffer_should_read_in_253_byte_chunks, setup),
        cmocka_unit_test_setup(test_reads_outside_the_whitelist_or_misaligned_should_be_refused,
                               setup),
        cmocka_unit_test_setup(test_gains_should_be_applied_through_the_mailbox_and_read_back,
                               setup),
        cmocka_unit_test_setup(test_speed_reference_should_be_remote_until_zero_gives_the_pot_back,
                               setup),
        cmocka_unit_test_setup(test_run_should_start_and_stop_like_s2_and_follow_its_guard, setup),
        cmocka_unit_test_setup(test_identify_should_request_a_measurement_from_stopped_only, setup),
        cmocka_unit_test_setup(test_the_identification_result_should_read_as_the_core_reports_it,
                               setup),
        cmocka_unit_test_setup(test_writes_other_than_a_whole_tunable_should_be_refused, setup),
        cmocka_unit_test(test_a_request_left_unfinished_should_not_answer_the_next_client),
        cmocka_unit_test_setup(test_scope_should_sample_until_full_and_report_its_state, setup),
        cmocka_unit_test_setup(test_scope_configurations_outside_the_rules_should_be_refused,
                               setup),
        cmocka_unit_test_setup(test_scope_trigger_should_place_the_edge_where_the_client_rotates_to,
                               setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
