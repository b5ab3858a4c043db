/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* x2c_vars.h - the X2Cscope target's whitelist: every variable a client may read, scope or tune. */
#ifndef X2C_VARS_H
#define X2C_VARS_H

/*
 * Nothing outside these rows is reachable over the UART: every service
 * (read, write, a scope channel, the trigger source) resolves its address
 * to one row and is refused when it does not fall inside one
 * (docs/x2cscope.md, "Our target").
 *
 * The names are the C paths of the objects the clients find in the
 * firmware's ELF (`motor` is firmware/motor.c's mc_t, `x2c` the target's
 * instance in firmware/main.c), so a variable picked by name in the MPLAB X
 * plugin or pyx2cscope is one of these rows; on the PC the simulator
 * presents the same names in a 16-bit address window (x2c_map.c).
 *
 * X2C_MOTOR_VARS(X): the motor's variables, read-only (a client may read
 * and scope them, never write them: the core's state is written by the
 * core alone).
 *   X(path, type, unit, full_scale)
 *   path        the member of mc_t (`i_dq.d`);
 *   type        S (signed), U (unsigned) or B (bool): how the raw bytes read;
 *   unit        the engineering unit of full_scale, "" for a code or count;
 *   full_scale  engineering value of 32768 raw counts (Q15), or 0 when the
 *               raw value is the value (states, codes, flags, counts).
 * The rows are read raw in the ADC interrupt's own units (Q15 of the full
 * scales of firmware/UserParms.h and the board profile); nothing here
 * converts.
 */

#include "mc.h"
#include "x2c_scope.h" /* X2C_SCOPE: whether the scope's buffer is a row */

/* Full scales of the Q15 rows, engineering units per 32768 counts. */
#define X2C_FS_RPM  (MC_SPEED_FULLSCALE_RPM)
#define X2C_FS_AMP  (BOARD_I_FULLSCALE_A)
#define X2C_FS_VOLT (MC_VOLTAGE_FULLSCALE_V)
#define X2C_FS_VBUS (BOARD_VBUS_FULLSCALE_V)
#define X2C_FS_EMF  (SMC_EMF_FS_RATIO * MC_VOLTAGE_FULLSCALE_V) /* smc.h: E_FS */
#define X2C_FS_DEG  180.0                                       /* a Q15 binary angle: 32768 = pi */
#define X2C_FS_CODE 0.0                                         /* the raw value is the value */

/* clang-format off */
#define X2C_MOTOR_VARS(X)                                        \
    X(state,           U, "",    X2C_FS_CODE)                   \
    X(fault,           U, "",    X2C_FS_CODE)                   \
    X(timer,           U, "",    X2C_FS_CODE)                   \
    X(retries,         U, "",    X2C_FS_CODE)                   \
    X(ia,              S, "A",   X2C_FS_AMP)                    \
    X(ib,              S, "A",   X2C_FS_AMP)                    \
    X(vbus,            S, "V",   X2C_FS_VBUS)                   \
    X(pot,             S, "",    X2C_FS_CODE)                   \
    X(i_dq.d,          S, "A",   X2C_FS_AMP)                    \
    X(i_dq.q,          S, "A",   X2C_FS_AMP)                    \
    X(i_ref.d,         S, "A",   X2C_FS_AMP)                    \
    X(i_ref.q,         S, "A",   X2C_FS_AMP)                    \
    X(v_dq.d,          S, "V",   X2C_FS_VOLT)                   \
    X(v_dq.q,          S, "V",   X2C_FS_VOLT)                   \
    X(speed_target,    S, "rpm", X2C_FS_RPM)                    \
    X(speed_ref,       S, "rpm", X2C_FS_RPM)                    \
    X(torque_target,   S, "A",   X2C_FS_AMP)                    \
    X(theta,           S, "deg", X2C_FS_DEG)                    \
    X(ol_angle,        U, "",    X2C_FS_CODE)                   \
    X(duty[0],         U, "",    X2C_FS_CODE)                   \
    X(duty[1],         U, "",    X2C_FS_CODE)                   \
    X(duty[2],         U, "",    X2C_FS_CODE)                   \
    X(outputs_on,      B, "",    X2C_FS_CODE)                   \
    X(stopping,        B, "",    X2C_FS_CODE)                   \
    X2C_ESTIMATOR_VARS(X)                                        \
    X(dt_counts,       S, "",    X2C_FS_CODE)
/* The estimator's, in the drive (MC_DRIVE 1); the commissioning image has none. */
#if MC_DRIVE
#define X2C_ESTIMATOR_VARS(X)                                    \
    X(smc.theta,       S, "deg", X2C_FS_DEG)                    \
    X(smc.omega,       S, "rpm", X2C_FS_RPM)                    \
    X(smc.emf_mag,     S, "V",   X2C_FS_EMF)                    \
    X(smc.valid,       B, "",    X2C_FS_CODE)
#else
#define X2C_ESTIMATOR_VARS(X)
#endif
/* clang-format on */

/*
 * X2C_ID_VARS(X): the identification's result (mc.h mc_id_result_t),
 * read-only, refreshed from the motor whenever a client reads one of them
 * (motor_identify_result): status (mc_id_status_t: 0 none, 1 running,
 * 2 done, 3 failed), the error (mc_id.h MC_ID_ERROR_LIST) and the values
 * in their integer units. Not scope channels: the values change once a run.
 *   X(field, type, unit, full_scale) as in X2C_MOTOR_VARS
 */
/* clang-format off */
#define X2C_ID_VARS(X)                                           \
    X(status,          U, "",    X2C_FS_CODE)                   \
    X(error,           U, "",    X2C_FS_CODE)                   \
    X(rs_uohm,         U, "",    X2C_FS_CODE)                   \
    X(ls_nh,           U, "",    X2C_FS_CODE)                   \
    X(ke_uv_per_rpm,   U, "",    X2C_FS_CODE)                   \
    X(j_ng_m2,         U, "",    X2C_FS_CODE)                   \
    X(deadtime_ns,     U, "",    X2C_FS_CODE)                   \
    X(ld_nh,           U, "",    X2C_FS_CODE)                   \
    X(lq_nh,           U, "",    X2C_FS_CODE)                   \
    X(pole_pairs,      U, "",    X2C_FS_CODE)
/* clang-format on */

/*
 * X2C_TUNABLES(X): the only variables a client may write, fields of
 * x2c_tune_t (x2c.h). A write is accepted only whole (the row's address,
 * the row's size), only inside [min, max], and is then applied through the
 * motor's mailbox (motor.h), masked, exactly as the board's own controls
 * do; the field keeps what was applied, and reading it back reads the
 * motor's value.
 *   X(field, min, max, unit, full_scale)
 * The gains are the PI mantissas (Q15, exponent fixed at build time,
 * mc.h note 3): the build-time value x MC_GAIN_*_MIN8 / 8 .. x 8, at least 1
 * (the current gains from 1/8, the speed Kp from the built-in, its Ki from
 * 1/2), and a loop's pair within the core's bound on Ki / Kp, which
 * refuses a write that would leave it (X2C_ERR_LIMIT): wide enough to
 * tune, never a pair the simulated drive was not proven stable with. speed_ref_rpm, in
 * rpm, is 0 (the pot again) or the pot's range, X2C_RPM_MIN..X2C_RPM_MAX:
 * the values between are refused (X2C_ERR_LIMIT); run is S2 (1 start,
 * 0 stop); identify 1 measures the motor (MC_REQUEST_IDENTIFY, only from
 * STOPPED, refused otherwise), 0 stops a measurement going on, and it
 * reads 1 while the motor is in IDENTIFY.
 */
/* at least min8 / 8 of the built-in g, rounded up, and 1 (mc.h MC_GAIN_*_MIN8) */
#define X2C_GAIN_MIN(g, min8)                                                                      \
    ((int16_t)(((int32_t)(g) * (int32_t)(min8) + 7) / 8 > 0                                        \
                   ? ((int32_t)(g) * (int32_t)(min8) + 7) / 8                                      \
                   : 1))
#define X2C_GAIN_MAX(g) ((int16_t)((int32_t)(g)*8 > 32767 ? 32767 : (int32_t)(g)*8))
#define X2C_RPM_MIN     ((int16_t)(SPEED_REF_MIN_RPM + 0.5))
#define X2C_RPM_MAX     ((int16_t)(SPEED_REF_MAX_RPM + 0.5))

/* clang-format off */
#define X2C_TUNABLES(X)                                                                 \
    X(cur_kp,        X2C_GAIN_MIN(MC_CUR_KP, MC_GAIN_CUR_KP_MIN8), X2C_GAIN_MAX(MC_CUR_KP), "", X2C_FS_CODE) \
    X(cur_ki,        X2C_GAIN_MIN(MC_CUR_KI, MC_GAIN_CUR_KI_MIN8), X2C_GAIN_MAX(MC_CUR_KI), "", X2C_FS_CODE) \
    X(spd_kp,        X2C_GAIN_MIN(MC_SPD_KP, MC_GAIN_SPD_KP_MIN8), X2C_GAIN_MAX(MC_SPD_KP), "", X2C_FS_CODE) \
    X(spd_ki,        X2C_GAIN_MIN(MC_SPD_KI, MC_GAIN_SPD_KI_MIN8), X2C_GAIN_MAX(MC_SPD_KI), "", X2C_FS_CODE) \
    X(speed_ref_rpm, 0,                       X2C_RPM_MAX,             "rpm", X2C_FS_CODE) \
    X(run,           0,                       1,                       "", X2C_FS_CODE) \
    X(identify,      0,                       1,                       "", X2C_FS_CODE)
/* clang-format on */

/* The tunables, one int16 each (the target's RAM; x2c.h's x2c_t.tune). */
typedef struct {
#define X2C_TUNE_FIELD(field, min, max, unit, fs) int16_t field;
    X2C_TUNABLES(X2C_TUNE_FIELD)
#undef X2C_TUNE_FIELD
} x2c_tune_t;

/* Row counts: the motor's, the tunables', the result's, and the scope buffer's one. */
#define X2C_COUNT_ROW(a, b, c, d)     +1U
#define X2C_COUNT_TUNE(a, b, c, d, e) +1U
#define X2C_MOTOR_ROWS                (0U X2C_MOTOR_VARS(X2C_COUNT_ROW))
#define X2C_TUNE_ROWS                 (0U X2C_TUNABLES(X2C_COUNT_TUNE))
#define X2C_ID_ROWS                   (0U X2C_ID_VARS(X2C_COUNT_ROW))
/* X2C_TUNE_<field>: a tunable's number. */
enum {
#define X2C_TUNE_INDEX(field, min, max, unit, fs) X2C_TUNE_##field,
    X2C_TUNABLES(X2C_TUNE_INDEX)
#undef X2C_TUNE_INDEX
        X2C_TUNE_COUNT_
};
#define X2C_ROWS                                                                                   \
    (X2C_MOTOR_ROWS + X2C_TUNE_ROWS + (unsigned)X2C_SCOPE + X2C_ID_ROWS) /* + the scope buffer */

/* The objects the rows lie in, and where each appears on the wire. */
typedef enum { X2C_OBJ_MOTOR, X2C_OBJ_TUNE, X2C_OBJ_SCOPE, X2C_OBJ_ID, X2C_OBJ_COUNT } x2c_obj_t;

/* Row flags. */
#define X2C_ROW_READ    0x01U /* readable */
#define X2C_ROW_TUNE    0x02U /* writable, through the mailbox (x2c.c, tune_apply) */
#define X2C_ROW_CHANNEL 0x04U /* a scope channel or trigger source (not the scope's own buffer) */

/* Four bytes a row (the table is in flash: 2 of every 3 bytes of a program
 * word hold it): the size in 11 bits (the scope's buffer, the largest row,
 * is checked against it in x2c.c), the object in 2, the flags in 3. */
typedef struct {
    uint16_t offset;    /* in its object, bytes */
    uint16_t size : 11; /* bytes */
    uint16_t obj : 2;   /* x2c_obj_t */
    uint16_t flags : 3; /* X2C_ROW_* */
} x2c_row_t;
#define X2C_ROW_SIZE_MAX 2047U

/* The rows, in the order above (const: program memory on the dsPIC). */
extern const x2c_row_t x2c_rows[X2C_ROWS];

#endif /* X2C_VARS_H */
