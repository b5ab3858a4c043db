/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_cl_faults.c - protections in closed loop: detection time, outputs off, restart. */
#include "cl_helpers.h"

#include <string.h>

/* Runs until FAULT (or max_s); returns the time of the step that reported it,
 * -1 if none. Checks the same step switched the outputs off. */
static double run_until_fault(simcore_t *s, double max_s)
{
    double t_end = s->rig.t + max_s;
    while (s->rig.t < t_end) {
        simcore_step(s);
        if (s->now.state == MC_STATE_FAULT) {
            assert_false(s->now.outputs_on);
            return s->now.t_s;
        }
    }
    return -1.0;
}

static void restart_should_work(simcore_t *s, double rpm, const char *what)
{
    double t0 = s->rig.t;
    cl_start_and_reach(s, rpm, 8.0);
    printf("measured: %s: restart by START back at %.0f rpm after %.2f s\n", what, rpm,
           s->rig.t - t0);
}

static void setup_running(simcore_t *s, double rpm)
{
    simcore_cfg_t cfg;
    simcore_cfg_default(&cfg);
    cl_setup(s, &cfg, "hurst", "mclv");
    cl_start_and_reach(s, rpm, 8.0);
    cl_run(s, 0.3);
}

static void test_current_spike_should_fault_within_one_period_with_outputs_off(void **state)
{
    static simcore_t s;
    (void)state;
    setup_running(&s, 2000.0);
    cl_event(&s, SIM_EV_CURRENT_SPIKE, 6.0, 1.0);
    simcore_step(&s); /* this period samples the spike */
    printf("measured: 6 A spike: state after the sampling period %s, fault %s, outputs %s\n",
           mc_state_name(s.now.state), mc_fault_name(s.now.fault), s.now.outputs_on ? "on" : "off");
    assert_int_equal(s.now.state, MC_STATE_FAULT);
    assert_int_equal(s.now.fault, MC_FAULT_OVERCURRENT);
    assert_false(s.now.outputs_on);
    cl_run(&s, 0.2);
    assert_int_equal(s.now.state, MC_STATE_FAULT);
    restart_should_work(&s, 2000.0, "current spike");
}

static void test_locked_rotor_should_fault_and_switch_off(void **state)
{
    static simcore_t s;
    double t_lock, t_f;
    (void)state;
    setup_running(&s, 1000.0);
    cl_event(&s, SIM_EV_LOCK_ROTOR, 0.0, 0.0);
    t_lock = s.rig.t;
    t_f = run_until_fault(&s, 0.5);
    printf(
        "measured: locked rotor at 1000 rpm: FAULT %s after %.2f ms, peak phase current %.2f A\n",
        mc_fault_name(s.now.fault), (t_f >= 0.0) ? 1000.0 * (t_f - t_lock) : -1.0, s.log.i_peak_a);
    assert_cmp(t_f, >=, 0.0);
    assert_cmp(t_f - t_lock, <=, 0.050);
    cl_event(&s, SIM_EV_UNLOCK_ROTOR, 0.0, 0.0);
    cl_run(&s, 0.1);
    restart_should_work(&s, 1000.0, "locked rotor");
}

/* From 24 V to vbus_v at 2000 rpm: FAULT `fault` within 5 ms, then the bus
 * back to 24 V, the rotor coasts down, and START brings it back. */
static void check_bus_fault(simcore_t *s, double vbus_v, unsigned fault, const char *what)
{
    double t_ev, t_f;
    cl_event(s, SIM_EV_VBUS, vbus_v, 0.0);
    t_ev = s->rig.t;
    t_f = run_until_fault(s, 0.2);
    printf("measured: bus 24 -> %.0f V at 2000 rpm: FAULT %s after %.2f ms\n", vbus_v,
           mc_fault_name(s->now.fault), (t_f >= 0.0) ? 1000.0 * (t_f - t_ev) : -1.0);
    assert_cmp(t_f, >=, 0.0);
    assert_cmp(t_f - t_ev, <=, 0.005);
    assert_int_equal(s->now.fault, fault);
    cl_run(s, 0.1);
    cl_event(s, SIM_EV_VBUS, 24.0, 0.0);
    cl_run(s, 0.5); /* the rotor coasts down */
    restart_should_work(s, 2000.0, what);
}

static void test_bus_undervoltage_and_overvoltage_should_stop_safely(void **state)
{
    static simcore_t s;
    (void)state;
    setup_running(&s, 2000.0);
    check_bus_fault(&s, 12.0, MC_FAULT_UNDERVOLTAGE, "undervoltage");
    check_bus_fault(&s, 36.0, MC_FAULT_OVERVOLTAGE, "overvoltage");
}

static void test_stall_under_excessive_load_should_be_detected_within_50_ms(void **state)
{
    static simcore_t s;
    double t_load, t_stall = -1.0, t_f = -1.0, t_end;
    (void)state;
    setup_running(&s, 2000.0);
    /* 3x rated: more than the speed loop's current limit can hold */
    cl_event(&s, SIM_EV_LOAD, 3.0 * s.rated_nm, 0.0);
    t_load = s.rig.t;
    t_end = t_load + 0.5;
    while (s.rig.t < t_end) {
        simcore_step(&s);
        if (t_stall < 0.0 && s.now.speed_rpm < 0.5 * 2000.0) {
            t_stall = s.now.t_s;
        }
        if (s.now.state == MC_STATE_FAULT) {
            assert_false(s.now.outputs_on);
            t_f = s.now.t_s;
            break;
        }
    }
    printf("measured: 3x rated load at 2000 rpm: true speed below 50 %% after %.1f ms, FAULT %s "
           "after %.1f ms (%.1f ms after the stall)\n",
           1000.0 * (t_stall - t_load), mc_fault_name(s.now.fault), 1000.0 * (t_f - t_load),
           1000.0 * (t_f - t_stall));
    assert_cmp(t_f, >=, 0.0);
    /* the fault is one of the stall detectors, not another protection */
    assert_true(s.now.fault == MC_FAULT_STALL_SPEED || s.now.fault == MC_FAULT_STALL_BEMF ||
                s.now.fault == MC_FAULT_STALL_TRACK);
    assert_true(t_stall < 0.0 || t_f - t_stall <= 0.050);
    cl_event(&s, SIM_EV_LOAD, 0.0, 0.0);
    cl_run(&s, 0.2);
    restart_should_work(&s, 2000.0, "stall");
}

static void test_hardware_fault_should_switch_off_at_the_next_period(void **state)
{
    static simcore_t s;
    (void)state;
    setup_running(&s, 2000.0);
    cl_event(&s, SIM_EV_HW_FAULT, 0.0, 0.0);
    simcore_step(&s);
    printf("measured: FLTA trip: state %s, fault %s after one period\n", mc_state_name(s.now.state),
           mc_fault_name(s.now.fault));
    assert_int_equal(s.now.state, MC_STATE_FAULT);
    assert_int_equal(s.now.fault, MC_FAULT_HARDWARE);
    assert_false(s.now.outputs_on);
    cl_run(&s, 0.5);
    restart_should_work(&s, 2000.0, "hardware fault");
}

/* A current sensor fails (sim event kind on phase 0 = A / 1 = B, value
 * v2): FAULT within 50 ms with the outputs off, MC_FAULT_CURRENT_SENSOR
 * when `own` (a reading frozen at 0 A or an open input: nothing but the
 * plausibility check can see it), else whichever protection answers
 * first. Then the sensor is healthy again and START brings the motor back. */
static void check_sensor_fault(simcore_t *s, sim_event_kind_t kind, double phase, double v2,
                               bool own, const char *what)
{
    double t_ev, t_f;
    double peak0 = s->log.i_peak_a;
    cl_event(s, kind, phase, v2);
    t_ev = s->rig.t;
    s->log.i_peak_a = 0.0;
    t_f = run_until_fault(s, 0.2);
    printf("measured: %s: FAULT %s after %.1f ms, peak true phase current %.2f A\n", what,
           mc_fault_name(s->now.fault), (t_f >= 0.0) ? 1000.0 * (t_f - t_ev) : -1.0,
           s->log.i_peak_a);
    assert_cmp(t_f, >=, 0.0);
    assert_cmp(t_f - t_ev, <=, 0.050);
    if (own) {
        assert_int_equal(s->now.fault, MC_FAULT_CURRENT_SENSOR);
    }
    s->log.i_peak_a = (peak0 > s->log.i_peak_a) ? peak0 : s->log.i_peak_a;
    cl_event(s, SIM_EV_SENSOR_OK, phase, 0.0);
    cl_run(s, 0.3);
}

static void test_failed_current_sensor_in_closed_loop_should_fault_within_50_ms(void **state)
{
    static simcore_t s;
    static const struct {
        sim_event_kind_t kind;
        double phase, v2, load;
        bool own;
        const char *what;
    } cases[] = {
        {SIM_EV_SENSOR_STUCK, 0.0, 0.0, 0.5, true, "2000 rpm, half load, phase A stuck at 0 A"},
        {SIM_EV_SENSOR_STUCK, 1.0, 0.0, 0.5, true, "2000 rpm, half load, phase B stuck at 0 A"},
        {SIM_EV_SENSOR_OPEN, 0.0, 0.0, 0.5, true, "2000 rpm, half load, phase A open"},
        {SIM_EV_SENSOR_OPEN, 1.0, 0.0, 0.0, true, "2000 rpm, no load, phase B open"},
        {SIM_EV_SENSOR_STUCK, 0.0, 0.0, 0.0, true, "2000 rpm, no load, phase A stuck at 0 A"},
        {SIM_EV_SENSOR_STUCK, 0.0, 1.0, 0.5, false, "2000 rpm, half load, phase A stuck at 1 A"},
        {SIM_EV_SENSOR_STUCK, 1.0, 4.5, 0.5, false, "2000 rpm, half load, phase B at full scale"},
    };
    size_t k;
    (void)state;
    for (k = 0; k < sizeof(cases) / sizeof(cases[0]); k++) {
        setup_running(&s, 2000.0);
        cl_event(&s, SIM_EV_LOAD, cases[k].load * s.rated_nm, 0.0);
        cl_run(&s, 0.3);
        assert_int_equal(s.now.state, MC_STATE_CLOSED_LOOP);
        check_sensor_fault(&s, cases[k].kind, cases[k].phase, cases[k].v2, cases[k].own,
                           cases[k].what);
    }
    cl_event(&s, SIM_EV_LOAD, 0.0, 0.0);
    restart_should_work(&s, 2000.0, "failed current sensor");
}

/* The same at settled speeds from low to nominal, no load and half load,
 * each failure at four instants a fraction of an electrical period apart
 * (a failure's timing against the rotor's angle matters): every one
 * faults, as CURRENT_SENSOR or (the current past the trip first)
 * OVERCURRENT, within 50 ms; and a rotor locked in the same places is a
 * stall, never a failed sensor. */
static void test_failed_sensors_and_locked_rotors_across_speeds_should_be_told_apart(void **state)
{
    static simcore_t s;
    static const double speed_frac[] = {0.3, 0.6, 1.0};
    static const double loads[] = {0.0, 0.5};
    static const sim_event_kind_t kinds[] = {SIM_EV_SENSOR_STUCK, SIM_EV_SENSOR_OPEN};
    double worst = 0.0;
    int n = 0, n_lock = 0, n_skip = 0;
    (void)state;
    for (size_t a = 0; a < sizeof(speed_frac) / sizeof(speed_frac[0]); a++) {
        for (size_t l = 0; l < sizeof(loads) / sizeof(loads[0]); l++) {
            for (int o = 0; o < 4; o++) {
                double rpm = speed_frac[a] * MOTOR_SPEED_NOMINAL_RPM;
                for (int k = -1; k < 4; k++) { /* -1: a locked rotor */
                    double t_ev, t_f;
                    setup_running(&s, rpm);
                    cl_event(&s, SIM_EV_LOAD, loads[l] * s.rated_nm, 0.0);
                    cl_run(&s, 0.3 + 0.0011 * o);
                    if (s.now.state != MC_STATE_CLOSED_LOOP) {
                        /* the load step alone lost the rotor: a profile's
                         * speed loop, not the sensor check (the hand-tuned
                         * Hurst holds every case) */
#if defined(MC_MOTOR_HURST)
                        fail_msg("%.0f rpm, load %.1f: %s before the event", rpm, loads[l],
                                 mc_fault_name(s.now.fault));
#endif
                        n_skip++;
                        continue;
                    }
                    if (k < 0) {
                        cl_event(&s, SIM_EV_LOCK_ROTOR, 0.0, 0.0);
                    } else {
                        cl_event(&s, kinds[k & 1], (k & 2) ? 1.0 : 0.0, 0.0);
                    }
                    t_ev = s.rig.t;
                    t_f = run_until_fault(&s, 0.2);
                    if (t_f < 0.0 || t_f - t_ev > 0.050 ||
                        (k < 0 && s.now.fault == MC_FAULT_CURRENT_SENSOR) ||
                        (k >= 0 && s.now.fault != MC_FAULT_CURRENT_SENSOR &&
                         s.now.fault != MC_FAULT_OVERCURRENT)) {
                        fail_msg("%.0f rpm, load %.1f, instant %d, %s: FAULT %s after %.1f ms", rpm,
                                 loads[l], o, (k < 0) ? "locked rotor" : "failed sensor",
                                 mc_fault_name(s.now.fault), 1000.0 * (t_f - t_ev));
                    }
                    if (k < 0) {
                        n_lock++;
                    } else {
                        worst = (t_f - t_ev > worst) ? t_f - t_ev : worst;
                        n++;
                    }
                }
            }
        }
    }
    printf("measured: %d failed sensors (stuck or open, A or B, %.0f to %.0f rpm, no load and half "
           "load, 4 instants) all faulted within %.1f ms; %d locked rotors all stalls; %d cases "
           "lost the rotor to the load step before the event\n",
           n, speed_frac[0] * MOTOR_SPEED_NOMINAL_RPM, MOTOR_SPEED_NOMINAL_RPM, 1000.0 * worst,
           n_lock, n_skip);
    assert_cmp(n, >=, 48); /* at least half the cases ran */
}

/* In LOCK and OPEN_LOOP: START, run to `at_s` after it, fail the sensor. */
static void check_sensor_fault_at_start(sim_event_kind_t kind, double phase, double at_s,
                                        const char *what)
{
    static simcore_t s;
    simcore_cfg_t cfg;
    simcore_cfg_default(&cfg);
    cl_setup(&s, &cfg, "hurst", "mclv");
    simcore_request(&s, MC_REQUEST_START);
    cl_run(&s, at_s);
    printf("measured: %s: state %s at the failure\n", what, mc_state_name(s.now.state));
    check_sensor_fault(&s, kind, phase, 0.0, true, what);
}

static void test_failed_current_sensor_at_start_should_fault_within_50_ms(void **state)
{
    (void)state;
    /* the lock puts its current on beta: phase B carries it */
    check_sensor_fault_at_start(SIM_EV_SENSOR_STUCK, 1.0, 0.15, "LOCK, phase B stuck at 0 A");
    check_sensor_fault_at_start(SIM_EV_SENSOR_OPEN, 1.0, 0.15, "LOCK, phase B open");
    check_sensor_fault_at_start(SIM_EV_SENSOR_STUCK, 0.0, 0.6, "OPEN_LOOP, phase A stuck at 0 A");
    check_sensor_fault_at_start(SIM_EV_SENSOR_OPEN, 0.0, 0.6, "OPEN_LOOP, phase A open");
    check_sensor_fault_at_start(SIM_EV_SENSOR_STUCK, 1.0, 0.6, "OPEN_LOOP, phase B stuck at 0 A");
}

/* A healthy drive held at the voltage circle below the nominal speed (a
 * load or a sagging bus that asks more than the bus can drive) leaves q
 * short of its reference by any amount: the sensor check must not call
 * that a failed sensor. The speed sags; nothing trips. */
static void test_voltage_limited_running_should_not_trip_the_sensor_check(void **state)
{
    static simcore_t s;
    static const struct {
        double rpm, load, vbus;
    } cases[] = {
        {2200.0, 0.8, 24.0}, /* 0.08 N m at 2,200 rpm: the bus holds 2,050 */
        {1800.0, 1.0, 24.0}, /* rated load at 1,800 rpm */
        {2200.0, 0.5, 22.0}, /* a sag under half load */
        {2200.0, 0.0, 16.0}, /* a deep sag, no load: q short by Imax */
        {2000.0, 1.0, 16.0},
    };
    size_t k;
    (void)state;
    for (k = 0; k < sizeof(cases) / sizeof(cases[0]); k++) {
        double sat = 0.0;
        long n = 0;
        setup_running(&s, cases[k].rpm);
        cl_event(&s, SIM_EV_LOAD, cases[k].load * s.rated_nm, 0.0);
        cl_event(&s, SIM_EV_VBUS, cases[k].vbus, 0.0);
        while (n < (long)(1.5 * PWM_FREQUENCY_HZ)) {
            simcore_step(&s);
            /* the last window's count of periods with the q PI at the circle */
            sat += (2U * s.mc.ho.in.sens_qsat > MC_SLOW_STEP_PERIODS) ? 1.0 : 0.0;
            n++;
        }
        printf("measured: %.0f rpm asked, %.2f x rated load, %.0f V: %s at %.0f rpm, q at the "
               "voltage limit in %.0f %% of the windows\n",
               cases[k].rpm, cases[k].load, cases[k].vbus, mc_state_name(s.now.state),
               s.now.speed_rpm, 100.0 * sat / (double)n);
        /* never the sensor; a profile whose speed loop loses the rotor to
         * the step may stall (a stall fault), the hand-tuned Hurst holds */
        assert_int_not_equal(s.now.fault, MC_FAULT_CURRENT_SENSOR);
        if (s.now.state != MC_STATE_CLOSED_LOOP) {
            printf("measured: ... ended in %s (%s)\n", mc_state_name(s.now.state),
                   mc_fault_name(s.now.fault));
            assert_int_equal(s.now.state, MC_STATE_FAULT);
#if defined(MC_MOTOR_HURST)
            fail_msg("the hand-tuned Hurst must hold every case");
#endif
            continue;
        }
        assert_cmp(sat, >, 0.2 * (double)n); /* it did run at the limit */
    }
}

/* Not the core's protection but the bench's: a plant driven beyond what its
 * integration follows, or gone non-finite, stops the run with one message
 * instead of feeding the core nonsense. */
static void test_bench_should_stop_when_the_plant_diverges(void **state)
{
    static simcore_t s;
    simcore_cfg_t cfg;
    char msg[320];
    long period;
    double lim_w;
    (void)state;
    simcore_cfg_default(&cfg);
    cl_setup(&s, &cfg, "hurst", "mclv");
    cl_run(&s, 0.01);
    assert_false(s.diverged);
    /* just inside the limit: runs on; just beyond: stops */
    lim_w = SIMCORE_MAX_STEP_RAD * (double)s.rig.substeps / s.rig.ts / (double)MOTOR_POLE_PAIRS;
    s.rig.plant.s.omega_m = -0.99 * lim_w;
    s.rig.plant.s.stuck = false;
    simcore_step(&s);
    assert_false(s.diverged);
    s.rig.plant.s.omega_m = -1.01 * lim_w;
    simcore_step(&s);
    assert_true(s.diverged);
    period = s.rig.period;
    simcore_step(&s);
    assert_int_equal(s.rig.period, period); /* a no-op from then on */
    simcore_diverged_msg(&s, msg, sizeof(msg));
    printf("measured: %s\n", msg);
    assert_non_null(strstr(msg, "rpm, beyond the"));

    cl_setup(&s, &cfg, "hurst", "mclv");
    cl_run(&s, 0.01);
    s.rig.plant.s.omega_m = NAN;
    s.rig.plant.s.stuck = false;
    simcore_step(&s);
    assert_true(s.diverged);
    simcore_diverged_msg(&s, msg, sizeof(msg));
    assert_non_null(strstr(msg, "non-finite"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_current_spike_should_fault_within_one_period_with_outputs_off),
        cmocka_unit_test(test_locked_rotor_should_fault_and_switch_off),
        cmocka_unit_test(test_bus_undervoltage_and_overvoltage_should_stop_safely),
        cmocka_unit_test(test_stall_under_excessive_load_should_be_detected_within_50_ms),
        cmocka_unit_test(test_hardware_fault_should_switch_off_at_the_next_period),
        cmocka_unit_test(test_failed_current_sensor_in_closed_loop_should_fault_within_50_ms),
        cmocka_unit_test(test_failed_current_sensor_at_start_should_fault_within_50_ms),
        cmocka_unit_test(test_failed_sensors_and_locked_rotors_across_speeds_should_be_told_apart),
        cmocka_unit_test(test_voltage_limited_running_should_not_trip_the_sensor_check),
        cmocka_unit_test(test_bench_should_stop_when_the_plant_diverges),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
