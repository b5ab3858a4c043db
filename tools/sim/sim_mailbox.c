/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_mailbox.c - motor.h's mailbox over the attached motor, no interrupts to mask. */
#include "sim_mailbox.h"

#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

#include "motor.h"

static mc_t *attached;

void sim_mailbox_attach(mc_t *mc)
{
    attached = mc;
}

/* A call before sim_mailbox_attach() is a bug of the caller: stop loudly. */
static mc_t *the_motor(void)
{
    if (attached == NULL) {
        fputs("sim_mailbox: motor_* called with no motor attached\n", stderr);
        abort();
    }
    return attached;
}

void motor_request(mc_request_t request)
{
    mc_request(the_motor(), request);
}

void motor_status(mc_status_t *status)
{
    mc_status(the_motor(), status);
}

void motor_identify_result(mc_id_result_t *r)
{
    mc_identify_result(the_motor(), r);
}

uint8_t motor_set_reference(int16_t ref)
{
    return mc_set_reference(the_motor(), ref);
}

int16_t motor_get_gain(mc_gain_t gain)
{
    return mc_get_gain(the_motor(), gain);
}

bool motor_set_gain(mc_gain_t gain, int16_t value)
{
    return mc_set_gain(the_motor(), gain, value);
}

const mc_t *motor_view(void)
{
    return the_motor();
}

void motor_copy(void *dst, const volatile void *src, uint8_t n)
{
    uint8_t *d = (uint8_t *)dst;
    const volatile uint8_t *p = (const volatile uint8_t *)src;
    while (n-- != 0U) {
        *d++ = *p++; /* one thread steps the motor and serves the mailbox: nothing to mask */
    }
}
