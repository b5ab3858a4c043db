/* test_monitor.c - the monitor's protocol: encoding, CRC, every command, every error path, the
 * recorder. */
#include "test_support.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mon_util.h"
#include "monitor.h"
#include "sim_mailbox.h"

typedef struct {
    mc_t mc;
    monitor_t mon;
    uint8_t raw[4096];
    mon_frame_t fr[64];
} fixture_t;

static fixture_t fx;

static int setup(void **state)
{
    memset(&fx, 0, sizeof fx);
    mc_init(&fx.mc);
    sim_mailbox_attach(&fx.mc);
    monitor_init(&fx.mon);
    *state = &fx;
    return 0;
}

/* Sends a request and returns the one frame it produced. */
static mon_frame_t *transact(uint8_t cmd, const uint8_t *payload, uint8_t len)
{
    size_t n;
    int k;
    mon_send(&fx.mon, cmd, payload, len);
    n = mon_drain(&fx.mon, fx.raw, sizeof fx.raw);
    k = mon_decode_all(fx.raw, n, fx.fr, 64);
    assert_int_equal(k, 1);
    return &fx.fr[0];
}

static void expect_ok(const mon_frame_t *f, uint8_t cmd)
{
    assert_int_equal(f->cmd, cmd | MONITOR_REPLY);
}

static void expect_error(const mon_frame_t *f, uint8_t cmd, uint8_t err)
{
    assert_int_equal(f->cmd, MONITOR_CMD_ERROR);
    assert_int_equal(f->len, 2);
    assert_int_equal(f->payload[0], cmd);
    assert_int_equal(f->payload[1], err);
}

/* A stopped motor, one period with the given bus reading (the monitor's vbus channel follows it).
 */
static void step_with_vbus(int16_t vbus)
{
    mc_adc_frame_t in = {0, 0, vbus, 0};
    mc_pwm_out_t out;
    mc_step(&fx.mc, &in, &out);
    mc_slow_step(&fx.mc);
    (void)monitor_sample(&fx.mon, &fx.mc);
}

/* ---- CRC and framing ------------------------------------------------------------ */

static void test_crc_should_give_the_ccitt_false_check_value(void **state)
{
    const char *s = "123456789";
    uint16_t crc = 0xFFFFU;
    size_t i;
    (void)state;
    for (i = 0; i < 9; i++) {
        crc = monitor_crc16(crc, (uint8_t)s[i]);
    }
    assert_int_equal(crc, 0x29B1);
    assert_int_equal(mon_ref_crc((const uint8_t *)s, 9), 0x29B1);
}

static void test_crc_should_match_the_reference_for_random_messages(void **state)
{
    uint32_t seed = 12345U;
    uint8_t msg[64];
    int t;
    (void)state;
    for (t = 0; t < 2000; t++) {
        size_t n = test_rand_u32(&seed) % sizeof msg;
        uint16_t crc = 0xFFFFU;
        size_t i;
        for (i = 0; i < n; i++) {
            msg[i] = (uint8_t)test_rand_u32(&seed);
            crc = monitor_crc16(crc, msg[i]);
        }
        assert_int_equal(crc, mon_ref_crc(msg, n));
    }
}

static void test_info_should_report_version_counts_sizes_and_pwm_frequency(void **state)
{
    mon_frame_t *f;
    (void)state;
    f = transact(MONITOR_CMD_INFO, NULL, 0);
    expect_ok(f, MONITOR_CMD_INFO);
    assert_int_equal(f->len, 11);
    assert_int_equal(f->payload[0], MONITOR_VERSION);
    assert_int_equal(f->payload[1], MONITOR_NUM_VARS);
    assert_int_equal(f->payload[2], MONITOR_NUM_PARAMS);
    assert_int_equal(f->payload[3], MONITOR_MAX_CH);
    assert_int_equal(mon_u16(&f->payload[4]), MONITOR_BUF_WORDS);
    assert_int_equal(mon_u32(&f->payload[6]), PWM_FREQUENCY_HZ);
    assert_int_equal(f->payload[10], MONITOR_MAX_PAYLOAD);
}

static void test_noise_before_a_frame_and_back_to_back_frames_should_all_be_understood(void **state)
{
    uint8_t buf[64];
    size_t n = 0;
    int k;
    (void)state;
    buf[n++] = 0x00;
    buf[n++] = 0x13;
    buf[n++] = 0xFF;
    n += mon_encode(&buf[n], MONITOR_CMD_INFO, NULL, 0);
    n += mon_encode(&buf[n], MONITOR_CMD_STATUS, NULL, 0);
    mon_feed(&fx.mon, buf, n);
    n = mon_drain(&fx.mon, fx.raw, sizeof fx.raw);
    k = mon_decode_all(fx.raw, n, fx.fr, 64);
    assert_int_equal(k, 2);
    expect_ok(&fx.fr[0], MONITOR_CMD_INFO);
    expect_ok(&fx.fr[1], MONITOR_CMD_STATUS);
}

/* ---- error paths ----------------------------------------------------------------- */

static void test_a_corrupted_crc_should_get_a_crc_error_and_change_nothing(void **state)
{
    uint8_t f[16];
    uint8_t p[2] = {MONITOR_MOTOR_START, 0};
    size_t n;
    mon_frame_t *r;
    uint8_t posted = fx.mc.req_posted[MC_REQUEST_START];
    (void)state;
    n = mon_encode(f, MONITOR_CMD_MOTOR, p, 1);
    f[n - 1] ^= 0x40U;
    mon_feed(&fx.mon, f, n);
    n = mon_drain(&fx.mon, fx.raw, sizeof fx.raw);
    assert_int_equal(mon_decode_all(fx.raw, n, fx.fr, 64), 1);
    r = &fx.fr[0];
    expect_error(r, MONITOR_CMD_MOTOR, MONITOR_ERR_CRC);
    assert_int_equal(fx.mc.req_posted[MC_REQUEST_START], posted);
}

static void test_a_length_above_the_maximum_should_get_a_length_error(void **state)
{
    uint8_t f[3] = {MONITOR_SOF, MONITOR_MAX_PAYLOAD + 1U, 0};
    size_t n;
    (void)state;
    mon_feed(&fx.mon, f, 2);
    n = mon_drain(&fx.mon, fx.raw, sizeof fx.raw);
    assert_int_equal(mon_decode_all(fx.raw, n, fx.fr, 64), 1);
    expect_error(&fx.fr[0], 0, MONITOR_ERR_LENGTH);
    /* and the parser is back at the start: a good frame follows */
    expect_ok(transact(MONITOR_CMD_INFO, NULL, 0), MONITOR_CMD_INFO);
}

static void test_an_unknown_command_should_get_an_unknown_error(void **state)
{
    static const uint8_t unknown[] = {0x00, 0x09, 0x0F, 0x13, 0x40, 0x7F, 0x81, 0xFF};
    size_t i;
    (void)state;
    for (i = 0; i < sizeof unknown; i++) {
        expect_error(transact(unknown[i], NULL, 0), unknown[i], MONITOR_ERR_UNKNOWN);
    }
}

static void test_every_command_with_a_wrong_length_should_get_a_length_error(void **state)
{
    static const struct {
        uint8_t cmd, len;
    } cases[] = {
        {MONITOR_CMD_INFO, 0},      {MONITOR_CMD_VAR_INFO, 1}, {MONITOR_CMD_PARAM_INFO, 1},
        {MONITOR_CMD_START, 2},     {MONITOR_CMD_STOP, 0},     {MONITOR_CMD_TRIGGER, 0},
        {MONITOR_CMD_STATUS, 0},    {MONITOR_CMD_MOTOR, 1},    {MONITOR_CMD_SET_SPEED, 2},
        {MONITOR_CMD_SET_PARAM, 3},
    };
    uint8_t zeros[MONITOR_MAX_PAYLOAD] = {0};
    size_t i;
    (void)state;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        expect_error(transact(cases[i].cmd, zeros, (uint8_t)(cases[i].len + 1U)), cases[i].cmd,
                     MONITOR_ERR_LENGTH);
        if (cases[i].len > 0U) {
            expect_error(transact(cases[i].cmd, zeros, (uint8_t)(cases[i].len - 1U)), cases[i].cmd,
                         MONITOR_ERR_LENGTH);
        }
    }
    /* SELECT: the length must be 3 + n */
    {
        uint8_t p[8] = {1, 0, 2, 2, 3, 0, 0, 0};
        expect_error(transact(MONITOR_CMD_SELECT, p, 4), MONITOR_CMD_SELECT, MONITOR_ERR_LENGTH);
        expect_error(transact(MONITOR_CMD_SELECT, p, 6), MONITOR_CMD_SELECT, MONITOR_ERR_LENGTH);
        expect_error(transact(MONITOR_CMD_SELECT, p, 2), MONITOR_CMD_SELECT, MONITOR_ERR_LENGTH);
        assert_int_equal(fx.mon.nch, 1);
    }
}

static void test_a_truncated_frame_should_time_out_after_the_gap_and_change_nothing(void **state)
{
    uint8_t f[16];
    uint8_t p[1] = {MONITOR_MOTOR_START};
    size_t n = mon_encode(f, MONITOR_CMD_MOTOR, p, 1);
    uint8_t posted = fx.mc.req_posted[MC_REQUEST_START];
    unsigned t;
    (void)state;
    mon_feed(&fx.mon, f, n - 1U); /* last CRC byte missing */
    for (t = 0; t + 1U < MONITOR_RX_TIMEOUT_MS; t++) {
        monitor_tick_1ms(&fx.mon);
    }
    assert_int_equal(mon_drain(&fx.mon, fx.raw, sizeof fx.raw), 0);
    monitor_tick_1ms(&fx.mon);
    n = mon_drain(&fx.mon, fx.raw, sizeof fx.raw);
    assert_int_equal(mon_decode_all(fx.raw, n, fx.fr, 64), 1);
    expect_error(&fx.fr[0], 0, MONITOR_ERR_TIMEOUT);
    assert_int_equal(fx.mc.req_posted[MC_REQUEST_START], posted);
    /* ticks while idle do nothing */
    for (t = 0; t < 100U; t++) {
        monitor_tick_1ms(&fx.mon);
    }
    assert_int_equal(mon_drain(&fx.mon, fx.raw, sizeof fx.raw), 0);
    expect_ok(transact(MONITOR_CMD_INFO, NULL, 0), MONITOR_CMD_INFO);
}

static void
test_a_frame_completed_without_tx_room_should_be_dropped_and_change_nothing(void **state)
{
    uint8_t p[1] = {MONITOR_MOTOR_START};
    uint8_t posted = fx.mc.req_posted[MC_REQUEST_START];
    int i;
    (void)state;
    /* fill the TX queue with replies nobody reads */
    for (i = 0; monitor_rx_ready(&fx.mon); i++) {
        mon_send(&fx.mon, MONITOR_CMD_INFO, NULL, 0);
    }
    assert_cmp(i, >, 0);
    mon_send(&fx.mon, MONITOR_CMD_MOTOR, p, 1);
    assert_int_equal(fx.mc.req_posted[MC_REQUEST_START], posted);
    assert_int_equal(fx.mon.rx_dropped, 1);
}

/* ---- variables and parameters ---------------------------------------------------- */

static void test_var_info_should_name_every_variable_with_its_unit_and_full_scale(void **state)
{
    uint8_t i;
    (void)state;
    for (i = 0; i < MONITOR_NUM_VARS; i++) {
        mon_frame_t *f = transact(MONITOR_CMD_VAR_INFO, &i, 1);
        const char *name = (const char *)&f->payload[6];
        size_t nl = strlen(monitor_vars[i].name);
        expect_ok(f, MONITOR_CMD_VAR_INFO);
        assert_int_equal(f->payload[0], i);
        assert_int_equal(f->payload[1], monitor_vars[i].kind);
        assert_int_equal((int32_t)mon_u32(&f->payload[2]), monitor_vars[i].fs_milli);
        assert_int_equal(f->len, 6U + nl + 1U + strlen(monitor_vars[i].unit));
        assert_memory_equal(name, monitor_vars[i].name, nl);
        assert_int_equal(f->payload[6 + nl], 0);
        assert_memory_equal(&f->payload[7 + nl], monitor_vars[i].unit,
                            strlen(monitor_vars[i].unit));
    }
    assert_int_equal(monitor_vars[2].fs_milli, (int32_t)(MC_SPEED_FULLSCALE_RPM * 1000.0 + 0.5));
    assert_int_equal(monitor_vars[7].fs_milli, (int32_t)(BOARD_I_FULLSCALE_A * 1000.0 + 0.5));
    /* bemf is in the estimator's back-EMF scale E_FS = 2 V_FS (smc.h), twice vd's */
    assert_string_equal(monitor_vars[15].name, "bemf");
    assert_string_equal(monitor_vars[13].name, "vd");
    assert_cmp(labs((long)monitor_vars[15].fs_milli - 2L * (long)monitor_vars[13].fs_milli), <=,
               1L);
    i = MONITOR_NUM_VARS;
    expect_error(transact(MONITOR_CMD_VAR_INFO, &i, 1), MONITOR_CMD_VAR_INFO, MONITOR_ERR_RANGE);
}

static void test_var_read_should_return_what_mc_status_reports(void **state)
{
    static mc_t core; /* static: its size is the firmware's concern, not the test stack's */
    mc_status_t st;
    uint8_t i;
    (void)state;
    mc_init(&core);
    /* A distinct value in every field the variables come from. */
    core.state = MC_STATE_CLOSED_LOOP;
    core.fault = 0x8007U; /* the top bit is not part of the variable */
    core.smc.omega = 1001;
    core.speed_ref = 1002;
    core.speed_target = 1003;
    core.theta = -1004;
    core.ol_angle = (int32_t)((uint32_t)1005U << 16) + 0x1234;
    core.i_dq.d = -1006;
    core.i_dq.q = 1007;
    core.i_ref.d = 1008;
    core.i_ref.q = 1009;
    core.ia = -1010;
    core.ib = 1011;
    core.v_dq.d = 1012;
    core.v_dq.q = -1013;
    core.smc.emf_mag = 1014;
    core.vbus = 1015;
    core.smc.valid = true;
    mc_status(&core, &st);
    {
        /* The variables in their index order, as mc_status() gives them. */
        const int16_t want[MONITOR_NUM_VARS] = {(int16_t)st.state,
                                                (int16_t)(st.fault & 0x7FFFU),
                                                st.speed_est,
                                                st.speed_ref,
                                                st.speed_target,
                                                st.theta_est,
                                                st.theta_forced,
                                                st.id,
                                                st.iq,
                                                st.id_ref,
                                                st.iq_ref,
                                                st.ia,
                                                st.ib,
                                                st.vd,
                                                st.vq,
                                                st.bemf,
                                                st.vbus,
                                                st.estimator_valid ? 1 : 0};
        const int16_t literal[MONITOR_NUM_VARS] = {MC_STATE_CLOSED_LOOP,
                                                   7,
                                                   1001,
                                                   1002,
                                                   1003,
                                                   -1004,
                                                   1005,
                                                   -1006,
                                                   1007,
                                                   1008,
                                                   1009,
                                                   -1010,
                                                   1011,
                                                   1012,
                                                   -1013,
                                                   1014,
                                                   1015,
                                                   1};
        for (i = 0; i < MONITOR_NUM_VARS; i++) {
            assert_int_equal(monitor_var_read(&core, i), want[i]);
            assert_int_equal(want[i], literal[i]);
        }
        assert_int_equal(monitor_var_read(&core, MONITOR_NUM_VARS), 0);
    }
}

static void
test_param_info_and_set_param_should_accept_the_range_ends_and_refuse_beyond(void **state)
{
    uint8_t i;
    (void)state;
    for (i = 0; i < MONITOR_NUM_PARAMS; i++) {
        const monitor_param_t *q = &monitor_params[i];
        int16_t before = monitor_param_get(i);
        uint8_t p[3];
        mon_frame_t *f = transact(MONITOR_CMD_PARAM_INFO, &i, 1);
        expect_ok(f, MONITOR_CMD_PARAM_INFO);
        assert_int_equal(mon_i16(&f->payload[1]), before);
        assert_int_equal(mon_i16(&f->payload[3]), q->min);
        assert_int_equal(mon_i16(&f->payload[5]), q->max);
        assert_memory_equal(&f->payload[7], q->name, strlen(q->name));
        assert_cmp(q->min, <=, before);
        assert_cmp(before, <=, q->max);
        assert_cmp(q->min, >=, 1);

        p[0] = i;
        p[1] = (uint8_t)((uint16_t)(q->min - 1) & 0xFFU);
        p[2] = (uint8_t)((uint16_t)(q->min - 1) >> 8);
        expect_error(transact(MONITOR_CMD_SET_PARAM, p, 3), MONITOR_CMD_SET_PARAM,
                     MONITOR_ERR_RANGE);
        assert_int_equal(monitor_param_get(i), before);
        if (q->max < 32767) {
            p[1] = (uint8_t)((uint16_t)(q->max + 1) & 0xFFU);
            p[2] = (uint8_t)((uint16_t)(q->max + 1) >> 8);
            expect_error(transact(MONITOR_CMD_SET_PARAM, p, 3), MONITOR_CMD_SET_PARAM,
                         MONITOR_ERR_RANGE);
            assert_int_equal(monitor_param_get(i), before);
        }
        p[1] = 0x00;
        p[2] = 0x80; /* -32768 */
        expect_error(transact(MONITOR_CMD_SET_PARAM, p, 3), MONITOR_CMD_SET_PARAM,
                     MONITOR_ERR_RANGE);
        p[1] = (uint8_t)((uint16_t)q->max & 0xFFU);
        p[2] = (uint8_t)((uint16_t)q->max >> 8);
        expect_ok(transact(MONITOR_CMD_SET_PARAM, p, 3), MONITOR_CMD_SET_PARAM);
        assert_int_equal(monitor_param_get(i), q->max);
        p[1] = (uint8_t)((uint16_t)q->min & 0xFFU);
        p[2] = (uint8_t)((uint16_t)q->min >> 8);
        expect_ok(transact(MONITOR_CMD_SET_PARAM, p, 3), MONITOR_CMD_SET_PARAM);
        assert_int_equal(monitor_param_get(i), q->min);
    }
    /* applied by the core's next step, not before; then to both d and q,
     * ki also to kc */
    assert_int_not_equal(fx.mc.pi_q.p.kp, monitor_params[0].min);
    step_with_vbus(0);
    assert_int_equal(fx.mc.pi_d.p.kp, monitor_params[0].min);
    assert_int_equal(fx.mc.pi_q.p.kp, monitor_params[0].min);
    assert_int_equal(fx.mc.pi_q.p.ki, monitor_params[1].min);
    assert_int_equal(fx.mc.pi_q.p.kc, monitor_params[1].min);
    /* the speed gains go to the speed loop with the slow step's inputs */
    assert_int_equal(fx.mc.spd_ki_base, monitor_params[3].min);
    i = MONITOR_NUM_PARAMS;
    expect_error(transact(MONITOR_CMD_PARAM_INFO, &i, 1), MONITOR_CMD_PARAM_INFO,
                 MONITOR_ERR_RANGE);
    {
        uint8_t p[3] = {MONITOR_NUM_PARAMS, 1, 0};
        expect_error(transact(MONITOR_CMD_SET_PARAM, p, 3), MONITOR_CMD_SET_PARAM,
                     MONITOR_ERR_RANGE);
    }
}

/* ---- motor commands ---------------------------------------------------------------- */

static void test_motor_command_should_post_start_stop_and_pot_requests(void **state)
{
    static const struct {
        uint8_t action;
        mc_request_t req;
    } cases[] = {{MONITOR_MOTOR_START, MC_REQUEST_START},
                 {MONITOR_MOTOR_STOP, MC_REQUEST_STOP},
                 {MONITOR_MOTOR_POT, MC_REQUEST_REF_POT}};
    size_t i;
    uint8_t bad = 3;
    uint8_t before[MC_REQUEST_COUNT];
    (void)state;
    for (i = 0; i < 3; i++) {
        uint8_t was = fx.mc.req_posted[cases[i].req];
        uint8_t was_seq = fx.mc.ref_remote_seq;
        expect_ok(transact(MONITOR_CMD_MOTOR, &cases[i].action, 1), MONITOR_CMD_MOTOR);
        if (cases[i].req == MC_REQUEST_REF_POT) {
            /* a choice of reference: on the reference's own sequence (mc.c) */
            assert_true(fx.mc.ref_to_pot);
            assert_int_equal(fx.mc.ref_remote_seq, (uint8_t)(was_seq + 1U));
        } else {
            assert_int_equal(fx.mc.req_posted[cases[i].req], (uint8_t)(was + 1U));
        }
    }
    memcpy(before, (const void *)fx.mc.req_posted, sizeof before);
    expect_error(transact(MONITOR_CMD_MOTOR, &bad, 1), MONITOR_CMD_MOTOR, MONITOR_ERR_RANGE);
    bad = 0xFF;
    expect_error(transact(MONITOR_CMD_MOTOR, &bad, 1), MONITOR_CMD_MOTOR, MONITOR_ERR_RANGE);
    assert_memory_equal(before, (const void *)fx.mc.req_posted, sizeof before);
}

static void
test_set_speed_should_post_the_q15_reference_and_refuse_outside_the_pot_range(void **state)
{
    uint8_t p[2];
    uint8_t seq = fx.mc.ref_remote_seq;
    const int16_t lo = (int16_t)(SPEED_REF_MIN_RPM + 0.5), hi = (int16_t)(SPEED_REF_MAX_RPM + 0.5);
    const int16_t bad[] = {(int16_t)(lo - 1), (int16_t)(hi + 1), -2000, -32768, 32767, 0};
    size_t i;
    (void)state;
    p[0] = (uint8_t)(2000 & 0xFF);
    p[1] = (uint8_t)(2000 >> 8);
    expect_ok(transact(MONITOR_CMD_SET_SPEED, p, 2), MONITOR_CMD_SET_SPEED);
    assert_int_equal(fx.mc.ref_remote_seq, (uint8_t)(seq + 1U));
    /* 2000 rpm in Q15 of the full scale, rounded: the reference's resolution */
    assert_int_equal(fx.mc.ref_remote, (int16_t)(2000.0 * 32768.0 / MC_SPEED_FULLSCALE_RPM + 0.5));
    assert_true(fx.mon.remote);
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        p[0] = (uint8_t)((uint16_t)bad[i] & 0xFFU);
        p[1] = (uint8_t)((uint16_t)bad[i] >> 8);
        expect_error(transact(MONITOR_CMD_SET_SPEED, p, 2), MONITOR_CMD_SET_SPEED,
                     MONITOR_ERR_RANGE);
        assert_int_equal(fx.mc.ref_remote_seq, (uint8_t)(seq + 1U));
    }
    p[0] = (uint8_t)((uint16_t)lo & 0xFFU);
    p[1] = (uint8_t)((uint16_t)lo >> 8);
    expect_ok(transact(MONITOR_CMD_SET_SPEED, p, 2), MONITOR_CMD_SET_SPEED);
    p[0] = (uint8_t)((uint16_t)hi & 0xFFU);
    p[1] = (uint8_t)((uint16_t)hi >> 8);
    expect_ok(transact(MONITOR_CMD_SET_SPEED, p, 2), MONITOR_CMD_SET_SPEED);
    assert_int_equal(fx.mc.ref_remote_seq, (uint8_t)(seq + 3U));
    /* back to the pot: remote off */
    p[0] = MONITOR_MOTOR_POT;
    expect_ok(transact(MONITOR_CMD_MOTOR, p, 1), MONITOR_CMD_MOTOR);
    assert_false(fx.mon.remote);
}

static bool guard_answer;
static int guard_calls;
static bool guard(void *ctx)
{
    assert_ptr_equal(ctx, &guard_answer);
    guard_calls++;
    return guard_answer;
}

static void test_start_should_be_refused_while_the_fault_pin_holds(void **state)
{
    uint8_t p[1] = {MONITOR_MOTOR_START};
    uint8_t posted = fx.mc.req_posted[MC_REQUEST_START];
    (void)state;
    monitor_set_start_guard(&fx.mon, guard, &guard_answer);
    guard_answer = false; /* the application's rule: the pin still asserted */
    guard_calls = 0;
    expect_error(transact(MONITOR_CMD_MOTOR, p, 1), MONITOR_CMD_MOTOR, MONITOR_ERR_STATE);
    assert_int_equal(fx.mc.req_posted[MC_REQUEST_START], posted);
    assert_int_equal(guard_calls, 1);
    guard_answer = true; /* cleared */
    expect_ok(transact(MONITOR_CMD_MOTOR, p, 1), MONITOR_CMD_MOTOR);
    assert_int_equal(fx.mc.req_posted[MC_REQUEST_START], (uint8_t)(posted + 1U));
    /* STOP and POT do not ask */
    guard_answer = false;
    p[0] = MONITOR_MOTOR_STOP;
    expect_ok(transact(MONITOR_CMD_MOTOR, p, 1), MONITOR_CMD_MOTOR);
    assert_int_equal(guard_calls, 2);
}

static void test_status_should_show_remote_only_while_the_reference_is_the_monitors(void **state)
{
    uint8_t p[2] = {(uint8_t)(2000 & 0xFF), (uint8_t)(2000 >> 8)};
    mon_frame_t *f;
    (void)state;
    expect_ok(transact(MONITOR_CMD_SET_SPEED, p, 2), MONITOR_CMD_SET_SPEED);
    step_with_vbus(20000); /* the core takes the new reference */
    f = transact(MONITOR_CMD_STATUS, NULL, 0);
    assert_int_equal(f->payload[21], 1);
    /* the board (S3) sets its own: the monitor no longer owns it */
    mc_set_reference(&fx.mc, 1000);
    step_with_vbus(20000);
    f = transact(MONITOR_CMD_STATUS, NULL, 0);
    assert_int_equal(f->payload[21], 0);
    /* and back: the monitor sets again, then the pot takes over */
    expect_ok(transact(MONITOR_CMD_SET_SPEED, p, 2), MONITOR_CMD_SET_SPEED);
    step_with_vbus(20000);
    assert_int_equal(transact(MONITOR_CMD_STATUS, NULL, 0)->payload[21], 1);
    mc_request(&fx.mc, MC_REQUEST_REF_POT);
    step_with_vbus(20000);
    assert_int_equal(transact(MONITOR_CMD_STATUS, NULL, 0)->payload[21], 0);
}

/* ---- recorder ------------------------------------------------------------------------ */

static void select_channels(uint16_t decim, const uint8_t *ch, uint8_t n)
{
    uint8_t p[8];
    p[0] = (uint8_t)(decim & 0xFFU);
    p[1] = (uint8_t)(decim >> 8);
    p[2] = n;
    memcpy(&p[3], ch, n);
    expect_ok(transact(MONITOR_CMD_SELECT, p, (uint8_t)(3U + n)), MONITOR_CMD_SELECT);
}

static void start(uint8_t mode, uint8_t trig)
{
    uint8_t p[2] = {mode, trig};
    expect_ok(transact(MONITOR_CMD_START, p, 2), MONITOR_CMD_START);
}

static void test_select_should_refuse_bad_decimation_channel_counts_and_indices(void **state)
{
    uint8_t p[8];
    (void)state;
    /* decim 0 */
    p[0] = 0;
    p[1] = 0;
    p[2] = 1;
    p[3] = 2;
    expect_error(transact(MONITOR_CMD_SELECT, p, 4), MONITOR_CMD_SELECT, MONITOR_ERR_RANGE);
    /* decim above the maximum */
    p[0] = (uint8_t)((MONITOR_DECIM_MAX + 1U) & 0xFFU);
    p[1] = (uint8_t)((MONITOR_DECIM_MAX + 1U) >> 8);
    expect_error(transact(MONITOR_CMD_SELECT, p, 4), MONITOR_CMD_SELECT, MONITOR_ERR_RANGE);
    /* no channel, too many */
    p[0] = 10;
    p[1] = 0;
    p[2] = 0;
    expect_error(transact(MONITOR_CMD_SELECT, p, 3), MONITOR_CMD_SELECT, MONITOR_ERR_RANGE);
    p[2] = 5;
    memset(&p[3], 2, 5);
    expect_error(transact(MONITOR_CMD_SELECT, p, 8), MONITOR_CMD_SELECT, MONITOR_ERR_RANGE);
    /* a channel that does not exist */
    p[2] = 2;
    p[3] = 2;
    p[4] = MONITOR_NUM_VARS;
    expect_error(transact(MONITOR_CMD_SELECT, p, 5), MONITOR_CMD_SELECT, MONITOR_ERR_RANGE);
    assert_int_equal(fx.mon.nch, 1);
    assert_int_equal(fx.mon.decim, 1);
    /* the ends are accepted */
    p[0] = (uint8_t)(MONITOR_DECIM_MAX & 0xFFU);
    p[1] = (uint8_t)(MONITOR_DECIM_MAX >> 8);
    p[2] = 4;
    p[3] = 0;
    p[4] = MONITOR_NUM_VARS - 1U;
    p[5] = 3;
    p[6] = 4;
    expect_ok(transact(MONITOR_CMD_SELECT, p, 7), MONITOR_CMD_SELECT);
    assert_int_equal(fx.mon.nch, 4);
    assert_int_equal(fx.mon.decim, MONITOR_DECIM_MAX);
    assert_int_equal(fx.mon.cap, MONITOR_BUF_WORDS / 4U);
    /* not while recording */
    start(MONITOR_MODE_STREAM, MONITOR_TRIG_NOW);
    expect_error(transact(MONITOR_CMD_SELECT, p, 7), MONITOR_CMD_SELECT, MONITOR_ERR_STATE);
    {
        uint8_t s[2] = {MONITOR_MODE_STREAM, MONITOR_TRIG_NOW};
        expect_error(transact(MONITOR_CMD_START, s, 2), MONITOR_CMD_START, MONITOR_ERR_STATE);
    }
}

static void test_start_should_refuse_unknown_modes_and_triggered_streams(void **state)
{
    static const uint8_t bad[][2] = {{2, 0}, {0xFF, 0}, {1, 3}, {0, 1}, {0, 2}};
    size_t i;
    (void)state;
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        expect_error(transact(MONITOR_CMD_START, bad[i], 2), MONITOR_CMD_START, MONITOR_ERR_RANGE);
        assert_int_equal(fx.mon.run, 0);
    }
}

/* Collects the DATA frames in the TX queue into vals (nch per set); checks indices run on. */
static int collect(int16_t *vals, int max_sets, uint16_t *next_index, uint8_t *last_flags)
{
    size_t n = mon_drain(&fx.mon, fx.raw, sizeof fx.raw);
    int k = mon_decode_all(fx.raw, n, fx.fr, 64);
    int got = 0, i, j;
    assert_cmp(k, >=, 0);
    for (i = 0; i < k; i++) {
        const mon_frame_t *f = &fx.fr[i];
        uint8_t nsets;
        assert_int_equal(f->cmd, MONITOR_CMD_DATA);
        nsets = f->payload[3];
        assert_int_equal(mon_u16(&f->payload[1]), *next_index);
        assert_int_equal(f->len, 4U + 2U * fx.mon.nch * nsets);
        for (j = 0; j < nsets * fx.mon.nch; j++) {
            assert_cmp(got, <, max_sets * fx.mon.nch);
            vals[got++] = mon_i16(&f->payload[4 + 2 * j]);
        }
        *next_index = (uint16_t)(*next_index + nsets);
        *last_flags = f->payload[0];
    }
    return got;
}

static void test_a_stream_should_deliver_every_decimated_sample_in_order(void **state)
{
    const uint8_t ch[2] = {16, 0}; /* vbus, state */
    static int16_t vals[4000];
    int got = 0;
    uint16_t next = 0;
    uint8_t flags = 0;
    int t, i;
    (void)state;
    select_channels(3, ch, 2);
    start(MONITOR_MODE_STREAM, MONITOR_TRIG_NOW);
    for (t = 1; t <= 3000; t++) {
        step_with_vbus((int16_t)(10000 + t));
        monitor_poll(&fx.mon);
        got += collect(&vals[got], 2000 - got / 2, &next, &flags);
    }
    /* 3000 periods / 3 = 1000 sets, the first at period 1 */
    assert_int_equal(next, 1000);
    assert_int_equal(got, 2000);
    for (i = 0; i < 1000; i++) {
        assert_int_equal(vals[2 * i], 10000 + 1 + 3 * i);
        assert_int_equal(vals[2 * i + 1], MC_STATE_STOPPED);
    }
    assert_int_equal(flags, 0);
    expect_ok(transact(MONITOR_CMD_STOP, NULL, 0), MONITOR_CMD_STOP);
    step_with_vbus(1);
    monitor_poll(&fx.mon);
    assert_int_equal(mon_drain(&fx.mon, fx.raw, sizeof fx.raw), 0);
    printf("measured: stream of 2 channels, decimation 3: 1000 of 1000 sets delivered in order\n");
}

static void test_a_stream_the_host_does_not_read_should_stop_with_the_overflow_flag(void **state)
{
    const uint8_t ch[1] = {16};
    static int16_t vals[2 * MONITOR_BUF_WORDS];
    uint16_t next = 0;
    uint8_t flags = 0;
    int got, t;
    mon_frame_t *f;
    (void)state;
    select_channels(1, ch, 1);
    start(MONITOR_MODE_STREAM, MONITOR_TRIG_NOW);
    for (t = 0; t < 3 * (int)MONITOR_BUF_WORDS; t++) {
        step_with_vbus((int16_t)t);
    }
    assert_int_equal(fx.mon.isr_overflow, 1);
    assert_int_equal(fx.mon.wr, MONITOR_BUF_WORDS);
    f = transact(MONITOR_CMD_STATUS, NULL, 0);
    assert_int_equal(f->payload[0], MONITOR_REC_RUNNING);
    assert_int_equal(f->payload[13], 1);
    got = 0;
    for (t = 0; t < 200 && fx.mon.run != 0U; t++) {
        monitor_poll(&fx.mon);
        got += collect(&vals[got], (int)(2 * MONITOR_BUF_WORDS) - got, &next, &flags);
    }
    assert_int_equal(got, MONITOR_BUF_WORDS);
    assert_int_equal(flags, MONITOR_DATA_LAST | MONITOR_DATA_OVERFLOW);
    for (t = 0; t < (int)MONITOR_BUF_WORDS; t++) {
        assert_int_equal(vals[t], t);
    }
    assert_int_equal(fx.mon.run, 0);
}

static void run_snapshot_until_sent(int16_t *vals, int max_words, int *got, uint8_t *flags)
{
    uint16_t next = 0;
    int t;
    for (t = 0; t < 400 && fx.mon.run != 0U; t++) {
        monitor_poll(&fx.mon);
        *got += collect(&vals[*got], max_words - *got, &next, flags);
    }
}

static void test_a_snapshot_should_fill_the_buffer_at_full_rate_then_send_it_whole(void **state)
{
    const uint8_t ch[4] = {16, 0, 7, 8};
    static int16_t vals[MONITOR_BUF_WORDS];
    uint8_t flags = 0;
    int got = 0, t;
    const int cap = (int)(MONITOR_BUF_WORDS / 4U);
    (void)state;
    select_channels(1, ch, 4);
    start(MONITOR_MODE_SNAPSHOT, MONITOR_TRIG_NOW);
    for (t = 0; t < cap + 50; t++) {
        step_with_vbus((int16_t)(100 + t));
        monitor_poll(&fx.mon);
        if (t < cap - 1) {
            /* nothing goes out before the buffer is full */
            assert_int_equal(mon_drain(&fx.mon, fx.raw, sizeof fx.raw), 0);
        }
    }
    assert_int_equal(fx.mon.wr, cap);
    run_snapshot_until_sent(vals, (int)MONITOR_BUF_WORDS, &got, &flags);
    assert_int_equal(got, cap * 4);
    assert_int_equal(flags, MONITOR_DATA_LAST);
    for (t = 0; t < cap; t++) {
        assert_int_equal(vals[4 * t], 100 + t);
    }
}

static void test_a_snapshot_armed_for_the_command_trigger_should_wait_for_it(void **state)
{
    const uint8_t ch[2] = {16, 16};
    static int16_t vals[MONITOR_BUF_WORDS];
    uint8_t flags = 0;
    int got = 0, t;
    mon_frame_t *f;
    (void)state;
    expect_error(transact(MONITOR_CMD_TRIGGER, NULL, 0), MONITOR_CMD_TRIGGER, MONITOR_ERR_STATE);
    select_channels(2, ch, 2);
    start(MONITOR_MODE_SNAPSHOT, MONITOR_TRIG_CMD);
    for (t = 0; t < 1000; t++) {
        step_with_vbus((int16_t)t);
    }
    assert_int_equal(fx.mon.wr, 0);
    f = transact(MONITOR_CMD_STATUS, NULL, 0);
    assert_int_equal(f->payload[0], MONITOR_REC_ARMED);
    expect_ok(transact(MONITOR_CMD_TRIGGER, NULL, 0), MONITOR_CMD_TRIGGER);
    for (t = 1000; t < 1000 + (int)MONITOR_BUF_WORDS; t++) {
        step_with_vbus((int16_t)t);
    }
    expect_error(transact(MONITOR_CMD_TRIGGER, NULL, 0), MONITOR_CMD_TRIGGER, MONITOR_ERR_STATE);
    f = transact(MONITOR_CMD_STATUS, NULL, 0);
    assert_int_equal(f->payload[0], MONITOR_REC_SENDING);
    run_snapshot_until_sent(vals, (int)MONITOR_BUF_WORDS, &got, &flags);
    assert_int_equal(got, MONITOR_BUF_WORDS);
    /* the first sample is the first decimated period after the trigger */
    assert_cmp(vals[0], >=, 1000);
    assert_cmp(vals[0], <=, 1001);
    for (t = 1; t < (int)MONITOR_BUF_WORDS / 2; t++) {
        assert_int_equal(vals[2 * t], vals[0] + 2 * t);
    }
}

static void
test_a_snapshot_armed_for_a_state_change_should_start_when_the_motor_starts(void **state)
{
    const uint8_t ch[1] = {0};
    static int16_t vals[MONITOR_BUF_WORDS];
    uint8_t flags = 0, act = MONITOR_MOTOR_START;
    int got = 0, t;
    (void)state;
    select_channels(1, ch, 1);
    start(MONITOR_MODE_SNAPSHOT, MONITOR_TRIG_STATE);
    for (t = 0; t < 100; t++) {
        step_with_vbus(Q15(0.46)); /* 24 V on the 52.8 V scale: no bus fault */
    }
    assert_int_equal(fx.mon.wr, 0);
    expect_ok(transact(MONITOR_CMD_MOTOR, &act, 1), MONITOR_CMD_MOTOR);
    for (t = 0; t < 2 * (int)MONITOR_BUF_WORDS; t++) {
        step_with_vbus(Q15(0.46));
    }
    run_snapshot_until_sent(vals, (int)MONITOR_BUF_WORDS, &got, &flags);
    assert_int_equal(got, MONITOR_BUF_WORDS);
    assert_int_not_equal(vals[0], MC_STATE_STOPPED);
}

static void test_status_should_report_the_recorder_and_the_motor(void **state)
{
    const uint8_t ch[3] = {3, 2, 8};
    mon_frame_t *f;
    (void)state;
    select_channels(7, ch, 3);
    f = transact(MONITOR_CMD_STATUS, NULL, 0);
    expect_ok(f, MONITOR_CMD_STATUS);
    assert_int_equal(f->len, 26);
    assert_int_equal(f->payload[0], MONITOR_REC_IDLE);
    assert_int_equal(mon_u16(&f->payload[2]), 7);
    assert_int_equal(f->payload[4], 3);
    assert_memory_equal(&f->payload[5], ch, 3);
    assert_int_equal(f->payload[14], MC_STATE_STOPPED);
    assert_int_equal(mon_u16(&f->payload[15]), MC_FAULT_NONE);
    assert_int_equal(f->payload[21], 0);
    {
        mc_status_t st;
        mc_status(&fx.mc, &st);
        assert_int_equal(mon_i16(&f->payload[19]), st.speed_ref);
    }
    start(MONITOR_MODE_STREAM, MONITOR_TRIG_NOW);
    f = transact(MONITOR_CMD_STATUS, NULL, 0);
    assert_int_equal(f->payload[0], MONITOR_REC_RUNNING);
    expect_ok(transact(MONITOR_CMD_STOP, NULL, 0), MONITOR_CMD_STOP);
    f = transact(MONITOR_CMD_STATUS, NULL, 0);
    assert_int_equal(f->payload[0], MONITOR_REC_IDLE);
    assert_int_equal(mon_u16(&f->payload[22]), 0); /* no error replies so far */
}

static void test_the_recorder_should_cost_nothing_while_stopped(void **state)
{
    monitor_t before;
    int t;
    (void)state;
    memcpy(&before, &fx.mon, sizeof before);
    for (t = 0; t < 1000; t++) {
        assert_false(monitor_sample(&fx.mon, &fx.mc));
    }
    assert_memory_equal(&before, &fx.mon, sizeof before);
    printf("measured: sizeof(monitor_t) = %u bytes on this host (buffer %u words)\n",
           (unsigned)sizeof(monitor_t), (unsigned)MONITOR_BUF_WORDS);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_crc_should_give_the_ccitt_false_check_value, setup),
        cmocka_unit_test_setup(test_crc_should_match_the_reference_for_random_messages, setup),
        cmocka_unit_test_setup(test_info_should_report_version_counts_sizes_and_pwm_frequency,
                               setup),
        cmocka_unit_test_setup(
            test_noise_before_a_frame_and_back_to_back_frames_should_all_be_understood, setup),
        cmocka_unit_test_setup(test_a_corrupted_crc_should_get_a_crc_error_and_change_nothing,
                               setup),
        cmocka_unit_test_setup(test_a_length_above_the_maximum_should_get_a_length_error, setup),
        cmocka_unit_test_setup(test_an_unknown_command_should_get_an_unknown_error, setup),
        cmocka_unit_test_setup(test_every_command_with_a_wrong_length_should_get_a_length_error,
                               setup),
        cmocka_unit_test_setup(
            test_a_truncated_frame_should_time_out_after_the_gap_and_change_nothing, setup),
        cmocka_unit_test_setup(
            test_a_frame_completed_without_tx_room_should_be_dropped_and_change_nothing, setup),
        cmocka_unit_test_setup(
            test_var_info_should_name_every_variable_with_its_unit_and_full_scale, setup),
        cmocka_unit_test_setup(test_var_read_should_return_what_mc_status_reports, setup),
        cmocka_unit_test_setup(
            test_param_info_and_set_param_should_accept_the_range_ends_and_refuse_beyond, setup),
        cmocka_unit_test_setup(test_motor_command_should_post_start_stop_and_pot_requests, setup),
        cmocka_unit_test_setup(
            test_set_speed_should_post_the_q15_reference_and_refuse_outside_the_pot_range, setup),
        cmocka_unit_test_setup(test_select_should_refuse_bad_decimation_channel_counts_and_indices,
                               setup),
        cmocka_unit_test_setup(test_start_should_refuse_unknown_modes_and_triggered_streams, setup),
        cmocka_unit_test_setup(test_a_stream_should_deliver_every_decimated_sample_in_order, setup),
        cmocka_unit_test_setup(
            test_a_stream_the_host_does_not_read_should_stop_with_the_overflow_flag, setup),
        cmocka_unit_test_setup(
            test_a_snapshot_should_fill_the_buffer_at_full_rate_then_send_it_whole, setup),
        cmocka_unit_test_setup(test_a_snapshot_armed_for_the_command_trigger_should_wait_for_it,
                               setup),
        cmocka_unit_test_setup(
            test_a_snapshot_armed_for_a_state_change_should_start_when_the_motor_starts, setup),
        cmocka_unit_test_setup(test_status_should_report_the_recorder_and_the_motor, setup),
        cmocka_unit_test_setup(test_start_should_be_refused_while_the_fault_pin_holds, setup),
        cmocka_unit_test_setup(
            test_status_should_show_remote_only_while_the_reference_is_the_monitors, setup),
        cmocka_unit_test_setup(test_the_recorder_should_cost_nothing_while_stopped, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
