/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* hal_frame.h - the two values one PWM period hands across the seam: the ADC set in, the duties
 * out. */
#ifndef HAL_FRAME_H
#define HAL_FRAME_H

/*
 * Plain value types with no behaviour, in the board's scalings
 * (boards/board.h). The HAL fills the first and applies the second; the
 * core (firmware/mc.h) computes one from the other and names them
 * mc_adc_frame_t and mc_pwm_out_t.
 */

#include <stdbool.h>
#include <stdint.h>

typedef struct {    /* one ADC conversion set, sampled PWM_ADC_TRIGGER_TCY after mid-period */
    int16_t ia, ib; /* phase currents, Q15 of BOARD_I_FULLSCALE_A, + = into the motor,
                       still carrying the amplifier offset (the core calibrates it) */
    int16_t vbus;   /* DC bus, Q15 of BOARD_VBUS_FULLSCALE_V (0..32767) */
    int16_t pot;    /* potentiometer, 0..32767 = 0..100 % of travel */
} hal_adc_frame_t;

typedef struct {
    uint16_t duty[3]; /* PDC1..PDC3, 0..PWM_DUTY_MAX; phase k mean voltage vs the
                         negative rail = duty[k] / PWM_DUTY_MAX * Vbus */
    bool outputs_on;  /* false: all six switches off */
} hal_pwm_out_t;

#endif /* HAL_FRAME_H */
