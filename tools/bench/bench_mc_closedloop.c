/* bench_mc_closedloop.c - instructions per mc_step in closed loop, the core on the simulated Hurst.
 */
/* bench-requires: firmware/mc.c smc_estimator/smc.c tools/sim/sim_rig.c */
/* bench-symbols: mc_init mc_step sim_rig_init sim_rig_sample sim_rig_advance */
#include "bench.h"

#include <string.h>

#include "mc.h"
#include "sim_profiles.h"
#include "sim_rig.h"

/*
 * The core is started on the simulator's Hurst (tools/sim, ideal 24 V bus,
 * board dead time and ADC noise) and run into CLOSED_LOOP with plain
 * mc_step() calls, which callgrind does not count; then every period of the
 * measured run goes through mc_bench_cl_step(), the counted symbol: one
 * mc_step() plus a call's overhead. The run ramps the speed from 1500 rpm to
 * the top of field weakening and back, so every path of the closed loop
 * (speed loop every IRP_PERCALC periods, field weakening, voltage limit) is
 * in the max and the mean.
 */

static sim_rig_t rig;
static mc_t mc;

static void rig_init(void)
{
    sim_rig_params_t rp;
    const sim_motor_profile_t *mp = sim_motor_profile("hurst");
    const sim_board_profile_t *bp = sim_board_profile("mclv");
    memset(&rp, 0, sizeof(rp));
    sim_motor_params_from_profile(mp, &rp.motor);
    rp.inv.vbus_v = bp->vbus_v;
    rp.inv.deadtime_s = bp->deadtime_s;
    rp.inv.pwm_hz = (double)PWM_FREQUENCY_HZ;
    rp.inv.duty_max = (double)PWM_DUTY_MAX;
    rp.adc.i_fs_a = (double)BOARD_I_FULLSCALE_A;
    rp.adc.vbus_fs_v = (double)BOARD_VBUS_FULLSCALE_V;
    rp.adc.bits = 10;
    rp.adc.offset_a_codes = bp->offset_a_codes;
    rp.adc.offset_b_codes = bp->offset_b_codes;
    rp.adc.noise_codes = bp->noise_codes;
    rp.adc.seed = 4242U;
    rp.substeps = 2;
    rp.sample_at = MC_SAMPLE_AT; /* the chip's timing (mc.h) */
    rp.amp_tau_s = bp->amp_tau_s;
    rp.theta_e0 = 0.3;
    rp.fan_rated_rpm = mp->rated_rpm;
    sim_rig_init(&rig, &rp);
}

static void frame_in(mc_adc_frame_t *in)
{
    sim_adc_frame_t f;
    sim_rig_sample(&rig, &f);
    in->ia = f.ia;
    in->ib = f.ib;
    in->vbus = f.vbus;
    in->pot = f.pot;
}

/* The counted symbols: the step, and the slow step after each window end. */
__attribute__((noinline)) void mc_bench_cl_step(const mc_adc_frame_t *in, mc_pwm_out_t *out);
__attribute__((noinline)) void mc_bench_cl_step(const mc_adc_frame_t *in, mc_pwm_out_t *out)
{
    mc_step(&mc, in, out);
}
__attribute__((noinline)) void mc_bench_cl_slow(void);
__attribute__((noinline)) void mc_bench_cl_slow(void)
{
    mc_slow_step(&mc);
}

static void run_periods(uint32_t n)
{
    uint32_t k;
    mc_adc_frame_t in;
    mc_pwm_out_t out;
    rig_init();
    mc_init(&mc);
    rig.pot = 0.2; /* about 1460 rpm */
    mc_request(&mc, MC_REQUEST_START);
    for (k = 0U; k < 200000UL && mc.state != MC_STATE_CLOSED_LOOP; k++) {
        frame_in(&in);
        mc_step(&mc, &in, &out);
        mc_slow_step(&mc);
        sim_rig_advance(&rig, out.duty, out.outputs_on);
    }
    for (k = 0U; k < n; k++) {
        /* Pot to full travel after a quarter of the run: the reference
         * ramps into field weakening at MC_SPEED_RAMP_RPM_PER_S. */
        rig.pot = (k < n / 4U) ? 0.2 : 1.0;
        frame_in(&in);
        mc_bench_cl_step(&in, &out);
        if (mc.slow_busy) {
            mc_bench_cl_slow();
        } else {
            mc_slow_step(&mc); /* the same no-op, uncounted */
        }
        sim_rig_advance(&rig, out.duty, out.outputs_on);
        bench_sink += (int32_t)out.duty[0] + (int32_t)mc.state;
    }
}

/* n periods: n calls of mc_bench_cl_step. */
static void run_closed_loop(uint32_t n)
{
    run_periods(n);
}

/* n calls of mc_bench_cl_slow: one per window. */
static void run_closed_loop_slow(uint32_t n)
{
    run_periods(n * MC_SLOW_STEP_PERIODS);
}

void bench_mc_closedloop(void)
{
    bench_add("mc_step/closed_loop_sim", "mc_bench_cl_step", 20000U, run_closed_loop);
    bench_add("mc_slow_step/closed_loop_sim", "mc_bench_cl_slow", 20000U / MC_SLOW_STEP_PERIODS,
              run_closed_loop_slow);
}
