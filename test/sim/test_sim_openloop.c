/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_sim_openloop.c - the whole bench driven by an ideal double-precision FOC with the true
 * angle. */
#include "test_support.h"

#include <math.h>
#include <string.h>
#include <stdio.h>

#include "sim_profiles.h"
#include "sim_rig.h"

/*
 * An ideal current controller in double precision, fed by the bench's ADC
 * frames and the plant's true angle (a perfect sensor), drives the Hurst
 * held at a constant speed (huge inertia). It checks the bench as a whole:
 * ADC scaling and sign, the one-period duty delay, inverter and plant.
 *
 *  - Without dead time the voltage the controller settles at is the
 *    steady-state voltage of the motor equations: vd = R id - we L iq,
 *    vq = R iq + we (L id + psi).
 *  - With dead time Td the inverter loses, on each pin, Td/Ts Vbus against
 *    the sign of the current (linear within the band). For a sinusoidal
 *    current of amplitude I along q that is a voltage along q whose
 *    fundamental is c Td/Ts Vbus, c = (1/pi) int sat(sin t / b) sin t dt
 *    over one turn, b = band / I (c = 4/pi for a pure sign), which the
 *    controller must add.
 */

#define TS (1.0 / 20000.0)

typedef struct {
    double vd, vq, id, iq; /* averages over the measuring window */
} foc_result_t;

static foc_result_t run_ideal_foc(double deadtime_s, double rpm, double iq_ref, double *band)
{
    static sim_rig_t rig;
    sim_rig_params_t p;
    double wm = rpm * 2.0 * M_PI / 60.0, we, ci_d = 0.0, ci_q = 0.0;
    double wc = 2000.0, sum_vd = 0.0, sum_vq = 0.0, sum_id = 0.0, sum_iq = 0.0;
    foc_result_t r;
    long n, N = 8000, n_avg = 0;

    memset(&p, 0, sizeof(p));
    sim_motor_params_from_profile(sim_motor_profile("hurst"), &p.motor);
    p.motor.j_kgm2 = 1e3; /* speed held */
    p.inv.vbus_v = 24.0;
    p.inv.ripple_v = 0.0;
    p.inv.ripple_hz = 0.0;
    p.inv.deadtime_s = deadtime_s;
    p.inv.pwm_hz = 20000.0;
    p.inv.duty_max = 2000.0;
    p.inv.i_band_a = 0.0;
    p.adc.i_fs_a = 4.4;
    p.adc.vbus_fs_v = 52.8;
    p.adc.bits = 10;
    p.adc.offset_a_codes = 0.0;
    p.adc.offset_b_codes = 0.0;
    p.adc.noise_codes = 0.0;
    p.adc.seed = 3u;
    p.substeps = 4;
    p.sample_at = 0.0; /* this bench's own FOC assumes a sample at the period start */
    p.amp_tau_s = 0.0; /* with ideal current sensors */
    p.theta_e0 = 0.4;
    p.omega0_m = wm;
    p.fan_rated_rpm = sim_motor_profile("hurst")->rated_rpm;
    sim_rig_init(&rig, &p);
    *band = rig.inv.i_band_a;
    we = (double)p.motor.pole_pairs * wm;

    for (n = 0; n < N; n++) {
        sim_adc_frame_t f;
        double ia, ib, ial, ibe, th, cs, sn, id, iq, ed, eq, vd, vq, va, vb;
        double vabc[3];
        uint16_t duty[3];
        int k;
        sim_rig_sample(&rig, &f);
        ia = (double)f.ia / 32768.0 * 4.4;
        ib = (double)f.ib / 32768.0 * 4.4;
        th = rig.plant.s.theta_e; /* true angle at the sample */
        ial = ia;
        ibe = (ia + 2.0 * ib) / sqrt(3.0);
        cs = cos(th);
        sn = sin(th);
        id = ial * cs + ibe * sn;
        iq = -ial * sn + ibe * cs;
        /* PI with Kp = L wc, Ki = R wc (pole cancellation) + decoupling */
        ed = 0.0 - id;
        eq = iq_ref - iq;
        ci_d += p.motor.rs_ohm * wc * TS * ed;
        ci_q += p.motor.rs_ohm * wc * TS * eq;
        vd = p.motor.ld_h * wc * ed + ci_d - we * p.motor.lq_h * iq;
        vq = p.motor.lq_h * wc * eq + ci_q + we * (p.motor.ld_h * id + p.motor.psi_vs);
        if (n >= N - 2000) {
            sum_vd += vd;
            sum_vq += vq;
            sum_id += id;
            sum_iq += iq;
            n_avg++;
        }
        /* applied during the next period: rotate to its middle */
        th += 1.5 * we * TS;
        va = vd * cos(th) - vq * sin(th);
        vb = vd * sin(th) + vq * cos(th);
        vabc[0] = va;
        vabc[1] = -0.5 * va + 0.5 * sqrt(3.0) * vb;
        vabc[2] = -0.5 * va - 0.5 * sqrt(3.0) * vb;
        {
            /* min-max (space-vector equivalent) zero sequence: linear up to Vbus/sqrt(3) */
            double vmax = fmax(vabc[0], fmax(vabc[1], vabc[2]));
            double vmin = fmin(vabc[0], fmin(vabc[1], vabc[2]));
            double v0 = 0.5 * (vmax + vmin);
            for (k = 0; k < 3; k++) {
                vabc[k] -= v0;
            }
        }
        for (k = 0; k < 3; k++) {
            double d = 0.5 + vabc[k] / 24.0;
            d = (d < 0.0) ? 0.0 : ((d > 1.0) ? 1.0 : d);
            duty[k] = (uint16_t)floor(d * 2000.0 + 0.5);
        }
        sim_rig_advance(&rig, duty, true);
    }
    r.vd = sum_vd / (double)n_avg;
    r.vq = sum_vq / (double)n_avg;
    r.id = sum_id / (double)n_avg;
    r.iq = sum_iq / (double)n_avg;
    return r;
}

static void test_ideal_foc_should_settle_at_the_steady_state_voltage_without_dead_time(void **state)
{
    sim_motor_params_t m;
    double rpms[3] = {500.0, 1000.0, 2000.0}, band;
    int k;
    (void)state;
    sim_motor_params_from_profile(sim_motor_profile("hurst"), &m);
    for (k = 0; k < 3; k++) {
        double we = (double)m.pole_pairs * rpms[k] * 2.0 * M_PI / 60.0;
        foc_result_t r = run_ideal_foc(0.0, rpms[k], 1.0, &band);
        double vd_ref = -we * m.lq_h * 1.0;
        double vq_ref = m.rs_ohm * 1.0 + we * m.psi_vs;
        printf("measured: ideal FOC, no dead time, %.0f rpm, iq 1 A: vd %.4f V (analytic %.4f), "
               "vq %.4f V (analytic %.4f), id %.4f A, iq %.4f A\n",
               rpms[k], r.vd, vd_ref, r.vq, vq_ref, r.id, r.iq);
        assert_cmp(fabs(r.iq - 1.0), <, 0.005);
        assert_cmp(fabs(r.id), <, 0.005);
        assert_cmp(fabs(r.vd - vd_ref), <, 0.005 * fabs(vq_ref));
        assert_cmp(fabs(r.vq - vq_ref), <, 0.005 * fabs(vq_ref));
    }
}

static void test_dead_time_should_cost_its_analytic_fundamental_along_the_current(void **state)
{
    double band, c = 0.0, b, expect;
    foc_result_t r0, r1;
    int k, K = 100000;
    (void)state;
    r0 = run_ideal_foc(0.0, 1000.0, 1.0, &band);
    r1 = run_ideal_foc(2e-6, 1000.0, 1.0, &band);
    b = band / 1.0;
    for (k = 0; k < K; k++) {
        double t = 2.0 * M_PI * ((double)k + 0.5) / (double)K;
        double s = sin(t) / b;
        s = (s > 1.0) ? 1.0 : ((s < -1.0) ? -1.0 : s);
        c += s * sin(t) * (2.0 * M_PI / (double)K) / M_PI;
    }
    expect = c * 2e-6 * 20000.0 * 24.0;
    printf("measured: dead time 2 us at 1000 rpm, 1 A: extra vq %.4f V (expected c Td/Ts Vbus = "
           "%.4f V, c = %.4f, 4/pi = %.4f, band %.4f A), extra vd %.4f V\n",
           r1.vq - r0.vq, expect, c, 4.0 / M_PI, band, r1.vd - r0.vd);
    assert_cmp(fabs((r1.vq - r0.vq) - expect), <, 0.03 * expect);
    assert_cmp(fabs(r1.vd - r0.vd), <, 0.05 * expect);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(
            test_ideal_foc_should_settle_at_the_steady_state_voltage_without_dead_time),
        cmocka_unit_test(test_dead_time_should_cost_its_analytic_fundamental_along_the_current),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
