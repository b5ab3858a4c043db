/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_mc_id.c - the identification's sequence alone (mc_id.h): its math against double
 * precision, and its stages fed synthetic windows. */
#include "test_support.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "mc.h"
#include "mc_id.h"

#if MC_IDENTIFY

/* ---- the math -------------------------------------------------------------- */

/* floor((a1 b1 + a2 b2) / 2^s) as the int64 expression gives it, bit for
 * bit: every shift, the b's edges, a's sign and 16-bit boundaries, and
 * 10^6 drawn operands whose result fits 32 bits. */
static int64_t mac2_ref(int32_t a1, uint16_t b1, int32_t a2, uint16_t b2, uint8_t s)
{
    int64_t p = (int64_t)a1 * b1 + (int64_t)a2 * b2;
    return (p - (((p % ((int64_t)1 << s)) + ((int64_t)1 << s)) % ((int64_t)1 << s))) /
           ((int64_t)1 << s); /* floor, without shifting a negative */
}

static void test_mac2_shr_should_equal_the_64_bit_product_shifted(void **state)
{
    (void)state;
    static const int32_t as[] = {0,         1,          -1,          65535,      65536,
                                 -65536,    -65537,     32767,       -32768,     0x7FFFFFFF,
                                 INT32_MIN, 0x12345678, -0x12345678, 0x0000FFFF, -0x0000FFFF};
    static const uint16_t bs[] = {0U, 1U, 2U, 16384U, 32767U, 32768U};
    uint32_t seed = 12345U, n = 0, k;
    uint8_t s;
    size_t i, j, m;
    for (s = 1U; s <= 16U; s++) {
        for (i = 0; i < sizeof as / sizeof as[0]; i++) {
            for (j = 0; j < sizeof bs / sizeof bs[0]; j++) {
                for (m = 0; m < sizeof bs / sizeof bs[0]; m++) {
                    int32_t a2 = as[(i + m) % (sizeof as / sizeof as[0])];
                    int64_t want = mac2_ref(as[i], bs[j], a2, bs[m], s);
                    if (want < INT32_MIN || want > INT32_MAX) {
                        continue;
                    }
                    assert_int_equal(mc_id_mac2_shr(as[i], bs[j], a2, bs[m], s), (int32_t)want);
                    n++;
                }
            }
        }
    }
    for (k = 0; k < 1000000U; k++) {
        int32_t a1, a2;
        uint16_t b1, b2;
        int64_t want;
        seed = seed * 1664525U + 1013904223U;
        a1 = (int32_t)(seed ^ 0x5A5A5A5AU) >> (seed % 13U);
        seed = seed * 1664525U + 1013904223U;
        a2 = (int32_t)seed >> (seed % 17U);
        seed = seed * 1664525U + 1013904223U;
        b1 = (uint16_t)((seed >> 8) % 32769U);
        b2 = (uint16_t)((seed >> 3) % 32769U);
        s = (uint8_t)(1U + (seed >> 27) % 16U);
        want = mac2_ref(a1, b1, a2, b2, s);
        if (want < INT32_MIN || want > INT32_MAX) {
            continue;
        }
        assert_int_equal(mc_id_mac2_shr(a1, b1, a2, b2, s), (int32_t)want);
        n++;
    }
    printf("mc_id_mac2_shr: %u cases bit-identical to the 64-bit expression\n", (unsigned)n);
}

/* x / d and the high half of a b against 64-bit arithmetic: every 16-bit
 * divisor against edge dividends, 32-bit divisors (the plain path), and
 * 10^6 drawn operands of each. */
static void test_udiv_and_mulhi_should_equal_64_bit_arithmetic(void **state)
{
    (void)state;
    static const uint32_t xs[] = {0U,          1U,          0xFFFFU,     0x10000U,    0x1FFFFU,
                                  0x7FFFFFFFU, 0x80000000U, 0xFFFEFFFFU, 0xFFFFFFFFU, 12345678U};
    uint32_t seed = 777U, n = 0, d, k;
    size_t i, j;
    for (d = 1U; d <= 0xFFFFU; d++) {
        for (i = 0; i < sizeof xs / sizeof xs[0]; i++) {
            assert_int_equal(mc_id_udiv(xs[i], d), xs[i] / d);
            assert_int_equal(mc_id_udiv(xs[i] - xs[i] % d, d), xs[i] / d); /* exact multiples */
            n += 2U;
        }
    }
    for (i = 0; i < sizeof xs / sizeof xs[0]; i++) {
        for (j = 0; j < sizeof xs / sizeof xs[0]; j++) {
            if (xs[j] > 0xFFFFU) {
                assert_int_equal(mc_id_udiv(xs[i], xs[j]), xs[i] / xs[j]);
            }
            assert_int_equal(mc_id_mulhi(xs[i], xs[j]),
                             (uint32_t)(((uint64_t)xs[i] * xs[j]) >> 32));
            n++;
        }
    }
    for (k = 0; k < 1000000U; k++) {
        uint32_t a, b;
        seed = seed * 1664525U + 1013904223U;
        a = seed;
        seed = seed * 1664525U + 1013904223U;
        b = seed >> (seed % 31U);
        assert_int_equal(mc_id_mulhi(a, b), (uint32_t)(((uint64_t)a * b) >> 32));
        if (b != 0U) {
            assert_int_equal(mc_id_udiv(a, b), a / b);
        }
        n += 2U;
    }
    printf("mc_id_udiv, mc_id_mulhi: %u cases equal to 64-bit arithmetic\n", (unsigned)n);
}

/* -ln(a), a in (0, 1] Q30, into Q24: within 2^-22 (4 counts) of the double. */
static void test_neg_ln_should_match_double_over_its_range(void **state)
{
    (void)state;
    double worst = 0.0;
    uint32_t k, n = 0;
    for (k = 1; k <= 200000U; k++) {
        /* a dense log sweep from 2^-30 to 1, and the edges */
        uint32_t a =
            (k == 200000U)
                ? (1UL << 30)
                : (uint32_t)ldexp(1.0, 30 - (int)(30.0 * (double)(200000U - k) / 200000.0)) +
                      (k % 977U);
        double want, got, err;
        if (a > (1UL << 30)) {
            a = 1UL << 30;
        }
        want = -log((double)a / 1073741824.0) * 16777216.0;
        got = (double)mc_id_neg_ln_q24(a);
        err = fabs(got - want);
        worst = (err > worst) ? err : worst;
        n++;
    }
    printf("measured: -ln Q24 over %u inputs: worst %.2f counts (2^-24)\n", (unsigned)n, worst);
    assert_true(worst <= 4.0);
    assert_int_equal(mc_id_neg_ln_q24(0U), 0U);               /* outside: 0 */
    assert_int_equal(mc_id_neg_ln_q24((1UL << 30) + 1U), 0U); /* above 1 */
    assert_int_equal(mc_id_neg_ln_q24(1UL << 30), 0U);        /* -ln 1 */
}

/* e^-x, x >= 0 Q24, into Q30: within 2^-28 (4 counts) plus 1e-7 relative. */
static void test_exp_neg_should_match_double_over_its_range(void **state)
{
    (void)state;
    double worst = 0.0;
    uint32_t k;
    for (k = 0; k <= 400000U; k++) {
        uint32_t x = k * 1000U; /* 0 .. 23.8 */
        double want = exp(-(double)x / 16777216.0) * 1073741824.0;
        double err = fabs((double)mc_id_exp_neg_q30(x) - want) - 1e-7 * want;
        worst = (err > worst) ? err : worst;
    }
    printf("measured: e^-x Q30 over 0..23.8: worst %.2f counts (2^-30) beyond 1e-7 relative\n",
           worst);
    assert_true(worst <= 4.0);
    assert_int_equal(mc_id_exp_neg_q30(0U), 1UL << 30);
}

static const mc_id_params_t params = MC_ID_PARAMS_INIT;

/* The spin's dead-time band (mc_id.c note 7) against the ripple
 * Vbus / (12 L fpwm) in double precision from the physical units: the bus
 * (Q15 of BOARD_VBUS_FULLSCALE_V) from 0 to full scale, L (Q12 of Ts Z_FS)
 * from 1 LSB to 2^30 in steps of 1/64, dead times from below 0 to beyond
 * the band's floor; within a count (the division truncates; k's rounding
 * adds below 2^-14 of the band), never below dt + 1 nor above 8192. At the
 * profile's L and nominal bus it is the build's band. */
static double band_ref(int16_t dt, q15_t vbus, int32_t l)
{
    double v = (vbus > 0 ? vbus : 0) / 32768.0 * BOARD_VBUS_FULLSCALE_V;
    double z_fs = MC_VOLTAGE_FULLSCALE_V / BOARD_I_FULLSCALE_A;
    double l_h = l / 4096.0 * z_fs / (double)PWM_FREQUENCY_HZ;
    double b = v / (12.0 * l_h * (double)PWM_FREQUENCY_HZ) / BOARD_I_FULLSCALE_A * 32768.0;
    double lo = (dt > 0) ? dt + 1.0 : 1.0;
    return (b > 8192.0) ? ((lo > 8192.0) ? lo : 8192.0) : (b < lo) ? lo : b;
}

static void test_the_spin_band_should_be_the_ripple_of_the_measured_inductance(void **state)
{
    static const int16_t dts[] = {-7,  0,   1, 2, MC_DT_COUNTS_MIN, MC_DT_COUNTS, MC_DT_COUNTS_MAX,
                                  400, 2000};
    long n = 0;
    double worst = 0.0;
    (void)state;
    assert_int_equal(
        params.band_k,
        (uint16_t)floor(BOARD_VBUS_FULLSCALE_V / (12.0 * MC_VOLTAGE_FULLSCALE_V) * 65536.0 + 0.5));
    for (unsigned k = 0; k < sizeof dts / sizeof dts[0]; k++) {
        for (int32_t vb = 0; vb <= 32767; vb += (vb < 64) ? 1 : 61 + vb / 64) {
            for (double lf = 1.0; lf < 1073741824.0; lf *= 1.0 + 1.0 / 64.0) {
                int32_t l = (int32_t)lf;
                q15_t got = mc_id_dt_band(dts[k], (q15_t)vb, l, params.band_k);
                double ref = band_ref(dts[k], (q15_t)vb, l);
                double e = got - ref;
                if (fabs(e) > 1.0 + ref / 16384.0) {
                    fail_msg("dt %d vbus %ld l %ld: %d against %.3f", dts[k], (long)vb, (long)l,
                             got, ref);
                }
                assert_true(got > dts[k] && got >= 1);
                assert_true(got <= 8192 || got == dts[k] + 1);
                worst = (fabs(e) > worst) ? fabs(e) : worst;
                n++;
            }
        }
    }
    {
        /* the profile's motor on the nominal bus: the build's band */
        q15_t vnom = MC_Q15_VBUS(BOARD_VBUS_NOMINAL_V);
        int32_t l = (int32_t)floor(MOTOR_LS_H * (double)PWM_FREQUENCY_HZ /
                                       (MC_VOLTAGE_FULLSCALE_V / BOARD_I_FULLSCALE_A) * 4096.0 +
                                   0.5);
        q15_t b = mc_id_dt_band(MC_DT_COUNTS, vnom, l, params.band_k);
        printf("measured: %ld cases of the spin's band, |error| at most %.3f LSB; the profile's L "
               "(%ld Q12) on %.1f V: %d against MC_DT_BAND_Q15 %d (ratio %.4f)\n",
               n, worst, (long)l, (double)BOARD_VBUS_NOMINAL_V, b, MC_DT_BAND_Q15,
               (double)b / MC_DT_BAND_Q15);
        assert_true(fabs((double)b / MC_DT_BAND_Q15 - 1.0) < 0.01);
    }
}

/* ---- the stages fed windows of a resistive motor at rest -------------------- */

/* One window at the command's open-loop voltage on a motor of R (Z_FS
 * units) at rest: i = v / R on d, iq on q; returns the stage after it. */
static uint8_t feed(mc_id_t *id, mc_id_cmd_t *cmd, double r, double iq)
{
    mc_id_win_t w;
    int32_t n = (int32_t)params.n;
    double i = (double)cmd->v_d / r;
    memset(&w, 0, sizeof w);
    i = (i > 32767.0) ? 32767.0 : i;
    w.i_d = (int32_t)i * n;
    w.i_q = (int32_t)iq * n;
    w.u_d = (int32_t)cmd->v_d * n;
    w.v_d = w.u_d;
    mc_id_window(id, &w, 30000, cmd);
    return id->stage;
}

static void test_the_ramp_should_raise_the_voltage_until_the_target_current(void **state)
{
    static mc_id_t id;
    mc_id_cmd_t cmd;
    uint16_t k;
    (void)state;
    mc_id_begin(&id, &params, &cmd);
    assert_int_equal(id.stage, MC_ID_STAGE_RAMP);
    assert_true(cmd.open_loop);
    assert_int_equal(cmd.dt_counts, 0); /* the dead time measured, not compensated */
    for (k = 0; k < 1000U && id.stage == MC_ID_STAGE_RAMP; k++) {
        (void)feed(&id, &cmd, 0.5, 0.0);
    }
    printf("measured: R = 0.5 Z_FS: ramp to %d (target %d) in %u windows\n", id.i_dc,
           params.i_target, k);
    assert_int_equal(id.stage, MC_ID_STAGE_R);
    assert_true(id.i_dc >= params.i_target - params.i_target / 8 &&
                id.i_dc <= params.i_target + params.i_target / 8);
}

static void test_no_current_at_the_largest_voltage_should_be_an_open_circuit(void **state)
{
    static mc_id_t id;
    mc_id_cmd_t cmd;
    uint16_t k;
    (void)state;
    mc_id_begin(&id, &params, &cmd);
    for (k = 0; k < 3000U && id.stage == MC_ID_STAGE_RAMP; k++) {
        (void)feed(&id, &cmd, 1e9, 0.0);
    }
    assert_int_equal(id.stage, MC_ID_STAGE_FAILED);
    assert_int_equal(id.error, MC_ID_ERROR_OPEN_CIRCUIT);
    assert_true(cmd.end);
    assert_true(cmd.v_d <= params.v_max); /* never past the limit */
}

static void test_a_small_current_at_the_largest_voltage_should_be_too_small(void **state)
{
    static mc_id_t id;
    mc_id_cmd_t cmd;
    uint16_t k;
    double r = (double)params.v_max / ((double)params.i_min * 0.6); /* 0.6 of the least current */
    (void)state;
    mc_id_begin(&id, &params, &cmd);
    for (k = 0; k < 3000U && id.stage == MC_ID_STAGE_RAMP; k++) {
        (void)feed(&id, &cmd, r, 0.0);
    }
    assert_int_equal(id.error, MC_ID_ERROR_TOO_SMALL);
}

static void test_a_rotor_that_keeps_moving_should_hold_the_ramp_then_fail(void **state)
{
    static mc_id_t id;
    mc_id_cmd_t cmd;
    uint16_t k;
    q15_t v_held = 0;
    (void)state;
    mc_id_begin(&id, &params, &cmd);
    for (k = 0; k < 60U; k++) {
        (void)feed(&id, &cmd, 0.5, 0.0);
    }
    v_held = cmd.v_d;
    for (k = 0; k < 2000U && id.stage == MC_ID_STAGE_RAMP; k++) {
        /* a q current that swings window to window: a turning rotor */
        (void)feed(&id, &cmd, 0.5, (k % 2U) ? 2000.0 : -2000.0);
        if (id.stage == MC_ID_STAGE_RAMP) {
            assert_int_equal(cmd.v_d, v_held); /* held while it turns */
        }
    }
    assert_int_equal(id.error, MC_ID_ERROR_ROTOR_MOVING);
}

static void test_a_failure_should_end_the_sequence_once(void **state)
{
    static mc_id_t id;
    mc_id_cmd_t cmd;
    (void)state;
    mc_id_begin(&id, &params, &cmd);
    mc_id_fail(&id, MC_ID_ERROR_TIMEOUT);
    mc_id_fail(&id, MC_ID_ERROR_OPEN_PHASE); /* the first cause stays */
    assert_int_equal(id.stage, MC_ID_STAGE_FAILED);
    assert_int_equal(id.error, MC_ID_ERROR_TIMEOUT);
    (void)feed(&id, &cmd, 0.5, 0.0); /* a window after it changes nothing */
    assert_int_equal(id.stage, MC_ID_STAGE_FAILED);
    assert_true(cmd.end);
}

/* ---- any window: the command stays within its limits -------------------------- */

static uint32_t rnd_state = 12345U;
static int32_t rnd(int32_t lo, int32_t hi) /* xorshift32, uniform enough */
{
    rnd_state ^= rnd_state << 13;
    rnd_state ^= rnd_state >> 17;
    rnd_state ^= rnd_state << 5;
    return lo + (int32_t)(rnd_state % (uint32_t)(hi - lo + 1));
}

/* Each stage entered with drawn state and fed 20,000 drawn windows in all (sums of any size
 * the interrupt can give, the results of every branch): under ASan and UBSan, no overflow;
 * the command never asks past its limits; an ended sequence is DONE or FAILED with a code. */
static void test_drawn_windows_should_keep_the_command_within_its_limits(void **state)
{
    static mc_id_t id;
    uint8_t st;
    uint32_t n = 0, ended = 0;
    (void)state;
    for (st = MC_ID_STAGE_RAMP; st <= MC_ID_STAGE_SPIN4; st++) {
        int rep;
        for (rep = 0; rep < 20; rep++) {
            mc_id_cmd_t cmd;
            int k;
            mc_id_begin(&id, &params, &cmd);
            id.stage = st;
            id.sub = (uint8_t)rnd(0, 9);
            id.i_dc = (q15_t)rnd(params.i_min, params.i_target);
            id.r_q16 = rnd(1, 16L * 65536L);
            id.l_q12 = rnd(1, 4000000L);
            id.v0 = rnd(-2000000L, 20000000L);
            id.goal = (int32_t)params.accel;
            id.cmd.i_ref.d = (q15_t)(id.i_dc / 3);
            id.cmd.v_d = (q15_t)rnd(64, params.v_max);
            id.cmd.inj = (q15_t)rnd(0, params.inj_max);
            id.cmd.inj_half = (uint8_t)(4 << rnd(0, 3));
            id.x1 = (uint32_t)rnd(1000, (int32_t)(params.step_max / 2U));
            id.m1 = rnd(0, 300000L);
            for (k = 0; k < 100 && id.stage != MC_ID_STAGE_DONE && id.stage != MC_ID_STAGE_FAILED;
                 k++) {
                mc_id_win_t w;
                int32_t nn = (int32_t)params.n;
                uint8_t c;
                memset(&w, 0, sizeof w);
                w.i_d = rnd(-32768, 32767) * nn;
                w.i_q = rnd(-32768, 32767) * nn;
                w.u_d = rnd(-32768, 32767) * nn;
                w.u_q = rnd(-32768, 32767) * nn;
                w.v_d = w.u_d;
                w.v_q = w.u_q;
                for (c = 0; c < 8U; c++) {
                    w.c[c] = rnd(-30000000L, 30000000L);
                }
                w.step = (uint32_t)rnd(0, (int32_t)params.step_max);
                mc_id_window(&id, &w, (q15_t)rnd(0, 32767), &cmd);
                n++;
                assert_true(cmd.v_d <= params.v_max || !cmd.open_loop);
                assert_true(cmd.inj >= 0 && cmd.inj <= params.inj_max);
                assert_true(cmd.kp_shift <= 7U);
                assert_true(cmd.inj_half >= 4U && cmd.inj_half <= 32U);
                assert_true(cmd.i_ref.d >= 0 &&
                            cmd.i_ref.d <= params.i_target + params.i_target / 4);
                assert_true(id.damp <= (int32_t)params.step_max &&
                            id.damp >= -(int32_t)params.step_max);
                if (cmd.end) {
                    assert_true(id.stage == MC_ID_STAGE_DONE ||
                                (id.stage == MC_ID_STAGE_FAILED && id.error != MC_ID_ERROR_NONE));
                }
            }
            ended += (id.stage == MC_ID_STAGE_DONE || id.stage == MC_ID_STAGE_FAILED);
        }
    }
    printf("measured: %u drawn windows into every stage, %u of %u runs ended\n", (unsigned)n,
           (unsigned)ended, (unsigned)(20U * (MC_ID_STAGE_SPIN4 - MC_ID_STAGE_RAMP + 1U)));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_drawn_windows_should_keep_the_command_within_its_limits),
        cmocka_unit_test(test_mac2_shr_should_equal_the_64_bit_product_shifted),
        cmocka_unit_test(test_udiv_and_mulhi_should_equal_64_bit_arithmetic),
        cmocka_unit_test(test_neg_ln_should_match_double_over_its_range),
        cmocka_unit_test(test_exp_neg_should_match_double_over_its_range),
        cmocka_unit_test(test_the_spin_band_should_be_the_ripple_of_the_measured_inductance),
        cmocka_unit_test(test_the_ramp_should_raise_the_voltage_until_the_target_current),
        cmocka_unit_test(test_no_current_at_the_largest_voltage_should_be_an_open_circuit),
        cmocka_unit_test(test_a_small_current_at_the_largest_voltage_should_be_too_small),
        cmocka_unit_test(test_a_rotor_that_keeps_moving_should_hold_the_ramp_then_fail),
        cmocka_unit_test(test_a_failure_should_end_the_sequence_once),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

#else
int main(void)
{
    printf("MC_IDENTIFY 0: no sequence to test\n");
    return 0;
}
#endif
