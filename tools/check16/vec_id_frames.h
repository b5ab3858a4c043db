/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* vec_id_frames.h - what cycles.c and gen_id_frames.c share: an identification's recorded frames.
 */
#ifndef VEC_ID_FRAMES_H
#define VEC_ID_FRAMES_H

#include <stdint.h>

#include "mc.h"

/* Frames replayed, and the frame at which IDENTIFY is requested. The
 * recording covers CALIBRATE and IDENTIFY's RAMP, R, LD and LQ stages (the
 * DC levels and the injected square waves, the heaviest periods and the
 * windows that solve for R and L) into SPIN1, on the Hurst with the default
 * build: frame 281 IDENTIFY, 4,759 R, 13,299 LD, 14,159 LQ, 15,279 SPIN1.
 * The rest of the sequence (the spins, 3.2 s in all) would not fit the AVR's
 * near flash; the dsPIC figures of docs/performance.md cover it. */
#define ID_FRAMES_N     15600U
#define ID_FRAMES_START 10U

/* Frame n as the core takes it: the bus at its nominal, the pot at 0. */
#if defined(ID_FRAMES_RECORDED_N)
static inline void id_frames_input(mc_t *mc, uint32_t n, mc_adc_frame_t *in)
{
    if (n == ID_FRAMES_START) {
        mc_request(mc, MC_REQUEST_IDENTIFY);
    }
    in->ia = vec_rom_i16(&id_frames_a[n]);
    in->ib = vec_rom_i16(&id_frames_b[n]);
    in->vbus = MC_VBUS_NOMINAL_Q15;
    in->pot = 0;
}
#endif

#endif /* VEC_ID_FRAMES_H */
