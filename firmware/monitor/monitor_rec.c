/* monitor_rec.c - the monitor's recorder (see monitor_rec.h and monitor.h "Shared data"). */
#include "monitor_rec.h"

#include "q15.h"

Q15_STATIC_ASSERT(MONITOR_BUF_WORDS >= MONITOR_MAX_CH && MONITOR_BUF_WORDS <= 16384U,
                  "MONITOR_BUF_WORDS out of range");

/* DATA payload: flags, index of the first set:2, nsets, then the sets. */
#define DATA_HEADER 4U

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

void monitor_rec_init(monitor_t *m)
{
    uint16_t i;
    m->decim = 1;
    m->nch = 1;
    for (i = 0; i < MONITOR_MAX_CH; i++) {
        m->ch[i] = (uint8_t)MONITOR_VAR_speed_est;
    }
    m->cap = MONITOR_BUF_WORDS;
    m->mode = MONITOR_MODE_STREAM;
    m->trig = MONITOR_TRIG_NOW;
    m->run = 0;
    rec_clear(m);
    m->isr_started = 0;
    m->div = 0;
    m->last_state = 0;
    for (i = 0; i < MONITOR_BUF_WORDS; i++) {
        m->buf[i] = 0;
    }
}

/* ---- the ISR side ------------------------------------------------------------------------ *
 * Cost per period: one test when stopped; when running a counter and a
 * compare, and on the sampled periods (every decim-th) nch reads of the
 * core (monitor_var_read, inline) and stores. No loop depends on anything but nch <= 4. */

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
        slot[k] = monitor_var_read(mc, m->ch[k]);
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

/* ---- the protocol's calls (main loop) ------------------------------------------------------ */

uint8_t monitor_rec_select(monitor_t *m, uint16_t decim, uint8_t n, const uint8_t *ch)
{
    uint8_t k;
    if (m->run != 0U) {
        return MONITOR_ERR_STATE;
    }
    if (decim < 1U || decim > MONITOR_DECIM_MAX || n < 1U || n > MONITOR_MAX_CH) {
        return MONITOR_ERR_RANGE;
    }
    for (k = 0; k < n; k++) {
        if (ch[k] >= MONITOR_NUM_VARS) {
            return MONITOR_ERR_RANGE;
        }
    }
    m->decim = decim;
    m->nch = n;
    for (k = 0; k < n; k++) {
        m->ch[k] = ch[k];
    }
    m->cap = (uint16_t)(MONITOR_BUF_WORDS / n);
    return MONITOR_ERR_NONE;
}

uint8_t monitor_rec_start(monitor_t *m, uint8_t mode, uint8_t trig, uint8_t motor_state)
{
    if (m->run != 0U) {
        return MONITOR_ERR_STATE;
    }
    if (mode > MONITOR_MODE_SNAPSHOT || trig > MONITOR_TRIG_STATE ||
        (mode == MONITOR_MODE_STREAM && trig != MONITOR_TRIG_NOW)) {
        return MONITOR_ERR_RANGE;
    }
    m->mode = mode;
    m->trig = trig;
    rec_clear(m);
    m->div = (uint16_t)(m->decim - 1U); /* the first sample is the next period */
    m->last_state = motor_state;
    m->isr_started = (trig == MONITOR_TRIG_NOW) ? 1U : 0U;
    m->run = 1; /* last: from here on the ISR records */
    return MONITOR_ERR_NONE;
}

void monitor_rec_stop(monitor_t *m)
{
    m->run = 0;
}

uint8_t monitor_rec_trigger(monitor_t *m)
{
    if (m->run == 0U || m->isr_started != 0U || m->trig != MONITOR_TRIG_CMD) {
        return MONITOR_ERR_STATE;
    }
    m->trig_req = 1;
    return MONITOR_ERR_NONE;
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

uint8_t monitor_rec_status(const monitor_t *m, uint8_t *p)
{
    uint8_t k;
    p[0] = rec_state(m);
    p[1] = m->mode;
    monitor_put16(&p[2], m->decim);
    p[4] = m->nch;
    for (k = 0; k < MONITOR_MAX_CH; k++) {
        p[5U + k] = m->ch[k];
    }
    monitor_put16(&p[9], m->wr);
    monitor_put16(&p[11], (uint16_t)(m->wr - m->rd));
    p[13] = m->isr_overflow;
    return 14U;
}

/* ---- sending the recorded data (main loop) ------------------------------------------------ */

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
    per_frame = (uint8_t)((MONITOR_MAX_PAYLOAD - DATA_HEADER) / (2U * m->nch));
    nsets = (uint8_t)(avail < per_frame ? avail : per_frame);
    if (nsets == 0U && !finished) {
        return;
    }
    /* keep room for a reply behind the data frame */
    if (monitor_link_tx_free(&m->link) < MONITOR_REPLY_MAX * 2U) {
        return;
    }
    flags = 0;
    if (finished && nsets == avail) {
        flags = (uint8_t)(MONITOR_DATA_LAST | (m->isr_overflow != 0U ? MONITOR_DATA_OVERFLOW : 0U));
    }
    p[0] = flags;
    monitor_put16(&p[1], m->rd);
    p[3] = nsets;
    n = DATA_HEADER;
    for (s = 0; s < nsets; s++) {
        const int16_t *slot = &m->buf[(uint16_t)(m->ri * m->nch)];
        for (k = 0; k < m->nch; k++) {
            monitor_put16(&p[n], (uint16_t)slot[k]);
            n = (uint8_t)(n + 2U);
        }
        m->ri = (uint16_t)(m->ri + 1U);
        if (m->ri >= m->cap) {
            m->ri = 0;
        }
    }
    m->rd = (uint16_t)(m->rd + nsets);
    monitor_link_send(&m->link, (uint8_t)MONITOR_CMD_DATA, p, n);
    if (flags != 0U) {
        m->run = 0;
    }
}
