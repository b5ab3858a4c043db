/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_adc.h - the ADC as the core sees it: 10-bit, offsets, noise, saturation. */
#ifndef SIM_ADC_H
#define SIM_ADC_H

#include <stdint.h>

/*
 * One conversion set per PWM period (the values at the sampling instant).
 * Bipolar channels (phase currents, amplifier biased at mid-rail, the dsPIC's
 * signed-fractional format):
 *   code = round(512 + x / fs * 512 + offset + noise), clamped to 0..1023,
 *   q15  = (code - 512) * 64              -> -32768..32704 (64-LSB steps)
 * Unipolar channels (DC bus through its divider, potentiometer):
 *   code = round(x / fs * 1024 + noise), clamped to 0..1023,
 *   q15  = code * 32                      -> 0..32736
 * so q15 = 32768 * x / fs in both cases, quantised, and a value beyond the
 * full scale saturates at the last code. Noise is Gaussian, sigma in codes.
 */

typedef struct {
    double i_fs_a;         /* current full scale: +-i_fs_a maps to +-32768, A */
    double vbus_fs_v;      /* bus full scale: vbus_fs_v maps to 32768, V */
    int bits;              /* resolution, 10 on the dsPIC33F with 4 S&H */
    double offset_a_codes; /* amplifier offset of the phase-A channel, codes */
    double offset_b_codes; /* phase B */
    double noise_codes;    /* Gaussian noise, sigma, codes (all channels) */
    uint32_t seed;         /* noise seed, non-zero */
} sim_adc_params_t;

typedef struct {
    sim_adc_params_t prm;
    uint64_t rng; /* xorshift64* state */
    double spare; /* second Box-Muller deviate */
    int has_spare;
} sim_adc_t;

typedef struct {
    int16_t ia, ib; /* Q15 of i_fs_a, with offset, + = into the motor */
    int16_t vbus;   /* Q15 of vbus_fs_v, 0..32767 */
    int16_t pot;    /* 0..32767 = 0..100 % */
} sim_adc_frame_t;

void sim_adc_init(sim_adc_t *adc, const sim_adc_params_t *prm);

/* One conversion of each channel. ia/ib in A, vbus in V, pot in 0..1. */
void sim_adc_sample(sim_adc_t *adc, double ia, double ib, double vbus, double pot,
                    sim_adc_frame_t *out);

/* A single bipolar / unipolar conversion (x as a fraction of full scale). */
int16_t sim_adc_bipolar(sim_adc_t *adc, double x_fs, double offset_codes);
int16_t sim_adc_unipolar(sim_adc_t *adc, double x_fs);
/* A bipolar code without noise (a frozen channel). */
int16_t sim_adc_bipolar_exact(const sim_adc_t *adc, double x_fs, double offset_codes);

/* Standard normal deviate from the ADC's generator (used for noise). */
double sim_adc_gauss(sim_adc_t *adc);

/* Uniform [0, 1) from a caller-owned xorshift64* state (non-zero). */
double sim_rand_uniform(uint64_t *state);

#endif /* SIM_ADC_H */
