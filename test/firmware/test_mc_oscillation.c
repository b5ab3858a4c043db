/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_mc_oscillation.c - a speed loop too hot for its rotor ends in SPEED_UNSTABLE, outputs
 * off; the profile's rotor, and rotors up to 20 times heavier, never trip it. */
#include "test_support.h"

#include <math.h>
#include <stdio.h>

#include "mc_bench.h"
#include "mc_internal.h"

static mc_bench_t b;

typedef struct {
    long flips;       /* reversals of the speed PI between its limits */
    long fault_at;    /* periods from CLOSED_LOOP to the fault; -1 none */
    uint16_t fault;   /* the fault, MC_FAULT_NONE if none */
    double err_rms;   /* speed reference - true speed, rpm RMS, over the run */
    bool outputs_off; /* after the fault */
} swing_run_t;

/* The rotor's inertia j_scale times the profile's (the core's speed gains
 * are the profile's: a rotor 10 times lighter is a speed loop 10 times
 * hotter, as an inertia glitched 10 x high by the identification, or a
 * client's gains, make it). Started at the lowest speed, stepped to the top
 * at 1 s, back at 3 s; 5 s in CLOSED_LOOP unless it faults. */
static swing_run_t run(double j_scale)
{
    swing_run_t r = {0, -1, MC_FAULT_NONE, 0.0, false};
    mc_bench_cfg_t c;
    mc_bench_cfg_default(&c);
    c.j_scale = j_scale;
    c.pot = 0.0;
    mc_bench_init(&b, &c);
    mc_request(&b.mc, MC_REQUEST_START);
    assert_cmp(mc_bench_run_until(&b, MC_STATE_CLOSED_LOOP, 8L * PWM_FREQUENCY_HZ), >, 0);
    int last = 0;
    double e2 = 0.0;
    long n = 0;
    for (long k = 0; k < 5L * PWM_FREQUENCY_HZ; k++) {
        if (k == PWM_FREQUENCY_HZ) {
            simcore_set_speed(&b, SPEED_REF_MAX_RPM);
        } else if (k == 3L * PWM_FREQUENCY_HZ) {
            simcore_set_speed(&b, MOTOR_SPEED_MIN_RPM);
        }
        mc_bench_step(&b);
        if (b.st.state != MC_STATE_CLOSED_LOOP) {
            r.fault = b.st.fault;
            r.fault_at = k;
            break;
        }
        if (k % MC_SLOW_STEP_PERIODS == 0) {
            const pi_t *p = &b.mc.slow.pi_w;
            int s = (p->out >= p->p.out_max) ? 1 : (p->out <= p->p.out_min) ? -1 : 0;
            if (s != 0 && last != 0 && s != last) {
                r.flips++;
            }
            if (s != 0) {
                last = s;
            }
            double e = mc_rpm_of_q15(b.st.speed_ref) - mc_bench_rpm(&b);
            e2 += e * e;
            n++;
        }
    }
    r.err_rms = (n > 0) ? sqrt(e2 / (double)n) : 0.0;
    if (r.fault != MC_FAULT_NONE) {
        for (int k = 0; k < 4; k++) {
            mc_bench_step(&b);
        }
        r.outputs_off = !b.st.outputs_on;
    }
    printf(
        "measured: rotor J x %.2f: %ld reversals, speed error %.0f rpm RMS, fault %u at %.0f ms\n",
        j_scale, r.flips, r.err_rms, (unsigned)r.fault,
        (r.fault_at < 0) ? -1.0 : 1000.0 * (double)r.fault_at / PWM_FREQUENCY_HZ);
    return r;
}

/* Lighter rotors, each a limit cycle at the Iq limit that STALL_TRACK misses
 * (its error passes through zero twice a cycle) once the step to the top
 * speed leaves the low-speed schedule's reduced gains: SPEED_UNSTABLE,
 * outputs off, within a second of that step, before any other fault's name
 * (a limit cycle used to end in CURRENT_SENSOR, a sensor fault that was
 * not there). */
static void test_a_speed_loop_limit_cycling_should_end_in_speed_unstable(void **state)
{
    (void)state;
    const double light[] = {0.2, 0.1, 0.05};
    for (unsigned i = 0; i < sizeof light / sizeof light[0]; i++) {
        swing_run_t r = run(light[i]);
        assert_int_equal(r.fault, MC_FAULT_SPEED_UNSTABLE);
        assert_cmp(r.fault_at, >, PWM_FREQUENCY_HZ);
        assert_cmp(r.fault_at, <, 2L * PWM_FREQUENCY_HZ);
        assert_true(r.outputs_off);
    }
}

/* The profile's rotor, half of it and up to 20 times it (make robust's
 * range), through steps from the lowest speed to the top and back: no
 * fault, and at most two reversals. */
static void test_a_stable_speed_loop_should_never_trip_it_through_large_steps(void **state)
{
    (void)state;
    const double ok[] = {0.5, 1.0, 5.0, 20.0};
    for (unsigned i = 0; i < sizeof ok / sizeof ok[0]; i++) {
        swing_run_t r = run(ok[i]);
        assert_int_equal(r.fault, MC_FAULT_NONE);
        assert_cmp(r.flips, <=, 2);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_speed_loop_limit_cycling_should_end_in_speed_unstable),
        cmocka_unit_test(test_a_stable_speed_loop_should_never_trip_it_through_large_steps),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
