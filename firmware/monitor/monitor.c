/* monitor.c - live data monitor (see monitor.h and docs/monitor.md). */
#include "monitor.h"

#include "q15.h"
#include <stddef.h>

Q15_STATIC_ASSERT((MONITOR_TX_SIZE & (MONITOR_TX_SIZE - 1U)) == 0U && MONITOR_TX_SIZE <= 256U,
                  "MONITOR_TX_SIZE must be a power of two up to 256");
Q15_STATIC_ASSERT(MONITOR_TX_SIZE >= 2U * MONITOR_REPLY_MAX + 1U,
                  "the TX queue must hold a data frame and a reply");
Q15_STATIC_ASSERT(MONITOR_BUF_WORDS >= MONITOR_MAX_CH && MONITOR_BUF_WORDS <= 16384U,
                  "MONITOR_BUF_WORDS out of range");
Q15_STATIC_ASSERT(MONITOR_MAX_PAYLOAD >= 36U && MONITOR_MAX_PAYLOAD <= 250U,
                  "MONITOR_MAX_PAYLOAD out of range");

/* ---- the variables ----------------------------------------------------------- *
 * Full scales are the core's scale macros (engineering units x 1000, rounded);
 * an angle's full scale is 180 degrees (Q15 binary angle: 32768 = pi). */
#define FS_MILLI(x)     ((int32_t)((x)*1000.0 + 0.5))
#define EMF_FULLSCALE_V (SMC_EMF_FS_RATIO * MC_VOLTAGE_FULLSCALE_V) /* smc.h E_FS */

const monitor_var_t monitor_vars[MONITOR_NUM_VARS] = {
    {"state", "", MONITOR_KIND_INT, 1000},
    {"fault", "", MONITOR_KIND_INT, 1000},
    {"speed_est", "rpm", MONITOR_KIND_Q15, FS_MILLI(MC_SPEED_FULLSCALE_RPM)},
    {"speed_ref", "rpm", MONITOR_KIND_Q15, FS_MILLI(MC_SPEED_FULLSCALE_RPM)},
    {"speed_target", "rpm", MONITOR_KIND_Q15, FS_MILLI(MC_SPEED_FULLSCALE_RPM)},
    {"theta_est", "deg", MONITOR_KIND_Q15, 180000},
    {"theta_forced", "deg", MONITOR_KIND_Q15, 180000},
    {"id", "A", MONITOR_KIND_Q15, FS_MILLI(BOARD_I_FULLSCALE_A)},
    {"iq", "A", MONITOR_KIND_Q15, FS_MILLI(BOARD_I_FULLSCALE_A)},
    {"id_ref", "A", MONITOR_KIND_Q15, FS_MILLI(BOARD_I_FULLSCALE_A)},
    {"iq_ref", "A", MONITOR_KIND_Q15, FS_MILLI(BOARD_I_FULLSCALE_A)},
    {"ia", "A", MONITOR_KIND_Q15, FS_MILLI(BOARD_I_FULLSCALE_A)},
    {"ib", "A", MONITOR_KIND_Q15, FS_MILLI(BOARD_I_FULLSCALE_A)},
    {"vd", "V", MONITOR_KIND_Q15, FS_MILLI(MC_VOLTAGE_FULLSCALE_V)},
    {"vq", "V", MONITOR_KIND_Q15, FS_MILLI(MC_VOLTAGE_FULLSCALE_V)},
    /* the estimator's filtered |e| (mc.h mc_status_t.bemf): Q15 of its E_FS = 2 V_FS, and
     * about 0.3..0.4 of the true phase amplitude (a consistency figure, not volts of EMF) */
    {"bemf", "V", MONITOR_KIND_Q15, FS_MILLI(EMF_FULLSCALE_V)},
    {"vbus", "V", MONITOR_KIND_Q15, FS_MILLI(BOARD_VBUS_FULLSCALE_V)},
    {"est_valid", "", MONITOR_KIND_INT, 1000},
};

/* Each case reads what mc_status() copies into the field of the same name
 * (test_monitor pins the two together), without the copy of the whole
 * status: this runs in the ADC interrupt for every recorded channel. */
static inline int16_t var_read(const mc_t *mc, uint8_t idx)
{
    switch (idx) {
        case 0:
            return (int16_t)mc->state;
        case 1:
            return (int16_t)(mc->fault & 0x7FFFU);
        case 2:
            return smc_omega(&mc->smc);
        case 3:
            return mc->speed_ref;
        case 4:
            return mc->speed_target;
        case 5:
            return mc->theta;
        case 6:
            return (int16_t)(uint16_t)(mc->ol_angle >> 16);
        case 7:
            return mc->i_dq.d;
        case 8:
            return mc->i_dq.q;
        case 9:
            return mc->i_ref.d;
        case 10:
            return mc->i_ref.q;
        case 11:
            return mc->ia;
        case 12:
            return mc->ib;
        case 13:
            return mc->v_dq.d;
        case 14:
            return mc->v_dq.q;
        case 15:
            return smc_emf_amplitude(&mc->smc);
        case 16:
            return mc->vbus;
        case 17:
            return smc_valid(&mc->smc) ? 1 : 0;
        default:
            return 0;
    }
}

int16_t monitor_var_read(const mc_t *mc, uint8_t idx)
{
    return var_read(mc, idx);
}

/* ---- the tuning whitelist ------------------------------------------------------ *
 * The PI gains of the current loops (d and q together) and of the speed loop,
 * as the pi_params_t mantissas (Q15, with the exponent kp_shift fixed at build
 * time). They go through mc_set_gain() (mc.h note 3): posted from the main
 * loop, applied by the next mc_step() to d and q together, and the speed
 * gains are the base the low-speed schedule scales, so they survive it.
 * A ki change also sets kc (AN1078 uses Kc = Ki). The accepted
 * range is the build-time gain / 8 .. x 8 (at least 1, at most 32767): wide
 * enough to tune, narrow enough that a typo cannot zero a loop. mc_init()
 * (a reset) restores the build-time gains. */
#define GAIN_MIN(g) ((int16_t)((g) / 8 > 0 ? (g) / 8 : 1))
#define GAIN_MAX(g) ((int16_t)((int32_t)(g)*8 > 32767 ? 32767 : (int32_t)(g)*8))

const monitor_param_t monitor_params[MONITOR_NUM_PARAMS] = {
    {"cur_kp", GAIN_MIN(MC_CUR_KP), GAIN_MAX(MC_CUR_KP)},
    {"cur_ki", GAIN_MIN(MC_CUR_KI), GAIN_MAX(MC_CUR_KI)},
    {"spd_kp", GAIN_MIN(MC_SPD_KP), GAIN_MAX(MC_SPD_KP)},
    {"spd_ki", GAIN_MIN(MC_SPD_KI), GAIN_MAX(MC_SPD_KI)},
};

/* The whitelist's order is mc_gain_t's, so an index is the gain. */
Q15_STATIC_ASSERT(MONITOR_NUM_PARAMS == (unsigned)MC_GAIN_COUNT,
                  "monitor_params[] must list the gains of mc_gain_t, in order");

int16_t monitor_param_get(const mc_t *mc, uint8_t idx)
{
    return (idx < MONITOR_NUM_PARAMS) ? mc_get_gain(mc, (mc_gain_t)idx) : 0;
}

static void param_set(mc_t *mc, uint8_t idx, int16_t v)
{
    /* idx and v are range-checked against monitor_params[] by the caller;
     * mc applies d and q together at its next step (mc.h note 3). */
    (void)mc_set_gain(mc, (mc_gain_t)idx, v);
}

/* ---- CRC ---------------------------------------------------------------------- */

uint16_t monitor_crc16(uint16_t crc, uint8_t byte)
{
    uint8_t i;
    crc = (uint16_t)(crc ^ (uint16_t)((uint16_t)byte << 8));
    for (i = 0; i < 8U; i++) {
        if ((crc & 0x8000U) != 0U) {
            crc = (uint16_t)((uint16_t)(crc << 1) ^ 0x1021U);
        } else {
            crc = (uint16_t)(crc << 1);
        }
    }
    return crc;
}

/* ---- transmit queue ----------------------------------------------------------------- */

static unsigned tx_free(const monitor_t *m)
{
    unsigned used = ((unsigned)m->tx_head - (unsigned)m->tx_tail) & (MONITOR_TX_SIZE - 1U);
    return MONITOR_TX_SIZE - 1U - used;
}

static void tx_put(monitor_t *m, uint8_t b)
{
    m->tx[m->tx_head] = b;
    m->tx_head = (uint8_t)((m->tx_head + 1U) & (MONITOR_TX_SIZE - 1U));
}

/* Queues one frame; the caller has checked the room (len + overhead). */
static void tx_frame(monitor_t *m, uint8_t cmd, const uint8_t *payload, uint8_t len)
{
    uint16_t crc = 0xFFFFU;
    uint8_t i;
    tx_put(m, (uint8_t)MONITOR_SOF);
    tx_put(m, len);
    crc = monitor_crc16(crc, len);
    tx_put(m, cmd);
    crc = monitor_crc16(crc, cmd);
    for (i = 0; i < len; i++) {
        tx_put(m, payload[i]);
        crc = monitor_crc16(crc, payload[i]);
    }
    tx_put(m, (uint8_t)(crc & 0xFFU));
    tx_put(m, (uint8_t)(crc >> 8));
}

bool monitor_tx_byte(monitor_t *m, uint8_t *byte)
{
    if (m->tx_tail == m->tx_head) {
        return false;
    }
    *byte = m->tx[m->tx_tail];
    m->tx_tail = (uint8_t)((m->tx_tail + 1U) & (MONITOR_TX_SIZE - 1U));
    return true;
}

bool monitor_rx_ready(const monitor_t *m)
{
    return tx_free(m) >= MONITOR_REPLY_MAX;
}

/* ---- little-endian helpers ----------------------------------------------------------- */

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

static uint16_t get16(const uint8_t *p)
{
    return (uint16_t)((uint16_t)p[0] | (uint16_t)((uint16_t)p[1] << 8));
}

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

/* An empty ring, no trigger request, no end flag (main loop, run == 0). */
static void rec_clear(monitor_t *m)
{
    m->wr = 0;
    m->rd = 0;
    m->wi = 0;
    m->ri = 0;
    m->trig_req = 0;
    m->isr_done = 0;
    m->isr_overflow = 0;
}

/* ---- init ---------------------------------------------------------------------------- */

void monitor_init(monitor_t *m, mc_t *mc)
{
    uint16_t i;
    m->mc = mc;
    m->rx_state = MONITOR_RX_SOF;
    m->rx_len = 0;
    m->rx_cmd = 0;
    m->rx_pos = 0;
    m->rx_crc = 0xFFFFU;
    m->rx_crc_lo = 0;
    m->rx_idle_ms = 0;
    for (i = 0; i < MONITOR_MAX_PAYLOAD; i++) {
        m->rx_buf[i] = 0;
    }
    m->rx_errors = 0;
    m->rx_dropped = 0;
    for (i = 0; i < MONITOR_TX_SIZE; i++) {
        m->tx[i] = 0;
    }
    m->tx_head = 0;
    m->tx_tail = 0;
    m->decim = 1;
    m->nch = 1;
    for (i = 0; i < MONITOR_MAX_CH; i++) {
        m->ch[i] = 2U; /* speed_est */
    }
    m->cap = MONITOR_BUF_WORDS;
    m->mode = MONITOR_MODE_STREAM;
    m->trig = MONITOR_TRIG_NOW;
    m->remote = false;
    m->ref_seq_mine = 0;
    m->may_start = NULL;
    m->may_start_ctx = NULL;
    m->run = 0;
    rec_clear(m);
    m->isr_started = 0;
    m->div = 0;
    m->last_state = 0;
    for (i = 0; i < MONITOR_BUF_WORDS; i++) {
        m->buf[i] = 0;
    }
}

void monitor_set_start_guard(monitor_t *m, bool (*may_start)(void *ctx), void *ctx)
{
    m->may_start = may_start;
    m->may_start_ctx = ctx;
}

/* ---- the ISR side ------------------------------------------------------------------------ *
 * Cost per period: one test when stopped; when running a counter and a
 * compare, and on the sampled periods (every decim-th) nch reads of the
 * core (monitor_var_read) and stores. No loop depends on anything but nch <= 4. */

bool monitor_sample(monitor_t *m, const mc_t *mc)
{
    uint16_t used;
    uint8_t k;
    int16_t *slot;

    if (m->run == 0U || m->isr_done != 0U || m->isr_overflow != 0U) {
        return false;
    }
    m->div = (uint16_t)(m->div + 1U);
    if (m->div < m->decim) {
        return false;
    }
    m->div = 0;
    if (m->isr_started == 0U) {
        /* armed snapshot: wait for the trigger */
        bool fire = (m->trig == MONITOR_TRIG_NOW) ||
                    (m->trig == MONITOR_TRIG_CMD && m->trig_req != 0U) ||
                    (m->trig == MONITOR_TRIG_STATE && (uint8_t)mc->state != m->last_state);
        m->last_state = (uint8_t)mc->state;
        if (!fire) {
            return false;
        }
        m->isr_started = 1;
    }
    used = (uint16_t)(m->wr - m->rd);
    if (used >= m->cap) {
        /* a stream the host did not keep up with: stop, never wait */
        m->isr_overflow = 1;
        return false;
    }
    slot = &m->buf[(uint16_t)(m->wi * m->nch)];
    for (k = 0; k < m->nch; k++) {
        slot[k] = var_read(mc, m->ch[k]);
    }
    m->wi = (uint16_t)(m->wi + 1U);
    if (m->wi >= m->cap) {
        m->wi = 0;
    }
    m->wr = (uint16_t)(m->wr + 1U);
    if (m->mode == MONITOR_MODE_SNAPSHOT && used + 1U >= m->cap) {
        m->isr_done = 1;
    }
    return true;
}

/* ---- replies ------------------------------------------------------------------------------ */

static void reply(monitor_t *m, const uint8_t *payload, uint8_t len)
{
    tx_frame(m, (uint8_t)(m->rx_cmd | MONITOR_REPLY), payload, len);
}

static void reply_error(monitor_t *m, uint8_t cmd, uint8_t err)
{
    uint8_t p[2];
    p[0] = cmd;
    p[1] = err;
    if (m->rx_errors < 0xFFFFU) {
        m->rx_errors++;
    }
    if (tx_free(m) < 2U + MONITOR_FRAME_OVERHEAD) {
        if (m->rx_dropped < 0xFFFFU) {
            m->rx_dropped++;
        }
        return;
    }
    tx_frame(m, (uint8_t)MONITOR_CMD_ERROR, p, 2U);
}

static uint8_t rec_state(const monitor_t *m)
{
    if (m->run == 0U) {
        return MONITOR_REC_IDLE;
    }
    if (m->isr_started == 0U) {
        return MONITOR_REC_ARMED;
    }
    if (m->isr_done != 0U) {
        return MONITOR_REC_SENDING;
    }
    return MONITOR_REC_RUNNING;
}

/* ---- command handlers: each validates everything before it changes anything ---- */

static uint8_t cmd_info(monitor_t *m, uint8_t *p)
{
    (void)m;
    p[0] = MONITOR_VERSION;
    p[1] = MONITOR_NUM_VARS;
    p[2] = MONITOR_NUM_PARAMS;
    p[3] = MONITOR_MAX_CH;
    put16(&p[4], MONITOR_BUF_WORDS);
    put32(&p[6], (uint32_t)PWM_FREQUENCY_HZ);
    p[10] = MONITOR_MAX_PAYLOAD;
    return 11U;
}

static uint8_t cmd_var_info(monitor_t *m, uint8_t *p, uint8_t *err)
{
    uint8_t idx = m->rx_buf[0];
    uint8_t n;
    const monitor_var_t *v;
    if (idx >= MONITOR_NUM_VARS) {
        *err = MONITOR_ERR_RANGE;
        return 0;
    }
    v = &monitor_vars[idx];
    p[0] = idx;
    p[1] = v->kind;
    put32(&p[2], (uint32_t)v->fs_milli);
    n = put_str(p, 6U, v->name);
    p[n++] = 0;
    n = put_str(p, n, v->unit);
    return n;
}

static uint8_t cmd_param_info(monitor_t *m, uint8_t *p, uint8_t *err)
{
    uint8_t idx = m->rx_buf[0];
    const monitor_param_t *q;
    if (idx >= MONITOR_NUM_PARAMS) {
        *err = MONITOR_ERR_RANGE;
        return 0;
    }
    q = &monitor_params[idx];
    p[0] = idx;
    put16(&p[1], (uint16_t)monitor_param_get(m->mc, idx));
    put16(&p[3], (uint16_t)q->min);
    put16(&p[5], (uint16_t)q->max);
    return put_str(p, 7U, q->name);
}

static void cmd_select(monitor_t *m, uint8_t *err)
{
    uint16_t decim = get16(&m->rx_buf[0]);
    uint8_t n = m->rx_buf[2];
    uint8_t k;
    if (m->rx_len < 3U || m->rx_len != 3U + n) {
        *err = MONITOR_ERR_LENGTH;
        return;
    }
    if (m->run != 0U) {
        *err = MONITOR_ERR_STATE;
        return;
    }
    if (decim < 1U || decim > MONITOR_DECIM_MAX || n < 1U || n > MONITOR_MAX_CH) {
        *err = MONITOR_ERR_RANGE;
        return;
    }
    for (k = 0; k < n; k++) {
        if (m->rx_buf[3U + k] >= MONITOR_NUM_VARS) {
            *err = MONITOR_ERR_RANGE;
            return;
        }
    }
    m->decim = decim;
    m->nch = n;
    for (k = 0; k < n; k++) {
        m->ch[k] = m->rx_buf[3U + k];
    }
    m->cap = (uint16_t)(MONITOR_BUF_WORDS / n);
}

static void cmd_start(monitor_t *m, uint8_t *err)
{
    uint8_t mode = m->rx_buf[0];
    uint8_t trig = m->rx_buf[1];
    mc_status_t st;
    if (m->run != 0U) {
        *err = MONITOR_ERR_STATE;
        return;
    }
    if (mode > MONITOR_MODE_SNAPSHOT || trig > MONITOR_TRIG_STATE ||
        (mode == MONITOR_MODE_STREAM && trig != MONITOR_TRIG_NOW)) {
        *err = MONITOR_ERR_RANGE;
        return;
    }
    mc_status(m->mc, &st);
    m->mode = mode;
    m->trig = trig;
    rec_clear(m);
    m->div = (uint16_t)(m->decim - 1U); /* the first sample is the next period */
    m->last_state = (uint8_t)st.state;
    m->isr_started = (trig == MONITOR_TRIG_NOW) ? 1U : 0U;
    m->run = 1; /* last: from here on the ISR records */
}

static void cmd_stop(monitor_t *m)
{
    m->run = 0;
}

static void cmd_trigger(monitor_t *m, uint8_t *err)
{
    if (m->run == 0U || m->isr_started != 0U || m->trig != MONITOR_TRIG_CMD) {
        *err = MONITOR_ERR_STATE;
        return;
    }
    m->trig_req = 1;
}

static uint8_t cmd_status(monitor_t *m, uint8_t *p)
{
    mc_status_t st;
    uint8_t k;
    mc_status(m->mc, &st);
    p[0] = rec_state(m);
    p[1] = m->mode;
    put16(&p[2], m->decim);
    p[4] = m->nch;
    for (k = 0; k < MONITOR_MAX_CH; k++) {
        p[5U + k] = m->ch[k];
    }
    put16(&p[9], m->wr);
    put16(&p[11], (uint16_t)(m->wr - m->rd));
    p[13] = m->isr_overflow;
    p[14] = (uint8_t)st.state;
    put16(&p[15], st.fault);
    put16(&p[17], (uint16_t)st.speed_est);
    put16(&p[19], (uint16_t)st.speed_ref);
    /* remote while the reference is still the one SET_SPEED set: S3 or the
     * pot may have taken it since (app.c's owner rule) */
    p[21] = (m->remote && st.ref_remote && st.ref_seq == m->ref_seq_mine) ? 1U : 0U;
    put16(&p[22], m->rx_errors);
    put16(&p[24], m->rx_dropped);
    return 26U;
}

static void cmd_motor(monitor_t *m, uint8_t *err)
{
    uint8_t a = m->rx_buf[0];
    if (a == MONITOR_MOTOR_STOP) {
        mc_request(m->mc, MC_REQUEST_STOP);
    } else if (a == MONITOR_MOTOR_START) {
        if (m->may_start != NULL && !m->may_start(m->may_start_ctx)) {
            *err = MONITOR_ERR_STATE; /* the fault pin still holds a hardware fault */
            return;
        }
        mc_request(m->mc, MC_REQUEST_START);
    } else if (a == MONITOR_MOTOR_POT) {
        mc_request(m->mc, MC_REQUEST_REF_POT);
        m->remote = false;
    } else {
        *err = MONITOR_ERR_RANGE;
    }
}

static void cmd_set_speed(monitor_t *m, uint8_t *err)
{
#if defined(TORQUEMODE)
    (void)m;
    *err = MONITOR_ERR_STATE; /* no speed loop to set */
#else
    const int32_t lo = (int32_t)(SPEED_REF_MIN_RPM + 0.5);
    const int32_t hi = (int32_t)(SPEED_REF_MAX_RPM + 0.5);
    int32_t rpm = as_i16(get16(&m->rx_buf[0]));
    if (rpm < lo || rpm > hi) {
        *err = MONITOR_ERR_RANGE;
        return;
    }
    {
        /* rpm * 32768 / fs, rounded: |rpm| < 2^15 so the product fits in 31 bits */
        const int32_t fs = (int32_t)(MC_SPEED_FULLSCALE_RPM + 0.5);
        int32_t q = (rpm * (int32_t)32768 + fs / 2) / fs;
        mc_set_reference(m->mc, (int16_t)(q > 32767 ? 32767 : q));
    }
    m->remote = true;
    m->ref_seq_mine = m->mc->ref_remote_seq;
#endif
}

static void cmd_set_param(monitor_t *m, uint8_t *err)
{
    uint8_t idx = m->rx_buf[0];
    int16_t v = as_i16(get16(&m->rx_buf[1]));
    if (idx >= MONITOR_NUM_PARAMS || v < monitor_params[idx].min || v > monitor_params[idx].max) {
        *err = MONITOR_ERR_RANGE;
        return;
    }
    param_set(m->mc, idx, v);
}

/* Expected payload length of each command, 0xFF = variable (checked inside), 0xFE = unknown. */
static uint8_t expected_len(uint8_t cmd)
{
    switch (cmd) {
        case MONITOR_CMD_INFO:
        case MONITOR_CMD_STOP:
        case MONITOR_CMD_TRIGGER:
        case MONITOR_CMD_STATUS:
            return 0;
        case MONITOR_CMD_VAR_INFO:
        case MONITOR_CMD_PARAM_INFO:
        case MONITOR_CMD_MOTOR:
            return 1;
        case MONITOR_CMD_START:
        case MONITOR_CMD_SET_SPEED:
            return 2;
        case MONITOR_CMD_SET_PARAM:
            return 3;
        case MONITOR_CMD_SELECT:
            return 0xFFU;
        default:
            return 0xFEU;
    }
}

static void dispatch(monitor_t *m)
{
    uint8_t p[MONITOR_MAX_PAYLOAD];
    uint8_t n = 0;
    uint8_t err = 0;
    uint8_t want = expected_len(m->rx_cmd);

    if (tx_free(m) < MONITOR_REPLY_MAX) {
        /* the caller fed a byte without monitor_rx_ready(): nothing happens */
        if (m->rx_dropped < 0xFFFFU) {
            m->rx_dropped++;
        }
        return;
    }
    if (want == 0xFEU) {
        reply_error(m, m->rx_cmd, MONITOR_ERR_UNKNOWN);
        return;
    }
    if (want != 0xFFU && m->rx_len != want) {
        reply_error(m, m->rx_cmd, MONITOR_ERR_LENGTH);
        return;
    }
    switch (m->rx_cmd) {
        case MONITOR_CMD_INFO:
            n = cmd_info(m, p);
            break;
        case MONITOR_CMD_VAR_INFO:
            n = cmd_var_info(m, p, &err);
            break;
        case MONITOR_CMD_PARAM_INFO:
            n = cmd_param_info(m, p, &err);
            break;
        case MONITOR_CMD_SELECT:
            cmd_select(m, &err);
            break;
        case MONITOR_CMD_START:
            cmd_start(m, &err);
            if (err == 0U) {
                put32(p, 0U); /* reserved: first sample's period offset */
                n = 4U;
            }
            break;
        case MONITOR_CMD_STOP:
            cmd_stop(m);
            break;
        case MONITOR_CMD_TRIGGER:
            cmd_trigger(m, &err);
            break;
        case MONITOR_CMD_STATUS:
            n = cmd_status(m, p);
            break;
        case MONITOR_CMD_MOTOR:
            cmd_motor(m, &err);
            break;
        case MONITOR_CMD_SET_SPEED:
            cmd_set_speed(m, &err);
            break;
        default: /* MONITOR_CMD_SET_PARAM, the only one left */
            cmd_set_param(m, &err);
            break;
    }
    if (err != 0U) {
        reply_error(m, m->rx_cmd, err);
    } else {
        reply(m, p, n);
    }
}

/* ---- receiver ------------------------------------------------------------------------------ */

void monitor_rx_byte(monitor_t *m, uint8_t byte)
{
    m->rx_idle_ms = 0;
    switch (m->rx_state) {
        case MONITOR_RX_SOF:
            if (byte == MONITOR_SOF) {
                m->rx_state = MONITOR_RX_LEN;
                m->rx_crc = 0xFFFFU;
            }
            break; /* anything else between frames is noise: skipped */
        case MONITOR_RX_LEN:
            if (byte > MONITOR_MAX_PAYLOAD) {
                m->rx_state = MONITOR_RX_SOF;
                reply_error(m, 0U, MONITOR_ERR_LENGTH);
                break;
            }
            m->rx_len = byte;
            m->rx_crc = monitor_crc16(m->rx_crc, byte);
            m->rx_state = MONITOR_RX_CMD;
            break;
        case MONITOR_RX_CMD:
            m->rx_cmd = byte;
            m->rx_crc = monitor_crc16(m->rx_crc, byte);
            m->rx_pos = 0;
            m->rx_state = (m->rx_len == 0U) ? MONITOR_RX_CRC0 : MONITOR_RX_PAYLOAD;
            break;
        case MONITOR_RX_PAYLOAD:
            m->rx_buf[m->rx_pos++] = byte;
            m->rx_crc = monitor_crc16(m->rx_crc, byte);
            if (m->rx_pos >= m->rx_len) {
                m->rx_state = MONITOR_RX_CRC0;
            }
            break;
        case MONITOR_RX_CRC0:
            m->rx_crc_lo = byte;
            m->rx_state = MONITOR_RX_CRC1;
            break;
        default: /* MONITOR_RX_CRC1 */
            m->rx_state = MONITOR_RX_SOF;
            if (m->rx_crc_lo != (uint8_t)(m->rx_crc & 0xFFU) || byte != (uint8_t)(m->rx_crc >> 8)) {
                reply_error(m, m->rx_cmd, MONITOR_ERR_CRC);
            } else {
                dispatch(m);
            }
            break;
    }
}

void monitor_tick_1ms(monitor_t *m)
{
    if (m->rx_state == MONITOR_RX_SOF) {
        return;
    }
    m->rx_idle_ms++;
    if (m->rx_idle_ms >= MONITOR_RX_TIMEOUT_MS) {
        m->rx_state = MONITOR_RX_SOF;
        m->rx_idle_ms = 0;
        reply_error(m, 0U, MONITOR_ERR_TIMEOUT);
    }
}

/* ---- sending the recorded data ----------------------------------------------------------- */

void monitor_poll(monitor_t *m)
{
    uint8_t p[MONITOR_MAX_PAYLOAD];
    uint16_t avail;
    uint8_t per_frame, nsets, s, k, n, flags;
    bool finished;

    if (m->run == 0U) {
        return;
    }
    if (m->mode == MONITOR_MODE_SNAPSHOT && m->isr_done == 0U) {
        return; /* a snapshot goes out once it is whole */
    }
    /* Read the ISR's flags before wr: a set written after the flag is
     * then still counted (a stream only stops, it never restarts). */
    finished = (m->isr_done != 0U) || (m->isr_overflow != 0U);
    avail = (uint16_t)(m->wr - m->rd);
    per_frame = (uint8_t)((MONITOR_MAX_PAYLOAD - 4U) / (2U * m->nch));
    nsets = (uint8_t)(avail < per_frame ? avail : per_frame);
    if (nsets == 0U && !finished) {
        return;
    }
    /* keep room for a reply behind the data frame */
    if (tx_free(m) < MONITOR_REPLY_MAX * 2U) {
        return;
    }
    flags = 0;
    if (finished && nsets == avail) {
        flags = (uint8_t)(MONITOR_DATA_LAST | (m->isr_overflow != 0U ? MONITOR_DATA_OVERFLOW : 0U));
    }
    p[0] = flags;
    put16(&p[1], m->rd);
    p[3] = nsets;
    n = 4U;
    for (s = 0; s < nsets; s++) {
        const int16_t *slot = &m->buf[(uint16_t)(m->ri * m->nch)];
        for (k = 0; k < m->nch; k++) {
            put16(&p[n], (uint16_t)slot[k]);
            n = (uint8_t)(n + 2U);
        }
        m->ri = (uint16_t)(m->ri + 1U);
        if (m->ri >= m->cap) {
            m->ri = 0;
        }
    }
    m->rd = (uint16_t)(m->rd + nsets);
    tx_frame(m, (uint8_t)MONITOR_CMD_DATA, p, n);
    if (flags != 0U) {
        m->run = 0;
    }
}
