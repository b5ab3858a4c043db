/* monitor.c - the monitor's protocol: one table row per command (monitor.h, docs/monitor.md). */
#include "monitor.h"

#include <stddef.h>

#include "monitor_rec.h"
#include "motor.h"

/* ---- the motor ---------------------------------------------------------------------------- *
 * Every call the monitor makes to the motor from the main loop goes
 * through its mailbox (motor.h: on the dsPIC firmware/motor.c, with the
 * interrupt masked; on the PC tools/sim/sim_mailbox.c), as the board's main
 * loop does; the recorder reads the motor in the interrupt through
 * monitor_var_read() (monitor_vars.h), on the object the observer hands it. */

int16_t monitor_param_get(uint8_t idx)
{
    return (idx < MONITOR_NUM_PARAMS) ? motor_get_gain((mc_gain_t)monitor_params[idx].gain) : 0;
}

/* The board's start rule, handed in by the application (monitor_set_start_guard). */
static bool core_may_start(const monitor_t *m)
{
    return m->may_start == NULL || m->may_start(m->may_start_ctx);
}

/* ---- payload helpers ---------------------------------------------------------------------- */

/* uint16 -> int16 without an implementation-defined conversion */
static int16_t as_i16(uint16_t u)
{
    return (u >= 0x8000U) ? (int16_t)(-(int16_t)(0xFFFFU - u) - 1) : (int16_t)u;
}

static uint8_t put_str(uint8_t *p, uint8_t at, const char *s)
{
    while (*s != '\0' && at < MONITOR_MAX_PAYLOAD - 1U) {
        p[at++] = (uint8_t)*s++;
    }
    return at;
}

static void count(uint16_t *counter)
{
    if (*counter < 0xFFFFU) {
        (*counter)++;
    }
}

static void reply_error(monitor_t *m, uint8_t cmd, uint8_t err)
{
    uint8_t p[2];
    p[0] = cmd;
    p[1] = err;
    count(&m->rx_errors);
    if (monitor_link_tx_free(&m->link) < 2U + MONITOR_FRAME_OVERHEAD) {
        count(&m->rx_dropped);
        return;
    }
    monitor_link_send(&m->link, (uint8_t)MONITOR_CMD_ERROR, p, 2U);
}

/* ---- command handlers ------------------------------------------------------------------------ *
 * Each gets the request's payload (req, len bytes; the table has checked a
 * fixed length), writes its reply payload into reply and its length into
 * *n, and returns MONITOR_ERR_NONE or an error code. Each validates
 * everything before it changes anything: an error reply means nothing changed. */

typedef uint8_t cmd_fn_t(monitor_t *m, const uint8_t *req, uint8_t len, uint8_t *reply, uint8_t *n);

static uint8_t cmd_info(monitor_t *m, const uint8_t *req, uint8_t len, uint8_t *reply, uint8_t *n)
{
    (void)m;
    (void)req;
    (void)len;
    reply[0] = MONITOR_VERSION;
    reply[1] = MONITOR_NUM_VARS;
    reply[2] = MONITOR_NUM_PARAMS;
    reply[3] = MONITOR_MAX_CH;
    monitor_put16(&reply[4], MONITOR_BUF_WORDS);
    monitor_put32(&reply[6], (uint32_t)PWM_FREQUENCY_HZ);
    reply[10] = MONITOR_MAX_PAYLOAD;
    *n = 11U;
    return MONITOR_ERR_NONE;
}

static uint8_t cmd_var_info(monitor_t *m, const uint8_t *req, uint8_t len, uint8_t *reply,
                            uint8_t *n)
{
    uint8_t idx = req[0];
    uint8_t at;
    const monitor_var_t *v;
    (void)m;
    (void)len;
    if (idx >= MONITOR_NUM_VARS) {
        return MONITOR_ERR_RANGE;
    }
    v = &monitor_vars[idx];
    reply[0] = idx;
    reply[1] = v->kind;
    monitor_put32(&reply[2], (uint32_t)v->fs_milli);
    at = put_str(reply, 6U, v->name);
    reply[at++] = 0;
    *n = put_str(reply, at, v->unit);
    return MONITOR_ERR_NONE;
}

static uint8_t cmd_param_info(monitor_t *m, const uint8_t *req, uint8_t len, uint8_t *reply,
                              uint8_t *n)
{
    (void)m; /* the gains are the motor's (motor.h) */
    uint8_t idx = req[0];
    const monitor_param_t *q;
    (void)len;
    if (idx >= MONITOR_NUM_PARAMS) {
        return MONITOR_ERR_RANGE;
    }
    q = &monitor_params[idx];
    reply[0] = idx;
    monitor_put16(&reply[1], (uint16_t)monitor_param_get(idx));
    monitor_put16(&reply[3], (uint16_t)q->min);
    monitor_put16(&reply[5], (uint16_t)q->max);
    *n = put_str(reply, 7U, q->name);
    return MONITOR_ERR_NONE;
}

static uint8_t cmd_select(monitor_t *m, const uint8_t *req, uint8_t len, uint8_t *reply, uint8_t *n)
{
    (void)reply;
    (void)n;
    if (len < 3U || len != 3U + req[2]) {
        return MONITOR_ERR_LENGTH;
    }
    return monitor_rec_select(m, monitor_get16(&req[0]), req[2], &req[3]);
}

static uint8_t cmd_start(monitor_t *m, const uint8_t *req, uint8_t len, uint8_t *reply, uint8_t *n)
{
    mc_status_t st;
    uint8_t err;
    (void)len;
    motor_status(&st);
    err = monitor_rec_start(m, req[0], req[1], (uint8_t)st.state);
    if (err == MONITOR_ERR_NONE) {
        monitor_put32(reply, 0U); /* reserved: first sample's period offset */
        *n = 4U;
    }
    return err;
}

static uint8_t cmd_stop(monitor_t *m, const uint8_t *req, uint8_t len, uint8_t *reply, uint8_t *n)
{
    (void)req;
    (void)len;
    (void)reply;
    (void)n;
    monitor_rec_stop(m);
    return MONITOR_ERR_NONE;
}

static uint8_t cmd_trigger(monitor_t *m, const uint8_t *req, uint8_t len, uint8_t *reply,
                           uint8_t *n)
{
    (void)req;
    (void)len;
    (void)reply;
    (void)n;
    return monitor_rec_trigger(m);
}

static uint8_t cmd_status(monitor_t *m, const uint8_t *req, uint8_t len, uint8_t *reply, uint8_t *n)
{
    mc_status_t st;
    uint8_t at;
    (void)req;
    (void)len;
    at = monitor_rec_status(m, reply);
    motor_status(&st);
    reply[at] = (uint8_t)st.state;
    monitor_put16(&reply[at + 1U], st.fault);
    monitor_put16(&reply[at + 3U], (uint16_t)st.speed_est);
    monitor_put16(&reply[at + 5U], (uint16_t)st.speed_ref);
    /* remote while the reference is still the one SET_SPEED set: S3 or the
     * pot may have taken it since (the owner rule, mc_reference_held) */
    reply[at + 7U] = (m->remote && mc_reference_held(&st, m->ref_seq_mine)) ? 1U : 0U;
    monitor_put16(&reply[at + 8U], m->rx_errors);
    monitor_put16(&reply[at + 10U], m->rx_dropped);
    *n = (uint8_t)(at + 12U);
    return MONITOR_ERR_NONE;
}

static uint8_t cmd_motor(monitor_t *m, const uint8_t *req, uint8_t len, uint8_t *reply, uint8_t *n)
{
    (void)len;
    (void)reply;
    (void)n;
    switch (req[0]) {
        case MONITOR_MOTOR_STOP:
            motor_request(MC_REQUEST_STOP);
            return MONITOR_ERR_NONE;
        case MONITOR_MOTOR_START:
            if (!core_may_start(m)) {
                return MONITOR_ERR_STATE; /* the fault pin still holds a hardware fault */
            }
            motor_request(MC_REQUEST_START);
            return MONITOR_ERR_NONE;
        case MONITOR_MOTOR_POT:
            motor_request(MC_REQUEST_REF_POT);
            m->remote = false;
            return MONITOR_ERR_NONE;
        default:
            return MONITOR_ERR_RANGE;
    }
}

static uint8_t cmd_set_speed(monitor_t *m, const uint8_t *req, uint8_t len, uint8_t *reply,
                             uint8_t *n)
{
    (void)len;
    (void)reply;
    (void)n;
#if defined(TORQUEMODE)
    (void)m;
    (void)req;
    return MONITOR_ERR_STATE; /* no speed loop to set */
#else
    {
        const int32_t lo = (int32_t)(SPEED_REF_MIN_RPM + 0.5);
        const int32_t hi = (int32_t)(SPEED_REF_MAX_RPM + 0.5);
        const int32_t fs = (int32_t)(MC_SPEED_FULLSCALE_RPM + 0.5);
        int32_t rpm = as_i16(monitor_get16(&req[0]));
        int32_t q;
        if (rpm < lo || rpm > hi) {
            return MONITOR_ERR_RANGE;
        }
        /* rpm * 32768 / fs, rounded: |rpm| < 2^15 so the product fits in 31 bits */
        q = (rpm * (int32_t)32768 + fs / 2) / fs;
        m->ref_seq_mine = motor_set_reference((int16_t)(q > 32767 ? 32767 : q));
        m->remote = true;
        return MONITOR_ERR_NONE;
    }
#endif
}

static uint8_t cmd_set_param(monitor_t *m, const uint8_t *req, uint8_t len, uint8_t *reply,
                             uint8_t *n)
{
    (void)m; /* the gains are the motor's (motor.h) */
    uint8_t idx = req[0];
    int16_t v = as_i16(monitor_get16(&req[1]));
    (void)len;
    (void)reply;
    (void)n;
    if (idx >= MONITOR_NUM_PARAMS || v < monitor_params[idx].min || v > monitor_params[idx].max) {
        return MONITOR_ERR_RANGE;
    }
    (void)motor_set_gain((mc_gain_t)monitor_params[idx].gain, v);
    return MONITOR_ERR_NONE;
}

/* ---- the commands: one row each (const: program memory on the dsPIC) ---------------------- */

#define LEN_ANY 0xFFU /* the request's length varies: its handler checks it */

typedef struct {
    uint8_t code; /* MONITOR_CMD_* */
    uint8_t len;  /* request payload bytes, or LEN_ANY */
    cmd_fn_t *run;
} cmd_row_t;

static const cmd_row_t cmd_table[] = {
    {MONITOR_CMD_INFO, 0U, cmd_info},
    {MONITOR_CMD_VAR_INFO, 1U, cmd_var_info},
    {MONITOR_CMD_PARAM_INFO, 1U, cmd_param_info},
    {MONITOR_CMD_SELECT, LEN_ANY, cmd_select},
    {MONITOR_CMD_START, 2U, cmd_start},
    {MONITOR_CMD_STOP, 0U, cmd_stop},
    {MONITOR_CMD_TRIGGER, 0U, cmd_trigger},
    {MONITOR_CMD_STATUS, 0U, cmd_status},
    {MONITOR_CMD_MOTOR, 1U, cmd_motor},
    {MONITOR_CMD_SET_SPEED, 2U, cmd_set_speed},
    {MONITOR_CMD_SET_PARAM, 3U, cmd_set_param},
};

#define CMD_COUNT (sizeof cmd_table / sizeof cmd_table[0])

static const cmd_row_t *cmd_find(uint8_t code)
{
    uint8_t i;
    for (i = 0; i < CMD_COUNT; i++) {
        if (cmd_table[i].code == code) {
            return &cmd_table[i];
        }
    }
    return NULL;
}

/* A whole frame with a good CRC is in m->link. */
static void dispatch(monitor_t *m)
{
    uint8_t reply[MONITOR_MAX_PAYLOAD];
    uint8_t n = 0;
    uint8_t err;
    uint8_t cmd = m->link.rx_cmd;
    uint8_t len = m->link.rx_len;
    const cmd_row_t *c = cmd_find(cmd);

    if (monitor_link_tx_free(&m->link) < MONITOR_REPLY_MAX) {
        /* the caller fed a byte without monitor_rx_ready(): nothing happens */
        count(&m->rx_dropped);
        return;
    }
    if (c == NULL) {
        reply_error(m, cmd, MONITOR_ERR_UNKNOWN);
        return;
    }
    if (c->len != LEN_ANY && len != c->len) {
        reply_error(m, cmd, MONITOR_ERR_LENGTH);
        return;
    }
    err = c->run(m, m->link.rx_buf, len, reply, &n);
    if (err != MONITOR_ERR_NONE) {
        reply_error(m, cmd, err);
    } else {
        monitor_link_send(&m->link, (uint8_t)(cmd | MONITOR_REPLY), reply, n);
    }
}

/* ---- the main loop's entry points ----------------------------------------------------------- */

void monitor_init(monitor_t *m)
{
    monitor_link_init(&m->link);
    m->rx_errors = 0;
    m->rx_dropped = 0;
    m->may_start = NULL;
    m->may_start_ctx = NULL;
    m->remote = false;
    m->ref_seq_mine = 0;
    monitor_rec_init(m);
}

void monitor_set_start_guard(monitor_t *m, bool (*may_start)(void *ctx), void *ctx)
{
    m->may_start = may_start;
    m->may_start_ctx = ctx;
}

void monitor_rx_byte(monitor_t *m, uint8_t byte)
{
    switch (monitor_link_rx_byte(&m->link, byte)) {
        case MONITOR_LINK_FRAME:
            dispatch(m);
            break;
        case MONITOR_LINK_BAD_CRC:
            reply_error(m, m->link.rx_cmd, MONITOR_ERR_CRC);
            break;
        case MONITOR_LINK_TOO_LONG:
            reply_error(m, 0U, MONITOR_ERR_LENGTH); /* no command read yet: CMD 0 */
            break;
        default: /* MONITOR_LINK_NONE */
            break;
    }
}

void monitor_tick_1ms(monitor_t *m)
{
    if (monitor_link_tick_1ms(&m->link)) {
        reply_error(m, 0U, MONITOR_ERR_TIMEOUT);
    }
}

bool monitor_rx_ready(const monitor_t *m)
{
    return monitor_link_tx_free(&m->link) >= MONITOR_REPLY_MAX;
}

bool monitor_tx_byte(monitor_t *m, uint8_t *byte)
{
    return monitor_link_tx_byte(&m->link, byte);
}
