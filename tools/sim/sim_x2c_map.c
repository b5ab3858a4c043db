/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_x2c_map.c - the simulator's X2Cscope variable map (see sim_x2c_map.h). */
#include "sim_x2c_map.h"

#include <stddef.h>

#include "q15.h"
#include "x2c.h"

Q15_STATIC_ASSERT(sizeof(sim_x2c_map_row_t) == 80U, "x2cmap.py reads 80-byte rows");

#define MEMBER_SIZE(type, member) sizeof(((type *)0)->member)

#define KIND_S 'S'
#define KIND_U 'U'
#define KIND_B 'B'

#if defined(X2C_READ_ONLY)
#define TUNABLE 0U
#else
#define TUNABLE 1U
#endif

const sim_x2c_map_row_t sim_x2c_map[] = {
#define MOTOR_ROW(path, kind, unit, fs)                                                            \
    {"motor." #path,                                                                               \
     unit,                                                                                         \
     (double)(fs),                                                                                 \
     0,                                                                                            \
     0,                                                                                            \
     (uint16_t)(X2C_WINDOW_MOTOR + offsetof(mc_t, path)),                                          \
     (uint16_t)MEMBER_SIZE(mc_t, path),                                                            \
     0U,                                                                                           \
     (uint8_t)KIND_##kind,                                                                         \
     {0}},
    X2C_MOTOR_VARS(MOTOR_ROW)
#undef MOTOR_ROW
#define TUNE_ROW(field, min, max, unit, fs)                                                        \
    {"x2c.tune." #field,                                                                           \
     unit,                                                                                         \
     (double)(fs),                                                                                 \
     (int32_t)(min),                                                                               \
     (int32_t)(max),                                                                               \
     (uint16_t)(X2C_WINDOW_TUNE + offsetof(x2c_tune_t, field)),                                    \
     2U,                                                                                           \
     TUNABLE,                                                                                      \
     (uint8_t)KIND_S,                                                                              \
     {0}},
        X2C_TUNABLES(TUNE_ROW)
#undef TUNE_ROW
#define ID_ROW(field, kind, unit, fs)                                                              \
    {"x2c.id." #field,                                                                             \
     unit,                                                                                         \
     (double)(fs),                                                                                 \
     0,                                                                                            \
     0,                                                                                            \
     (uint16_t)(X2C_WINDOW_ID + offsetof(mc_id_result_t, field)),                                  \
     (uint16_t)MEMBER_SIZE(mc_id_result_t, field),                                                 \
     0U,                                                                                           \
     (uint8_t)KIND_##kind,                                                                         \
     {0}},
            X2C_ID_VARS(ID_ROW)
#undef ID_ROW
};

const uint16_t sim_x2c_map_rows = (uint16_t)(sizeof sim_x2c_map / sizeof sim_x2c_map[0]);
