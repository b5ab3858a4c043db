/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_inverter.h - three-phase inverter (averaged or switching) with dead time, DC bus with ripple.
 */
#ifndef SIM_INVERTER_H
#define SIM_INVERTER_H

#include <stdbool.h>
#include <stdint.h>

#include "sim_parse.h"

/*
 * Averaged model (no switching ripple): over one integration sub-step the pin
 * of phase k sits, on average, at
 *
 *   V_k = (d_k - Td/Ts * s(i_k)) * Vbus,  clamped to [0, Vbus]
 *
 * versus the negative rail, with d_k = duty[k] / duty_max. s(i) is the sign of
 * the phase current (+ = into the motor), made linear inside +-i_band: while the
 * current is smaller than the PWM current ripple it changes sign inside the
 * period and the dead-time error fades (note 1 in sim_inverter.c). A duty of
 * exactly 0 or duty_max has no switching edge, hence no dead time.
 * The star point floats: phase-to-neutral voltages are the pin voltages minus
 * their mean. With all switches off the pins are set by the free-wheeling
 * diodes (handled by sim_rig.c).
 *
 * The shape of s(i) (dt_shape, note 2 in sim_inverter.c):
 *   SIM_DT_LINEAR  clamp(i / i_band, -1, 1)            (the default)
 *   SIM_DT_HARD    sign(i): the dead-time error at full size down to 0 A
 *   SIM_DT_RIPPLE  (2 / pi) asin(clamp(i / i_band)): sign(i + a sin phi)
 *                  averaged over the phase phi of a ripple of peak a = i_band
 *
 * Switching model (model = SIM_INV_SWITCHING): the pins are evaluated at
 * each instant of the period instead (sim_inverter_pin_at), with the
 * switching edges as integration boundaries (sim_inverter_edges). Centre-
 * aligned, as the dsPIC's MCPWM: with h = d Ts / 2, phase k's high switch
 * is on for t < h and from Ts - h + Td (it carries on into the next period),
 * its low switch from h + Td to Ts - h; between, both are off for a dead
 * time and the diode of the rail the current flows from conducts (current
 * into the motor: the low diode, pin at -Vf; out of it: the high diode,
 * Vbus + Vf), by the sign of the current at the edge that began the dead
 * time. A switch that conducts drops i r_on. A high pulse shorter than the
 * dead time (h < Td) vanishes; so does a low one (Ts - 2h < Td). Duty 0 and
 * 100 % have no edge.
 */

typedef enum {
    SIM_INV_AVERAGED = 0, /* period-averaged pin voltages (the default) */
    SIM_INV_SWITCHING = 1 /* every edge of the period, dead time and diodes */
} sim_inv_model_t;

typedef enum {
    SIM_DT_LINEAR = 0, /* the averaged model's dead-time shape, see above */
    SIM_DT_HARD = 1,
    SIM_DT_RIPPLE = 2
} sim_dt_shape_t;

typedef struct {
    double vbus_v;     /* DC bus level, V */
    double ripple_v;   /* peak of a sinusoidal bus ripple, V (0 = none) */
    double ripple_hz;  /* its frequency, Hz */
    double deadtime_s; /* Td, s (the boards: 2e-6) */
    double pwm_hz;     /* 1/Ts, Hz */
    double duty_max;   /* duty count of 100 % (PWM_DUTY_MAX) */
    double i_band_a;   /* dead-time linear band, A; <= 0: automatic, see sim_inverter_init */
    int model;         /* sim_inv_model_t */
    int dt_shape;      /* sim_dt_shape_t, averaged model only */
    double r_on_ohm;   /* switching model: conducting switch's resistance, ohm (0: none) */
    double v_diode_v;  /* switching model: diode forward drop, V (0: none) */
} sim_inverter_params_t;

typedef struct {
    sim_inverter_params_t prm;
    double i_band_a;  /* band in use, A */
    uint16_t duty[3]; /* latched duties, applied during the present period */
    bool on;          /* latched output enable */
} sim_inverter_t;

/* The names scenario files and the command line use, with the value of
 * each: "averaged", "switching" (sim_inv_model_t); "linear", "hard",
 * "ripple" (sim_dt_shape_t). */
extern const sim_word_t sim_inverter_models[];
extern const sim_word_t sim_inverter_shapes[];

/* Outputs off, duties 0. l_h: motor inductance used for the automatic band
 * Vbus / (12 L fpwm), about half the peak PWM current ripple. */
void sim_inverter_init(sim_inverter_t *inv, const sim_inverter_params_t *prm, double l_h);

/* Latches the duties and enable that apply from now on (next period). */
void sim_inverter_latch(sim_inverter_t *inv, const uint16_t duty[3], bool on);

/* Bus voltage at time t (s), V, never negative. */
double sim_inverter_vbus(const sim_inverter_t *inv, double t_s);

/* Pin voltages vs the negative rail (V) with the outputs on. */
void sim_inverter_pins(const sim_inverter_t *inv, double vbus, const double i_abc[3],
                       double v_pin[3]);

/* Switching model: the edges of the latched duties strictly inside
 * (t0, t1), times within the period (0..Ts), s, ascending, at most
 * SIM_INV_MAX_EDGES. Returns their count. */
#define SIM_INV_MAX_EDGES 15
int sim_inverter_edges(const sim_inverter_t *inv, double t0, double t1, double edge[]);

/* Switching model: pin voltages vs the negative rail (V) with the outputs on,
 * over the interval that starts at t (within the period, s) and ends at the
 * next edge; i_abc, the currents at its start, give the diodes' rails. */
void sim_inverter_pins_at(const sim_inverter_t *inv, double vbus, const double i_abc[3], double t,
                          double v_pin[3]);

/* How long phase k's low leg (its switch, or for a current i >= 0 into the
 * motor its diode from the high switch's turn-off) has carried the phase
 * current at time t within the period, s; 0 if the high side holds the pin
 * then. The edges are those of sim_inverter_edges; used for the shunt
 * window in both models (sim_rig.h). */
double sim_inverter_low_conduction(const sim_inverter_t *inv, int k, double t, double i);

/* Phase-to-neutral alpha-beta voltage of three pin voltages (floating star). */
void sim_pins_to_ab(const double v_pin[3], double *v_alpha, double *v_beta);

#endif /* SIM_INVERTER_H */
