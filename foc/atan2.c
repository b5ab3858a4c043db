/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* atan2.c - four-quadrant arctangent from one octant table with linear interpolation. */
#include "atan2.h"

/* round(4 atan(i / 128) 32768 / pi), i = 0..128: the first-octant angle in
 * quarter LSB of the binary angle (32768 at 45 degrees); const, so the
 * dsPIC linker places it in flash (258 bytes). */
const uint16_t atan2_table[ATAN2_TABLE_SIZE] = {
    0U,     326U,   652U,   978U,   1303U,  1629U,  1954U,  2279U,  2604U,  2929U,  3253U,  3577U,
    3900U,  4223U,  4545U,  4867U,  5188U,  5509U,  5829U,  6148U,  6467U,  6784U,  7101U,  7418U,
    7733U,  8047U,  8361U,  8673U,  8985U,  9296U,  9605U,  9914U,  10221U, 10527U, 10832U, 11136U,
    11439U, 11740U, 12040U, 12339U, 12637U, 12933U, 13228U, 13522U, 13814U, 14105U, 14394U, 14682U,
    14968U, 15253U, 15537U, 15819U, 16100U, 16379U, 16656U, 16932U, 17206U, 17479U, 17750U, 18020U,
    18288U, 18554U, 18819U, 19083U, 19344U, 19604U, 19862U, 20119U, 20374U, 20627U, 20879U, 21129U,
    21378U, 21624U, 21870U, 22113U, 22355U, 22595U, 22834U, 23070U, 23306U, 23539U, 23771U, 24001U,
    24230U, 24457U, 24682U, 24906U, 25128U, 25349U, 25568U, 25785U, 26001U, 26215U, 26427U, 26638U,
    26848U, 27056U, 27262U, 27467U, 27670U, 27871U, 28072U, 28270U, 28467U, 28663U, 28857U, 29050U,
    29241U, 29430U, 29619U, 29805U, 29991U, 30175U, 30357U, 30538U, 30718U, 30896U, 31073U, 31248U,
    31423U, 31595U, 31767U, 31937U, 32106U, 32273U, 32439U, 32604U, 32768U,
};

/*
 * Notes
 *
 * 1. Error budget, in LSB of the binary angle (2 pi / 65536 rad):
 *    the ratio r = floor(num 2^16 / den) is below the true num / den by
 *    less than 2^-16, which moves atan by less than 2^-16 rad = 0.16 LSB
 *    (atan' <= 1); when the inputs were shifted right (the larger above
 *    16 bits), the smaller one loses less than one of its 16-bit units
 *    against a larger one of at least 2^15: 0.32 LSB more. The table holds
 *    each entry to 1/8 LSB; the chord between two entries of a 1/128 step
 *    is within h^2 / 8 max|atan''| = 0.65 / 131072 rad = 0.05 LSB of the
 *    curve; the interpolation rounds to 1/8 LSB; the final rounding to
 *    whole LSB adds 0.5. The unfolding (16384 - a, 32768 - a, -a) is
 *    exact. Sum: <= 0.96 LSB for 16-bit inputs, <= 1.28 LSB for larger
 *    ones; test_atan2.c measures both.
 *
 * 2. Why a division. The alternatives cost more on the dsPIC33F: CORDIC
 *    needs about 12 vectoring steps of 32-bit shifts and adds for
 *    0.05 degree (measured 564 cycles for 15 steps), a polynomial in the
 *    ratio still needs the ratio. div.ud is 18 cycles plus its REPEAT.
 */
