/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sincos.c - sine and cosine from one quarter-wave table with linear interpolation. */
#include "sincos.h"

/*
 * Table: SINCOS_TABLE_INTERVALS + 1 = 129 entries of round(32768 sin(i pi / 256)),
 * i = 0..128, covering 0..pi/2 (the last entry, 32768, saturated to 32767),
 * and a pad, sin(129 pi / 256) = entry 127, which only r = 2^14 (fraction
 * 0) reads: the interpolation needs no test. const, so the dsPIC linker
 * places it in flash (260 bytes).
 *
 * Angle decomposition (theta as uint16_t, one turn = 2^16):
 *   bits 15..14  quadrant (0..3)
 *   bits 13..7   table index within the quadrant (0..127)
 *   bits  6..0   interpolation fraction, 1/128 of a table step
 * Quadrants 1 and 3 read the quarter wave backwards (r -> 2^14 - r);
 * quadrants 2 and 3 negate. The magnitude is computed first and negated
 * last, so sin(-x) = -sin(x) and sin(pi - x) = sin(x) hold bit for bit.
 *
 * Accuracy (test/foc/test_sincos.c, all 65,536 angles, against 32768 sin/cos
 * in double): max |error| 1.44 LSB, made of table rounding (0.5), the chord
 * error of a 2 pi / 512 step (32768 h^2 / 8 = 0.62 LSB) and the rounding of
 * the interpolation (0.5). Exact at 0, 90, 180, 270 degrees (0 and +-32767);
 * |output| <= 32767 always, so negating it never saturates.
 *
 * Cost: per output two table reads and one 16 x 16 multiply (difference x
 * fraction, <= 402 x 127 = 51,054: unsigned 16-bit arithmetic), no branch
 * on the fraction, no division, no float.
 */

const q15_t sincos_table[SINCOS_TABLE_SIZE] = {
    0,     402,   804,   1206,  1608,  2009,  2411,  2811,  3212,  3612,  4011,  4410,
    4808,  5205,  5602,  5998,  6393,  6787,  7180,  7571,  7962,  8351,  8740,  9127,
    9512,  9896,  10279, 10660, 11039, 11417, 11793, 12167, 12540, 12910, 13279, 13646,
    14010, 14373, 14733, 15091, 15447, 15800, 16151, 16500, 16846, 17190, 17531, 17869,
    18205, 18538, 18868, 19195, 19520, 19841, 20160, 20475, 20788, 21097, 21403, 21706,
    22006, 22302, 22595, 22884, 23170, 23453, 23732, 24008, 24279, 24548, 24812, 25073,
    25330, 25583, 25833, 26078, 26320, 26557, 26791, 27020, 27246, 27467, 27684, 27897,
    28106, 28311, 28511, 28707, 28899, 29086, 29269, 29448, 29622, 29792, 29957, 30118,
    30274, 30425, 30572, 30715, 30853, 30986, 31114, 31238, 31357, 31471, 31581, 31686,
    31786, 31881, 31972, 32058, 32138, 32214, 32286, 32352, 32413, 32470, 32522, 32568,
    32610, 32647, 32679, 32706, 32729, 32746, 32758, 32766, 32767, 32766, /* pad: sin(129 pi / 256),
                                                                             read only with fraction
                                                                             0 */
};

sincos_q15_t sincos_call(angle_q15_t theta)
{
    return sincos_compute(theta);
}
