/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_sim_plant.c - the PMSM plant against analytic solutions. */
#include "test_support.h"

#include <math.h>
#include <stdio.h>

#include "sim_plant.h"
#include "sim_profiles.h"

static sim_motor_params_t hurst(void)
{
    sim_motor_params_t m;
    sim_motor_params_from_profile(sim_motor_profile("hurst"), &m);
    return m;
}

static void test_psi_from_ke_should_give_the_hurst_flux_linkage_and_rated_torque(void **state)
{
    const sim_motor_profile_t *mp = sim_motor_profile("hurst");
    double p = (double)mp->pole_pairs;
    double psi = sim_psi_from_ke(mp->ke_ll, mp->pole_pairs);
    /* Ke / sqrt(3) peak phase at we = 1000 * 2 pi / 60 * p rad/s. */
    double expect = mp->ke_ll / sqrt(3.0) / (1000.0 * 2.0 * M_PI / 60.0 * p);
    (void)state;
    printf("measured: hurst psi = %.6f V s/rad, Kt = %.5f N m/A, rated torque = %.4f N m\n", psi,
           1.5 * p * psi, sim_motor_rated_torque(mp));
    assert_cmp(fabs(psi - expect), <, 1e-12);
    assert_cmp(fabs(psi - 0.0080492), <, 1e-6);
    assert_cmp(fabs(sim_motor_rated_torque(mp) - 0.0990), <, 0.001);
    assert_non_null(sim_motor_profile("hurst300"));
    assert_non_null(sim_motor_profile("hispeed"));
    assert_non_null(sim_board_profile("mclv"));
    assert_non_null(sim_board_profile("mchv"));
    assert_null(sim_motor_profile("nonesuch"));
}

static void test_plant_should_follow_the_rl_step_response_with_the_rotor_locked(void **state)
{
    sim_motor_params_t m = hurst();
    sim_plant_t p;
    double h = 50e-6 / 4.0, t = 0.0, v = 5.0;
    double tau = m.ld_h / m.rs_ohm;
    err_stats_t e;
    int n;
    (void)state;
    err_stats_init(&e);
    sim_plant_init(&p, &m, 0.0);
    p.s.locked = true;
    for (n = 0; n < 400; n++) {
        double ref;
        sim_plant_step(&p, v, 0.0, h, false);
        t += h;
        ref = v / m.rs_ohm * (1.0 - exp(-t / tau));
        err_stats_add(&e, p.s.id - ref, t);
        assert_cmp(fabs(p.s.iq), <, 1e-12);
    }
    err_stats_print("locked-rotor RL step id vs V/R(1-exp(-t/tau))", &e, "A");
    assert_cmp(e.max_abs, <, 1e-7);
    assert_cmp(p.s.omega_m, ==, 0.0);
}

static void
test_plant_should_accelerate_at_torque_over_inertia_and_settle_with_viscous_friction(void **state)
{
    sim_motor_params_t m = hurst();
    sim_plant_t p;
    double h = 12.5e-6, t = 0.0, drive = 0.01;
    err_stats_t e1, e2;
    int n;
    (void)state;
    err_stats_init(&e1);
    err_stats_init(&e2);
    m.b_nms = 0.0;
    m.coulomb_nm = 0.0;
    sim_plant_init(&p, &m, 0.0);
    p.load.active_nm = -drive; /* a forward-driving torque */
    for (n = 0; n < 20000; n++) {
        sim_plant_step(&p, 0.0, 0.0, h, true);
        t += h;
        err_stats_add(&e1, p.s.omega_m - drive / m.j_kgm2 * t, t);
    }
    err_stats_print("omega vs T/J t", &e1, "rad/s");
    assert_cmp(e1.max_abs, <, 1e-9 * drive / m.j_kgm2 * t + 1e-9);
    /* theta_m = 1/2 a t^2 */
    assert_cmp(fabs(p.s.theta_m - 0.5 * drive / m.j_kgm2 * t * t), <, 1e-6 * p.s.theta_m);

    m.b_nms = 3e-5;
    sim_plant_init(&p, &m, 0.0);
    p.load.active_nm = -drive;
    t = 0.0;
    for (n = 0; n < 40000; n++) {
        double ref;
        sim_plant_step(&p, 0.0, 0.0, h, true);
        t += h;
        ref = drive / m.b_nms * (1.0 - exp(-t * m.b_nms / m.j_kgm2));
        err_stats_add(&e2, p.s.omega_m - ref, t);
    }
    err_stats_print("omega vs T/B (1-exp(-tB/J))", &e2, "rad/s");
    assert_cmp(e2.max_abs, <, 1e-6);
}

static void test_plant_should_hold_the_rotor_while_the_passive_load_exceeds_the_drive(void **state)
{
    sim_motor_params_t m = hurst();
    sim_plant_t p;
    double h = 12.5e-6, t = 0.0, w_prev = 0.0;
    int n;
    (void)state;
    m.b_nms = 0.0;
    sim_plant_init(&p, &m, 0.3);
    p.load.passive_nm = 0.05;
    p.load.active_nm = -0.04; /* drives forward, but less than 0.05 + 1 mN m */
    for (n = 0; n < 8000; n++) {
        sim_plant_step(&p, 0.0, 0.0, h, true);
    }
    assert_cmp(p.s.omega_m, ==, 0.0);
    assert_cmp(fabs(p.s.theta_e - 0.3), <, 1e-12);
    p.load.active_nm = -0.07; /* now 0.019 N m net forward */
    for (n = 0; n < 8000; n++) {
        sim_plant_step(&p, 0.0, 0.0, h, true);
        t += h;
    }
    printf("measured: breakaway acceleration %.3f rad/s^2, expected %.3f\n", p.s.omega_m / t,
           (0.07 - 0.05 - m.coulomb_nm) / m.j_kgm2);
    assert_cmp(fabs(p.s.omega_m / t - (0.07 - 0.05 - m.coulomb_nm) / m.j_kgm2), <, 1e-6 * 2700.0);
    /* Remove the drive: the passive torque brakes it to rest, no reversal. */
    p.load.active_nm = 0.0;
    for (n = 0; n < 40000; n++) {
        sim_plant_step(&p, 0.0, 0.0, h, true);
        assert_cmp(p.s.omega_m, >=, 0.0);
        assert_true(p.s.omega_m <= w_prev || n == 0);
        w_prev = p.s.omega_m;
    }
    assert_cmp(p.s.omega_m, ==, 0.0);
    assert_true(p.s.stuck);
}

/* Rotating voltage that holds (id, iq) at constant speed, from the steady-state equations. */
static void steady_voltage(const sim_motor_params_t *m, double we, double id, double iq, double *vd,
                           double *vq)
{
    *vd = m->rs_ohm * id - we * m->lq_h * iq;
    *vq = m->rs_ohm * iq + we * (m->ld_h * id + m->psi_vs);
}

static void
test_plant_should_settle_at_the_analytic_currents_torque_and_power_at_constant_speed(void **state)
{
    sim_motor_params_t m = hurst();
    double rpms[3] = {500.0, 2000.0, 5000.0};
    double ids[3] = {0.0, -0.5, -2.0};
    int k;
    (void)state;
    m.lq_h = 1.5 * m.ld_h; /* saliency, so the reluctance torque term is exercised */
    m.j_kgm2 = 1e6;        /* speed held */
    m.b_nms = 0.0;
    m.coulomb_nm = 0.0;
    for (k = 0; k < 3; k++) {
        sim_plant_t p;
        double wm = rpms[k] * 2.0 * M_PI / 60.0, we = (double)m.pole_pairs * wm;
        double id = ids[k], iq = 1.2, vd, vq, h = 12.5e-6;
        double te_ref = 1.5 * (double)m.pole_pairs * (m.psi_vs * iq + (m.ld_h - m.lq_h) * id * iq);
        double p_in, p_out;
        int n;
        sim_plant_init(&p, &m, 1.0);
        p.s.omega_m = wm;
        p.s.stuck = false;
        steady_voltage(&m, we, id, iq, &vd, &vq);
        for (n = 0; n < 8000 * 4; n++) {
            /* the voltage vector at the sub-step's mid angle */
            double th = p.s.theta_e + 0.5 * we * h;
            double va = vd * cos(th) - vq * sin(th);
            double vb = vd * sin(th) + vq * cos(th);
            sim_plant_step(&p, va, vb, h, false);
        }
        p_in = 1.5 * (vd * p.s.id + vq * p.s.iq);
        p_out = 1.5 * m.rs_ohm * (p.s.id * p.s.id + p.s.iq * p.s.iq) + sim_plant_torque(&p) * wm;
        printf("measured: %.0f rpm: id %.5f (ref %.2f), iq %.5f (ref %.2f), Te %.6f (ref %.6f) "
               "N m, power balance %.2e W of %.3f W\n",
               rpms[k], p.s.id, id, p.s.iq, iq, sim_plant_torque(&p), te_ref, p_in - p_out, p_in);
        assert_cmp(fabs(p.s.id - id), <, 1e-3);
        assert_cmp(fabs(p.s.iq - iq), <, 1e-3);
        assert_cmp(fabs(sim_plant_torque(&p) - te_ref), <, 1e-3 * fabs(te_ref));
        assert_cmp(fabs(p_in - p_out), <, 1e-3 * fabs(p_in));
    }
}

static void test_plant_should_report_phase_currents_and_back_emf_of_the_catalogue(void **state)
{
    sim_motor_params_t m = hurst();
    sim_plant_t p;
    double ia, ib, ic;
    err_stats_t e;
    int k;
    (void)state;
    err_stats_init(&e);
    sim_plant_init(&p, &m, 0.0);
    p.s.omega_m = 1000.0 * 2.0 * M_PI / 60.0;
    /* the catalogue's peak line-to-line volts per 1000 rpm */
    assert_cmp(fabs(sim_plant_emf_ll_peak(&p) - sim_motor_profile("hurst")->ke_ll), <, 1e-9);
    assert_cmp(fabs(sim_plant_rpm(&p) - 1000.0), <, 1e-9);
    for (k = 0; k < 360; k++) {
        double th = (double)k * M_PI / 180.0;
        p.s.theta_e = sim_wrap_pi(th);
        p.s.id = 0.3;
        p.s.iq = 1.1;
        sim_plant_currents(&p, &ia, &ib, &ic);
        /* amplitude-invariant: ia = |i| cos(theta + atan2(iq, id)) */
        err_stats_add(&e, ia - hypot(0.3, 1.1) * cos(th + atan2(1.1, 0.3)), th);
        err_stats_add(&e, ib - hypot(0.3, 1.1) * cos(th + atan2(1.1, 0.3) - 2.0 * M_PI / 3.0), th);
        err_stats_add(&e, ia + ib + ic, th);
    }
    err_stats_print("phase currents vs |i| cos(theta + phi - k 120 deg)", &e, "A");
    assert_cmp(e.max_abs, <, 1e-12);
    assert_cmp(fabs(sim_wrap_pi(3.5 * M_PI) + 0.5 * M_PI), <, 1e-12);
    assert_cmp(sim_wrap_pi(M_PI), ==, -M_PI);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_psi_from_ke_should_give_the_hurst_flux_linkage_and_rated_torque),
        cmocka_unit_test(test_plant_should_follow_the_rl_step_response_with_the_rotor_locked),
        cmocka_unit_test(
            test_plant_should_accelerate_at_torque_over_inertia_and_settle_with_viscous_friction),
        cmocka_unit_test(test_plant_should_hold_the_rotor_while_the_passive_load_exceeds_the_drive),
        cmocka_unit_test(
            test_plant_should_settle_at_the_analytic_currents_torque_and_power_at_constant_speed),
        cmocka_unit_test(test_plant_should_report_phase_currents_and_back_emf_of_the_catalogue),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
