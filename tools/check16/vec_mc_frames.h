/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* vec_mc_frames.h - what vec_mc.c and gen_mc_frames.c share: frame count, bus and pot formulas. */
#ifndef VEC_MC_FRAMES_H
#define VEC_MC_FRAMES_H

#include <stdint.h>

#include "mc.h"

/* Frames replayed, and the frame at which START is requested. */
#define MC_FRAMES_N     8000U
#define MC_FRAMES_START 10U

/* The bus: nominal with a small deterministic triangle ripple (+-16 LSB),
 * so the ripple compensation's division sees changing inputs. */
static inline int16_t mc_frames_bus(uint32_t n)
{
    int16_t tri = (int16_t)(n % 64U);
    if (tri >= 32) {
        tri = (int16_t)(63 - tri);
    }
    return (int16_t)(MC_VBUS_NOMINAL_Q15 - 16 + tri);
}

/* The pot: 30 % of travel, then full travel from frame 7000 on (the
 * start reaches CLOSED_LOOP at frame 5525, after the dead-time measurement). */
static inline int16_t mc_frames_pot(uint32_t n)
{
    return (n < 7000U) ? (int16_t)9830 : (int16_t)32767;
}

/* Frame n of the recording as the core takes it, with START requested at
 * MC_FRAMES_START: what vec_mc.c and cycles.c replay (both include
 * emit.h and mc_frames.h first; gen_mc_frames.c, which writes the
 * recording, does not use it). */
#if defined(MC_FRAMES_RECORDED_N)
static inline void mc_frames_input(mc_t *mc, uint32_t n, mc_adc_frame_t *in)
{
    if (n == MC_FRAMES_START) {
        mc_request(mc, MC_REQUEST_START);
    }
    in->ia = vec_rom_i16(&mc_frames[2U * n]);
    in->ib = vec_rom_i16(&mc_frames[2U * n + 1U]);
    in->vbus = mc_frames_bus(n);
    in->pot = mc_frames_pot(n);
}
#endif

#endif /* VEC_MC_FRAMES_H */
