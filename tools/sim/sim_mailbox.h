/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_mailbox.h - motor.h's mailbox over a motor the caller steps itself (the simulator, tests). */
#ifndef SIM_MAILBOX_H
#define SIM_MAILBOX_H

/*
 * firmware/motor.c implements motor.h on the dsPIC, over the one motor the
 * ADC interrupt steps, masking that interrupt around each call. On the PC
 * the motor is stepped by the same thread that serves the mailbox (the
 * simulator's loop, a test), so there is nothing to mask: this
 * implementation runs each call straight on the attached mc_t. The X2Cscope target
 * and the board's main loop then run unchanged on either. One motor at a
 * time; motor_start() and motor_observe() are the dsPIC's and are not
 * provided (the caller inits and steps its motor and calls its observer).
 */

#include "mc.h"

/* The motor the motor_* calls act on from now on. */
void sim_mailbox_attach(mc_t *mc);

#endif /* SIM_MAILBOX_H */
