/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_mc_closedloop.c - the mc core on the simulated Hurst: start, tracking, field weakening,
 * ripple compensation, voltage limit, stall detection, no false trips. */
#include "test_support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mc_bench.h"
#include "mc_internal.h"
#include "vlimit.h"

static mc_bench_t b;

#define PERIODS(s) ((long)((s) * (double)PWM_FREQUENCY_HZ))

static double pot_for_rpm(double rpm)
{
    return (rpm - SPEED_REF_MIN_RPM) / (SPEED_REF_MAX_RPM - SPEED_REF_MIN_RPM);
}

/* Bench with the pot at `rpm`, started, run into CLOSED_LOOP. Returns the
 * time it took, s. */
static double start_at(double rpm)
{
    mc_bench_cfg_t c;
    mc_bench_cfg_default(&c);
    c.pot = pot_for_rpm(rpm);
    mc_bench_init(&b, &c);
    mc_request(&b.mc, MC_REQUEST_START);
    long n = mc_bench_run_until(&b, MC_STATE_CLOSED_LOOP, PERIODS(4.0));
    assert_cmp(n, >, 0);
    return (double)n / (double)PWM_FREQUENCY_HZ;
}

static void run(double seconds)
{
    long n = PERIODS(seconds);
    for (long k = 0; k < n; k++) {
        mc_bench_step(&b);
        assert_int_equal(b.st.state, MC_STATE_CLOSED_LOOP);
    }
}

static void set_pot_rpm(double rpm)
{
    b.rig.pot = pot_for_rpm(rpm);
    b.rig.pot_target = b.rig.pot;
}

/* ---- start-up and tracking ----------------------------------------------------- */

static void test_core_should_start_the_hurst_and_hold_the_pot_speed(void **state)
{
    (void)state;
    double t_cl = start_at(1500.0);
    printf("measured: START -> CLOSED_LOOP in %.3f s (calibration %.4f s, lock %.2f s, ramp %.2f "
           "s)\n",
           t_cl, (double)MC_CALIB_PERIODS / PWM_FREQUENCY_HZ, MOTOR_LOCK_TIME_S, MOTOR_RAMP_TIME_S);
    assert_cmp(t_cl, <,
               MC_OFFSET_CALIB_TIME_S + MOTOR_LOCK_TIME_S + MOTOR_RAMP_TIME_S + MC_HANDOFF_WAIT_S +
                   0.01);

    /* The hand-off must not make the speed dip. */
    double rpm_min = 1e9;
    for (long k = 0; k < PERIODS(0.2); k++) {
        mc_bench_step(&b);
        if (b.rpm_sample < rpm_min) {
            rpm_min = b.rpm_sample;
        }
    }
    printf("measured: lowest speed in the 200 ms after hand-off: %.0f rpm (ramp end %.0f)\n",
           rpm_min, MOTOR_RAMP_END_RPM);
    assert_cmp(rpm_min, >, 0.8 * MOTOR_RAMP_END_RPM);

    run(2.0); /* ramp to 1500 rpm at MC_SPEED_RAMP_RPM_PER_S and settle */
    err_stats_t spd, ang;
    err_stats_init(&spd);
    err_stats_init(&ang);
    double target = mc_rpm_of_q15(b.st.speed_target);
    for (long k = 0; k < PERIODS(1.0); k++) {
        mc_bench_step(&b);
        assert_int_equal(b.st.state, MC_STATE_CLOSED_LOOP);
        err_stats_add(&spd, b.rpm_sample - target, (double)k);
        err_stats_add(&ang, mc_bench_angle_err_deg(&b), (double)k);
    }
    err_stats_print("speed at 1500 rpm (true - reference)", &spd, "rpm");
    err_stats_print("angle at 1500 rpm (used - true)", &ang, "deg");
    assert_cmp(fabs(err_stats_mean(&spd)), <, 0.01 * target);
    assert_cmp(spd.max_abs, <, 0.05 * target);
    /* The project's claim (README, test_cl_accuracy): 2 deg on every sample
     * at 1000..3000 rpm (measured 0.7 on this bench's seed). */
    assert_cmp(fabs(err_stats_mean(&ang)), <, 2.0);
    assert_cmp(ang.max_abs, <, 2.0);
}

static void test_core_should_reach_top_speed_with_field_weakening_from_the_table(void **state)
{
    (void)state;
    start_at(SPEED_REF_MAX_RPM);
    /* Every speed-loop run: Id reference = linear interpolation of the
     * table (Q15 entries) at the speed reference, in double, no larger than
     * the light-load floor -(MC_ID_MIN_Q15 - |Iq reference|). */
    static const q15_t table[16] = MC_FW_TABLE_Q15;
    const double nom = MC_Q15_RPM(MOTOR_SPEED_NOMINAL_RPM);
    const double top = MC_Q15_RPM(MOTOR_SPEED_FW_MAX_RPM);
    err_stats_t e;
    err_stats_init(&e);
    long n_fw = 0;
    for (long k = 0; k < PERIODS(6.5); k++) {
        mc_bench_step(&b);
        assert_int_equal(b.st.state, MC_STATE_CLOSED_LOOP);
        double s = b.st.speed_ref;
        double ref = 0.0;
        if (s >= top) {
            ref = table[15];
        } else if (s >= nom) {
            double pos = 15.0 * (s - nom) / (top - nom);
            int i = (int)floor(pos);
            ref = table[i] + (pos - i) * (table[i + 1] - table[i]);
            n_fw++;
        }
        ref = fmin(ref, -((double)MC_ID_MIN_Q15 - fabs((double)b.st.iq_ref)));
        err_stats_add(&e, b.st.id_ref - ref, s);
    }
    err_stats_print("Id reference vs table interpolation at the speed reference", &e, "LSB");
    assert_cmp(n_fw, >, 1000);
    assert_cmp(e.max_abs, <=, 1.0);
    err_stats_t spd, ang;
    err_stats_init(&spd);
    err_stats_init(&ang);
    for (long k = 0; k < PERIODS(0.5); k++) {
        mc_bench_step(&b);
        err_stats_add(&spd, b.rpm_sample - SPEED_REF_MAX_RPM, (double)k);
        err_stats_add(&ang, mc_bench_angle_err_deg(&b), (double)k);
    }
    err_stats_print("speed at the top of field weakening (true - reference)", &spd, "rpm");
    err_stats_print("angle at the top of field weakening", &ang, "deg");
    printf("measured: Id at %.0f rpm: %.3f A (table end %.3f A)\n", SPEED_REF_MAX_RPM,
           b.st.id * BOARD_I_FULLSCALE_A / 32768.0, table[15] * BOARD_I_FULLSCALE_A / 32768.0);
    assert_int_equal(b.st.state, MC_STATE_CLOSED_LOOP);
    assert_cmp(fabs(err_stats_mean(&spd)), <, 0.02 * SPEED_REF_MAX_RPM);
    assert_cmp(fabs(err_stats_mean(&ang)), <, 10.0);
}

static void
test_the_angle_should_hold_at_the_minimum_speed_with_dead_time_compensation(void **state)
{
    (void)state;
    start_at(SPEED_REF_MIN_RPM);
    run(1.0);
    err_stats_t ang;
    err_stats_init(&ang);
    for (long k = 0; k < PERIODS(2.0); k++) {
        mc_bench_step(&b);
        assert_int_equal(b.st.state, MC_STATE_CLOSED_LOOP);
        err_stats_add(&ang, mc_bench_angle_err_deg(&b), (double)k);
    }
    err_stats_print("angle at the minimum speed (500 rpm), dead-time compensation on", &ang, "deg");
    /* The claim at the lowest speed: 2.5 deg, ADC-noise limited (measured
     * 1.95 on this bench's seed; 1.4..2.25 over eight seeds in
     * test_cl_accuracy). */
    assert_cmp(fabs(err_stats_mean(&ang)), <, 2.0);
    assert_cmp(ang.max_abs, <, 2.5);
}

static void test_speed_reference_should_ramp_at_the_configured_rate_to_the_pot_target(void **state)
{
    (void)state;
    start_at(1000.0);
    run(1.0);
    set_pot_rpm(3000.0);
    int16_t prev = b.st.speed_ref;
    long runs = 0;
    for (long k = 0; k < PERIODS(3.0); k++) {
        mc_bench_step(&b);
        int16_t d = (int16_t)(b.st.speed_ref - prev);
        /* At most one step per speed-loop run; a full step while the
         * target (the pot, with its ADC noise) is more than a step away. */
        assert_cmp(abs(d), <=, MC_SPEED_RAMP_STEP);
        if (b.st.speed_target - prev > MC_SPEED_RAMP_STEP &&
            b.mc.slow_div == MC_SLOW_APPLY_PERIODS) {
            assert_int_equal(d, MC_SPEED_RAMP_STEP);
            runs++;
        }
        prev = b.st.speed_ref;
    }
    double rate = (double)runs * MC_SPEED_RAMP_STEP * MC_SPEED_FULLSCALE_RPM / 32768.0 /
                  ((double)runs / MC_SPEED_LOOP_HZ);
    printf("measured: speed reference ramp %.0f rpm/s (MC_SPEED_RAMP_RPM_PER_S = %.0f), %ld runs\n",
           rate, MC_SPEED_RAMP_RPM_PER_S, runs);
    /* Arrived: within the pot's ADC noise (one pot code moves the target
     * by about 19 LSB of speed; 64 LSB = 16 rpm). The rate is the step
     * rounded to whole Q15 counts: 4 LSB per run = 977 rpm/s for 1000. */
    assert_cmp(abs(b.st.speed_ref - b.st.speed_target), <=, 64);
    assert_cmp(fabs(rate - MC_SPEED_RAMP_RPM_PER_S), <, 0.03 * MC_SPEED_RAMP_RPM_PER_S);
    assert_cmp(fabs(b.rpm_sample - mc_rpm_of_q15(b.st.speed_target)), <, 30.0);
}

/* ---- voltage: ripple compensation and circle limit ------------------------------- */

static void test_ripple_compensation_should_follow_equation_8_on_a_rippling_bus(void **state)
{
    (void)state;
    start_at(2000.0);
    b.rig.inv.prm.ripple_v = 3.0;
    b.rig.inv.prm.ripple_hz = 100.0;
    err_stats_t e;
    err_stats_init(&e);
    const double target = MC_VBUS_NOMINAL_Q15;
    long n_up = 0, n_down = 0;
    for (long k = 0; k < PERIODS(1.0); k++) {
        /* The gain is the previous sample's (formed after the duties, mc.c). */
        double dc = b.frame.vbus;
        mc_bench_step(&b);
        double vpi[2] = {b.mc.pi_d.out, b.mc.pi_q.out};
        double got[2] = {b.st.vd, b.st.vq};
        for (int j = 0; j < 2; j++) {
            double v;
            /* AN1078 Equation 8, both branches as written. */
            if (target > dc) {
                v = vpi[j] + (target - dc) / dc * vpi[j];
                n_up++;
            } else if (dc > target) {
                v = target / dc * vpi[j];
                n_down++;
            } else {
                v = vpi[j];
            }
            if (fabs(v) < 32767.0) {
                err_stats_add(&e, got[j] - v, dc);
            }
        }
    }
    err_stats_print("Vd, Vq after ripple compensation vs Equation 8 (double)", &e, "LSB");
    assert_cmp(n_up, >, 1000);
    assert_cmp(n_down, >, 1000);
    assert_cmp(e.max_abs, <=, 1.0); /* ripple.h: one gain per period, then one product */
}

static void test_voltage_vector_should_stay_inside_the_circle_when_the_loops_saturate(void **state)
{
    (void)state;
    start_at(2000.0);
    /* A weak bus and the top speed: the current loops run into the limit. */
    b.rig.inv.prm.vbus_v = 17.0;
    set_pot_rpm(SPEED_REF_MAX_RPM);
    double over = -1e9;
    long at_limit = 0;
    uint16_t redos0 = b.mc.circle_redos;
    for (long k = 0; k < PERIODS(3.0) && b.st.state == MC_STATE_CLOSED_LOOP; k++) {
        mc_bench_step(&b);
        double m = hypot((double)b.mc.pi_d.out, (double)b.mc.pi_q.out);
        over = fmax(over, m - MC_VMAX_Q15);
        assert_cmp(m, <=, MC_VMAX_Q15 + 0.5); /* vlimit.h: lim rounded */
        assert_cmp(abs(b.mc.pi_d.out), <=, MC_VMAX_Q15);
        if (m > MC_VMAX_Q15 - 2.0) {
            at_limit++;
        }
    }
    printf("measured: %ld periods at the voltage limit (|V| from 2 LSB below %d), |V| - Vmax at "
           "most %.2f LSB, %d redone at the circle\n",
           at_limit, MC_VMAX_Q15, over, (int)(uint16_t)(b.mc.circle_redos - redos0));
    assert_cmp(at_limit, >, 1000);
}

/* Near the voltage circle the q limit is formed before the q PI, which then
 * runs once (mc.c note 3). Held at the circle (the top speed against more
 * load than it leaves, then a bus step), every period whose q output sits
 * at its limit must be at AN1078's exact limit, and the redo (a second q PI
 * run before the duties) must stay a transient's exception. The 0.1 % bound
 * is this test's choice: a period redone writes its duties later
 * (docs/board.md "Timing"). */
static void test_at_the_voltage_circle_the_q_limit_should_be_exact_without_a_redo(void **state)
{
    (void)state;
    start_at(SPEED_REF_MAX_RPM);
    b.rig.plant.load.active_nm = 0.02;
    run(4.0);
    long clamped = 0, periods = 0;
    double lo = 1e9, hi = -1e9, sum = 0.0;
    uint16_t redos0 = b.mc.circle_redos;
    for (int phase = 0; phase < 2; phase++) {
        if (phase == 1) {
            b.rig.inv.prm.vbus_v = 22.0; /* a bus step: a transient on the circle */
        }
        for (long k = 0; k < PERIODS(1.0); k++) {
            mc_bench_step(&b);
            assert_int_equal(b.st.state, MC_STATE_CLOSED_LOOP);
            periods++;
            q15_t vq = b.mc.pi_q.out;
            if (vq == b.mc.pi_q.p.out_max || vq == b.mc.pi_q.p.out_min) {
                double m = hypot((double)b.mc.pi_d.out, (double)vq);
                lo = fmin(lo, m - MC_VMAX_Q15);
                hi = fmax(hi, m - MC_VMAX_Q15);
                sum += m - MC_VMAX_Q15;
                assert_int_equal(abs(vq), vlimit_vq_max(b.mc.pi_d.out, MC_VMAX_Q15));
                clamped++;
            }
        }
    }
    long redos = (long)(uint16_t)(b.mc.circle_redos - redos0);
    printf("measured: %ld of %ld periods with Vq at its limit, |V| - Vmax %.2f .. %.2f LSB (mean "
           "%.2f); %ld redone at the circle\n",
           clamped, periods, lo, hi, sum / (double)clamped, redos);
    assert_cmp(clamped, >, periods / 4);
    assert_cmp(lo, >=, -0.5);
    assert_cmp(hi, <=, 0.5); /* AN1078's rounded limit */
    assert_cmp(redos * 1000L, <=, periods);
}

/* ---- the shunt window ---------------------------------------------------------------- */

/* What the chip gives phase k's low-side switch before the sample, us: the
 * centre-aligned period counts PTMR up to PTPER and down again; the high side
 * is on while PTMR < PDC / 2, the low side from a dead time after it turns
 * off on the way up until PTMR = PDC / 2 on the way down; the ADC triggers
 * PWM_ADC_TRIGGER_TCY after the midpoint. <= 0: off at the sample. */
static double low_side_on_us(uint16_t pdc)
{
    const double ptper = (double)PWM_DUTY_MAX / 2.0 - 1.0;
    const double tcy_us = 1e6 / (double)BOARD_FCY_HZ;
    const double dt_tcy = (double)PWM_DEADTIME_NS * 1e-3 / tcy_us;
    if (pdc == 0U) {
        return 1e6 / (double)PWM_FREQUENCY_HZ; /* no edge: on all period */
    }
    if ((double)pdc / 2.0 >= ptper - (double)PWM_ADC_TRIGGER_TCY) {
        return 0.0; /* turned off before the trigger */
    }
    return ((ptper - (double)pdc / 2.0) + (double)PWM_ADC_TRIGGER_TCY - dt_tcy) * tcy_us;
}

typedef struct {
    long on;        /* periods with the outputs on */
    long at_window; /* ... with phase A or B within 2 counts of MC_DUTY_SAMPLE_MAX */
    double min_on_us;
    long states[8]; /* periods per state with the outputs on */
} window_stats_t;

/* Steps the bench n periods and checks every duty it latches. */
static void run_checking_window(long n, window_stats_t *w)
{
    for (long k = 0; k < n && b.st.state != MC_STATE_FAULT; k++) {
        mc_bench_step(&b);
        if (!b.out.outputs_on) {
            continue;
        }
        w->on++;
        w->states[b.st.state & 7U]++;
        for (int ph = 0; ph < 2; ph++) {
            assert_cmp(b.out.duty[ph], <=, (uint16_t)MC_DUTY_SAMPLE_MAX);
            double t = low_side_on_us(b.out.duty[ph]);
            w->min_on_us = fmin(w->min_on_us, t);
            if (b.out.duty[ph] + 2U >= (uint16_t)MC_DUTY_SAMPLE_MAX) {
                w->at_window++;
            }
        }
    }
}

/* The core never commands a duty that corrupts its next sample: phases A
 * and B leave their low side on for BOARD_SHUNT_MIN_ON_NS before the
 * trigger in every period with the outputs on, through the lock, the ramp,
 * closed loop at full load, field weakening at the top speed with more load
 * than the voltage allows (the q loop held at the voltage circle), and a
 * weak bus that over-modulates at 3,000 rpm. The simulator's amplifiers
 * (sim_rig.h) confirm it: no sample short of their settling. */
static void test_the_measured_phases_should_keep_their_shunt_window_in_every_state(void **state)
{
    (void)state;
    window_stats_t w;
    memset(&w, 0, sizeof(w));
    w.min_on_us = 1e9;
    mc_bench_cfg_t c;
    mc_bench_cfg_default(&c);
    c.pot = pot_for_rpm(1500.0);
    mc_bench_init(&b, &c);
    mc_request(&b.mc, MC_REQUEST_START);
    run_checking_window(PERIODS(4.0), &w); /* calibration, lock, ramp, closed loop at 1500 */
    assert_int_equal(b.st.state, MC_STATE_CLOSED_LOOP);
    b.rig.plant.load.active_nm = 0.1; /* near the current limit */
    run_checking_window(PERIODS(1.0), &w);
    b.rig.plant.load.active_nm = 0.02; /* beyond what the top speed leaves (16 mN m) */
    set_pot_rpm(SPEED_REF_MAX_RPM);
    run_checking_window(PERIODS(5.0), &w);
    long circle = 0;
    for (long k = 0; k < PERIODS(0.5); k++) {
        run_checking_window(1, &w);
        double m = hypot((double)b.mc.v_dq.d, (double)b.mc.v_dq.q);
        circle += (m > MC_VMAX_Q15 - 40.0);
    }
    printf("measured: top speed with 20 mN m: %.0f rpm, Id %.2f A, %ld of %ld periods with |V| "
           "at the circle\n",
           b.rpm_sample, b.st.id * BOARD_I_FULLSCALE_A / 32768.0, circle, PERIODS(0.5));
    assert_cmp(circle, >, PERIODS(0.25));
    b.rig.plant.load.active_nm = 0.03;
    set_pot_rpm(3000.0);
    run_checking_window(PERIODS(3.0), &w);
    b.rig.inv.prm.vbus_v = 17.0; /* weak bus: over-modulation at 3000 rpm */
    run_checking_window(PERIODS(1.0), &w);
    printf("measured: 3000 rpm, 30 mN m on a 17 V bus: %.0f rpm, state %d fault %d\n", b.rpm_sample,
           (int)b.st.state, (int)b.st.fault);
    assert_int_equal(b.st.state, MC_STATE_CLOSED_LOOP);
    printf("measured: %ld periods with the outputs on (LOCK %ld, OPEN_LOOP %ld, CLOSED_LOOP %ld), "
           "%ld phase-periods at the window's limit %d; shortest low-side time before the "
           "sample %.2f us (BOARD_SHUNT_MIN_ON_NS %.2f us); simulator: %ld samples short of the "
           "amplifiers' settling, shortest conduction %.2f us\n",
           w.on, w.states[MC_STATE_LOCK], w.states[MC_STATE_OPEN_LOOP],
           w.states[MC_STATE_CLOSED_LOOP], w.at_window, MC_DUTY_SAMPLE_MAX, w.min_on_us,
           (double)BOARD_SHUNT_MIN_ON_NS * 1e-3, b.rig.samples_short, b.rig.t_cond_min_s * 1e6);
    assert_cmp(w.states[MC_STATE_LOCK], >, 0);
    assert_cmp(w.states[MC_STATE_OPEN_LOOP], >, 0);
    assert_cmp(w.at_window, >, 1000); /* the limit was active, not merely never reached */
    assert_cmp(w.min_on_us, >=, (double)BOARD_SHUNT_MIN_ON_NS * 1e-3 - 1e-9);
    assert_int_equal(b.rig.samples_short, 0);
}

/* The check above can fail: the same run against amplifiers slower than
 * the board constant allows for (0.6 us, settling in 4.2 us) gives
 * corrupted samples, and the simulator counts them. */
static void test_amplifiers_slower_than_the_window_should_show_as_short_samples(void **state)
{
    (void)state;
    mc_bench_cfg_t c;
    mc_bench_cfg_default(&c);
    c.pot = pot_for_rpm(SPEED_REF_MAX_RPM);
    c.amp_tau_s = 0.6e-6;
    mc_bench_init(&b, &c);
    mc_request(&b.mc, MC_REQUEST_START);
    for (long k = 0; k < PERIODS(8.0) && b.st.state != MC_STATE_FAULT; k++) {
        mc_bench_step(&b);
    }
    printf("measured: amplifier tau 0.6 us: %ld samples short of its settling (%.2f us), "
           "shortest conduction %.2f us, state %d at %.0f rpm\n",
           b.rig.samples_short, SIM_AMP_SETTLE_TAUS * 0.6, b.rig.t_cond_min_s * 1e6,
           (int)b.st.state, b.rpm_sample);
    assert_cmp(b.rig.samples_short, >, 1000);
}

/* ---- protections in closed loop ---------------------------------------------------- */

static void test_stall_should_fault_within_50_ms_when_the_rotor_locks(void **state)
{
    (void)state;
    const double speeds[] = {800.0, 1500.0, 3000.0};
    for (int s = 0; s < 3; s++) {
        start_at(speeds[s]);
        run(2.5);
        b.rig.plant.s.locked = true;
        long k = 0;
        for (; k < PERIODS(0.1) && b.st.state != MC_STATE_FAULT; k++) {
            mc_bench_step(&b);
        }
        double t = (double)k / PWM_FREQUENCY_HZ;
        printf("measured: locked rotor at %.0f rpm -> FAULT code %u after %.1f ms\n", speeds[s],
               b.st.fault, 1000.0 * t);
        assert_int_equal(b.st.state, MC_STATE_FAULT);
        assert_true(b.st.fault == MC_FAULT_STALL_SPEED || b.st.fault == MC_FAULT_STALL_BEMF ||
                    b.st.fault == MC_FAULT_STALL_TRACK);
        assert_cmp(t, <=, 0.050);
        assert_false(b.out.outputs_on);
        assert_int_equal(b.out.duty[0], PWM_DUTY_MAX / 2U);
    }
}

static void test_a_back_emf_far_below_what_the_speed_implies_should_fault_as_a_stall(void **state)
{
    (void)state;
    /* The rotor flux collapses (a demagnetised or wrong motor): the speed
     * estimate still turns, but the back-EMF no longer matches it. */
    start_at(1500.0);
    run(2.0);
    b.rig.plant.m.psi_vs *= 0.25;
    long k = 0;
    for (; k < PERIODS(0.2) && b.st.state != MC_STATE_FAULT; k++) {
        mc_bench_step(&b);
    }
    printf("measured: flux at 25 %% at 1500 rpm -> FAULT code %u after %.1f ms\n", b.st.fault,
           1000.0 * (double)k / PWM_FREQUENCY_HZ);
    assert_int_equal(b.st.state, MC_STATE_FAULT);
    assert_int_equal(b.st.fault, MC_FAULT_STALL_BEMF);
}

static void test_an_overload_beyond_the_current_limit_should_fault_as_lost_tracking(void **state)
{
    (void)state;
    /* More load than MOTOR_CURRENT_MAX_A can hold: the speed PI saturates
     * and the speed falls away from the reference. */
    start_at(3000.0);
    run(3.0);
    b.rig.plant.load.active_nm = 0.125;
    long k = 0;
    double rpm_at_fault = 0.0;
    for (; k < PERIODS(1.0) && b.st.state != MC_STATE_FAULT; k++) {
        mc_bench_step(&b);
        rpm_at_fault = b.rpm_sample;
    }
    printf("measured: overload at 3000 rpm -> FAULT code %u after %.1f ms at %.0f rpm\n",
           b.st.fault, 1000.0 * (double)k / PWM_FREQUENCY_HZ, rpm_at_fault);
    assert_int_equal(b.st.state, MC_STATE_FAULT);
    assert_int_equal(b.st.fault, MC_FAULT_STALL_TRACK);
    assert_cmp(rpm_at_fault, <, 3000.0 - MC_STALL_SPEED_ERROR_RPM);
}

static void test_the_hand_off_difference_should_bleed_to_zero_by_the_step_each_period(void **state)
{
    (void)state;
    start_at(1500.0);
    run(0.5);
    const int16_t starts[] = {1000, -1000, (int16_t)(MC_BLEED_STEP / 2), 3000, -3000};
    for (unsigned j = 0; j < 5U; j++) {
        b.mc.theta_offset = starts[j];
        int32_t expect = starts[j];
        for (int k = 0; k < 5000 && expect != 0; k++) {
            if (expect > MC_BLEED_STEP) {
                expect -= MC_BLEED_STEP;
            } else if (expect < -MC_BLEED_STEP) {
                expect += MC_BLEED_STEP;
            } else {
                expect = 0;
            }
            mc_bench_step(&b);
            assert_int_equal(b.mc.theta_offset, expect);
        }
        assert_int_equal(b.mc.theta_offset, 0);
        run(0.3); /* let it settle again */
    }
}

static void test_closed_loop_should_not_trip_through_speed_changes_and_load_steps(void **state)
{
    (void)state;
    start_at(600.0);
    const double plan[][2] = {
        /* rpm, load N m */
        /* (the field-weakening table is for a light load: 0.02 N m at 3000 rpm) */
        {600.0, 0.0},  {1500.0, 0.0}, {3000.0, 0.0}, {3000.0, 0.02}, {1500.0, 0.06},
        {600.0, 0.06}, {600.0, 0.0},  {5300.0, 0.0}, {2000.0, 0.02}, {500.0, 0.0},
    };
    for (unsigned p = 0; p < sizeof(plan) / sizeof(plan[0]); p++) {
        set_pot_rpm(plan[p][0]);
        b.rig.plant.load.active_nm = plan[p][1];
        run(1.5 + fabs(plan[p][0] - mc_rpm_of_q15(b.st.speed_ref)) / MC_SPEED_RAMP_RPM_PER_S);
        printf("measured: %.0f rpm, load %.2f N m: speed %.0f rpm, Iq %.3f A\n", plan[p][0],
               plan[p][1], b.rpm_sample, b.st.iq * BOARD_I_FULLSCALE_A / 32768.0);
        assert_cmp(fabs(b.rpm_sample - plan[p][0]), <, 0.05 * plan[p][0] + 20.0);
    }
}

static void test_a_speed_gain_set_at_run_time_should_survive_the_low_speed_schedule(void **state)
{
    (void)state;
    /* Below MOTOR_SPEED_KP_FULL_RPM the speed loop scales its gains every
     * tick; a gain written straight into pi_w would be overwritten there. */
    start_at(SPEED_REF_MIN_RPM);
    run(0.3);
    assert_cmp(b.st.speed_ref, <, MC_Q15_RPM(MOTOR_SPEED_KP_FULL_RPM));
    q15_t kp_sched = b.mc.slow.pi_w.p.kp;
    q15_t base = mc_get_gain(&b.mc, MC_GAIN_SPD_KP);
    /* up by a quarter: a client may not go below the built-in Kp (mc.h note 3) */
    q15_t raised = (q15_t)(base + base / 4);
    assert_true(mc_set_gain(&b.mc, MC_GAIN_SPD_KP, raised));
    run((double)(3 * IRP_PERCALC) / (double)PWM_FREQUENCY_HZ); /* three speed-loop ticks */
    q15_t kp_now = b.mc.slow.pi_w.p.kp;
    printf("measured: scheduled speed Kp %d with base %d, %d after the base was raised to %d\n",
           (int)kp_sched, (int)base, (int)kp_now, (int)raised);
    assert_int_equal(mc_get_gain(&b.mc, MC_GAIN_SPD_KP), raised);
    /* Raised as the base was (the schedule factor itself may move a fraction of a
     * percent as the reference settles); before mc_set_gain existed the ratio was 1. */
    double ratio = (double)kp_now / (double)kp_sched;
    double want = (double)raised / (double)base;
    printf("measured: ratio %.4f (expected %.4f)\n", ratio, want);
    assert_cmp(fabs(ratio - want), <, 0.01);
    run(0.5); /* and the motor keeps running on it */
}

/* mc_step() is mc_step_control() then mc_step_finish() (mc.h), the way the
 * dsPIC's interrupt calls them: a twin core fed the same frames through the
 * two parts gives the same outputs and the same status every period,
 * through start-up, closed loop, a load step and a stall fault raised in
 * the finishing part (which turns the outputs off in that very period). */
static void test_the_two_part_step_should_equal_mc_step_bit_for_bit(void **state)
{
    (void)state;
    static mc_t twin;
    mc_bench_cfg_t c;
    mc_bench_cfg_default(&c);
    c.pot = pot_for_rpm(1500.0);
    mc_bench_init(&b, &c);
    mc_init(&twin);
    mc_request(&b.mc, MC_REQUEST_START);
    mc_request(&twin, MC_REQUEST_START);
    long compared = 0;
    bool faulted_in_finish = false;
    for (long k = 0; k < PERIODS(4.0) && b.st.state != MC_STATE_FAULT; k++) {
        if (k == PERIODS(2.5)) {
            b.rig.plant.load.active_nm = 0.03;
        }
        if (k == PERIODS(3.0)) {
            b.rig.plant.s.locked = true;
        }
        mc_state_t before = b.st.state;
        mc_bench_step(&b); /* mc_step() */
        mc_adc_frame_t in;
        in.ia = b.frame.ia;
        in.ib = b.frame.ib;
        in.vbus = b.frame.vbus;
        in.pot = b.frame.pot;
        mc_pwm_out_t out;
        memset(&out, 0, sizeof(out)); /* padding compared below, as b.out's (static) */
        mc_step_control(&twin, &in, &out);
        bool on_after_control = out.outputs_on;
        bool turned_off = mc_step_finish(&twin, &out);
        /* The finishing part says it turned the outputs off exactly when
         * it did, so its caller switches them off at once. */
        assert_int_equal(turned_off, on_after_control && !out.outputs_on);
        mc_slow_step(&twin);
        assert_memory_equal(&out, &b.out, sizeof(out));
        mc_status_t st;
        memset(&st, 0, sizeof(st));
        mc_status(&twin, &st);
        assert_memory_equal(&st, &b.st, sizeof(st));
        if (on_after_control && !out.outputs_on && before == MC_STATE_CLOSED_LOOP) {
            faulted_in_finish = true;
        }
        compared++;
    }
    printf("measured: %ld periods compared, the stall raised in the finishing part: %s\n", compared,
           faulted_in_finish ? "yes" : "no");
    assert_int_equal(b.st.state, MC_STATE_FAULT);
    assert_true(faulted_in_finish);
    assert_false(b.out.outputs_on);
}

static void test_stop_in_closed_loop_should_turn_the_outputs_off_at_once(void **state)
{
    (void)state;
    start_at(1000.0);
    run(0.5);
    mc_request(&b.mc, MC_REQUEST_START_STOP);
    mc_bench_step(&b);
    assert_int_equal(b.st.state, MC_STATE_STOPPED);
    assert_false(b.out.outputs_on);
    assert_int_equal(b.out.duty[1], PWM_DUTY_MAX / 2U);
}

/* A STOP at 2,000 rpm: the rotor coasts down for a second while the estimate reads unknown
 * (speed 0, not valid) from the stop's period on, never the last speed it had; the next START
 * starts as usual. */
static void test_after_stop_the_coasting_rotor_should_read_unknown_not_a_frozen_speed(void **state)
{
    (void)state;
    start_at(2000.0);
    run(1.5);
    double before = mc_rpm_of_q15(b.st.speed_est);
    assert_cmp(before, >, 1800.0);
    mc_request(&b.mc, MC_REQUEST_START_STOP);
    double coasting = 0.0;
    for (long k = 0; k < PWM_FREQUENCY_HZ; k++) {
        mc_bench_step(&b);
        assert_int_equal(b.st.state, MC_STATE_STOPPED);
        assert_int_equal(b.st.speed_est, 0);
        assert_false(b.st.estimator_valid);
        assert_int_equal(smc_omega(&b.mc.smc), 0); /* what X2Cscope's smc.omega reads */
        if (k == PWM_FREQUENCY_HZ / 10) {
            coasting = mc_bench_rpm(&b);
        }
    }
    printf("measured: STOP at %.0f rpm: the rotor at %.0f rpm 0.1 s later, %.0f after 1 s; the "
           "estimate "
           "0 rpm and not valid throughout\n",
           before, coasting, mc_bench_rpm(&b));
    assert_cmp(coasting, >, 500.0);
    mc_request(&b.mc, MC_REQUEST_START_STOP);
    assert_cmp(mc_bench_run_until(&b, MC_STATE_CLOSED_LOOP, 8L * PWM_FREQUENCY_HZ), >, 0);
}

/* A STOP at the top speed (field weakening: the Hurst's back-EMF 38 V line-to-line peak on a
 * 24 V bus) into the simulator's bus model (470 uF, a supply that takes nothing back):
 * releasing the switches at once let the diodes charge the bus past the 32 V trip in 4.7 ms.
 * The drive holds zero torque (Iq reference 0) while the rotor coasts, releases below the
 * speed whose back-EMF is 0.9 of the bus, and ends STOPPED without a fault, the bus near its
 * level. S2 while it coasts takes the speed loop back. */
static void
test_a_stop_above_the_release_speed_should_coast_at_zero_torque_then_let_go(void **state)
{
    (void)state;
    mc_bench_cfg_t c;
    mc_bench_cfg_default(&c);
    c.bus_model = true;
    c.pot = 1.0;
    mc_bench_init(&b, &c);
    mc_request(&b.mc, MC_REQUEST_START);
    assert_cmp(mc_bench_run_until(&b, MC_STATE_CLOSED_LOOP, 8L * PWM_FREQUENCY_HZ), >, 0);
    run(6.0);
    double from = mc_bench_rpm(&b);
    double release = mc_rpm_of_q15(mc_release_speed(b.st.vbus));
    assert_cmp(from, >, release + 1000.0);
    mc_request(&b.mc, MC_REQUEST_START_STOP);
    long coast = 0;
    while (b.st.state == MC_STATE_CLOSED_LOOP && coast < 5L * PWM_FREQUENCY_HZ) {
        mc_bench_step(&b);
        if (b.st.state == MC_STATE_CLOSED_LOOP) {
            assert_true(b.st.stopping);
            assert_true(b.st.outputs_on);
            if (coast > PWM_FREQUENCY_HZ / 500) { /* the first window's reference aside */
                assert_int_equal(b.st.iq_ref, 0);
            }
        }
        coast++;
    }
    double at = mc_bench_rpm(&b);
    printf(
        "measured: STOP at %.0f rpm into a %.0f uF bus: zero torque for %.0f ms, released at %.0f "
        "rpm (release speed %.0f), bus peak %.2f V, fault %u\n",
        from, b.rig.bus_c_f * 1e6, 1000.0 * (double)coast / PWM_FREQUENCY_HZ, at, release,
        b.rig.vbus_peak_v, (unsigned)b.st.fault);
    assert_int_equal(b.st.state, MC_STATE_STOPPED);
    assert_false(b.st.outputs_on);
    assert_false(b.st.stopping);
    assert_cmp(at, <, release + 200.0);
    assert_cmp(b.rig.vbus_peak_v, <, (double)MC_VBUS_REGEN_V);
    for (long k = 0; k < PWM_FREQUENCY_HZ / 2; k++) {
        mc_bench_step(&b);
        assert_int_equal(b.st.state, MC_STATE_STOPPED);
    }
    assert_cmp(b.rig.vbus_peak_v, <, (double)MC_VBUS_REGEN_V);

    /* again, and S2 while it coasts: back to the speed loop at once, the rotor driven up */
    mc_request(&b.mc, MC_REQUEST_START);
    assert_cmp(mc_bench_run_until(&b, MC_STATE_CLOSED_LOOP, 8L * PWM_FREQUENCY_HZ), >, 0);
    run(6.0);
    mc_request(&b.mc, MC_REQUEST_START_STOP);
    for (long k = 0; k < PWM_FREQUENCY_HZ / 20; k++) {
        mc_bench_step(&b);
    }
    assert_true(b.st.stopping);
    double low = mc_bench_rpm(&b);
    mc_request(&b.mc, MC_REQUEST_START_STOP);
    mc_bench_step(&b);
    assert_false(b.st.stopping);
    run(2.0);
    printf(
        "measured: S2 after 50 ms of coasting at %.0f rpm: closed loop again, %.0f rpm 2 s later\n",
        low, mc_bench_rpm(&b));
    assert_cmp(mc_bench_rpm(&b), >, low);
}

static void test_overcurrent_in_closed_loop_should_trip_in_the_period_it_is_seen(void **state)
{
    (void)state;
    start_at(1000.0);
    run(0.5);
    /* A current spike on the phase-A reading (sim: B gets the opposite)
     * that puts it 0.1 A beyond the trip whatever phase A carries (the
     * light-load Id floor gives it up to MC_ID_MIN_A at no load). */
    b.rig.spike_a = MC_OVERCURRENT_A + 0.1 - b.rig.i_abc[0];
    b.rig.spike_left = 1;
    mc_bench_step(&b);
    assert_int_equal(b.st.state, MC_STATE_FAULT);
    assert_int_equal(b.st.fault, MC_FAULT_OVERCURRENT);
    assert_false(b.out.outputs_on);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_core_should_start_the_hurst_and_hold_the_pot_speed),
        cmocka_unit_test(test_core_should_reach_top_speed_with_field_weakening_from_the_table),
        cmocka_unit_test(
            test_the_angle_should_hold_at_the_minimum_speed_with_dead_time_compensation),
        cmocka_unit_test(test_speed_reference_should_ramp_at_the_configured_rate_to_the_pot_target),
        cmocka_unit_test(test_ripple_compensation_should_follow_equation_8_on_a_rippling_bus),
        cmocka_unit_test(test_voltage_vector_should_stay_inside_the_circle_when_the_loops_saturate),
        cmocka_unit_test(test_at_the_voltage_circle_the_q_limit_should_be_exact_without_a_redo),
        cmocka_unit_test(test_the_measured_phases_should_keep_their_shunt_window_in_every_state),
        cmocka_unit_test(test_amplifiers_slower_than_the_window_should_show_as_short_samples),
        cmocka_unit_test(test_stall_should_fault_within_50_ms_when_the_rotor_locks),
        cmocka_unit_test(test_a_back_emf_far_below_what_the_speed_implies_should_fault_as_a_stall),
        cmocka_unit_test(test_an_overload_beyond_the_current_limit_should_fault_as_lost_tracking),
        cmocka_unit_test(test_the_hand_off_difference_should_bleed_to_zero_by_the_step_each_period),
        cmocka_unit_test(test_closed_loop_should_not_trip_through_speed_changes_and_load_steps),
        cmocka_unit_test(test_a_speed_gain_set_at_run_time_should_survive_the_low_speed_schedule),
        cmocka_unit_test(test_the_two_part_step_should_equal_mc_step_bit_for_bit),
        cmocka_unit_test(test_stop_in_closed_loop_should_turn_the_outputs_off_at_once),
        cmocka_unit_test(test_after_stop_the_coasting_rotor_should_read_unknown_not_a_frozen_speed),
        cmocka_unit_test(
            test_a_stop_above_the_release_speed_should_coast_at_zero_torque_then_let_go),
        cmocka_unit_test(test_overcurrent_in_closed_loop_should_trip_in_the_period_it_is_seen),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
