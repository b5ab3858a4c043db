/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_sim_bench.c - inverter, ADC and the period timing of the simulator's bench. */
#include "test_support.h"

#include <math.h>
#include <stdio.h>

#include "sim_adc.h"
#include "sim_inverter.h"
#include "sim_profiles.h"
#include "sim_rig.h"

/* The Hurst's inductance, H: the automatic dead-time band's. */
static double hurst_l(void)
{
    return sim_motor_profile("hurst")->l_h;
}

static sim_inverter_params_t mclv_inv(void)
{
    sim_inverter_params_t p = {
        24.0, 0.0, 0.0, 2e-6, 20000.0, 2000.0, 0.05, SIM_INV_AVERAGED, SIM_DT_LINEAR, 0.0, 0.0};
    return p;
}

static void test_inverter_should_apply_duty_times_vbus_minus_dead_time_by_current_sign(void **state)
{
    sim_inverter_params_t prm = mclv_inv();
    sim_inverter_t inv;
    uint16_t d;
    err_stats_t e;
    (void)state;
    err_stats_init(&e);
    sim_inverter_init(&inv, &prm, hurst_l());
    for (d = 0; d <= 2000; d++) {
        uint16_t duty[3] = {d, d, d};
        double i[3] = {1.0, -1.0, 0.0};
        double v[3], df = (double)d / 2000.0;
        double e_plus, e_minus;
        sim_inverter_latch(&inv, duty, true);
        sim_inverter_pins(&inv, 24.0, i, v);
        if (d == 0) {
            e_plus = 0.0;
            e_minus = 0.0;
        } else if (d == 2000) {
            e_plus = 24.0;
            e_minus = 24.0;
        } else {
            /* Td/Ts = 2 us * 20 kHz = 0.04 of the bus, clamped to the rails */
            e_plus = fmax(0.0, (df - 0.04) * 24.0);
            e_minus = fmin(24.0, (df + 0.04) * 24.0);
        }
        err_stats_add(&e, v[0] - e_plus, df);
        err_stats_add(&e, v[1] - e_minus, df);
        err_stats_add(&e, v[2] - df * 24.0, df);
    }
    err_stats_print("pin voltage vs (d -+ Td/Ts) Vbus", &e, "V");
    assert_cmp(e.max_abs, <, 1e-12);
    {
        /* inside the band the error is proportional to the current */
        uint16_t duty[3] = {1000, 1000, 1000};
        double i[3] = {0.025, -0.0125, -0.0125}, v[3];
        sim_inverter_latch(&inv, duty, true);
        sim_inverter_pins(&inv, 24.0, i, v);
        assert_cmp(fabs(v[0] - (0.5 - 0.04 * 0.5) * 24.0), <, 1e-12);
        assert_cmp(fabs(v[1] - (0.5 + 0.04 * 0.25) * 24.0), <, 1e-12);
    }
    /* automatic band = Vbus / (12 L fpwm) */
    prm.i_band_a = 0.0;
    sim_inverter_init(&inv, &prm, hurst_l());
    printf("measured: automatic dead-time band for the Hurst on 24 V = %.4f A\n", inv.i_band_a);
    assert_cmp(fabs(inv.i_band_a - 24.0 / (12.0 * hurst_l() * 20000.0)), <, 1e-12);
}

/* Mean pin voltage of the switching model over one period, integrated
 * exactly between its edges (the pins are constant in between). */
static void switching_mean(const sim_inverter_t *inv, const double i[3], double mean[3])
{
    double ts = 1.0 / inv->prm.pwm_hz, edge[SIM_INV_MAX_EDGES + 1], a = 0.0;
    int n = sim_inverter_edges(inv, 0.0, ts, edge), k, j;
    mean[0] = mean[1] = mean[2] = 0.0;
    for (k = 1; k < n; k++) {
        assert_cmp(edge[k], >=, edge[k - 1]); /* ascending */
    }
    edge[n] = ts;
    for (k = 0; k <= n; k++) {
        double v[3];
        sim_inverter_pins_at(inv, 24.0, i, a, v);
        for (j = 0; j < 3; j++) {
            mean[j] += v[j] * (edge[k] - a) / ts;
        }
        a = edge[k];
    }
}

/* The switching model against the averaged one's hard-sign shape, which
 * is its period mean when the current keeps its sign: (d - Td/Ts s) Vbus.
 * Diode drops add 2 Td/Ts Vf of loss; a high pulse shorter than the dead
 * time vanishes; 0 and 100 % have no edge. */
static void test_switching_inverter_should_average_to_the_hard_sign_dead_time(void **state)
{
    sim_inverter_params_t prm = mclv_inv();
    sim_inverter_t inv, avg;
    uint16_t duty[3] = {1300, 700, 1000};
    double i[3] = {1.0, -0.4, -0.6}, m[3], v[3];
    int k;
    (void)state;
    prm.model = SIM_INV_SWITCHING;
    sim_inverter_init(&inv, &prm, hurst_l());
    sim_inverter_latch(&inv, duty, true);
    prm.model = SIM_INV_AVERAGED;
    prm.dt_shape = SIM_DT_HARD;
    sim_inverter_init(&avg, &prm, hurst_l());
    sim_inverter_latch(&avg, duty, true);
    switching_mean(&inv, i, m);
    sim_inverter_pins(&avg, 24.0, i, v);
    for (k = 0; k < 3; k++) {
        double want = ((double)duty[k] / 2000.0 - 0.04 * ((i[k] > 0.0) ? 1.0 : -1.0)) * 24.0;
        printf("measured: phase %d: switching mean %.6f V, hard-sign averaged %.6f V\n", k, m[k],
               v[k]);
        assert_cmp(fabs(m[k] - want), <, 1e-9);
        assert_cmp(fabs(v[k] - want), <, 1e-9);
    }
    /* diode drop: the two dead times of a current into the motor at -Vf */
    inv.prm.v_diode_v = 0.7;
    switching_mean(&inv, i, m);
    assert_cmp(fabs(m[0] - ((1300.0 / 2000.0 - 0.04) * 24.0 - 0.08 * 0.7)), <, 1e-9);
    assert_cmp(fabs(m[1] - ((700.0 / 2000.0 + 0.04) * 24.0 + 0.08 * 0.7)), <, 1e-9);
    /* switch resistance: i r_on off the pin while a switch conducts (92 %) */
    inv.prm.v_diode_v = 0.0;
    inv.prm.r_on_ohm = 0.1;
    switching_mean(&inv, i, m);
    assert_cmp(fabs(m[0] - ((1300.0 / 2000.0 - 0.04) * 24.0 - 0.92 * 0.1)), <, 1e-9);
    /* a pulse shorter than the dead time (h = 1 us < 2 us), and no edges */
    {
        uint16_t d2[3] = {40, 0, 2000};
        inv.prm.r_on_ohm = 0.0;
        sim_inverter_latch(&inv, d2, true);
        assert_int_equal(sim_inverter_edges(&inv, 0.0, 50e-6, (double[SIM_INV_MAX_EDGES]){0}), 4);
        switching_mean(&inv, i, m);
        assert_cmp(fabs(m[0]), <, 1e-9);        /* high never on, low diode in the gaps */
        assert_cmp(fabs(m[1]), <, 1e-9);        /* low side all period */
        assert_cmp(fabs(m[2] - 24.0), <, 1e-9); /* high side all period */
    }
}

/* The averaged model's three dead-time shapes near zero current. */
static void test_averaged_inverter_should_offer_three_dead_time_shapes(void **state)
{
    sim_inverter_params_t prm = mclv_inv(); /* band 0.05 A */
    sim_inverter_t inv;
    uint16_t duty[3] = {1000, 1000, 1000};
    double i[3] = {0.025, -0.0125, -0.0125}, v[3];
    const double half = 0.5 * 24.0, err = 0.04 * 24.0;
    (void)state;
    prm.dt_shape = SIM_DT_HARD;
    sim_inverter_init(&inv, &prm, hurst_l());
    sim_inverter_latch(&inv, duty, true);
    sim_inverter_pins(&inv, 24.0, i, v);
    assert_cmp(fabs(v[0] - (half - err)), <, 1e-12);
    assert_cmp(fabs(v[1] - (half + err)), <, 1e-12);
    inv.prm.dt_shape = SIM_DT_RIPPLE; /* (2 / pi) asin(0.5) = 1/3 */
    sim_inverter_pins(&inv, 24.0, i, v);
    assert_cmp(fabs(v[0] - (half - err / 3.0)), <, 1e-12);
    inv.prm.dt_shape = SIM_DT_LINEAR;
    sim_inverter_pins(&inv, 24.0, i, v);
    assert_cmp(fabs(v[0] - (half - err * 0.5)), <, 1e-12);
}

static void test_inverter_should_float_the_star_point_and_ripple_the_bus(void **state)
{
    sim_inverter_params_t prm = mclv_inv();
    sim_inverter_t inv;
    double v[3] = {10.0, 10.0, 10.0}, va, vb, sum = 0.0, vmax = 0.0, vmin = 100.0;
    int k;
    (void)state;
    sim_pins_to_ab(v, &va, &vb);
    assert_cmp(fabs(va), <, 1e-12);
    assert_cmp(fabs(vb), <, 1e-12);
    /* pins 12 + A cos(th - k 120): alpha-beta amplitude A, angle th */
    for (k = 0; k < 3; k++) {
        v[k] = 12.0 + 5.0 * cos(0.7 - (double)k * 2.0 * M_PI / 3.0);
    }
    sim_pins_to_ab(v, &va, &vb);
    assert_cmp(fabs(va - 5.0 * cos(0.7)), <, 1e-12);
    assert_cmp(fabs(vb - 5.0 * sin(0.7)), <, 1e-12);

    prm.ripple_v = 2.0;
    prm.ripple_hz = 100.0;
    sim_inverter_init(&inv, &prm, hurst_l());
    for (k = 0; k < 2000; k++) {
        double x = sim_inverter_vbus(&inv, (double)k * 1e-5);
        sum += x;
        vmax = fmax(vmax, x);
        vmin = fmin(vmin, x);
    }
    printf("measured: bus with 2 V ripple: mean %.4f, max %.4f, min %.4f V\n", sum / 2000.0, vmax,
           vmin);
    assert_cmp(fabs(sum / 2000.0 - 24.0), <, 1e-9);
    assert_cmp(fabs(vmax - 26.0), <, 1e-3);
    assert_cmp(fabs(vmin - 22.0), <, 1e-3);
}

static sim_adc_params_t mclv_adc(double noise)
{
    sim_adc_params_t a = {4.4, 52.8, 10, 0.0, 0.0, noise, 12345u};
    return a;
}

static void test_adc_should_quantise_to_64_lsb_steps_and_saturate_at_full_scale(void **state)
{
    sim_adc_params_t prm = mclv_adc(0.0);
    sim_adc_t adc;
    err_stats_t e;
    double x;
    (void)state;
    err_stats_init(&e);
    sim_adc_init(&adc, &prm);
    for (x = -4.39; x < 4.39; x += 0.0007) {
        int16_t q = sim_adc_bipolar(&adc, x / 4.4, 0.0);
        assert_cmp(q % 64, ==, 0);
        err_stats_add(&e, (double)q - x / 4.4 * 32768.0, x);
    }
    err_stats_print("bipolar ADC vs 32768 x / fs", &e, "Q15 LSB");
    assert_cmp(e.max_abs, <=, 32.0 + 1e-9);
    assert_int_equal(sim_adc_bipolar(&adc, 6.0 / 4.4, 0.0), 32704);
    assert_int_equal(sim_adc_bipolar(&adc, -6.0 / 4.4, 0.0), -32768);
    assert_int_equal(sim_adc_bipolar(&adc, 0.0, 6.0), 384);
    assert_int_equal(sim_adc_bipolar(&adc, 0.0, -4.0), -256);
    err_stats_init(&e);
    for (x = 0.0; x < 52.7; x += 0.01) {
        int16_t q = sim_adc_unipolar(&adc, x / 52.8);
        assert_cmp(q % 32, ==, 0);
        assert_cmp(q, >=, 0);
        err_stats_add(&e, (double)q - x / 52.8 * 32768.0, x);
    }
    err_stats_print("unipolar ADC vs 32768 v / fs", &e, "Q15 LSB");
    assert_cmp(e.max_abs, <=, 16.0 + 1e-9);
    assert_int_equal(sim_adc_unipolar(&adc, 2.0), 32736);
    assert_int_equal(sim_adc_unipolar(&adc, -1.0), 0);
}

static void test_adc_noise_should_have_the_requested_sigma_and_zero_mean(void **state)
{
    sim_adc_params_t prm = mclv_adc(1.5);
    sim_adc_t adc;
    double s = 0.0, s2 = 0.0, sd;
    int n, N = 200000;
    (void)state;
    sim_adc_init(&adc, &prm);
    for (n = 0; n < N; n++) {
        /* half a code above a transition so the rounding adds no bias */
        double c = (double)sim_adc_bipolar(&adc, 0.0, 0.0) / 64.0;
        s += c;
        s2 += c * c;
    }
    sd = sqrt(s2 / N - (s / N) * (s / N));
    printf("measured: ADC noise mean %.4f codes, sigma %.4f codes (requested 1.5, plus "
           "quantisation 0.29)\n",
           s / N, sd);
    /* sigma of round(1.5 N(0,1)) is sqrt(1.5^2 + 1/12) = 1.527 */
    assert_cmp(fabs(sd - sqrt(1.5 * 1.5 + 1.0 / 12.0)), <, 0.02);
    assert_cmp(fabs(s / N), <, 0.02);
}

static sim_rig_params_t hurst_rig(void)
{
    sim_rig_params_t r;
    sim_motor_params_from_profile(sim_motor_profile("hurst"), &r.motor);
    r.inv = mclv_inv();
    r.inv.i_band_a = 0.0;
    r.adc = mclv_adc(0.0);
    r.substeps = 4;
    r.sample_at = 0.0; /* the period-level expectations below: sample at the start */
    r.amp_tau_s = 0.0; /* ideal current sensors (the shunt window is tested with the core) */
    r.theta_e0 = 0.0;
    r.omega0_m = 0.0;
    r.fan_rated_rpm = sim_motor_profile("hurst")->rated_rpm;
    r.bus_c_f = 0.0; /* the bus held at the supply's level (the bus model's tests set it) */
    r.supply_r_ohm = 0.0;
    return r;
}

/* ---- the bus model (sim_rig.h note 2) ---------------------------------------------------- */

/* The MCLV's bus model: its capacitor and supply resistance (boards/board_mclv.h). */
static sim_rig_params_t bus_rig(double rpm0)
{
    sim_rig_params_t prm = hurst_rig();
    prm.bus_c_f = sim_board_profile("mclv")->bus_c_f;
    prm.supply_r_ohm = sim_board_profile("mclv")->supply_r_ohm;
    prm.omega0_m = rpm0 * 2.0 * M_PI / 60.0;
    return prm;
}

/* A supply that rises from 24 to 30 V charges the capacitor through R: v = 30 - 6 e^(-t/RC)
 * at every period; one that falls to 20 V takes nothing back: the capacitor stays at 30 V
 * with the outputs off and the rotor at rest. */
static void test_bus_model_should_charge_through_r_and_never_discharge_into_the_supply(void **state)
{
    sim_rig_params_t prm = bus_rig(0.0);
    static sim_rig_t rig;
    sim_adc_frame_t f;
    uint16_t off[3] = {1000, 1000, 1000};
    sim_event_t up = {0};
    double tau = prm.bus_c_f * prm.supply_r_ohm, worst = 0.0;
    (void)state;
    assert_cmp(tau, >, 0.0);
    sim_rig_init(&rig, &prm);
    up.kind = SIM_EV_VBUS;
    up.v1 = 30.0;
    assert_true(sim_rig_apply(&rig, &up));
    for (int n = 1; n <= 40; n++) {
        sim_rig_advance(&rig, off, false);
        sim_rig_sample(&rig, &f);
        double want = 30.0 - 6.0 * exp(-(double)n * 50e-6 / tau);
        worst = fmax(worst, fabs(rig.vcap_v - want));
        assert_cmp(fabs(rig.vbus_sampled - rig.vcap_v), <, 1e-12); /* the ADC reads it */
    }
    printf("measured: a 24 -> 30 V supply step into %.0f uF through %.2f ohm: |v - (30 - 6 "
           "e^(-t/RC))| "
           "<= %.2e V over 40 periods\n",
           prm.bus_c_f * 1e6, prm.supply_r_ohm, worst);
    assert_cmp(worst, <, 1e-9);
    up.v1 = 20.0;
    assert_true(sim_rig_apply(&rig, &up));
    for (int n = 0; n < 200; n++) {
        sim_rig_advance(&rig, off, false);
    }
    assert_cmp(fabs(rig.vcap_v - 30.0), <, 1e-6);
}

/* A rotor spinning at 5,000 rpm with the outputs off: its line-to-line back-EMF (36.5 V peak)
 * is above the bus, the diodes rectify it into the capacitor, which the supply cannot drain.
 * The energy the inverter put into the bus is the capacitor's gain while the supply is
 * blocked, and no more than the rotor lost; the bus rises above the supply and below the
 * back-EMF's peak. */
static void test_bus_model_should_take_a_spinning_rotors_rectified_energy(void **state)
{
    sim_rig_params_t prm = bus_rig(5000.0);
    static sim_rig_t rig;
    uint16_t off[3] = {1000, 1000, 1000};
    (void)state;
    prm.motor.b_nms = 0.0;
    prm.motor.coulomb_nm = 0.0;
    sim_rig_init(&rig, &prm);
    double w0 = rig.plant.s.omega_m;
    double emf_pk = sim_plant_emf_ll_peak(&rig.plant);
    for (int n = 0; n < 2000; n++) { /* 0.1 s */
        sim_rig_advance(&rig, off, false);
    }
    double w1 = rig.plant.s.omega_m;
    double e_kin = 0.5 * prm.motor.j_kgm2 * (w0 * w0 - w1 * w1);
    double e_cap = 0.5 * prm.bus_c_f * (rig.vcap_v * rig.vcap_v - 24.0 * 24.0);
    printf("measured: outputs off at 5000 rpm (%.1f V LL peak): the bus %.2f V after 0.1 s (peak "
           "%.2f V), "
           "into it %.4f J, the capacitor's gain %.4f J, the rotor's loss %.4f J\n",
           emf_pk, rig.vcap_v, rig.vbus_peak_v, rig.e_bus_in_j, e_cap, e_kin);
    assert_cmp(rig.vbus_peak_v, >, 30.0);
    assert_cmp(rig.vbus_peak_v, <, emf_pk);
    assert_cmp(fabs(rig.e_bus_in_j - e_cap), <, 0.01 * e_cap);
    assert_cmp(rig.e_bus_in_j, <=, e_kin);
    assert_cmp(rig.e_bus_in_j, >, 0.5 * e_kin); /* the rest is the windings' copper loss */
}

static void test_rig_should_apply_the_duties_from_the_next_period(void **state)
{
    sim_rig_params_t prm = hurst_rig();
    sim_rig_t rig;
    sim_adc_frame_t f;
    uint16_t d[3] = {1400, 600, 1000};
    (void)state;
    prm.motor.coulomb_nm = 1.0; /* keep the rotor still */
    sim_rig_init(&rig, &prm);
    sim_rig_sample(&rig, &f);
    sim_rig_advance(&rig, d, true); /* period 0 runs with outputs off */
    sim_rig_sample(&rig, &f);
    assert_cmp(fabs(rig.i_abc[0]), <, 1e-12);
    assert_int_equal(f.ia, 0);
    sim_rig_advance(&rig, d, true); /* period 1 applies d */
    sim_rig_sample(&rig, &f);
    printf("measured: phase A current after one period of +9.6 V: %.4f A\n", rig.i_abc[0]);
    assert_cmp(rig.i_abc[0], >, 0.1);
    assert_cmp(rig.i_abc[1], <, -0.1);
    assert_cmp(f.ia, >, 0);
    assert_cmp(f.ib, <, 0);
    assert_cmp(fabs(rig.t - 2.0 * 50e-6), <, 1e-15);
    assert_int_equal(rig.period, 2);
}

/* The chip's timing: sample at a = 0.54 of the period, duties from the next
 * boundary. A voltage step commanded after sample 1 starts at the boundary,
 * a (1 - a) Ts later, so sample 2 sees it for a Ts and sample 3 for
 * (1 + a) Ts: with the rotor still (no back-EMF) and no dead time, phase A's
 * current is i_inf (1 - e^(-t / tau)), tau = L / R, at those two times. */
static void test_rig_should_sample_mid_period_and_apply_duties_from_the_boundary(void **state)
{
    sim_rig_params_t prm = hurst_rig();
    sim_rig_t rig;
    sim_adc_frame_t f;
    uint16_t off[3] = {1000, 1000, 1000};
    uint16_t d[3] = {1100, 950, 950};
    double i1, i2, i3, tau, want;
    (void)state;
    prm.motor.coulomb_nm = 1.0; /* keep the rotor still */
    prm.sample_at = 0.54;
    prm.inv.deadtime_s = 0.0;
    sim_rig_init(&rig, &prm);
    sim_rig_sample(&rig, &f);
    sim_rig_advance(&rig, off, true); /* balanced: no current */
    sim_rig_sample(&rig, &f);
    i1 = rig.i_abc[0];
    sim_rig_advance(&rig, d, true); /* d from the boundary after this sample */
    sim_rig_sample(&rig, &f);
    i2 = rig.i_abc[0];
    sim_rig_advance(&rig, d, true);
    sim_rig_sample(&rig, &f);
    i3 = rig.i_abc[0];
    tau = prm.motor.ld_h / prm.motor.rs_ohm;
    want = (1.0 - exp(-0.54 * 50e-6 / tau)) / (1.0 - exp(-1.54 * 50e-6 / tau));
    printf("measured: phase A after a Ts and (1 + a) Ts of the step: %.5f A, %.5f A, "
           "ratio %.4f (%.4f for a = 0.54; a sample at the period start would give 0)\n",
           i2, i3, i2 / i3, want);
    assert_cmp(fabs(i1), <, 1e-12);
    assert_cmp(i3, >, 0.01);
    assert_cmp(fabs(i2 / i3 - want), <, 0.002);
    assert_int_equal(rig.period, 3);
}

static void
test_rig_should_let_the_current_die_out_and_open_the_stator_when_switched_off(void **state)
{
    sim_rig_params_t prm = hurst_rig();
    sim_rig_t rig;
    sim_adc_frame_t f;
    uint16_t d[3] = {1300, 700, 1000}, off[3] = {1000, 1000, 1000};
    int n;
    double e0;
    (void)state;
    prm.motor.j_kgm2 = 1.0; /* speed nearly constant */
    prm.omega0_m = 1000.0 * 2.0 * M_PI / 60.0;
    sim_rig_init(&rig, &prm);
    for (n = 0; n < 40; n++) {
        sim_rig_sample(&rig, &f);
        sim_rig_advance(&rig, d, true);
    }
    assert_cmp(fabs(rig.i_abc[0]) + fabs(rig.i_abc[1]), >, 0.2);
    sim_rig_sample(&rig, &f);
    sim_rig_advance(&rig, off, false); /* the last on period */
    for (n = 0; n < 40; n++) {
        sim_rig_sample(&rig, &f);
        sim_rig_advance(&rig, off, false);
    }
    printf("measured: 2 ms after switch-off at 1000 rpm: ia %.2e ib %.2e A\n", rig.i_abc[0],
           rig.i_abc[1]);
    assert_cmp(fabs(rig.i_abc[0]), <, 1e-9);
    assert_cmp(fabs(rig.i_abc[1]), <, 1e-9);
    assert_true(rig.floating[0] && rig.floating[1] && rig.floating[2]);
    /* Above the bus (7.3 V/krpm: 24 V at 3288 rpm) the rectifier brakes the motor. */
    prm.omega0_m = 5000.0 * 2.0 * M_PI / 60.0;
    prm.motor.j_kgm2 = 1e-2;
    sim_rig_init(&rig, &prm);
    e0 = rig.plant.s.omega_m;
    for (n = 0; n < 200; n++) {
        sim_rig_sample(&rig, &f);
        sim_rig_advance(&rig, off, false);
    }
    printf("measured: switched off at 5000 rpm: torque %.4f N m, |i| %.3f A\n",
           sim_plant_torque(&rig.plant), hypot(rig.plant.s.id, rig.plant.s.iq));
    assert_cmp(sim_plant_torque(&rig.plant), <, -0.01);
    assert_cmp(rig.plant.s.omega_m, <, e0);
    prm.omega0_m = 3000.0 * 2.0 * M_PI / 60.0;
    sim_rig_init(&rig, &prm);
    for (n = 0; n < 200; n++) {
        sim_rig_sample(&rig, &f);
        sim_rig_advance(&rig, off, false);
    }
    assert_cmp(fabs(sim_plant_torque(&rig.plant)), <, 1e-12);
}

static void test_rig_should_apply_plant_events_and_leave_controller_events(void **state)
{
    sim_rig_params_t prm = hurst_rig();
    sim_rig_t rig;
    sim_adc_frame_t f;
    sim_event_t ev = {0.0, SIM_EV_LOAD, 0.05, 0.0};
    uint16_t d[3] = {1000, 1000, 1000};
    int n;
    (void)state;
    sim_rig_init(&rig, &prm);
    assert_true(sim_rig_apply(&rig, &ev));
    assert_cmp(rig.plant.load.passive_nm, ==, 0.05);
    ev.kind = SIM_EV_LOAD_FAN;
    ev.v1 = 0.1;
    assert_true(sim_rig_apply(&rig, &ev));
    assert_cmp(fabs(rig.plant.load.fan_k * pow(prm.fan_rated_rpm * M_PI / 30.0, 2.0) - 0.1), <,
               1e-12);
    ev.kind = SIM_EV_CURRENT_SPIKE;
    ev.v1 = 3.0;
    ev.v2 = 0.0;
    assert_true(sim_rig_apply(&rig, &ev));
    sim_rig_sample(&rig, &f);
    assert_int_equal(f.ia, (int16_t)(64 * 349)); /* round(3/4.4*512) = 349 codes */
    sim_rig_sample(&rig, &f);
    assert_int_equal(f.ia, 0);
    ev.kind = SIM_EV_POT_RAMP;
    ev.v1 = 1.0;
    ev.v2 = 0.01; /* 200 periods */
    assert_true(sim_rig_apply(&rig, &ev));
    for (n = 0; n < 100; n++) {
        sim_rig_advance(&rig, d, false);
    }
    assert_cmp(fabs(rig.pot - 0.5), <, 1e-9);
    for (n = 0; n < 150; n++) {
        sim_rig_advance(&rig, d, false);
    }
    assert_cmp(rig.pot, ==, 1.0);
    ev.kind = SIM_EV_START;
    assert_false(sim_rig_apply(&rig, &ev));
    ev.kind = SIM_EV_HW_FAULT;
    assert_false(sim_rig_apply(&rig, &ev));
    /* sensor drift: 2.2 A/s on phase A for 0.1 s builds 0.22 A (26 codes of
     * 4.4 A / 512); a rate of 0 then holds it; sensor_ok clears it */
    ev.kind = SIM_EV_SENSOR_DRIFT;
    ev.v1 = 0.0;
    ev.v2 = 2.2;
    assert_true(sim_rig_apply(&rig, &ev));
    for (n = 0; n < 2000; n++) {
        sim_rig_advance(&rig, d, false);
    }
    sim_rig_sample(&rig, &f);
    assert_int_equal(f.ia, (int16_t)(64 * 26));
    ev.v2 = 0.0;
    assert_true(sim_rig_apply(&rig, &ev));
    for (n = 0; n < 2000; n++) {
        sim_rig_advance(&rig, d, false);
    }
    sim_rig_sample(&rig, &f);
    assert_int_equal(f.ia, (int16_t)(64 * 26));
    ev.kind = SIM_EV_SENSOR_OK;
    assert_true(sim_rig_apply(&rig, &ev));
    sim_rig_sample(&rig, &f);
    assert_int_equal(f.ia, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(
            test_inverter_should_apply_duty_times_vbus_minus_dead_time_by_current_sign),
        cmocka_unit_test(test_switching_inverter_should_average_to_the_hard_sign_dead_time),
        cmocka_unit_test(test_averaged_inverter_should_offer_three_dead_time_shapes),
        cmocka_unit_test(test_inverter_should_float_the_star_point_and_ripple_the_bus),
        cmocka_unit_test(test_adc_should_quantise_to_64_lsb_steps_and_saturate_at_full_scale),
        cmocka_unit_test(test_adc_noise_should_have_the_requested_sigma_and_zero_mean),
        cmocka_unit_test(
            test_bus_model_should_charge_through_r_and_never_discharge_into_the_supply),
        cmocka_unit_test(test_bus_model_should_take_a_spinning_rotors_rectified_energy),
        cmocka_unit_test(test_rig_should_apply_the_duties_from_the_next_period),
        cmocka_unit_test(test_rig_should_sample_mid_period_and_apply_duties_from_the_boundary),
        cmocka_unit_test(
            test_rig_should_let_the_current_die_out_and_open_the_stator_when_switched_off),
        cmocka_unit_test(test_rig_should_apply_plant_events_and_leave_controller_events),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
