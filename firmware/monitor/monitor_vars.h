/* monitor_vars.h - the monitor's registry: the core variables it records and the gains it tunes. */
#ifndef MONITOR_VARS_H
#define MONITOR_VARS_H

#include <stdint.h>

#include "mc.h"

/* ---- the variables ------------------------------------------------------------ *
 * One row per variable, everything about it in the row:
 *   X(name, unit, kind, fs_milli, read)
 * name      the identifier the host shows (VAR_INFO), no spaces;
 * unit      engineering unit of the full scale, "" for a count or a code;
 * kind      Q15 (engineering value = raw / 32768 * fs) or INT (raw is the value);
 * fs_milli  full scale x 1000 in `unit` (MONITOR_FS_* below);
 * read      the value as int16, an expression in `mc` (const mc_t *): what
 *           mc_status() copies into the field of that name (test_monitor pins
 *           the two together), read without the copy of the whole status
 *           because the recorder reads it in the ADC interrupt.
 * The row order is the index of the protocol (VAR_INFO, SELECT): append only,
 * or tools that stored an index read another variable. */

/* Full scales x 1000 (engineering units), from the core's scale macros. */
#define MONITOR_FS_MILLI(x) ((int32_t)((x)*1000.0 + 0.5))
#define MONITOR_FS_COUNT    1000   /* INT kind: the raw value is the value */
#define MONITOR_FS_DEG      180000 /* Q15 binary angle: 32768 = pi = 180 degrees */
#define MONITOR_FS_RPM      MONITOR_FS_MILLI(MC_SPEED_FULLSCALE_RPM)
#define MONITOR_FS_AMP      MONITOR_FS_MILLI(BOARD_I_FULLSCALE_A)
#define MONITOR_FS_VOLT     MONITOR_FS_MILLI(MC_VOLTAGE_FULLSCALE_V)
#define MONITOR_FS_VBUS     MONITOR_FS_MILLI(BOARD_VBUS_FULLSCALE_V)
#define MONITOR_FS_EMF      MONITOR_FS_MILLI(MONITOR_EMF_FULLSCALE_V)
/* The estimator's back-EMF scale, volts (smc.h: E_FS = SMC_EMF_FS_RATIO * V_FS). */
#define MONITOR_EMF_FULLSCALE_V (SMC_EMF_FS_RATIO * MC_VOLTAGE_FULLSCALE_V)

/* clang-format off */
#define MONITOR_VAR_LIST(X)                                                                        \
    X(state,        "",    INT, MONITOR_FS_COUNT, (int16_t)mc->state)                              \
    X(fault,        "",    INT, MONITOR_FS_COUNT, (int16_t)(mc->fault & 0x7FFFU))                  \
    X(speed_est,    "rpm", Q15, MONITOR_FS_RPM,   smc_omega(&mc->smc))                             \
    X(speed_ref,    "rpm", Q15, MONITOR_FS_RPM,   mc->speed_ref)                                   \
    X(speed_target, "rpm", Q15, MONITOR_FS_RPM,   mc->speed_target)                                \
    X(theta_est,    "deg", Q15, MONITOR_FS_DEG,   mc->theta)                                       \
    X(theta_forced, "deg", Q15, MONITOR_FS_DEG,   (int16_t)(uint16_t)(mc->ol_angle >> 16))         \
    X(id,           "A",   Q15, MONITOR_FS_AMP,   mc->i_dq.d)                                      \
    X(iq,           "A",   Q15, MONITOR_FS_AMP,   mc->i_dq.q)                                      \
    X(id_ref,       "A",   Q15, MONITOR_FS_AMP,   mc->i_ref.d)                                     \
    X(iq_ref,       "A",   Q15, MONITOR_FS_AMP,   mc->i_ref.q)                                     \
    X(ia,           "A",   Q15, MONITOR_FS_AMP,   mc->ia)                                          \
    X(ib,           "A",   Q15, MONITOR_FS_AMP,   mc->ib)                                          \
    X(vd,           "V",   Q15, MONITOR_FS_VOLT,  mc->v_dq.d)                                      \
    X(vq,           "V",   Q15, MONITOR_FS_VOLT,  mc->v_dq.q)                                      \
    /* the estimator's filtered |e|: a consistency figure, not volts of EMF */                     \
    X(bemf,         "V",   Q15, MONITOR_FS_EMF,   smc_emf_amplitude(&mc->smc))                     \
    X(vbus,         "V",   Q15, MONITOR_FS_VBUS,  mc->vbus)                                        \
    X(est_valid,    "",    INT, MONITOR_FS_COUNT, smc_valid(&mc->smc) ? 1 : 0)
/* clang-format on */

/* variable kinds (VAR_INFO) */
#define MONITOR_KIND_Q15 0U /* engineering value = raw / 32768 * fs */
#define MONITOR_KIND_INT 1U /* engineering value = raw (enum, code, flag) */

/* MONITOR_VAR_<name>: the index of each variable. */
enum {
#define MONITOR_VAR_INDEX(name, unit, kind, fs_milli, read) MONITOR_VAR_##name,
    MONITOR_VAR_LIST(MONITOR_VAR_INDEX)
#undef MONITOR_VAR_INDEX
        MONITOR_VAR_COUNT_
};
#define MONITOR_NUM_VARS ((unsigned)MONITOR_VAR_COUNT_)

typedef struct {
    const char *name;
    const char *unit;
    uint8_t kind;     /* MONITOR_KIND_* */
    int32_t fs_milli; /* full scale x 1000 in `unit` (Q15 kind) */
} monitor_var_t;

/* The rows' names, units and scales, for VAR_INFO (const: program memory on the dsPIC). */
extern const monitor_var_t monitor_vars[MONITOR_NUM_VARS];

/* Value of variable idx in mc (0 for idx out of range). Inline: the
 * recorder calls it for every recorded channel in the ADC interrupt. */
static inline int16_t monitor_var_read(const mc_t *mc, uint8_t idx)
{
    switch (idx) {
#define MONITOR_VAR_CASE(name, unit, kind, fs_milli, read)                                         \
    case MONITOR_VAR_##name:                                                                       \
        return (read);
        MONITOR_VAR_LIST(MONITOR_VAR_CASE)
#undef MONITOR_VAR_CASE
        default:
            return 0;
    }
}

/* ---- the tuning whitelist ------------------------------------------------------ */

typedef struct {
    const char *name;
    int16_t min, max; /* inclusive range SET_PARAM accepts */
    uint8_t gain;     /* the mc_gain_t it reads and writes */
} monitor_param_t;

#define MONITOR_NUM_PARAMS 4U
extern const monitor_param_t monitor_params[MONITOR_NUM_PARAMS];

#endif /* MONITOR_VARS_H */
