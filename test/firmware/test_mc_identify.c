/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_mc_identify.c - self-commissioning against the simulated motor (the build's profile
 * and plant): its figures, every way it ends without numbers, and random motors that take
 * its branches (a unit test, so the coverage build measures mc_id.c through it). */
#include "cl_helpers.h" /* test/closedloop: the simulator's run, events and start */

#include <string.h>

#if MC_IDENTIFY

/* Requests IDENTIFY and runs until the core is back in STOPPED or FAULT with
 * a final status, or max_s; returns the time it took. */
static double identify(simcore_t *s, double max_s)
{
    double t0 = s->rig.t, t_end = t0 + max_s;
    simcore_request(s, MC_REQUEST_IDENTIFY);
    do {
        simcore_step(s);
    } while (s->rig.t < t_end &&
             !((s->now.state == MC_STATE_STOPPED || s->now.state == MC_STATE_FAULT) &&
               (s->mc.id_status == MC_ID_DONE || s->mc.id_status == MC_ID_FAILED)));
    return s->rig.t - t0;
}

/* The build's motor (the plant of its profile) scaled, on the build's board. */
static void setup_motor(simcore_t *s, double rs, double l, double ke, double j)
{
    simcore_cfg_t cfg;
    simcore_cfg_default(&cfg);
    cfg.rs_scale = rs;
    cfg.l_scale = l;
    cfg.ke_scale = ke;
    cfg.j_scale = j;
    cfg.progress = false;
    assert_int_equal(simcore_init(s, &cfg), 0);
    cl_run(s, 0.02);
}

/* A failed run: the state expected (STOPPED; FAULT for a fault; running on
 * for a refused request), the outputs off unless running, the status FAILED
 * with the code, no numbers. */
static void expect_failure(simcore_t *s, unsigned error, mc_state_t state, const char *what)
{
    mc_id_result_t r;
    mc_identify_result(&s->mc, &r);
    printf("measured: %s: %s, error %s, state %s\n", what,
           (r.status == MC_ID_FAILED) ? "FAILED" : "not failed", mc_id_error_name(r.error),
           mc_state_name(s->now.state));
    assert_int_equal(r.status, MC_ID_FAILED);
    assert_int_equal(r.error, error);
    assert_int_equal(s->now.state, state);
    assert_int_equal(s->now.outputs_on, state == MC_STATE_CLOSED_LOOP);
    assert_int_equal(r.rs_uohm, 0);
    assert_int_equal(r.ls_nh, 0);
    assert_int_equal(r.ke_uv_per_rpm, 0);
}

static void test_the_motor_should_be_measured_within_its_figures_in_under_10_s(void **state)
{
    static simcore_t s;
    mc_id_result_t r;
    simcore_id_err_t e;
    double t;
    (void)state;
    setup_motor(&s, 1.0, 1.0, 1.0, 1.0);
    t = identify(&s, 30.0);
    mc_identify_result(&s.mc, &r);
    simcore_identify_errors(&s, &r, &e);
    printf("measured: the profile's motor: %.2f s; R %+.2f %%, Ld %+.2f %%, Lq %+.2f %%, L %+.2f "
           "%%, Ke %+.2f "
           "%%, J %+.2f %%, "
           "dead time %+.2f %%; peak phase current %.2f A (MC_ID_CURRENT_A %.2f A)\n",
           t, e.rs, e.ld, e.lq, e.ls, e.ke, e.j, e.deadtime, s.log.i_peak_a,
           (double)MC_ID_CURRENT_A);
    assert_int_equal(r.status, MC_ID_DONE);
    assert_int_equal(s.now.state, MC_STATE_STOPPED);
    assert_false(s.now.outputs_on);
    assert_true(t < 10.0);
    assert_true(fabs(e.rs) < 1.0);
    assert_true(fabs(e.ld) < 2.0 && fabs(e.lq) < 2.0 && fabs(e.ls) < 2.0);
    assert_true(fabs(e.ke) < 1.0);
    assert_true(fabs(e.j) < 10.0);
    assert_true(fabs(e.deadtime) < 5.0);
    assert_true(s.log.i_peak_a < 1.6 * (double)MC_ID_CURRENT_A);
    assert_int_equal(r.pole_pairs, MOTOR_POLE_PAIRS);
    /* and the motor then starts as usual (the drive's build; the commissioning image has
     * nothing else to run) */
    if (MC_DRIVE) {
        cl_start_and_reach(&s, 0.5 * (SPEED_REF_MIN_RPM + SPEED_REF_MAX_RPM), 8.0);
    }
}

/* Where the sequence cannot measure, it says so and gives no numbers: a
 * rotor the spin's current cannot carry at the second speed. The profile's
 * motor with 50 times its viscous friction (0.77 mN m s/rad): at the first
 * speed (about 11 rev/s) the friction takes some 0.05 N m, at twice it
 * 0.11 N m, near the most the identification's whole current gives (0.12
 * N m at MC_ID_CURRENT_A, the load angle at 90 degrees), and the rotor
 * slips out of step on the way: |E| at the second hold is a fraction of
 * twice the first's, NO_SYNC (docs/identify.md). (The motor this test had,
 * R x3.7 L x0.34 Ke x4 J x0.5, ended NO_SYNC only because the spin took
 * the swing at its start for the first speed and held it at a thirteenth
 * of it; the spin now waits for the swing's mean and measures it, Ke
 * within 1 %.) */
static void test_a_motor_the_spin_cannot_hold_should_end_in_no_sync(void **state)
{
    static simcore_t s;
    simcore_cfg_t cfg;
    (void)state;
    simcore_cfg_default(&cfg);
    cfg.b_scale = 50.0;
    cfg.theta0_rad = 1.4;
    cfg.progress = false;
    assert_int_equal(simcore_init(&s, &cfg), 0);
    cl_run(&s, 0.02);
    identify(&s, 40.0);
    expect_failure(&s, MC_ID_ERROR_NO_SYNC, MC_STATE_STOPPED,
                   "a rotor whose friction the current cannot carry at the second speed");
}

static void test_a_cut_lead_should_end_in_open_phase(void **state)
{
    static simcore_t s;
    int lead;
    (void)state;
    for (lead = 0; lead < 3; lead++) {
        char what[32];
        setup_motor(&s, 1.0, 1.0, 1.0, 1.0);
        cl_event(&s, SIM_EV_OPEN_LEAD, (double)lead, 0.0);
        identify(&s, 30.0);
        snprintf(what, sizeof what, "lead %c cut", 'A' + lead);
        expect_failure(&s, MC_ID_ERROR_OPEN_PHASE, MC_STATE_STOPPED, what);
    }
}

static void test_a_locked_rotor_should_end_in_rotor_locked(void **state)
{
    static simcore_t s;
    (void)state;
    setup_motor(&s, 1.0, 1.0, 1.0, 1.0);
    cl_event(&s, SIM_EV_LOCK_ROTOR, 0.0, 0.0);
    identify(&s, 30.0);
    expect_failure(&s, MC_ID_ERROR_ROTOR_LOCKED, MC_STATE_STOPPED, "locked rotor");
}

static void test_a_motor_too_small_for_the_current_resolution_should_end_in_too_small(void **state)
{
    static simcore_t s;
    (void)state;
    /* R x60: at the largest voltage the measurement allows, under 16 ADC codes of current */
    setup_motor(&s, 60.0, 1.0, 1.0, 1.0);
    identify(&s, 30.0);
    expect_failure(&s, MC_ID_ERROR_TOO_SMALL, MC_STATE_STOPPED, "R x60");
    /* nothing that conducts: R and L x1000 (the same L / R, a current under 4 codes) */
    setup_motor(&s, 1000.0, 1000.0, 1.0, 1.0);
    identify(&s, 30.0);
    expect_failure(&s, MC_ID_ERROR_OPEN_CIRCUIT, MC_STATE_STOPPED, "no motor");
}

static void test_a_stop_during_identification_should_end_it_at_once(void **state)
{
    static simcore_t s;
    double t_stop;
    (void)state;
    setup_motor(&s, 1.0, 1.0, 1.0, 1.0);
    simcore_request(&s, MC_REQUEST_IDENTIFY);
    cl_run(&s, 1.5); /* into the spin */
    assert_int_equal(s.now.state, MC_STATE_IDENTIFY);
    t_stop = s.rig.t;
    simcore_request(&s, MC_REQUEST_STOP);
    simcore_step(&s);
    simcore_step(&s);
    printf("measured: STOP in IDENTIFY: outputs off %.0f us after the request\n",
           (s.rig.t - t_stop) * 1e6);
    expect_failure(&s, MC_ID_ERROR_ABORTED, MC_STATE_STOPPED, "stop at 1.5 s");
}

static void test_a_fault_during_identification_should_end_in_fault(void **state)
{
    static simcore_t s;
    (void)state;
    setup_motor(&s, 1.0, 1.0, 1.0, 1.0);
    simcore_request(&s, MC_REQUEST_IDENTIFY);
    cl_run(&s, 0.5);
    assert_int_equal(s.now.state, MC_STATE_IDENTIFY);
    cl_event(&s, SIM_EV_CURRENT_SPIKE, 6.0, 1.0);
    cl_run(&s, 0.01);
    expect_failure(&s, MC_ID_ERROR_FAULT, MC_STATE_FAULT, "current spike");
    assert_int_equal(s.now.fault, MC_FAULT_OVERCURRENT);
}

#if MC_DRIVE
static void test_a_request_while_running_should_be_refused_and_change_nothing(void **state)
{
    static simcore_t s;
    (void)state;
    setup_motor(&s, 1.0, 1.0, 1.0, 1.0);
    cl_start_and_reach(&s, 0.5 * (SPEED_REF_MIN_RPM + SPEED_REF_MAX_RPM), 8.0);
    simcore_request(&s, MC_REQUEST_IDENTIFY);
    cl_run(&s, 0.2);
    expect_failure(&s, MC_ID_ERROR_NOT_STOPPED, MC_STATE_CLOSED_LOOP, "request while running");
}
#else
/* The commissioning image (MC_DRIVE 0): a START (S2, x2c.tune.run) measures the motor as
 * MC_REQUEST_IDENTIFY does, the core never enters a drive state, and a second request
 * while it runs is refused and changes nothing. */
static void test_a_start_should_run_the_identification_and_nothing_else(void **state)
{
    static simcore_t s;
    mc_id_result_t r;
    double t0;
    bool drove = false;
    (void)state;
    setup_motor(&s, 1.0, 1.0, 1.0, 1.0);
    t0 = s.rig.t;
    simcore_request(&s, MC_REQUEST_START);
    cl_run(&s, 0.5);
    assert_int_equal(s.now.state, MC_STATE_IDENTIFY);
    simcore_request(&s, MC_REQUEST_IDENTIFY);
    do {
        simcore_step(&s);
        drove |= s.now.state == MC_STATE_LOCK || s.now.state == MC_STATE_OPEN_LOOP ||
                 s.now.state == MC_STATE_CLOSED_LOOP;
    } while (s.rig.t < t0 + 30.0 && s.now.state != MC_STATE_STOPPED &&
             s.now.state != MC_STATE_FAULT);
    mc_identify_result(&s.mc, &r);
    printf("measured: commissioning image: START -> %s in %.2f s, R %.4f ohm, Ke %.3f V/krpm\n",
           (r.status == MC_ID_DONE) ? "DONE" : "FAILED", s.rig.t - t0, r.rs_uohm * 1e-6,
           r.ke_uv_per_rpm * 1e-3);
    assert_false(drove);
    assert_int_equal(s.now.state, MC_STATE_STOPPED);
    assert_int_equal(r.status, MC_ID_DONE);
}
#endif

static void test_a_failed_identification_should_not_keep_the_next_from_working(void **state)
{
    static simcore_t s;
    mc_id_result_t r;
    (void)state;
    setup_motor(&s, 1.0, 1.0, 1.0, 1.0);
    cl_event(&s, SIM_EV_LOCK_ROTOR, 0.0, 0.0);
    identify(&s, 30.0);
    cl_event(&s, SIM_EV_UNLOCK_ROTOR, 0.0, 0.0);
    cl_run(&s, 0.2);
    identify(&s, 30.0);
    mc_identify_result(&s.mc, &r);
    assert_int_equal(r.status, MC_ID_DONE);
    assert_true(r.rs_uohm > 0U && r.ke_uv_per_rpm > 0U);
}

/* Motors far from the profile, the inverter's models and dead-time shapes: each is identified
 * (the accuracy over many is identify_campaign's, docs/identify.md); R and the dead time,
 * whose measurement no motor here strains, within the envelope. */
static void test_motors_far_from_the_profile_should_be_identified(void **state)
{
    static const struct {
        double rs, l, ke, j, dt_us;
        int model, shape;
    } m[] = {
        {0.25, 0.5, 4.2, 2.4, 0.6, SIM_INV_AVERAGED, 1},  /* small R, strong magnet: hard shape */
        {4.1, 0.3, 3.7, 2.2, 1.8, SIM_INV_SWITCHING, 0},  /* L / R near a period, switching */
        {3.2, 0.26, 3.2, 0.67, 1.8, SIM_INV_AVERAGED, 0}, /* light rotor on a stiff field: swings */
        {1.4, 2.3, 0.24, 1.1, 1.5, SIM_INV_AVERAGED, 2},  /* weak magnet: the speed limit */
        {0.26, 1.34, 2.4, 1.5, 1.8, SIM_INV_AVERAGED,
         0}, /* rotor near 180 degrees: the ramp waits */
        {0.35, 4.4, 0.3, 1.0, 0.9, SIM_INV_SWITCHING, 0},  /* L / R hundreds of periods */
        {2.3, 0.24, 4.35, 2.1, 3.0, SIM_INV_SWITCHING, 0}, /* phase A's current in the band */
        {1.0, 1.0, 1.0, 3.0, 2.0, SIM_INV_AVERAGED, 0},    /* heavy rotor */
    };
    static simcore_t s;
    unsigned k;
    (void)state;
    for (k = 0; k < sizeof m / sizeof m[0]; k++) {
        simcore_cfg_t cfg;
        mc_id_result_t r;
        simcore_id_err_t e;
        double t;
        simcore_cfg_default(&cfg);
        cfg.rs_scale = m[k].rs;
        cfg.l_scale = m[k].l;
        cfg.ke_scale = m[k].ke;
        cfg.j_scale = m[k].j;
        cfg.deadtime_s = m[k].dt_us * 1e-6;
        cfg.inv.model = m[k].model;
        cfg.inv.dt_shape = m[k].shape;
        cfg.theta0_rad = (k == 4U) ? 4.7 : 0.7 * k;
        cfg.progress = false;
        assert_int_equal(simcore_init(&s, &cfg), 0);
        cl_run(&s, 0.02);
        t = identify(&s, 40.0);
        mc_identify_result(&s.mc, &r);
        simcore_identify_errors(&s, &r, &e);
        printf("measured: R x%.2f L x%.2f Ke x%.2f J x%.1f, %.1f us %s: %s %s, %.2f s; R %+.2f %%, "
               "L %+.2f %%, "
               "Ke %+.2f %%, J %+.1f %%, dead time %+.2f %%\n",
               m[k].rs, m[k].l, m[k].ke, m[k].j, m[k].dt_us,
               (m[k].model == SIM_INV_SWITCHING) ? "switching" : "averaged",
               (r.status == MC_ID_DONE) ? "done" : "FAILED", mc_id_error_name(r.error), t, e.rs,
               e.ls, e.ke, e.j, e.deadtime);
        assert_int_equal(r.status, MC_ID_DONE);
        assert_int_equal(s.now.state, MC_STATE_STOPPED);
        assert_true(fabs(e.rs) < 5.0);
        assert_true(fabs(e.deadtime) < 15.0);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_the_motor_should_be_measured_within_its_figures_in_under_10_s),
        cmocka_unit_test(test_motors_far_from_the_profile_should_be_identified),
        cmocka_unit_test(test_a_motor_the_spin_cannot_hold_should_end_in_no_sync),
        cmocka_unit_test(test_a_cut_lead_should_end_in_open_phase),
        cmocka_unit_test(test_a_locked_rotor_should_end_in_rotor_locked),
        cmocka_unit_test(test_a_motor_too_small_for_the_current_resolution_should_end_in_too_small),
        cmocka_unit_test(test_a_stop_during_identification_should_end_it_at_once),
        cmocka_unit_test(test_a_fault_during_identification_should_end_in_fault),
#if MC_DRIVE
        cmocka_unit_test(test_a_request_while_running_should_be_refused_and_change_nothing),
#else
        cmocka_unit_test(test_a_start_should_run_the_identification_and_nothing_else),
#endif
        cmocka_unit_test(test_a_failed_identification_should_not_keep_the_next_from_working),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

#else
/* MC_IDENTIFY 0: the request fails at once, UNAVAILABLE, and nothing else changes. */
static void test_identify_should_be_unavailable_in_this_build(void **state)
{
    static simcore_t s;
    simcore_cfg_t cfg;
    mc_id_result_t r;
    (void)state;
    simcore_cfg_default(&cfg);
    cfg.progress = false;
    assert_int_equal(simcore_init(&s, &cfg), 0);
    simcore_request(&s, MC_REQUEST_IDENTIFY);
    cl_run(&s, 0.1);
    mc_identify_result(&s.mc, &r);
    assert_int_equal(r.status, MC_ID_FAILED);
    assert_int_equal(r.error, MC_ID_ERROR_UNAVAILABLE);
    assert_int_equal(s.now.state, MC_STATE_STOPPED);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_identify_should_be_unavailable_in_this_build),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
#endif
