/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_core.h - the one bench: the firmware core (mc.h) on the simulated plant, inverter and ADC. */
#ifndef SIM_CORE_H
#define SIM_CORE_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "mc.h"
#include "sim_log.h"
#include "sim_profiles.h"
#include "sim_rig.h"
#include "sim_sample.h"
#include "sim_scenario.h"

/*
 * The bench everything closed-loop runs on: the simulator program, sim
 * --pty, the randomized campaign (robust.c), the closed-loop tests
 * (test/closedloop), the firmware tests (test/firmware/mc_bench.h) and the
 * benchmarks (tools/bench). simcore_init builds it from a motor and a board
 * profile (sim_profiles.h; a profile the simulator lacks is taken from this
 * build's firmware headers) and a configuration; simcore_step runs one PWM
 * period: the ADC samples the plant, the core steps, the plant runs on to
 * the next sample with the duties latched at the period boundary.
 *
 * The core is reached only through firmware/mc.h; every conversion between
 * its Q15 values and physical units uses the scale macros that header
 * provides (BOARD_I_FULLSCALE_A, BOARD_VBUS_FULLSCALE_V, PWM_FREQUENCY_HZ,
 * PWM_DUTY_MAX, MOTOR_POLE_PAIRS, MC_SPEED_FULLSCALE_RPM, SPEED_REF_MIN_RPM,
 * SPEED_REF_MAX_RPM, MC_VOLTAGE_FULLSCALE_V). This file is compiled once
 * per copy of the core (sim_core_library in tools/sim/CMakeLists.txt).
 */

typedef struct {
    const char *motor; /* simulated motor profile (sim_profiles.h) */
    const char *board; /* simulated board profile */
    double rs_scale;   /* plant R = profile R * rs_scale (a mismatch with the firmware's profile) */
    double l_scale;    /* plant Ld, Lq */
    double ke_scale;   /* plant flux linkage */
    double j_scale;    /* plant inertia */
    double theta0_rad; /* initial electrical angle */
    double rpm0;       /* initial mechanical speed, rpm (a spinning rotor) */
    double pot;        /* initial potentiometer position, 0..1 */
    double deadtime_s; /* < 0: the board's */
    double noise_codes; /* < 0: the board's */
    double vbus_v;      /* < 0: the board's */
    uint32_t seed;      /* ADC noise seed */
    int substeps;       /* RK4 steps per PWM period */
    double sample_at;   /* ADC sample instant in the period; < 0: the chip's, MC_SAMPLE_AT */
    double amp_tau_s;   /* current amplifiers' time constant, s; < 0: the board's */
    bool bus_model;     /* the DC bus as its capacitor and a supply that only sources
                           (sim_rig.h); false: a bus held at the supply's level */
    bool offsets_set;   /* false: the board's amplifier offsets; true: the two below */
    double offset_a_codes, offset_b_codes; /* amplifier offsets, ADC codes */
    double j_extra_kgm2;       /* load inertia added to the motor's (after j_scale), kg m^2 */
    double b_scale;            /* plant viscous friction times this */
    double coulomb_nm;         /* plant dry friction, N m; < 0: the profile's */
    sim_inverter_params_t inv; /* model, dt_shape, i_band_a, r_on_ohm, v_diode_v taken from here */
    int csv_decim;             /* CSV row every N periods */
    FILE *csv;                 /* NULL: no CSV */
    FILE *record;              /* NULL: no period record (sim_record.h) */
    bool progress;             /* progress line on stderr for long runs */
} simcore_cfg_t;

typedef struct {
    simcore_cfg_t cfg;
    const sim_motor_profile_t *mp;
    const sim_board_profile_t *bp;
    sim_rig_t rig;
    mc_t mc;
    mc_status_t st;        /* after the last period's step */
    mc_pwm_out_t out;      /* the duties of the last period */
    sim_adc_frame_t frame; /* the last period's ADC conversion */
    double theta_sample;   /* true electrical angle at the last sample, rad */
    double rpm_sample;     /* true speed then, rpm */
    sim_sample_t now;      /* the last period, physical units */
    double rated_nm;       /* the motor's rated torque, N m */
    sim_log_t log;         /* the run so far */
    double zoom_until_s;   /* full-rate trace rows until this time */
    /* The plant left what its integration can follow (simcore_step): set once,
     * every later simcore_step is a no-op. */
    bool diverged;
    double diverged_t_s, diverged_rpm;
    uint16_t requests;  /* requests posted since the last step, for the record (bit r) */
    bool record_failed; /* a write of the period record failed */
} simcore_t;

/* The largest electrical angle the plant may turn in one RK4 sub-step, rad:
 * beyond it the rotating-frame coupling is integrated too coarsely to trust
 * (RK4 on a pure rotation is stable to 2.8 rad but loses accuracy long before;
 * 0.5 rad keeps the amplitude error per step near 0.01 %). */
#define SIMCORE_MAX_STEP_RAD 0.5

/* Defaults: hurst on mclv, no mismatch, at rest at angle 0, pot at 0, the
 * board's dead time, noise and offsets, noise seed 1, 4 sub-steps, the
 * chip's sample instant, no trace. */
void simcore_cfg_default(simcore_cfg_t *cfg);

/* Returns 0, or -1 with a message on stderr (unknown profile, pole pairs
 * differ from the core's MOTOR_POLE_PAIRS...). */
int simcore_init(simcore_t *s, const simcore_cfg_t *cfg);

/* One PWM period: simcore_sample, mc_step and mc_slow_step (into s->out),
 * simcore_finish. Once the plant's state is not finite or it turns faster
 * than SIMCORE_MAX_STEP_RAD per sub-step (an active load driving the
 * rotor), sets s->diverged and does nothing from then on. */
void simcore_step(simcore_t *s);

/* The period in two halves, for a caller that steps the core itself (the
 * benchmarks): the ADC conversion at this period's sample instant into in,
 * s->frame and the plant's side of s->now; then, with the core's duties in
 * s->out, its status and its side of s->now, the plant on to the next
 * sample, the run's record and trace. */
void simcore_sample(simcore_t *s, mc_adc_frame_t *in);
void simcore_finish(simcore_t *s);

/* One line saying where and how the plant diverged (s->diverged set). */
void simcore_diverged_msg(const simcore_t *s, char *buf, size_t len);

/* Applies a scenario event now (controller- or plant-side). */
void simcore_event(simcore_t *s, const sim_event_t *ev);

/* Runs a whole scenario; segments for the summary are set from its events.
 * Returns 0, or -1 when the plant diverged (the run stops there). */
int simcore_run_scenario(simcore_t *s, const sim_scenario_t *sc, const char *name);

/* Prints the summary table. */
void simcore_print_summary(const simcore_t *s, FILE *f, const char *name);

/* The identification's result against the plant's parameters (nothing
 * when none was requested). */
void simcore_print_identify(const simcore_t *s, FILE *f);

/* What the identification should have found: the plant's parameters in
 * mc_id_result_t's terms (R per phase, Ld, Lq and their mean, the peak
 * line-to-line back-EMF per mechanical rpm, the inertia, the inverter's
 * dead time), and the result's errors against them, per cent. */
typedef struct {
    double rs_ohm, ld_h, lq_h, ls_h, ke_v_per_krpm, j_kgm2, deadtime_s;
} simcore_id_truth_t;
typedef struct {
    double rs, ld, lq, ls, ke, j, deadtime; /* (measured / true - 1) x 100 */
} simcore_id_err_t;
void simcore_identify_truth(const simcore_t *s, simcore_id_truth_t *t);
void simcore_identify_errors(const simcore_t *s, const mc_id_result_t *r, simcore_id_err_t *e);

/* Helpers for tests and the program. */
void simcore_set_speed(simcore_t *s, double rpm); /* pot position for this reference */
void simcore_request(simcore_t *s, mc_request_t r);
double simcore_pot_for_rpm(double rpm);

#endif /* SIM_CORE_H */
