/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_adc.c - quantising, saturating, noisy ADC model. */
#include "sim_adc.h"

#include <math.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

double sim_rand_uniform(uint64_t *state)
{
    uint64_t x = *state;
    x ^= x >> 12;
    x ^= x << 25;
    x ^= x >> 27;
    *state = x;
    /* Top 53 bits of the multiplied state, as a double in [0, 1). */
    return (double)((x * 2685821657736338717ULL) >> 11) / 9007199254740992.0;
}

void sim_adc_init(sim_adc_t *adc, const sim_adc_params_t *prm)
{
    adc->prm = *prm;
    adc->rng = 0x9E3779B97F4A7C15ULL ^ (uint64_t)prm->seed;
    if (adc->rng == 0) {
        adc->rng = 1;
    }
    adc->spare = 0.0;
    adc->has_spare = 0;
}

double sim_adc_gauss(sim_adc_t *adc)
{
    double u1, u2, r;
    if (adc->has_spare) {
        adc->has_spare = 0;
        return adc->spare;
    }
    do {
        u1 = sim_rand_uniform(&adc->rng);
    } while (u1 <= 0.0);
    u2 = sim_rand_uniform(&adc->rng);
    r = sqrt(-2.0 * log(u1));
    adc->spare = r * sin(2.0 * M_PI * u2);
    adc->has_spare = 1;
    return r * cos(2.0 * M_PI * u2);
}

static double noise(sim_adc_t *adc)
{
    return (adc->prm.noise_codes > 0.0) ? adc->prm.noise_codes * sim_adc_gauss(adc) : 0.0;
}

static long clamp_code(double c, long top)
{
    double r = floor(c + 0.5);
    if (!(r >= 0.0)) {
        return 0; /* NaN too: a diverged plant never reaches the conversion below */
    }
    if (r > (double)top) {
        return top;
    }
    return (long)r;
}

int16_t sim_adc_bipolar(sim_adc_t *adc, double x_fs, double offset_codes)
{
    long half = 1L << (adc->prm.bits - 1);
    long top = (1L << adc->prm.bits) - 1;
    long shift = 1L << (16 - adc->prm.bits);
    long code = clamp_code((double)half + x_fs * (double)half + offset_codes + noise(adc), top);
    return (int16_t)((code - half) * shift);
}

int16_t sim_adc_bipolar_exact(const sim_adc_t *adc, double x_fs, double offset_codes)
{
    long half = 1L << (adc->prm.bits - 1);
    long top = (1L << adc->prm.bits) - 1;
    long shift = 1L << (16 - adc->prm.bits);
    long code = clamp_code((double)half + x_fs * (double)half + offset_codes, top);
    return (int16_t)((code - half) * shift);
}

int16_t sim_adc_unipolar(sim_adc_t *adc, double x_fs)
{
    long full = 1L << adc->prm.bits;
    long shift = 1L << (15 - adc->prm.bits);
    long code = clamp_code(x_fs * (double)full + noise(adc), full - 1);
    return (int16_t)(code * shift);
}

void sim_adc_sample(sim_adc_t *adc, double ia, double ib, double vbus, double pot,
                    sim_adc_frame_t *out)
{
    out->ia = sim_adc_bipolar(adc, ia / adc->prm.i_fs_a, adc->prm.offset_a_codes);
    out->ib = sim_adc_bipolar(adc, ib / adc->prm.i_fs_a, adc->prm.offset_b_codes);
    out->vbus = sim_adc_unipolar(adc, vbus / adc->prm.vbus_fs_v);
    out->pot = sim_adc_unipolar(adc, pot);
}
