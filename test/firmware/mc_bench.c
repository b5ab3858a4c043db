/* mc_bench.c - the mc core on the simulator's plant, for the firmware tests. */
#include "mc_bench.h"

#include <math.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

void mc_bench_cfg_default(mc_bench_cfg_t *c)
{
    c->motor = "hurst";
    c->board = "mclv";
    c->theta0_rad = 0.3;
    c->deadtime_s = -1.0;
    c->noise_codes = -1.0;
    c->vbus_v = -1.0;
    c->amp_tau_s = -1.0;
    c->pot = 0.0;
}

void mc_bench_init(mc_bench_t *b, const mc_bench_cfg_t *c)
{
    const sim_motor_profile_t *mp = sim_motor_profile(c->motor);
    const sim_board_profile_t *bp = sim_board_profile(c->board);
    sim_rig_params_t rp;
    memset(&rp, 0, sizeof(rp));
    sim_motor_params_from_profile(mp, &rp.motor);
    rp.inv.vbus_v = (c->vbus_v >= 0.0) ? c->vbus_v : bp->vbus_v;
    rp.inv.deadtime_s = (c->deadtime_s >= 0.0) ? c->deadtime_s : bp->deadtime_s;
    rp.inv.pwm_hz = (double)PWM_FREQUENCY_HZ;
    rp.inv.duty_max = (double)PWM_DUTY_MAX;
    rp.adc.i_fs_a = (double)BOARD_I_FULLSCALE_A;
    rp.adc.vbus_fs_v = (double)BOARD_VBUS_FULLSCALE_V;
    rp.adc.bits = 10;
    rp.adc.offset_a_codes = bp->offset_a_codes;
    rp.adc.offset_b_codes = bp->offset_b_codes;
    rp.adc.noise_codes = (c->noise_codes >= 0.0) ? c->noise_codes : bp->noise_codes;
    rp.adc.seed = 12345u;
    rp.substeps = 2;
    rp.sample_at = MC_SAMPLE_AT; /* the chip's timing (mc.h) */
    rp.amp_tau_s = (c->amp_tau_s >= 0.0) ? c->amp_tau_s : bp->amp_tau_s;
    rp.theta_e0 = c->theta0_rad;
    rp.fan_rated_rpm = mp->rated_rpm;
    sim_rig_init(&b->rig, &rp);
    b->rig.pot = c->pot;
    b->rig.pot_target = c->pot;
    mc_init(&b->mc);
    mc_status(&b->mc, &b->st); /* not the previous run's */
    b->n = 0;
    b->out.duty[0] = b->out.duty[1] = b->out.duty[2] = PWM_DUTY_MAX / 2U;
    b->out.outputs_on = false;
}

void mc_bench_step(mc_bench_t *b)
{
    mc_adc_frame_t in;
    sim_rig_sample(&b->rig, &b->frame);
    b->theta_sample = b->rig.plant.s.theta_e;
    b->rpm_sample = sim_plant_rpm(&b->rig.plant);
    in.ia = b->frame.ia;
    in.ib = b->frame.ib;
    in.vbus = b->frame.vbus;
    in.pot = b->frame.pot;
    mc_step(&b->mc, &in, &b->out);
    mc_slow_step(&b->mc); /* a no-op except after a window end (mc.h note 4) */
    sim_rig_advance(&b->rig, b->out.duty, b->out.outputs_on);
    mc_status(&b->mc, &b->st);
    b->n++;
}

long mc_bench_run_until(mc_bench_t *b, mc_state_t s, long n)
{
    for (long k = 0; k < n; k++) {
        mc_bench_step(b);
        if (b->st.state == s) {
            return k + 1;
        }
    }
    return -1;
}

double mc_bench_rpm(const mc_bench_t *b)
{
    return sim_plant_rpm(&b->rig.plant);
}

double mc_bench_angle_err_deg(const mc_bench_t *b)
{
    double est = (double)b->st.theta_est * M_PI / 32768.0;
    double d = sim_wrap_pi(est - b->theta_sample);
    return d * 180.0 / M_PI;
}

double mc_rpm_of_q15(int16_t q)
{
    return (double)q * (double)MC_SPEED_FULLSCALE_RPM / 32768.0;
}
