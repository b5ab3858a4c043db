/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_x2c_scope.c - the scope alone: trigger keys of every type, edges, delays, the prescaler. */
#include "test_support.h"

#include <stdio.h>
#include <string.h>

#include "x2c.h"
#include "x2c_scope.h"

static x2c_scope_t scope;

static uint32_t raw_of_float(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

/* Keys order as the values do: exhaustive for 8 and 16 bits, sampled for 32. */
static void test_keys_should_order_like_the_values_of_every_type(void **state)
{
    (void)state;
    uint32_t v, pairs = 0;
    for (v = 0; v < 0xFFU; v++) { /* int8: -128 .. 127 in raw order 0x80 .. 0x7F */
        int8_t a = (int8_t)(uint8_t)v, b = (int8_t)(uint8_t)(v + 1U);
        bool lt = x2c_scope_key(v, 0xA1) < x2c_scope_key(v + 1U, 0xA1);
        assert_int_equal(lt, a < b);
        assert_true(x2c_scope_key(v, 0x81) < x2c_scope_key(v + 1U, 0x81)); /* uint8 */
        pairs++;
    }
    for (v = 0; v < 0xFFFFU; v++) {
        int16_t a = (int16_t)(uint16_t)v, b = (int16_t)(uint16_t)(v + 1U);
        bool lt = x2c_scope_key(v, 0xA2) < x2c_scope_key(v + 1U, 0xA2);
        assert_int_equal(lt, a < b);
        assert_true(x2c_scope_key(v, 0x82) < x2c_scope_key(v + 1U, 0x82));
        pairs++;
    }
    {
        uint32_t s = 12345U;
        for (unsigned i = 0; i < 200000U; i++) {
            uint32_t x, y;
            int32_t a, b;
            float f, g;
            s = s * 1664525U + 1013904223U;
            x = s;
            s = s * 1664525U + 1013904223U;
            y = (i & 1U) ? s : x + (s & 3U); /* neighbours too */
            memcpy(&a, &x, 4);
            memcpy(&b, &y, 4);
            assert_int_equal(x2c_scope_key(x, 0xA4) < x2c_scope_key(y, 0xA4), a < b);
            assert_int_equal(x2c_scope_key(x, 0x84) < x2c_scope_key(y, 0x84), x < y);
            /* floats: finite values of every magnitude and sign */
            f = (float)a / (float)((y & 0xFFFFU) + 1U);
            g = (float)b / (float)((x & 0xFFU) + 1U);
            assert_int_equal(
                x2c_scope_key(raw_of_float(f), 0xC4) < x2c_scope_key(raw_of_float(g), 0xC4), f < g);
            pairs += 3U;
        }
    }
    printf("measured: %u ordered pairs checked\n", (unsigned)pairs);
}

/* A configuration of one 2-byte channel, the trigger on src (dtype) at level. */
static void start(const volatile void *chan, uint8_t csize, const volatile void *src, uint8_t dtype,
                  uint32_t level, bool rising, int32_t delay, uint16_t prescaler)
{
    x2c_scope_cfg_t c;
    memset(&c, 0, sizeof c);
    c.state = X2C_SCOPE_WAIT_TRIG;
    c.set.nch = 1;
    c.set.prescaler = prescaler;
    c.src[0] = (const volatile uint8_t *)chan;
    c.set.size[0] = csize;
    c.set.trig_src = (const volatile uint8_t *)src;
    c.set.trig_dtype = dtype;
    c.set.trig_level = x2c_scope_key(level, dtype);
    c.set.rising = rising;
    c.set.delay = delay;
    assert_int_equal(x2c_scope_check(&c), X2C_ERR_OK);
    x2c_scope_init(&scope);
    x2c_scope_start(&scope, &c);
}

static void test_a_float_trigger_should_fire_at_the_first_value_past_its_level(void **state)
{
    (void)state;
    static volatile float f;
    static volatile int16_t n;
    unsigned k = 0;
    f = -3.0f;
    start(&n, 2, &f, 0xC4, raw_of_float(1.5f), true, 0, 0);
    while (scope.run.state != X2C_SCOPE_IDLE) {
        n = (int16_t)k;
        f = -3.0f + 0.25f * (float)k; /* 1.5 at k = 18 */
        (void)x2c_scope_sample(&scope, NULL);
        k++;
        assert_cmp(k, <, 1000U);
    }
    /* delay 0: the dataset at the edge is the first after rotation */
    assert_int_equal(scope.buf[scope.run.trig_pos], 18);
    /* and falling, through a negative level */
    k = 0;
    start(&n, 2, &f, 0xC4, raw_of_float(-0.75f), false, 0, 0);
    while (scope.run.state != X2C_SCOPE_IDLE) {
        n = (int16_t)k;
        f = 3.0f - 0.25f * (float)k; /* -0.75 at k = 15 */
        (void)x2c_scope_sample(&scope, NULL);
        k++;
        assert_cmp(k, <, 1000U);
    }
    assert_int_equal(scope.buf[scope.run.trig_pos], 15);
}

static void test_integer_triggers_should_fire_on_their_edge_for_every_width(void **state)
{
    (void)state;
    static volatile int8_t s8;
    static volatile int32_t s32;
    static volatile uint16_t u16;
    static volatile int16_t n;
    unsigned k;
    /* int8 falling past -10 */
    k = 0;
    start(&n, 2, &s8, 0xA1, (uint8_t)(int8_t)-10, false, 0, 0);
    while (scope.run.state != X2C_SCOPE_IDLE) {
        n = (int16_t)k;
        s8 = (int8_t)(50 - (int)k); /* -10 at k = 60 */
        (void)x2c_scope_sample(&scope, NULL);
        k++;
    }
    assert_int_equal(scope.buf[scope.run.trig_pos], 60);
    /* int32 rising past -70000 */
    k = 0;
    start(&n, 2, &s32, 0xA4, (uint32_t)(int32_t)-70000, true, 0, 0);
    while (scope.run.state != X2C_SCOPE_IDLE) {
        n = (int16_t)k;
        s32 = -100000 + 1000 * (int32_t)k; /* -70000 at k = 30 */
        (void)x2c_scope_sample(&scope, NULL);
        k++;
    }
    assert_int_equal(scope.buf[scope.run.trig_pos], 30);
    /* uint16 rising past 40000 (a signed compare would see it negative) */
    k = 0;
    start(&n, 2, &u16, 0x82, 40000U, true, 0, 0);
    while (scope.run.state != X2C_SCOPE_IDLE) {
        n = (int16_t)k;
        u16 = (uint16_t)(39000U + 100U * k); /* 40000 at k = 10 */
        (void)x2c_scope_sample(&scope, NULL);
        k++;
    }
    assert_int_equal(scope.buf[scope.run.trig_pos], 10);
}

/* The edge is looked for on every call, the datasets stored every
 * (prescaler + 1)th: the dataset at the trigger position is the first
 * stored at or after the edge. */
static void test_the_prescaler_should_thin_the_datasets_not_the_trigger(void **state)
{
    (void)state;
    static volatile int16_t v, n;
    unsigned k = 0, stored = 0;
    start(&n, 2, &v, 0xA2, 500U, true, 4, 4); /* every 5th call, 2 datasets of history */
    while (scope.run.state != X2C_SCOPE_IDLE) {
        n = (int16_t)k;
        v = (int16_t)k; /* 500 at k = 500, not a storing call (every 5th from 0) */
        if (x2c_scope_sample(&scope, NULL)) {
            stored++;
        }
        k++;
        assert_cmp(k, <, 10000U);
    }
    assert_int_equal(stored, 500U / 5U + X2C_SCOPE_BYTES / 2U - 2U); /* the ring ran to the edge */
    {
        uint16_t p = scope.run.trig_pos;
        int16_t at = (int16_t)(uint16_t)(scope.buf[p] | (scope.buf[p + 1U] << 8));
        uint16_t q = (uint16_t)((p + X2C_SCOPE_BYTES - 2U) % X2C_SCOPE_BYTES);
        int16_t before = (int16_t)(uint16_t)(scope.buf[q] | (scope.buf[q + 1U] << 8));
        assert_int_equal(at, 500); /* k = 500 is a storing call: 500 = 5 x 100 */
        assert_int_equal(before, 495);
    }
}

static void test_auto_should_fire_once_the_history_is_in(void **state)
{
    (void)state;
    static volatile int16_t n;
    x2c_scope_cfg_t c;
    unsigned k = 0;
    memset(&c, 0, sizeof c);
    c.state = X2C_SCOPE_WAIT_TRIG;
    c.set.nch = 1;
    c.src[0] = (const volatile uint8_t *)&n;
    c.set.size[0] = 2;
    c.set.trig_src = NULL; /* auto */
    c.set.trig_dtype = 0x81;
    c.set.delay = 20; /* 10 datasets */
    assert_int_equal(x2c_scope_check(&c), X2C_ERR_OK);
    x2c_scope_init(&scope);
    x2c_scope_start(&scope, &c);
    while (scope.run.state != X2C_SCOPE_IDLE) {
        n = (int16_t)k;
        (void)x2c_scope_sample(&scope, NULL);
        k++;
    }
    assert_int_equal(k, X2C_SCOPE_BYTES / 2U);
    assert_int_equal(scope.run.trig_pos, 20U);
    assert_int_equal(scope.buf[0], 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_keys_should_order_like_the_values_of_every_type),
        cmocka_unit_test(test_a_float_trigger_should_fire_at_the_first_value_past_its_level),
        cmocka_unit_test(test_integer_triggers_should_fire_on_their_edge_for_every_width),
        cmocka_unit_test(test_the_prescaler_should_thin_the_datasets_not_the_trigger),
        cmocka_unit_test(test_auto_should_fire_once_the_history_is_in),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
