/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* mc_names.c - the names of the core's states and fault codes (mc.h), from
 * their one list. Beside the simulator, not in firmware/: the dsPIC image
 * has no use for the strings. */
#include "mc.h"

#define MC_STATE_NAME_(name)          #name,
#define MC_FAULT_NAME_(name, code)    #name,
#define MC_ID_ERROR_NAME_(name, code) #name,

const char *mc_state_name(int state)
{
    static const char *const names[] = {MC_STATE_LIST(MC_STATE_NAME_)};
    return (state >= 0 && (unsigned)state < sizeof(names) / sizeof(names[0])) ? names[state] : "?";
}

const char *mc_fault_name(unsigned fault)
{
    static const char *const names[] = {MC_FAULT_LIST(MC_FAULT_NAME_)};
    if (fault == MC_FAULT_NONE) {
        return "none";
    }
    return (fault < sizeof(names) / sizeof(names[0])) ? names[fault] : "?";
}

const char *mc_id_error_name(unsigned error)
{
    static const char *const names[] = {MC_ID_ERROR_LIST(MC_ID_ERROR_NAME_)};
    if (error == MC_ID_ERROR_NONE) {
        return "none";
    }
    return (error < sizeof(names) / sizeof(names[0])) ? names[error] : "?";
}
