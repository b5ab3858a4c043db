/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* variant_mc_plain.c - the core built without ripple and dead-time compensation and without the
 * identification (UserParms.h off). */
#include "test_support.h"

#include <math.h>
#include <stdio.h>

#include "mc_bench.h"
#include "mc_internal.h"

#if MC_VOLTAGE_RIPPLE || MC_DEADTIME_COMP || MC_IDENTIFY
#error "variant_mc_plain.c must be built against the core without compensations (mc_plain)"
#endif

static mc_bench_t b;

/* Angle error at 500 rpm, light load, for comparison with test_mc_closedloop's
 * figure with the compensation on. */
static void
test_without_compensation_the_voltage_should_pass_unchanged_and_the_motor_still_run(void **state)
{
    (void)state;
    mc_bench_cfg_t c;
    mc_bench_cfg_default(&c);
    c.pot = 0.0;
    mc_bench_init(&b, &c);
    b.rig.inv.prm.ripple_v = 2.0;
    b.rig.inv.prm.ripple_hz = 100.0;
    mc_request(&b.mc, MC_REQUEST_START);
    long n = mc_bench_run_until(&b, MC_STATE_CLOSED_LOOP, 4L * PWM_FREQUENCY_HZ);
    assert_cmp(n, >, 0);
    err_stats_t ang;
    err_stats_init(&ang);
    for (long k = 0; k < 3L * PWM_FREQUENCY_HZ; k++) {
        mc_bench_step(&b);
        assert_int_equal(b.st.state, MC_STATE_CLOSED_LOOP);
        /* No ripple compensation: the PI outputs are the voltages. */
        assert_int_equal(b.st.vd, b.mc.pi_d.out);
        assert_int_equal(b.st.vq, b.mc.pi_q.out);
        if (k > PWM_FREQUENCY_HZ) {
            err_stats_add(&ang, mc_bench_angle_err_deg(&b), (double)k);
        }
    }
    err_stats_print("angle at 500 rpm, no dead-time compensation (estimator fed duty - Td loss)",
                    &ang, "deg");
    assert_cmp(ang.max_abs, <, 45.0);
}

/* MC_IDENTIFY 0: the request fails at once, UNAVAILABLE, in STOPPED, and the motor then
 * starts as usual. */
static void test_without_identification_a_request_should_fail_unavailable(void **state)
{
    (void)state;
    mc_bench_cfg_t c;
    mc_id_result_t r;
    mc_bench_cfg_default(&c);
    mc_bench_init(&b, &c);
    mc_request(&b.mc, MC_REQUEST_IDENTIFY);
    for (long k = 0; k < PWM_FREQUENCY_HZ / 10; k++) {
        mc_bench_step(&b);
        assert_int_equal(b.st.state, MC_STATE_STOPPED);
        assert_false(b.st.outputs_on);
    }
    mc_identify_result(&b.mc, &r);
    assert_int_equal(r.status, MC_ID_FAILED);
    assert_int_equal(r.error, MC_ID_ERROR_UNAVAILABLE);
    assert_int_equal(r.rs_uohm, 0);
    mc_request(&b.mc, MC_REQUEST_START);
    assert_cmp(mc_bench_run_until(&b, MC_STATE_CLOSED_LOOP, 4L * PWM_FREQUENCY_HZ), >, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_without_identification_a_request_should_fail_unavailable),
        cmocka_unit_test(
            test_without_compensation_the_voltage_should_pass_unchanged_and_the_motor_still_run),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
