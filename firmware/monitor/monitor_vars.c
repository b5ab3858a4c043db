/* monitor_vars.c - the monitor's registry tables (see monitor_vars.h). */
#include "monitor_vars.h"

#include "q15.h"

/* Defined without a size: a row count other than MONITOR_NUM_VARS then
 * conflicts with the declaration in the header and stops the build. */
const monitor_var_t monitor_vars[] = {
#define MONITOR_VAR_ROW(name, unit, kind, fs_milli, read)                                          \
    {#name, unit, MONITOR_KIND_##kind, fs_milli},
    MONITOR_VAR_LIST(MONITOR_VAR_ROW)
#undef MONITOR_VAR_ROW
};

Q15_STATIC_ASSERT(MONITOR_NUM_VARS <= 255U, "a variable index is one byte of the protocol");

/* ---- the tuning whitelist ------------------------------------------------------ *
 * The PI gains of the current loops (d and q together) and of the speed loop,
 * as the pi_params_t mantissas (Q15, with the exponent kp_shift fixed at build
 * time). The monitor posts them with mc_set_gain() (mc.h note 3): applied by
 * the next mc_step() to d and q together; the speed gains are the base the
 * low-speed schedule scales, so they survive it. A ki change also sets kc
 * (AN1078 uses Kc = Ki). The accepted range is the build-time gain / 8 .. x 8
 * (at least 1, at most 32767): wide enough to tune, narrow enough that a typo
 * cannot zero a loop. mc_init() (a reset) restores the build-time gains.
 * The row order is the index of the protocol (PARAM_INFO, SET_PARAM). */
#define GAIN_MIN(g) ((int16_t)((g) / 8 > 0 ? (g) / 8 : 1))
#define GAIN_MAX(g) ((int16_t)((int32_t)(g)*8 > 32767 ? 32767 : (int32_t)(g)*8))
#define GAIN_ROW(name, gain, build_value)                                                          \
    {                                                                                              \
        name, GAIN_MIN(build_value), GAIN_MAX(build_value), (uint8_t)(gain)                        \
    }

const monitor_param_t monitor_params[] = {
    GAIN_ROW("cur_kp", MC_GAIN_CUR_KP, MC_CUR_KP),
    GAIN_ROW("cur_ki", MC_GAIN_CUR_KI, MC_CUR_KI),
    GAIN_ROW("spd_kp", MC_GAIN_SPD_KP, MC_SPD_KP),
    GAIN_ROW("spd_ki", MC_GAIN_SPD_KI, MC_SPD_KI),
};
