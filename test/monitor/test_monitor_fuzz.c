/* test_monitor_fuzz.c - a million random and mutated frames into the monitor's parser: no crash, no
 * state change from a bad frame. */
#include "test_support.h"

#include <stdio.h>
#include <string.h>

#include "mon_util.h"
#include "monitor.h"
#include "sim_mailbox.h"

/*
 * Every iteration builds one candidate frame (random bytes, or a valid
 * request mutated: bit flips, byte changes, truncation, extension, a wrong
 * length byte, a splice of two frames), feeds it to the parser, then lets the
 * receive timeout clear whatever partial frame is left. The device's replies
 * are decoded. The property checked each time:
 *   - every byte the device sends decodes as a well-formed frame;
 *   - if no success reply came back, the monitor's configuration and
 *     recorder and the whole mc_t (mailbox, reference, gains) are
 *     bit-for-bit what they were before;
 *   - a success reply only ever answers a frame that the test's own
 *     validator (reference CRC, known command, right length) accepts.
 * Under `make asan` the same run is checked by ASan + UBSan.
 */

#define FUZZ_FRAMES 1000000L

typedef struct {
    uint16_t decim;
    uint8_t nch, ch[MONITOR_MAX_CH];
    uint16_t cap;
    uint8_t mode, trig, run, trig_req, isr_started, isr_done, isr_overflow;
    bool remote;
    uint16_t wr, rd, wi, ri, div;
    uint8_t last_state;
} rec_snap_t;

static void snap(const monitor_t *m, rec_snap_t *s)
{
    memset(s, 0, sizeof *s);
    s->decim = m->decim;
    s->nch = m->nch;
    memcpy(s->ch, m->ch, sizeof s->ch);
    s->cap = m->cap;
    s->mode = m->mode;
    s->trig = m->trig;
    s->run = m->run;
    s->trig_req = m->trig_req;
    s->isr_started = m->isr_started;
    s->isr_done = m->isr_done;
    s->isr_overflow = m->isr_overflow;
    s->remote = m->remote;
    s->wr = m->wr;
    s->rd = m->rd;
    s->wi = m->wi;
    s->ri = m->ri;
    s->div = m->div;
    s->last_state = m->last_state;
}

/* The test's own idea of a well-formed request (independent of monitor.c). */
static bool frame_valid(const uint8_t *f, size_t n)
{
    uint8_t len, cmd;
    uint16_t crc;
    if (n < 5U || f[0] != MONITOR_SOF) {
        return false;
    }
    len = f[1];
    if (len > MONITOR_MAX_PAYLOAD || n < 5U + len) {
        return false;
    }
    crc = mon_ref_crc(&f[1], (size_t)len + 2U);
    if (f[3 + len] != (uint8_t)(crc & 0xFFU) || f[4 + len] != (uint8_t)(crc >> 8)) {
        return false;
    }
    cmd = f[2];
    switch (cmd) {
        case MONITOR_CMD_INFO:
        case MONITOR_CMD_STOP:
        case MONITOR_CMD_TRIGGER:
        case MONITOR_CMD_STATUS:
            return len == 0U;
        case MONITOR_CMD_VAR_INFO:
        case MONITOR_CMD_PARAM_INFO:
        case MONITOR_CMD_MOTOR:
            return len == 1U;
        case MONITOR_CMD_START:
        case MONITOR_CMD_SET_SPEED:
            return len == 2U;
        case MONITOR_CMD_SET_PARAM:
            return len == 3U;
        case MONITOR_CMD_SELECT:
            return len >= 3U && len == 3U + f[5];
        default:
            return false;
    }
}

/* A valid request with plausible arguments (some in range, some not). */
static size_t seed_frame(uint8_t *f, uint32_t *rng)
{
    static const uint8_t cmds[] = {
        MONITOR_CMD_INFO,  MONITOR_CMD_VAR_INFO,  MONITOR_CMD_PARAM_INFO, MONITOR_CMD_SELECT,
        MONITOR_CMD_START, MONITOR_CMD_STOP,      MONITOR_CMD_TRIGGER,    MONITOR_CMD_STATUS,
        MONITOR_CMD_MOTOR, MONITOR_CMD_SET_SPEED, MONITOR_CMD_SET_PARAM};
    uint8_t p[MONITOR_MAX_PAYLOAD];
    uint8_t cmd = cmds[test_rand_u32(rng) % sizeof cmds];
    uint8_t len = 0, i;
    uint32_t r = test_rand_u32(rng);
    switch (cmd) {
        case MONITOR_CMD_VAR_INFO:
        case MONITOR_CMD_PARAM_INFO:
        case MONITOR_CMD_MOTOR:
            p[0] = (uint8_t)(r % 24U);
            len = 1;
            break;
        case MONITOR_CMD_SELECT:
            p[0] = (uint8_t)(r % 50U);
            p[1] = (uint8_t)((r >> 8) % 3U);
            p[2] = (uint8_t)((r >> 16) % 6U);
            for (i = 0; i < p[2]; i++) {
                p[3 + i] = (uint8_t)(test_rand_u32(rng) % 20U);
            }
            len = (uint8_t)(3U + p[2]);
            break;
        case MONITOR_CMD_START:
            p[0] = (uint8_t)(r % 3U);
            p[1] = (uint8_t)((r >> 8) % 4U);
            len = 2;
            break;
        case MONITOR_CMD_SET_SPEED: {
            uint16_t rpm = (uint16_t)(r % 7000U);
            p[0] = (uint8_t)(rpm & 0xFFU);
            p[1] = (uint8_t)(rpm >> 8);
            len = 2;
            break;
        }
        case MONITOR_CMD_SET_PARAM:
            p[0] = (uint8_t)(r % 6U);
            p[1] = (uint8_t)(r >> 8);
            p[2] = (uint8_t)((r >> 16) % 0x90U);
            len = 3;
            break;
        default:
            break;
    }
    return mon_encode(f, cmd, p, len);
}

static size_t mutate(uint8_t *f, size_t n, uint32_t *rng)
{
    uint32_t r = test_rand_u32(rng);
    size_t i;
    switch (r % 7U) {
        case 0: /* flip one bit */
            i = test_rand_u32(rng) % n;
            f[i] ^= (uint8_t)(1U << (test_rand_u32(rng) % 8U));
            break;
        case 1: /* replace one byte */
            i = test_rand_u32(rng) % n;
            f[i] = (uint8_t)test_rand_u32(rng);
            break;
        case 2: /* truncate */
            n = test_rand_u32(rng) % n;
            break;
        case 3: /* extend with garbage */
        {
            size_t k = 1U + test_rand_u32(rng) % 8U;
            for (i = 0; i < k; i++) {
                f[n++] = (uint8_t)test_rand_u32(rng);
            }
            break;
        }
        case 4: /* wrong length byte */
            f[1] = (uint8_t)test_rand_u32(rng);
            break;
        case 5: /* several flips */
        {
            size_t k = 2U + test_rand_u32(rng) % 4U;
            for (i = 0; i < k; i++) {
                f[test_rand_u32(rng) % n] ^= (uint8_t)test_rand_u32(rng);
            }
            break;
        }
        default: /* the command byte changed, the CRC kept */
            f[2] = (uint8_t)test_rand_u32(rng);
            break;
    }
    return n;
}

static void test_the_parser_should_survive_a_million_bad_frames_without_a_state_change(void **state)
{
    static mc_t mc, mc_before;
    static monitor_t mon;
    static uint8_t raw[8192];
    static mon_frame_t fr[64];
    uint8_t f[128];
    rec_snap_t before, after;
    uint32_t rng = 0xC0FFEEU;
    long it, bad = 0, good = 0, changed_ok = 0, random_frames = 0;
    long errors_seen = 0;
    unsigned t;
    (void)state;

    mc_init(&mc);
    sim_mailbox_attach(&mc);
    monitor_init(&mon);
    for (it = 0; it < FUZZ_FRAMES; it++) {
        size_t n, out;
        int k, j;
        bool ok_reply = false, valid;
        uint32_t kind = test_rand_u32(&rng) % 10U;

        if (kind < 2U) { /* raw random bytes, sometimes starting with SOF */
            size_t i;
            n = 1U + test_rand_u32(&rng) % 50U;
            for (i = 0; i < n; i++) {
                f[i] = (uint8_t)test_rand_u32(&rng);
            }
            if ((test_rand_u32(&rng) & 1U) != 0U) {
                f[0] = MONITOR_SOF;
            }
            random_frames++;
        } else {
            n = seed_frame(f, &rng);
            if (kind < 9U) { /* 10 % stay unmutated: valid frames move the state around */
                n = mutate(f, n, &rng);
            }
        }
        valid = frame_valid(f, n);

        snap(&mon, &before);
        memcpy(&mc_before, &mc, sizeof mc);
        mon_feed(&mon, f, n);
        for (t = 0; t < MONITOR_RX_TIMEOUT_MS; t++) {
            monitor_tick_1ms(&mon);
        }
        out = mon_drain(&mon, raw, sizeof raw);
        k = mon_decode_all(raw, out, fr, 64);
        assert_cmp(k, >=, 0); /* the device never sends a malformed frame */
        for (j = 0; j < k; j++) {
            if (fr[j].cmd == MONITOR_CMD_ERROR) {
                errors_seen++;
            } else if ((fr[j].cmd & MONITOR_REPLY) != 0U) {
                ok_reply = true;
            }
        }
        snap(&mon, &after);
        if (!ok_reply) {
            bad++;
            assert_memory_equal(&before, &after, sizeof before);
            assert_memory_equal(&mc_before, &mc, sizeof mc);
        } else {
            /* only a frame the independent validator accepts may be acted on; the
             * extended mutation can leave a valid frame followed by garbage */
            if (!valid) {
                /* noise in front: a valid frame must start at a later SOF */
                size_t i;
                bool found = false;
                for (i = 1; i < n && !found; i++) {
                    found = frame_valid(&f[i], n - i);
                }
                assert_true(found);
            }
            good++;
            if (memcmp(&before, &after, sizeof before) != 0 ||
                memcmp(&mc_before, &mc, sizeof mc) != 0) {
                changed_ok++;
            }
        }
        /* keep the recorder moving now and then, so bad frames also meet a running one */
        if ((it & 63) == 0) {
            for (t = 0; t < 3U; t++) {
                (void)monitor_sample(&mon, &mc);
            }
            monitor_poll(&mon);
            (void)mon_drain(&mon, raw, sizeof raw);
        }
    }
    printf(
        "measured: %ld frames fed (%ld random, %ld mutated or valid): %ld without a success reply, "
        "state unchanged in all; %ld accepted (%ld changed state); %ld error replies\n",
        FUZZ_FRAMES, random_frames, FUZZ_FRAMES - random_frames, bad, good, changed_ok,
        errors_seen);
    assert_cmp(bad, >, FUZZ_FRAMES / 2);
    assert_cmp(changed_ok, >, 1000);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(
            test_the_parser_should_survive_a_million_bad_frames_without_a_state_change),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
