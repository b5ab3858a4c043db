/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_sample.h - one PWM period of the core on the bench, as an engineer reads it. */
#ifndef SIM_SAMPLE_H
#define SIM_SAMPLE_H

#include <stdbool.h>

/*
 * Physical units throughout. The plant's values are taken at the period's
 * ADC sample; the core's after its step of that period (sim_core.c fills it,
 * sim_window.c sums it, sim_trace.c writes it, sim_log.c keeps the run's
 * record of it).
 */
typedef struct {
    double t_s; /* start of the period, s */
    int state;  /* the core's mc_state_t */
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
} sim_sample_t;

#endif /* SIM_SAMPLE_H */
