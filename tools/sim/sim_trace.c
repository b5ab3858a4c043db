/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_trace.c - the CSV trace of a run (sim_trace.h). */
#include "sim_trace.h"

void sim_trace_header(FILE *f)
{
    fprintf(f, "t_s,state,fault,speed_target_rpm,speed_ref_rpm,speed_est_rpm,speed_rpm,"
               "theta_est_deg,theta_deg,theta_err_deg,id_ref_A,id_A,iq_ref_A,iq_A,id_true_A,"
               "iq_true_A,ia_A,ib_A,ic_A,duty_a,duty_b,duty_c,outputs_on,vbus_V,load_Nm,"
               "torque_Nm,vd_V,vq_V,estimator_valid,zoom\n");
}

void sim_trace_row(FILE *f, const sim_sample_t *s, bool zoom)
{
    fprintf(f,
            "%.6f,%d,%u,%.2f,%.2f,%.2f,%.2f,%.3f,%.3f,%.3f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,"
            "%.4f,%.4f,%.4f,%.4f,%.4f,%d,%.3f,%.5f,%.5f,%.3f,%.3f,%d,%d\n",
            s->t_s, s->state, s->fault, s->speed_target_rpm, s->speed_ref_rpm, s->speed_est_rpm,
            s->speed_rpm, s->theta_est_deg, s->theta_deg, s->theta_err_deg, s->id_ref_a, s->id_a,
            s->iq_ref_a, s->iq_a, s->id_true_a, s->iq_true_a, s->ia_a, s->ib_a, s->ic_a, s->duty[0],
            s->duty[1], s->duty[2], s->outputs_on ? 1 : 0, s->vbus_v, s->load_nm, s->torque_nm,
            s->vd_v, s->vq_v, s->estimator_valid ? 1 : 0, zoom ? 1 : 0);
}
