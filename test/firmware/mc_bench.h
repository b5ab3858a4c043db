/* mc_bench.h - the mc core on the simulator's plant (tools/sim simplant), for the firmware tests.
 */
#ifndef MC_BENCH_H
#define MC_BENCH_H

#include <stdbool.h>

#include "mc.h"
#include "sim_profiles.h"
#include "sim_rig.h"

/* One bench: the core driven exactly like the ISR (sample, mc_step, the
 * duties latched for the next period), the plant in physical units. */
typedef struct {
    sim_rig_t rig;
    mc_t mc;
    mc_pwm_out_t out;
    sim_adc_frame_t frame;
    mc_status_t st;
    double theta_sample; /* true electrical angle at this period's sample, rad */
    double rpm_sample;   /* true speed then */
    long n;
} mc_bench_t;

typedef struct {
    const char *motor; /* sim profile name */
    const char *board;
    double theta0_rad;
    double deadtime_s;  /* < 0: the board's */
    double noise_codes; /* < 0: the board's */
    double vbus_v;      /* < 0: the board's */
    double amp_tau_s;   /* current amplifiers' time constant, s; < 0: the board's */
    double pot;         /* 0..1 */
} mc_bench_cfg_t;

void mc_bench_cfg_default(mc_bench_cfg_t *c);
void mc_bench_init(mc_bench_t *b, const mc_bench_cfg_t *c);
void mc_bench_step(mc_bench_t *b);
/* Steps until the state is s or n periods have passed; returns periods used
 * or -1. */
long mc_bench_run_until(mc_bench_t *b, mc_state_t s, long n);
double mc_bench_rpm(const mc_bench_t *b);
/* Angle the core used for this period's sample minus the true angle at the
 * sample instant, degrees in [-180, 180). */
double mc_bench_angle_err_deg(const mc_bench_t *b);
double mc_rpm_of_q15(int16_t q);

#endif /* MC_BENCH_H */
