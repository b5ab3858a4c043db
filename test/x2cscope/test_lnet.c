/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_lnet.c - the LNet frame layer: known frames, every escape, resync, errors, round trips. */
#include "test_support.h"

#include <stdio.h>
#include <string.h>

#include "lnet.h"

/* a receiver for any frame (a target's buffer may be smaller: test_a_frame_longer_...) */
static uint8_t rx_buf[LNET_MAX_DATA];

/* The whole frame the sender gives for data, into out; its length. */
static size_t encode(uint8_t node, const uint8_t *data, uint8_t size, uint8_t *out)
{
    lnet_tx_t tx;
    size_t n = 0;
    uint8_t b;
    lnet_tx_start(&tx, node, data, size, NULL, size);
    while (lnet_tx_next(&tx, &b)) {
        out[n++] = b;
    }
    assert_false(lnet_tx_busy(&tx));
    return n;
}

/* Feeds bytes; returns the last event that was not LNET_RX_NONE (or NONE),
 * and how many such events there were. */
static lnet_rx_event_t feed(lnet_rx_t *rx, const uint8_t *bytes, size_t n, unsigned *events)
{
    lnet_rx_event_t last = LNET_RX_NONE;
    *events = 0U;
    for (size_t k = 0; k < n; k++) {
        lnet_rx_event_t e = lnet_rx_byte(rx, bytes[k]);
        if (e != LNET_RX_NONE) {
            last = e;
            (*events)++;
        }
    }
    return last;
}

static void test_device_info_request_should_be_the_five_bytes_the_protocol_gives(void **state)
{
    (void)state;
    static const uint8_t data[] = {0x00};
    static const uint8_t want[] = {0x55, 0x01, 0x01, 0x00, 0x57}; /* sum 0x57 */
    uint8_t out[8];
    assert_int_equal(encode(LNET_NODE, data, 1U, out), sizeof want);
    assert_memory_equal(out, want, sizeof want);

    lnet_rx_t rx;
    unsigned events;
    lnet_rx_init(&rx, rx_buf, (uint8_t)LNET_MAX_DATA);
    assert_int_equal(feed(&rx, want, sizeof want, &events), LNET_RX_FRAME);
    assert_int_equal(events, 1U);
    assert_int_equal(rx.size, 1U);
    assert_int_equal(rx.data[0], 0x00);
}

/* 0x55 and 0x02 in SIZE, NODE and DATA each get a 0x00 fill, neither
 * counted nor summed; SYN and CRC never do. */
static void test_reserved_bytes_should_take_a_fill_in_every_field_but_syn_and_crc(void **state)
{
    (void)state;
    static const uint8_t data[] = {0x55, 0x02, 0x00};
    /* sum 0x55 + 3 + 1 + 0x55 + 0x02 + 0 = 0xB0 */
    static const uint8_t want[] = {0x55, 0x03, 0x01, 0x55, 0x00, 0x02, 0x00, 0x00, 0xB0};
    uint8_t out[16];
    assert_int_equal(encode(LNET_NODE, data, 3U, out), sizeof want);
    assert_memory_equal(out, want, sizeof want);

    /* SIZE 0x55 and 0x02, NODE 0x02 */
    uint8_t big[0x55];
    memset(big, 0x11, sizeof big);
    uint8_t frame[2 * 256 + 8];
    size_t n = encode(LNET_NODE, big, 0x55U, frame);
    assert_int_equal(frame[1], 0x55);
    assert_int_equal(frame[2], 0x00); /* SIZE's fill */
    assert_int_equal(n, 1U + 2U + 1U + 0x55U + 1U);
    n = encode(0x02U, big, 0x02U, frame);
    static const uint8_t two[] = {0x55, 0x02, 0x00, 0x02,
                                  0x00, 0x11, 0x11, (uint8_t)(0x55 + 2 + 2 + 0x22)};
    assert_int_equal(n, sizeof two);
    assert_memory_equal(frame, two, sizeof two);
}

/* A sum that reads as a reserved byte is sent inverted. */
static void test_a_checksum_of_0x55_or_0x02_should_be_sent_inverted(void **state)
{
    (void)state;
    static const uint8_t d55[] = {0xFE}; /* 0x57 + 0xFE = 0x155 */
    static const uint8_t d02[] = {0xAB}; /* 0x57 + 0xAB = 0x102 */
    uint8_t out[8];
    lnet_rx_t rx;
    unsigned events;
    assert_int_equal(encode(LNET_NODE, d55, 1U, out), 5U);
    assert_int_equal(out[4], 0xAA);
    lnet_rx_init(&rx, rx_buf, (uint8_t)LNET_MAX_DATA);
    assert_int_equal(feed(&rx, out, 5U, &events), LNET_RX_FRAME);
    assert_int_equal(encode(LNET_NODE, d02, 1U, out), 5U);
    assert_int_equal(out[4], 0xFD);
    assert_int_equal(feed(&rx, out, 5U, &events), LNET_RX_FRAME);
    assert_int_equal(lnet_crc_byte(0x55), 0xAA);
    assert_int_equal(lnet_crc_byte(0x02), 0xFD);
    assert_int_equal(lnet_crc_byte(0x57), 0x57);
}

static void test_a_bad_checksum_should_drop_the_frame_and_keep_the_next(void **state)
{
    (void)state;
    static const uint8_t bad[] = {0x55, 0x01, 0x01, 0x00, 0x58};
    static const uint8_t good[] = {0x55, 0x01, 0x01, 0x09, 0x60};
    lnet_rx_t rx;
    unsigned events;
    lnet_rx_init(&rx, rx_buf, (uint8_t)LNET_MAX_DATA);
    assert_int_equal(feed(&rx, bad, sizeof bad, &events), LNET_RX_BAD_CRC);
    assert_int_equal(feed(&rx, good, sizeof good, &events), LNET_RX_FRAME);
    assert_int_equal(rx.data[0], 0x09);
    /* a SYN where the checksum belongs: the checksum is bad, and a new frame starts */
    static const uint8_t cut[] = {0x55, 0x01, 0x01, 0x00, 0x55, 0x01, 0x01, 0x09, 0x60};
    assert_int_equal(feed(&rx, cut, sizeof cut, &events), LNET_RX_FRAME);
    assert_int_equal(events, 2U);
    assert_int_equal(rx.data[0], 0x09);
}

static void test_a_0x02_without_its_fill_should_be_a_format_error(void **state)
{
    (void)state;
    static const uint8_t bad[] = {0x55, 0x01, 0x01, 0x02, 0x05, 0x55, 0x01, 0x01, 0x09, 0x60};
    lnet_rx_t rx;
    lnet_rx_init(&rx, rx_buf, (uint8_t)LNET_MAX_DATA);
    for (size_t k = 0; k < 4U; k++) {
        assert_int_equal(lnet_rx_byte(&rx, bad[k]), LNET_RX_NONE);
    }
    assert_int_equal(lnet_rx_byte(&rx, bad[4]), LNET_RX_BAD_FORMAT);
    unsigned events;
    assert_int_equal(feed(&rx, &bad[5], 5U, &events), LNET_RX_FRAME);
    assert_int_equal(rx.data[0], 0x09);
}

/* A 0x55 followed by anything but the fill is a new SYN: a frame cut off
 * anywhere is dropped and the next one is received. */
static void test_a_frame_cut_anywhere_should_not_cost_the_next_one(void **state)
{
    (void)state;
    uint8_t data[40];
    uint8_t frame[2 * 256 + 8];
    uint8_t next[2 * 256 + 8];
    for (unsigned k = 0; k < sizeof data; k++) {
        data[k] = (uint8_t)((k % 3U == 0U) ? 0x55U : (k % 3U == 1U) ? 0x02U : k);
    }
    size_t n = encode(LNET_NODE, data, (uint8_t)sizeof data, frame);
    static const uint8_t nd[] = {0x12, 0x55, 0x34};
    size_t m = encode(LNET_NODE, nd, 3U, next);
    unsigned cuts = 0U;
    for (size_t cut = 1; cut < n; cut++) {
        lnet_rx_t rx;
        unsigned events;
        lnet_rx_init(&rx, rx_buf, (uint8_t)LNET_MAX_DATA);
        (void)feed(&rx, frame, cut, &events);
        assert_int_equal(feed(&rx, next, m, &events), LNET_RX_FRAME);
        assert_int_equal(rx.size, 3U);
        assert_memory_equal(rx.data, nd, 3U);
        cuts++;
    }
    printf("measured: a frame cut after each of its %u bytes: the next frame received every time\n",
           cuts);
}

static void test_a_frame_for_another_node_should_be_dropped_silently(void **state)
{
    (void)state;
    static const uint8_t data[] = {0x09};
    uint8_t out[8];
    size_t n = encode(2U, data, 1U, out);
    lnet_rx_t rx;
    unsigned events;
    lnet_rx_init(&rx, rx_buf, (uint8_t)LNET_MAX_DATA);
    assert_int_equal(feed(&rx, out, n, &events), LNET_RX_NONE);
    assert_int_equal(events, 0U);
}

/* Out of a frame, 0x55 0x00 is a data byte 0x55 of a frame the receiver
 * missed (the clients' escape), not a SYN: 50 such pairs give no event, and
 * a frame after them arrives. */
static void test_escaped_syn_bytes_out_of_a_frame_should_not_start_one(void **state)
{
    (void)state;
    uint8_t noise[100];
    for (unsigned k = 0; k < 50U; k++) {
        noise[2U * k] = 0x55U;
        noise[2U * k + 1U] = 0x00U;
    }
    lnet_rx_t rx;
    unsigned events;
    lnet_rx_init(&rx, rx_buf, (uint8_t)LNET_MAX_DATA);
    assert_int_equal(feed(&rx, noise, sizeof noise, &events), LNET_RX_NONE);
    assert_int_equal(events, 0U);
    static const uint8_t data[] = {0x00};
    uint8_t out[8];
    size_t n = encode(LNET_NODE, data, 1U, out);
    assert_int_equal(feed(&rx, out, n, &events), LNET_RX_FRAME);
    assert_int_equal(events, 1U);
}

/* A frame for another node is not ours to answer, broken or not: a bad
 * checksum and a reserved byte without its fill give no event; the same
 * for node 1 give theirs. */
static void test_errors_of_another_nodes_frame_should_give_no_event(void **state)
{
    (void)state;
    static const uint8_t data[] = {0x09, 0x10};
    for (uint8_t node = 1U; node <= 2U; node++) {
        uint8_t out[16];
        size_t n = encode(node, data, 2U, out);
        lnet_rx_t rx;
        unsigned events;
        out[n - 1U] ^= 0x01U; /* the checksum */
        lnet_rx_init(&rx, rx_buf, (uint8_t)LNET_MAX_DATA);
        lnet_rx_event_t e = feed(&rx, out, n, &events);
        assert_int_equal(e, node == LNET_NODE ? LNET_RX_BAD_CRC : LNET_RX_NONE);
        /* SYN SIZE NODE, then a data byte 0x02 without its fill (node 2 is itself
         * reserved: its own fill follows it) */
        lnet_rx_init(&rx, rx_buf, (uint8_t)LNET_MAX_DATA);
        static const uint8_t n1[] = {0x55, 0x03, 0x01, 0x02, 0x09};
        static const uint8_t n2[] = {0x55, 0x03, 0x02, 0x00, 0x02, 0x09};
        if (node == LNET_NODE) {
            assert_int_equal(feed(&rx, n1, sizeof n1, &events), LNET_RX_BAD_FORMAT);
        } else {
            assert_int_equal(feed(&rx, n2, sizeof n2, &events), LNET_RX_NONE);
            assert_int_equal(events, 0U);
        }
    }
}

/* A frame its client left in the middle: after the line's gap
 * (lnet_rx_gap) the next client's frame is read from its SYN; without it,
 * its SYN would be taken for the missing checksum. At every cut. */
static void test_a_gap_should_drop_a_partial_frame(void **state)
{
    (void)state;
    static const uint8_t data[] = {0x09, 0x55, 0x30, 0x00, 0x02};
    static const uint8_t nd[] = {0x01};
    uint8_t frame[32], next[16];
    size_t n = encode(LNET_NODE, data, (uint8_t)sizeof data, frame);
    size_t m = encode(LNET_NODE, nd, 1U, next);
    for (size_t cut = 1; cut < n; cut++) {
        lnet_rx_t rx;
        unsigned events;
        lnet_rx_init(&rx, rx_buf, (uint8_t)LNET_MAX_DATA);
        (void)feed(&rx, frame, cut, &events);
        assert_true(lnet_rx_gap(&rx));
        assert_int_equal(feed(&rx, next, m, &events), LNET_RX_FRAME);
        assert_int_equal(events, 1U);
        assert_int_equal(rx.size, 1U);
        assert_false(lnet_rx_gap(&rx)); /* nothing partial after a whole frame */
    }
}

/* xorshift32, a fixed seed: the same bytes on every machine. */
static uint32_t rnd(uint32_t *s)
{
    uint32_t x = *s;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    *s = x;
    return x;
}

/* Bytes that favour the reserved values, so every escape is met often. */
static uint8_t rnd_byte(uint32_t *s)
{
    uint32_t r = rnd(s);
    switch (r & 7U) {
        case 0:
            return 0x55U;
        case 1:
            return 0x02U;
        case 2:
            return 0x00U;
        default:
            return (uint8_t)(r >> 8);
    }
}

/* Every size 0..255, 40 payloads each: sent and received, the same bytes. */
static void test_every_size_should_round_trip(void **state)
{
    (void)state;
    uint32_t seed = 0x1234567U;
    static uint8_t data[LNET_MAX_DATA];
    static uint8_t frame[2 * 256 + 8];
    size_t longest = 0;
    unsigned frames = 0U;
    lnet_rx_t rx;
    lnet_rx_init(&rx, rx_buf, (uint8_t)LNET_MAX_DATA);
    {
        /* SIZE 0 is no frame: after a SYN its 0x00 reads as the fill of an escaped 0x55,
         * as the clients read it (every request and reply has data) */
        unsigned events;
        size_t n = encode(LNET_NODE, data, 0U, frame);
        assert_int_equal(feed(&rx, frame, n, &events), LNET_RX_NONE);
        assert_int_equal(events, 0U);
    }
    for (unsigned size = 1; size <= LNET_MAX_DATA; size++) {
        for (unsigned k = 0; k < 40U; k++) {
            for (unsigned i = 0; i < size; i++) {
                data[i] = rnd_byte(&seed);
            }
            size_t n = encode(LNET_NODE, data, (uint8_t)size, frame);
            longest = n > longest ? n : longest;
            unsigned events;
            assert_int_equal(feed(&rx, frame, n, &events), LNET_RX_FRAME);
            assert_int_equal(events, 1U);
            assert_int_equal(rx.size, size);
            assert_memory_equal(rx.data, data, size);
            frames++;
        }
    }
    /* 255 reserved bytes: SYN, SIZE, NODE, 2 x 255, CRC */
    memset(data, 0x55, sizeof data);
    longest = encode(LNET_NODE, data, 255U, frame);
    assert_int_equal(longest, 514U);
    printf("measured: %u frames of 0..255 bytes round-tripped; the longest frame, 255 reserved "
           "bytes, is %zu bytes on the wire\n",
           frames, longest);
}

/* A million random bytes (the receiver never writes outside its buffer:
 * ASan), then frames after random noise: every one arrives. Whatever state
 * the noise left, the frame's SYN either starts a frame or is taken as a
 * reserved byte whose fill does not follow (a frame's SIZE is never 0: every
 * request holds its service byte), which is a new SYN. */
static void test_random_noise_should_be_survived_and_frames_after_it_should_arrive(void **state)
{
    (void)state;
    uint32_t seed = 0xBEEF01U;
    lnet_rx_t rx;
    lnet_rx_init(&rx, rx_buf, (uint8_t)LNET_MAX_DATA);
    unsigned long noise_frames = 0, bytes = 0;
    for (unsigned long k = 0; k < 1000000UL; k++) {
        if (lnet_rx_byte(&rx, rnd_byte(&seed)) == LNET_RX_FRAME) {
            noise_frames++; /* possible: noise can hold a whole valid frame */
        }
        bytes++;
    }
    static uint8_t frame[2 * 256 + 8];
    uint8_t data[16];
    unsigned sent = 0U, received = 0U;
    for (unsigned k = 0; k < 20000U; k++) {
        unsigned noise = rnd(&seed) % 24U;
        for (unsigned i = 0; i < noise; i++) {
            (void)lnet_rx_byte(&rx, rnd_byte(&seed));
        }
        uint8_t size = (uint8_t)(1U + rnd(&seed) % sizeof data);
        for (unsigned i = 0; i < size; i++) {
            data[i] = rnd_byte(&seed);
        }
        size_t n = encode(LNET_NODE, data, size, frame);
        bool got = false;
        for (size_t i = 0; i < n; i++) {
            if (lnet_rx_byte(&rx, frame[i]) == LNET_RX_FRAME && i == n - 1U) {
                got = rx.size == size && memcmp(rx.data, data, size) == 0;
            }
        }
        sent++;
        received += got ? 1U : 0U;
    }
    printf("measured: %lu random bytes (3/8 reserved or fill): %lu complete frames in them "
           "(checksum 1 in 256); %u of %u frames sent after random noise received\n",
           bytes, noise_frames, received, sent);
    assert_int_equal(received, sent);
}

/* A receiver whose buffer is smaller than a frame (a target sized for its largest request):
 * the whole frame is read to its checksum, reported LNET_RX_TOO_LONG with its size and first
 * bytes, nothing written past the buffer; a bad checksum is still BAD_CRC; the next frame that
 * fits arrives whole. */
static void test_a_frame_longer_than_the_buffer_should_be_reported_whole(void **state)
{
    uint8_t buf[9];
    uint8_t data[40], frame[2U * 40U + 8U];
    lnet_rx_t rx;
    unsigned events;
    size_t n;
    (void)state;
    for (unsigned k = 0; k < sizeof data; k++) {
        data[k] = (uint8_t)(k * 37U + 2U); /* reserved bytes among them: escapes too */
    }
    memset(buf, 0xEE, sizeof buf);
    lnet_rx_init(&rx, buf, 8U);
    n = encode(LNET_NODE, data, 40U, frame);
    assert_int_equal(feed(&rx, frame, n, &events), LNET_RX_TOO_LONG);
    assert_int_equal(events, 1U);
    assert_int_equal(rx.size, 40U);
    assert_memory_equal(buf, data, 8U);
    assert_int_equal(buf[8], 0xEE); /* the buffer's end untouched */
    assert_true(n > 0U && n <= sizeof frame);
    if (n > 0U && n <= sizeof frame) {
        frame[n - 1U] ^= 0x01U; /* the checksum */
    }
    assert_int_equal(feed(&rx, frame, n, &events), LNET_RX_BAD_CRC);
    n = encode(LNET_NODE, data, 8U, frame);
    assert_int_equal(feed(&rx, frame, n, &events), LNET_RX_FRAME);
    assert_int_equal(rx.size, 8U);
    assert_memory_equal(buf, data, 8U);
    /* a frame for another node is dropped, long or not */
    n = encode(2U, data, 40U, frame);
    assert_int_equal(feed(&rx, frame, n, &events), LNET_RX_NONE);
}

/* A frame sent from a head and a body is byte for byte the frame of the two joined, for
 * every split, reserved bytes on both sides of it. */
static void test_a_head_and_a_body_should_send_as_one_frame(void **state)
{
    static uint8_t data[LNET_MAX_DATA];
    static uint8_t want[2U * LNET_MAX_DATA + 8U], got[2U * LNET_MAX_DATA + 8U];
    (void)state;
    for (unsigned k = 0; k < sizeof data; k++) {
        data[k] = (uint8_t)((k % 3U == 0U) ? 0x55U : (k % 3U == 1U) ? 0x02U : k);
    }
    for (unsigned size = 0; size <= LNET_MAX_DATA; size += 17U) {
        size_t nw = encode(LNET_NODE, data, (uint8_t)size, want);
        for (unsigned head = 0; head <= size; head++) {
            lnet_tx_t tx;
            size_t ng = 0;
            uint8_t b;
            lnet_tx_start(&tx, LNET_NODE, data, (uint8_t)head, &data[head], (uint8_t)size);
            while (lnet_tx_next(&tx, &b)) {
                got[ng++] = b;
            }
            assert_int_equal(ng, nw);
            assert_memory_equal(got, want, nw);
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_device_info_request_should_be_the_five_bytes_the_protocol_gives),
        cmocka_unit_test(test_reserved_bytes_should_take_a_fill_in_every_field_but_syn_and_crc),
        cmocka_unit_test(test_a_checksum_of_0x55_or_0x02_should_be_sent_inverted),
        cmocka_unit_test(test_a_bad_checksum_should_drop_the_frame_and_keep_the_next),
        cmocka_unit_test(test_a_0x02_without_its_fill_should_be_a_format_error),
        cmocka_unit_test(test_a_frame_cut_anywhere_should_not_cost_the_next_one),
        cmocka_unit_test(test_a_frame_for_another_node_should_be_dropped_silently),
        cmocka_unit_test(test_escaped_syn_bytes_out_of_a_frame_should_not_start_one),
        cmocka_unit_test(test_errors_of_another_nodes_frame_should_give_no_event),
        cmocka_unit_test(test_a_gap_should_drop_a_partial_frame),
        cmocka_unit_test(test_every_size_should_round_trip),
        cmocka_unit_test(test_a_frame_longer_than_the_buffer_should_be_reported_whole),
        cmocka_unit_test(test_a_head_and_a_body_should_send_as_one_frame),
        cmocka_unit_test(test_random_noise_should_be_survived_and_frames_after_it_should_arrive),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
