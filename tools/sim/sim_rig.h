/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_rig.h - plant, inverter and ADC, one PWM period a step (sim_core.h adds the core). */
#ifndef SIM_RIG_H
#define SIM_RIG_H

#include <stdbool.h>
#include <stdint.h>

#include "sim_adc.h"
#include "sim_inverter.h"
#include "sim_plant.h"
#include "sim_scenario.h"

/*
 * Timing (the chip's, mc.h): the ADC samples the plant at sample_at of period
 * n (a fraction of the period after its start; the dsPIC: the midpoint plus
 * the trigger offset, MC_SAMPLE_AT) (sim_rig_sample); the controller
 * computes duties D(n); the plant runs the rest of period n with the duties
 * latched before, D(n-1), D(n) is latched at the period boundary, and the
 * plant runs on with it up to the next sample (sim_rig_advance). sample_at =
 * 0 is a sample at the period start and a whole period of delay. Each period is integrated in
 * `substeps` RK4 steps, the inverter re-evaluated (dead time, bus ripple) at
 * each. With the outputs off the phases are held by the free-wheeling diodes:
 * a conducting phase sits at the rail its current flows into, a phase whose
 * current has died out floats at its back-EMF, and a stator whose line-to-line
 * back-EMF stays below the bus is open (no current).
 */

typedef struct {
    sim_motor_params_t motor;
    sim_inverter_params_t inv;
    sim_adc_params_t adc;
    int substeps;         /* RK4 steps per PWM period (>= 1; >= 2 when sample_at > 0) */
    double sample_at;     /* ADC sample instant in the period, 0 <= x < 1 (0: at its start) */
    double amp_tau_s;     /* current amplifiers' time constant, s (0: ideal; note below) */
    double theta_e0;      /* initial electrical angle, rad */
    double omega0_m;      /* initial mechanical speed, rad/s */
    double fan_rated_rpm; /* speed at which load_fan gives its nominal torque, rpm */
    double bus_c_f;       /* the bus model's capacitance, F; 0: no model (note 2) */
    double supply_r_ohm;  /* its supply's output resistance, ohm */
} sim_rig_params_t;

/* A current sensor's health (scenario events sensor_*). */
typedef enum { SIM_SENSOR_OK, SIM_SENSOR_STUCK, SIM_SENSOR_OPEN } sim_sensor_mode_t;

typedef struct {
    sim_sensor_mode_t mode;
    double stuck_a;    /* SIM_SENSOR_STUCK: the frozen reading, A */
    double gain;       /* reading / current (1 healthy) */
    double drift_a_s;  /* offset drift, A/s ... */
    double drift_t0_s; /* ... since this time, s ... */
    double drift_a;    /* ... on top of the offset it had built up by then, A */
} sim_sensor_t;

typedef struct {
    sim_plant_t plant;
    sim_inverter_t inv;
    sim_adc_t adc;
    int substeps;
    double sample_at;       /* as in sim_rig_params_t */
    double ts;              /* PWM period, s */
    double t;               /* start of the period the last sample fell in, s */
    long period;            /* periods completed */
    double pot;             /* potentiometer, 0..1 */
    double pot_target;      /* ramp end, 0..1 */
    double pot_rate;        /* ramp rate, 1/s (0 = no ramp) */
    double spike_a;         /* current added to the phase-A reading (B: subtracted), A */
    long spike_left;        /* periods of spike still to come */
    sim_sensor_t sensor[2]; /* the phase-A and phase-B current sensors */
    bool floating[3];       /* outputs off: phase not conducting */
    int open_lead;          /* a motor lead cut (open_lead event): its phase, 0..2; -1: none */
    bool was_on;
    double fan_rated_w;  /* rad/s */
    double i_abc[3];     /* phase currents at the last sample, A */
    double vbus_sampled; /* V */
    double amp_tau_s;    /* as in sim_rig_params_t */
    long samples_short;  /* samples with the outputs on where a measured phase's shunt had
                            conducted less than SIM_AMP_SETTLE_TAUS time constants */
    double t_cond_min_s; /* shortest such conduction seen before a sample, s */
    double bus_c_f;      /* as in sim_rig_params_t */
    double supply_r_ohm;
    double vcap_v;                  /* the bus model: the capacitor's voltage, V */
    double vbus_peak_v, vbus_low_v; /* ... its highest and lowest so far, V */
    double t_vbus_peak_s;           /* ... when it was highest, s */
    double e_bus_in_j;              /* ... energy the inverter put into the bus, J (signed) */
} sim_rig_t;

/*
 * Note 2, the bus model (bus_c_f > 0). The bus is a capacitor C fed
 * through the supply's resistance R by a supply that only sources current
 * (a bench supply or a rectifier: no current back into it):
 *   C dv/dt = max(0, (v_s - v) / R) - i_dc,   i_dc = sum_k s_k i_k,
 * v_s the supply's level (the board's bus, `bus` events, ripple), i_k the
 * phase currents into the motor and s_k the share of the bus on pin k
 * (its duty, or 1 / 0 for a pin at the top / bottom rail; with the outputs
 * off, the conducting diodes'). A regenerating motor makes i_dc negative
 * and, the supply blocked, charges C. Each sub-step integrates exactly for
 * a constant i_dc while the supply conducts, linearly while it does not,
 * and the pins and the ADC see v. Without the model (bus_c_f 0) the bus is
 * v_s whatever the motor does.
 */

/*
 * The shunt window. Phases A and B are measured by low-side shunts and
 * amplifiers: a shunt carries the phase current only while its leg's low
 * side conducts (centre-aligned PWM: from d Ts / 2 after the period start
 * to d Ts / 2 before its end, d the latched duty), the switch after the
 * dead time, the diode at once for a current into the motor. At the sample
 * the amplifier reads i (1 - exp(-t / amp_tau_s)) after t of conduction, 0
 * if the low side is off then (the high side has held the shunt at zero
 * current): what a board reads when the core's duty leaves too short a
 * window. samples_short counts the samples where t was below
 * SIM_AMP_SETTLE_TAUS time constants, the settling to half a code of a
 * full-scale step of the 10-bit ADC.
 */
#define SIM_AMP_SETTLE_TAUS 6.93 /* ln(1024) */

void sim_rig_init(sim_rig_t *r, const sim_rig_params_t *prm);

/* ADC conversion at the sample instant of the present period. */
void sim_rig_sample(sim_rig_t *r, sim_adc_frame_t *out);

/* Runs from this sample to the next: the rest of the period with the latched
 * duties, then these latched at the boundary for the start of the next. */
void sim_rig_advance(sim_rig_t *r, const uint16_t duty[3], bool on);

/* Applies a plant-side event (load, bus, rotor lock, spike, pot, dead time,
 * noise). Returns false for controller-side events (start, stop, button,
 * speed, speed_ramp, hw_fault, end), which the caller handles. */
bool sim_rig_apply(sim_rig_t *r, const sim_event_t *ev);

#endif /* SIM_RIG_H */
