/* sim_core.h - the firmware core (mc.h) driven by the simulated bench, in physical units. */
#ifndef SIM_CORE_H
#define SIM_CORE_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "mc.h"
#include "sim_profiles.h"
#include "sim_rig.h"
#include "sim_scenario.h"

/*
 * Everything the simulator program and the closed-loop tests share. The core
 * is reached only through firmware/mc.h; every conversion between its Q15
 * values and physical units uses the scale macros that header provides
 * (BOARD_I_FULLSCALE_A, BOARD_VBUS_FULLSCALE_V, PWM_FREQUENCY_HZ,
 * PWM_DUTY_MAX, MOTOR_POLE_PAIRS, MC_SPEED_FULLSCALE_RPM, SPEED_REF_MIN_RPM,
 * SPEED_REF_MAX_RPM, MC_VOLTAGE_FULLSCALE_V).
 */

typedef struct {
    const char *motor;  /* simulated motor profile (sim_profiles.c) */
    const char *board;  /* simulated board profile */
    double rs_scale;    /* plant R = profile R * rs_scale (mismatch with UserParms.h) */
    double l_scale;     /* plant Ld, Lq */
    double ke_scale;    /* plant flux linkage */
    double j_scale;     /* plant inertia */
    double theta0_rad;  /* initial electrical angle */
    double rpm0;        /* initial mechanical speed, rpm (a spinning rotor) */
    double deadtime_s;  /* < 0: the board's */
    double noise_codes; /* < 0: the board's */
    double vbus_v;      /* < 0: the board's */
    uint32_t seed;      /* ADC noise seed */
    int substeps;       /* RK4 steps per PWM period */
    double sample_at;   /* ADC sample instant in the period; < 0: the chip's, MC_SAMPLE_AT */
    double amp_tau_s;   /* current amplifiers' time constant, s; < 0: the board's */
    bool offsets_set;   /* false: the board's amplifier offsets; true: the two below */
    double offset_a_codes, offset_b_codes; /* amplifier offsets, ADC codes */
    double j_extra_kgm2;       /* load inertia added to the motor's (after j_scale), kg m^2 */
    double b_scale;            /* plant viscous friction times this */
    double coulomb_nm;         /* plant dry friction, N m; < 0: the profile's */
    sim_inverter_params_t inv; /* model, dt_shape, i_band_a, r_on_ohm, v_diode_v taken from here */
    int csv_decim;             /* CSV row every N periods */
    FILE *csv;                 /* NULL: no CSV */
    bool progress;             /* progress line on stderr for long runs */
} simcore_cfg_t;

/* One PWM period as seen by an engineer, physical units. Taken at the
 * sampling instant (period start) for the plant, after mc_step() for the core. */
typedef struct {
    double t_s;
    int state;
    unsigned fault;
    double speed_target_rpm, speed_ref_rpm, speed_est_rpm, speed_rpm; /* mechanical */
    double theta_est_deg, theta_deg, theta_err_deg;                   /* electrical, wrapped */
    double id_ref_a, iq_ref_a, id_a, iq_a;                            /* the core's (its frame) */
    double id_true_a, iq_true_a;                                      /* the plant's (true frame) */
    double ia_a, ib_a, ic_a;                                          /* true phase currents */
    double duty[3]; /* 0..1, computed this period */
    bool outputs_on;
    double vbus_v, load_nm, torque_nm;
    double vd_v, vq_v; /* the core's voltage command */
    bool estimator_valid;
} simcore_sample_t;

#define SIMCORE_MAX_LOG 64
#define SIMCORE_MAX_SEG 96

typedef struct {
    double t0_s, t1_s, win_s; /* segment and the start of its measuring window */
    char label[40];           /* the event that opened it */
    long n;                   /* samples in the window (closed loop only) */
    long n_all;               /* samples in the window */
    double ref_sum, spd_sum, est_sum, iq_sum;
    double ang_sum, ang_sum2, ang_max;
    int state_end;
} simcore_segment_t;

typedef struct {
    simcore_cfg_t cfg;
    const sim_motor_profile_t *mp;
    const sim_board_profile_t *bp;
    sim_rig_t rig;
    mc_t mc;
    mc_status_t st;
    simcore_sample_t now;
    double rated_nm;
    /* run metrics */
    double t_start_s;  /* first start request, < 0 none */
    double t_closed_s; /* first CLOSED_LOOP, < 0 never */
    double t_enter_closed_s;
    double i_peak_a, t_i_peak_s;
    int n_log;
    struct {
        double t_s;
        int from, to;
        unsigned fault;
    } log[SIMCORE_MAX_LOG];
    int n_seg;
    simcore_segment_t seg[SIMCORE_MAX_SEG];
    int prev_state;
    double zoom_until_s; /* full-rate trace rows until this time */
    /* The plant left what its integration can follow (simcore_step): set once,
     * every later simcore_step is a no-op. */
    bool diverged;
    double diverged_t_s, diverged_rpm;
} simcore_t;

/* The largest electrical angle the plant may turn in one RK4 sub-step, rad:
 * beyond it the rotating-frame coupling is integrated too coarsely to trust
 * (RK4 on a pure rotation is stable to 2.8 rad but loses accuracy long before;
 * 0.5 rad keeps the amplitude error per step near 0.01 %). */
#define SIMCORE_MAX_STEP_RAD 0.5

/* Returns 0, or -1 with a message on stderr (unknown profile, pole pairs
 * differ from the core's MOTOR_POLE_PAIRS...). */
int simcore_init(simcore_t *s, const simcore_cfg_t *cfg);

/* Defaults: hurst on mclv, no mismatch, 4 sub-steps, board dead time and noise. */
void simcore_cfg_default(simcore_cfg_t *cfg);

/* One PWM period; fills s->now. Once the plant's state is not finite or it
 * turns faster than SIMCORE_MAX_STEP_RAD per sub-step (an active load driving
 * the rotor), sets s->diverged and does nothing from then on. */
void simcore_step(simcore_t *s);

/* One line saying where and how the plant diverged (s->diverged set). */
void simcore_diverged_msg(const simcore_t *s, char *buf, size_t len);

/* Applies a scenario event now (controller- or plant-side). */
void simcore_event(simcore_t *s, const sim_event_t *ev);

/* Runs a whole scenario; segments for the summary are set from its events.
 * Returns 0, or -1 when the plant diverged (the run stops there). */
int simcore_run_scenario(simcore_t *s, const sim_scenario_t *sc, const char *name);

/* Prints the summary table. */
void simcore_print_summary(const simcore_t *s, FILE *f, const char *name);

/* Helpers for tests and the program. */
void simcore_set_speed(simcore_t *s, double rpm); /* pot position for this reference */
void simcore_request(simcore_t *s, mc_request_t r);
double simcore_pot_for_rpm(double rpm);
void simcore_csv_header(FILE *f);

#endif /* SIM_CORE_H */
