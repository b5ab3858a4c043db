/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_x2c_readonly.c - the target built with X2C_READ_ONLY: every write refused, reads and the
 * scope as before. */
#include "../x2c_util.h"

static rig_t rig;

static int setup(void **state)
{
    (void)state;
    rig_init(&rig);
    return 0;
}

static uint8_t write_tunable(uint16_t addr, int16_t v)
{
    uint8_t req[6] = {X2C_SVC_PUT_RAM,
                      (uint8_t)(addr & 0xFFU),
                      (uint8_t)(addr >> 8),
                      2U,
                      (uint8_t)((uint16_t)v & 0xFFU),
                      (uint8_t)((uint16_t)v >> 8)};
    return rig_err(&rig, req, 6U);
}

static int16_t read_tunable(uint16_t addr)
{
    uint8_t req[5] = {X2C_SVC_GET_RAM, (uint8_t)(addr & 0xFFU), (uint8_t)(addr >> 8), 2U, 2U};
    uint8_t reply[LNET_MAX_DATA];
    assert_int_equal(rig_req(&rig, req, 5U, reply), 4);
    assert_int_equal(reply[1], X2C_ERR_OK);
    return (int16_t)(uint16_t)((uint16_t)reply[2] | (uint16_t)((uint16_t)reply[3] << 8));
}

static void test_every_tunable_should_read_but_refuse_every_write(void **state)
{
    (void)state;
    uint16_t t;
    for (t = 0; t < X2C_TUNE_ROWS; t++) {
        const x2c_row_t *row = &x2c_rows[X2C_MOTOR_ROWS + t];
        uint16_t addr = (uint16_t)(x2c_wire(&rig.x, X2C_OBJ_TUNE) + row->offset);
        int16_t now = read_tunable(addr);
        /* its own value, and one inside every tunable's range (run = 1 would start) */
        const int16_t tries[2] = {now, 1};
        unsigned k;
        assert_int_equal(row->flags & X2C_ROW_TUNE, 0);
        for (k = 0; k < 2U; k++) {
            rig_snap_t before;
            rig_snap(&rig, &before);
            assert_int_equal(write_tunable(addr, tries[k]), X2C_ERR_FORMAT);
            assert_true(rig_same(&rig, &before));
            assert_int_equal(read_tunable(addr), now);
        }
    }
    assert_int_equal(rig.mc.state, MC_STATE_STOPPED);
}

static void test_a_tunable_should_still_be_a_scope_channel(void **state)
{
    (void)state;
    uint16_t addr = (uint16_t)(x2c_wire(&rig.x, X2C_OBJ_TUNE) + offsetof(x2c_tune_t, cur_kp));
    /* save parameter 1: sample until full, one 2-byte channel, no trigger */
    uint8_t req[] = {X2C_SVC_SAVE_PARAM,
                     X2C_PARAM_SCOPE,
                     0,
                     X2C_SCOPE_SAMPLE,
                     1,
                     0,
                     0,
                     0,
                     (uint8_t)(addr & 0xFFU),
                     (uint8_t)(addr >> 8),
                     0,
                     0,
                     2,
                     0x82,
                     0,
                     0,
                     0,
                     0,
                     0,
                     0,
                     0,
                     0,
                     0,
                     0,
                     0,
                     1};
    unsigned calls = 0;
    assert_int_equal(rig_err(&rig, req, (uint8_t)sizeof req), X2C_ERR_OK);
    while (x2c_sample(&rig.x, NULL)) {
        calls++;
    }
    assert_int_equal(calls, X2C_SCOPE_BYTES / 2U);
    assert_int_equal(rig.x.scope.buf[0] | (rig.x.scope.buf[1] << 8), (uint16_t)rig.x.tune.cur_kp);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_every_tunable_should_read_but_refuse_every_write, setup),
        cmocka_unit_test_setup(test_a_tunable_should_still_be_a_scope_channel, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
