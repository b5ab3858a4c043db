/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_scenario.h - time-stamped scenario events read from small text files. */
#ifndef SIM_SCENARIO_H
#define SIM_SCENARIO_H

#include <stddef.h>

/*
 * File format: one event per line, `<time_s> <event> [values...]`, times
 * non-decreasing; `#` starts a comment; blank lines are ignored.
 *
 *   start                   press START/STOP if the core is stopped or faulted
 *   stop                    press START/STOP if the core is running
 *   button                  press START/STOP unconditionally
 *   identify                request the identification (MC_REQUEST_IDENTIFY)
 *   pot <0..1>              potentiometer position
 *   pot_ramp <0..1> <s>     move the potentiometer linearly over <s> seconds
 *   speed <rpm>|max|min     potentiometer position for this speed reference
 *   speed_ramp <rpm>|max <s>
 *   load <Nm>               brake-like load: opposes motion, holds at rest
 *   load_active <Nm>        constant signed torque against positive rotation
 *   load_fan <Nm>           fan load, <Nm> at the motor's rated speed, ~ speed^2
 *   vbus <V>                DC bus level
 *   vbus_ripple <V> <Hz>    sinusoidal bus ripple (peak V)
 *   lock_rotor / unlock_rotor
 *   current_spike <A> [periods]  short-circuit-like current added to phase A
 *                           (and subtracted from B) as the ADC sees it, default 1 period
 *   hw_fault                the FLTA pin trips (MC_REQUEST_HW_FAULT)
 *   deadtime <us>           inverter dead time
 *   noise <codes>           ADC noise sigma
 *   sensor_stuck a|b <A>    that phase's current reading freezes at <A> (one ADC
 *                           code, no noise: a dead amplifier or ADC channel)
 *   sensor_open a|b         its shunt amplifier's input open: it reads its bias
 *                           (0 A, with its offset and the noise)
 *   sensor_gain a|b <x>     its reading is <x> times the current
 *   sensor_drift a|b <A/s>  its offset drifts at <A/s> from now on
 *   sensor_ok a|b           that phase's sensor healthy again
 *   mark                    nothing happens: starts a new segment of the summary table
 *   zoom [s]                write every PWM period to the trace for [s] seconds
 *                           (default 0.02): the close-up panels of the plot
 *   end                     stop the simulation (required, last)
 */

typedef enum {
    SIM_EV_START,
    SIM_EV_STOP,
    SIM_EV_BUTTON,
    SIM_EV_IDENTIFY,
    SIM_EV_POT,
    SIM_EV_POT_RAMP,
    SIM_EV_SPEED,
    SIM_EV_SPEED_RAMP,
    SIM_EV_LOAD,
    SIM_EV_LOAD_ACTIVE,
    SIM_EV_LOAD_FAN,
    SIM_EV_VBUS,
    SIM_EV_VBUS_RIPPLE,
    SIM_EV_LOCK_ROTOR,
    SIM_EV_UNLOCK_ROTOR,
    SIM_EV_OPEN_LEAD,  /* v1 phase (0 = A, 1 = B, 2 = C): the motor's lead cut */
    SIM_EV_CLOSE_LEAD, /* ... connected again */
    SIM_EV_CURRENT_SPIKE,
    SIM_EV_HW_FAULT,
    SIM_EV_DEADTIME,
    SIM_EV_INVERTER,       /* averaged | switching (sim_inv_model_t) */
    SIM_EV_DEADTIME_SHAPE, /* linear | hard | ripple (sim_dt_shape_t) */
    SIM_EV_NOISE,
    SIM_EV_SENSOR_STUCK, /* v1 phase (0 = A, 1 = B), v2 A */
    SIM_EV_SENSOR_OPEN,  /* v1 phase */
    SIM_EV_SENSOR_GAIN,  /* v1 phase, v2 gain */
    SIM_EV_SENSOR_DRIFT, /* v1 phase, v2 A/s */
    SIM_EV_SENSOR_OK,    /* v1 phase */
    SIM_EV_ZOOM,
    SIM_EV_MARK,
    SIM_EV_END
} sim_event_kind_t;

/* Speed values given as `max` / `min` are flagged with these (rpm field). */
#define SIM_SPEED_MAX (-1.0)
#define SIM_SPEED_MIN (-2.0)

typedef struct {
    double t_s;
    sim_event_kind_t kind;
    double v1, v2; /* values, units as listed above; absent = 0 */
} sim_event_t;

#define SIM_SCENARIO_MAX_EVENTS 256

typedef struct {
    sim_event_t ev[SIM_SCENARIO_MAX_EVENTS];
    int n;
    double end_s; /* time of the `end` event */
} sim_scenario_t;

/* Parses a whole text (NUL-terminated). Returns 0, or -1 with a one-line
 * message "line N: <event> <value>: <why>" in err. Every number is checked
 * strictly (sim_parse.h): a plain decimal, finite, inside the value's range
 * (RULES in sim_scenario.c, listed in docs/sim.md); times 0..3600 s and
 * non-decreasing. */
int sim_scenario_parse(const char *text, sim_scenario_t *sc, char *err, size_t err_len);

/* Reads (at most 1 MiB) and parses a file; messages read "FILE:N: ...". */
int sim_scenario_load(const char *path, sim_scenario_t *sc, char *err, size_t err_len);

/* 0 when every value of every event has its range (RULES in sim_scenario.c);
 * else -1 with the event that lacks one in err. */
int sim_scenario_check_rules(char *err, size_t err_len);

/* Name of an event kind as written in the files. */
const char *sim_event_name(sim_event_kind_t k);

#endif /* SIM_SCENARIO_H */
