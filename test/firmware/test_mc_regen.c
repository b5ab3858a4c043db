/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_mc_regen.c - braking into a bus whose supply takes nothing back (the simulator's bus
 * model): the core limits the braking current so the bus stays below its overvoltage trip. */
#include "test_support.h"

#include <math.h>
#include <stdio.h>

#include "mc_bench.h"
#include "mc_internal.h"

static mc_bench_t b;

/* mc_regen_limit against its definition in doubles, every bus code 0..32767 at four current
 * limits: within 3 counts (1e-4 of full scale: the 2^10 reciprocal's and the product's
 * truncations) of iq_max * clamp((regen + band - vbus) / band, 0, 1), exact outside the band. */
static void test_the_braking_limit_should_fall_linearly_over_its_band(void **state)
{
    (void)state;
    const q15_t lims[] = {MC_IQ_MAX_Q15, 32767, 1000, 0};
    double worst = 0.0;
    for (unsigned i = 0; i < sizeof lims / sizeof lims[0]; i++) {
        for (int32_t v = 0; v <= 32767; v++) {
            double f = ((double)MC_VBUS_REGEN_Q15 + (double)MC_VBUS_REGEN_BAND_Q15 - (double)v) /
                       (double)MC_VBUS_REGEN_BAND_Q15;
            f = (f > 1.0) ? 1.0 : ((f < 0.0) ? 0.0 : f);
            q15_t got = mc_regen_limit(lims[i], (q15_t)v);
            worst = fmax(worst, fabs((double)got - (double)lims[i] * f));
            assert_cmp(got, >=, 0);
            assert_cmp(got, <=, lims[i]);
            if (v <= MC_VBUS_REGEN_Q15) {
                assert_int_equal(got, lims[i]);
            }
            if (v >= MC_VBUS_REGEN_Q15 + MC_VBUS_REGEN_BAND_Q15) {
                assert_int_equal(got, 0);
            }
        }
    }
    printf("measured: braking limit vs its double reference over every bus code: max |err| %.2f "
           "counts (from %.2f V to %.2f V)\n",
           worst, (double)MC_VBUS_REGEN_V, (double)(MC_VBUS_REGEN_V + MC_VBUS_REGEN_BAND_V));
    assert_cmp(worst, <=, 3.0);
}

/* A rotor 20 times the Hurst's inertia (make robust's heaviest) at 2,800 rpm asked for 500:
 * braking at the speed loop's will, its energy charged the MCLV's bus past the 32 V trip in
 * 0.1 s (OVERVOLTAGE). With the limit the bus stays below the trip by a margin, the drive
 * stays in closed loop, and the rotor slows by its losses to the new speed. */
static void test_a_heavy_rotor_braked_into_the_bus_should_stay_below_the_trip(void **state)
{
    (void)state;
    mc_bench_cfg_t c;
    mc_bench_cfg_default(&c);
    c.j_scale = 20.0;
    c.bus_model = true;
    mc_bench_init(&b, &c);
    simcore_set_speed(&b, 3000.0);
    mc_request(&b.mc, MC_REQUEST_START);
    assert_cmp(mc_bench_run_until(&b, MC_STATE_CLOSED_LOOP, 8L * PWM_FREQUENCY_HZ), >, 0);
    for (long k = 0; k < 3L * PWM_FREQUENCY_HZ; k++) {
        mc_bench_step(&b);
    }
    double from = mc_bench_rpm(&b);
    assert_cmp(from, >, 2500.0);
    simcore_set_speed(&b, 500.0);
    long reached = -1;
    for (long k = 0; k < 15L * PWM_FREQUENCY_HZ; k++) {
        mc_bench_step(&b);
        assert_int_equal(b.st.state, MC_STATE_CLOSED_LOOP);
        if (reached < 0 && mc_bench_rpm(&b) < 520.0) {
            reached = k;
        }
    }
    printf(
        "measured: J x20 braked from %.0f to 500 rpm on a %.0f uF bus: peak %.2f V (trip %.1f V, "
        "braking limited from %.1f V), 520 rpm after %.2f s, no fault\n",
        from, b.rig.bus_c_f * 1e6, b.rig.vbus_peak_v, (double)MC_VBUS_OVERVOLTAGE_V,
        (double)MC_VBUS_REGEN_V, (double)reached / PWM_FREQUENCY_HZ);
    assert_cmp(b.rig.bus_c_f, >, 0.0);
    assert_cmp(b.rig.vbus_peak_v, <, (double)MC_VBUS_OVERVOLTAGE_V - 1.0);
    assert_cmp(b.rig.vbus_peak_v, >, (double)MC_VBUS_REGEN_V); /* it did brake into the bus */
    assert_cmp(reached, >, 0);
    assert_cmp(fabs(mc_bench_rpm(&b) - 500.0), <, 15.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_the_braking_limit_should_fall_linearly_over_its_band),
        cmocka_unit_test(test_a_heavy_rotor_braked_into_the_bus_should_stay_below_the_trip),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
