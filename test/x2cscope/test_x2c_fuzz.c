/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_x2c_fuzz.c - a million random requests: one reply each, no crash, no change from a refusal.
 */
#include "x2c_util.h"

#include <stdio.h>
#include <stdlib.h>

#ifndef X2C_FUZZ_FRAMES
#define X2C_FUZZ_FRAMES 1000000UL
#endif

static rig_t rig;

static uint32_t rng = 0x2545F491UL;
static uint32_t rnd(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 17;
    rng ^= rng << 5;
    return rng;
}

/* An address near something real, or anywhere. */
static uint16_t some_address(void)
{
    switch (rnd() % 4U) {
        case 0: {
            const x2c_row_t *r = &x2c_rows[rnd() % X2C_ROWS];
            return (uint16_t)(x2c_wire(&rig.x, (x2c_obj_t)r->obj) + r->offset + (rnd() % 5U) - 2U);
        }
        case 1:
            return (uint16_t)(x2c_wire(&rig.x, X2C_OBJ_MOTOR) + rnd() % sizeof(mc_t));
        case 2:
            return (uint16_t)(x2c_wire(&rig.x, X2C_OBJ_TUNE) + rnd() % 16U);
        default:
            return (uint16_t)rnd();
    }
}

static uint8_t some_width(void)
{
    static const uint8_t w[] = {1, 2, 4, 1, 2, 4, 0, 3, 8, 255};
    return w[rnd() % sizeof w];
}

/* One random request into d; its length. */
static uint8_t some_request(uint8_t *d)
{
    static const uint8_t svc[] = {0x00, 0x01, 0x09, 0x09, 0x09, 0x0A, 0x0A, 0x0A,
                                  0x11, 0x12, 0x12, 0x12, 0x19, 0x02, 0xFF};
    uint8_t n, i;
    uint16_t a;
    d[0] = svc[rnd() % sizeof svc];
    switch (d[0]) {
        case 0x09:
            a = some_address();
            d[1] = (uint8_t)a;
            d[2] = (uint8_t)(a >> 8);
            d[3] = (uint8_t)((rnd() % 8U == 0U) ? rnd() : 1U + rnd() % 6U);
            d[4] = some_width();
            /* a wrong length now and then, never 0 (an empty frame is no frame, lnet.h) */
            n = (rnd() % 16U == 0U) ? (uint8_t)(1U + rnd() % 7U) : 5U;
            break;
        case 0x0A:
            a = some_address();
            d[1] = (uint8_t)a;
            d[2] = (uint8_t)(a >> 8);
            d[3] = some_width();
            n = (uint8_t)(4U + rnd() % 6U);
            for (i = 4; i < n; i++) {
                d[i] = (uint8_t)((rnd() % 2U) ? rnd() : rnd() % 4U); /* often small values */
            }
            break;
        case 0x12: {
            uint8_t nch = (uint8_t)((rnd() % 8U == 0U) ? rnd() % 12U : 1U + rnd() % 8U);
            d[1] = (uint8_t)((rnd() % 16U == 0U) ? rnd() : 1U);
            d[2] = 0;
            d[3] = (uint8_t)((rnd() % 8U == 0U) ? rnd() % 10U : 1U + rnd() % 2U);
            d[4] = nch;
            d[5] = (uint8_t)(rnd() % 4U);
            d[6] = 0;
            n = 7;
            for (i = 0; i < nch && n < 200U; i++) {
                a = some_address();
                d[n++] = (uint8_t)((rnd() % 16U == 0U) ? 1U : 0U);
                d[n++] = (uint8_t)a;
                d[n++] = (uint8_t)(a >> 8);
                d[n++] = (uint8_t)((rnd() % 16U == 0U) ? rnd() : 0U);
                d[n++] = 0;
                d[n++] = some_width();
            }
            {
                static const uint8_t dt[] = {0x82, 0xA2, 0x81, 0xA1, 0xA4, 0x84, 0xC4, 0xC2, 0x00};
                uint8_t dtype = dt[rnd() % sizeof dt];
                uint8_t lsize = (uint8_t)(dtype & 0x0FU);
                int32_t delay = (int32_t)(rnd() % 64U) * 2 - 40;
                a = some_address();
                d[n++] = dtype;
                d[n++] = 0;
                d[n++] = (uint8_t)a;
                d[n++] = (uint8_t)(a >> 8);
                d[n++] = 0;
                d[n++] = 0;
                for (i = 0; i < lsize; i++) {
                    d[n++] = (uint8_t)rnd();
                }
                d[n++] = (uint8_t)delay;
                d[n++] = (uint8_t)((uint32_t)delay >> 8);
                d[n++] = (uint8_t)((uint32_t)delay >> 16);
                d[n++] = (uint8_t)((uint32_t)delay >> 24);
                d[n++] = (uint8_t)(rnd() % 3U);
                if (rnd() % 2U) {
                    d[n++] = (uint8_t)(rnd() % 3U);
                }
            }
            if (rnd() % 8U == 0U) {
                /* cut anywhere but to nothing: after a SYN a SIZE of 0 reads as the fill of
                 * an escaped 0x55 (lnet.h), so an empty frame is no frame */
                n = (uint8_t)(1U + rnd() % (unsigned)n);
            }
            break;
        }
        default:
            n = (uint8_t)(1U + ((rnd() % 4U == 0U) ? rnd() % 8U : 0U));
            for (i = 1; i < n; i++) {
                d[i] = (uint8_t)rnd();
            }
            if (d[0] == 0x11 && n == 1U) {
                d[1] = 1;
                d[2] = 0;
                n = 3;
            }
            break;
    }
    return n;
}

static void
test_a_million_random_frames_should_each_get_one_reply_and_refusals_change_nothing(void **state)
{
    (void)state;
    static const char *const names[] = {"ok", "refused"};
    unsigned long frames, by[2] = {0, 0}, codes[256] = {0}, samples = 0;
    rig_init(&rig);
    for (frames = 0; frames < X2C_FUZZ_FRAMES; frames++) {
        uint8_t req[LNET_MAX_DATA], reply[LNET_MAX_DATA], frame[2U * 258U];
        uint8_t n = some_request(req);
        size_t k = rig_frame(req, n, frame);
        bool corrupt = (rnd() % 32U) == 0U;
        rig_snap_t before;
        int len;
        if (corrupt) {
            frame[k - 1] = (uint8_t)(frame[k - 1] + 1U + rnd() % 254U);
            if (frame[k - 1] == 0x55U) {
                frame[k - 1] = 0x56U; /* a 0x55 would start a frame, not end this one */
            }
        }
        rig_snap(&rig, &before);
        len = rig_bytes(&rig, frame, k, reply);
        if (len < 2) {
            fail_msg("frame %lu (service 0x%02x, %u bytes): no reply", frames, req[0], n);
        }
        codes[reply[1]]++;
        if (reply[1] != X2C_ERR_OK) {
            by[1]++;
            if (!rig_same(&rig, &before)) {
                fail_msg("frame %lu (service 0x%02x, %u bytes) refused with 0x%02x changed state",
                         frames, req[0], n, reply[1]);
            }
        } else {
            by[0]++;
            assert_false(corrupt);
        }
        if (corrupt) {
            assert_int_equal(reply[1], X2C_ERR_CHECKSUM);
        }
        /* the interrupt's side now and then, so the scope runs through its states */
        if ((frames & 3U) == 0U) {
            for (unsigned p = 0; p < 8U; p++) {
                rig.mc.i_dq.q = (int16_t)rnd();
                rig.mc.smc.omega = (int16_t)rnd();
                samples += x2c_sample(&rig.x, NULL) ? 1U : 0U;
            }
        }
    }
    printf("measured: %lu frames: %s %lu, %s %lu; scope datasets stored %lu\n", frames, names[0],
           by[0], names[1], by[1], samples);
    printf("measured: refusals by code: checksum %lu, format %lu, size %lu, service %lu, "
           "state %lu, parameter %lu, limit %lu\n",
           codes[0x13], codes[0x14], codes[0x15], codes[0x21], codes[0x22], codes[0x40],
           codes[0x42]);
    printf("measured: reply checksums sent inverted: %u\n", rig.crc_inverted);
    assert_cmp(frames, >=, 1000000UL);
    assert_cmp(by[0], >, frames / 20U); /* the valid paths were exercised too */
    assert_cmp(codes[0x14], >, 0UL);
    assert_cmp(codes[0x15], >, 0UL);
    assert_cmp(codes[0x21], >, 0UL);
    assert_cmp(codes[0x40], >, 0UL);
    assert_cmp(codes[0x42], >, 0UL);
    assert_cmp(rig.crc_inverted, >, 0U);
    assert_cmp(samples, >, 0UL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(
            test_a_million_random_frames_should_each_get_one_reply_and_refusals_change_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
