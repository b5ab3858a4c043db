/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* hal_regs.h - the ADC results and PWM duties as register accesses, inline for the ADC interrupt.
 */
#ifndef HAL_REGS_H
#define HAL_REGS_H

/*
 * Included after the device header by the two files that touch these
 * registers: hal_dspic33f.c (hal_adc_read, hal_pwm_write of hal.h) and
 * hal_isr.c (the ADC interrupt, which inlines them: no calls in the 50 us
 * path). Scalings in hal_dspic33f.h and docs/board.md.
 */

#include "hal_dspic33f.h"

/* ---- timing pin (board_mclv_hal.h) ------------------------------------------- */

#if HAL_TIMING_PIN_PORT == HAL_PORT_A
#define HAL_TIMING_LAT_ LATA
#elif HAL_TIMING_PIN_PORT == HAL_PORT_B
#define HAL_TIMING_LAT_ LATB
#elif HAL_TIMING_PIN_PORT == HAL_PORT_C
#define HAL_TIMING_LAT_ LATC
#endif

/* One bit set or cleared (bset / bclr on the chip); nothing without a pin. */
Q15_INLINE void hal_regs_timing_pin(bool high)
{
#if defined(HAL_TIMING_LAT_)
    if (high) {
        HAL_TIMING_LAT_ = (uint16_t)(HAL_TIMING_LAT_ | (1u << HAL_TIMING_PIN_BIT));
    } else {
        HAL_TIMING_LAT_ = (uint16_t)(HAL_TIMING_LAT_ & ~(1u << HAL_TIMING_PIN_BIT));
    }
#else
    (void)high;
#endif
}

/* ---- ADC --------------------------------------------------------------------- */

/* A signed fractional result (sddd dddd dd00 0000) as the int16_t it encodes,
 * without relying on an implementation-defined unsigned-to-signed cast. */
Q15_INLINE int16_t hal_regs_signed(uint16_t raw)
{
    return (int16_t)((int32_t)raw - ((raw & 0x8000u) ? 65536L : 0L));
}

/* A unipolar input (0 V .. AVDD) as 0..32767: the signed fractional result
 * offset by half scale, halved. 10-bit code n gives 32 n = Q15 of n / 1024. */
Q15_INLINE int16_t hal_regs_unipolar(uint16_t raw)
{
    return (int16_t)((uint16_t)(raw ^ 0x8000u) >> 1);
}

/* The board's amplifier sign; -32768 negates to 32767 (saturating). */
Q15_INLINE int16_t hal_regs_current(uint16_t raw)
{
    int16_t x = hal_regs_signed(raw);
#if HAL_BOARD_I_SIGN < 0
    return q15_neg_sat(x);
#else
    return x;
#endif
}

Q15_INLINE void hal_regs_adc_read(hal_adc_frame_t *frame)
{
    frame->pot = hal_regs_unipolar(ADC1BUF0);  /* CH0 = AN8 */
    frame->ia = hal_regs_current(ADC1BUF1);    /* CH1 = AN0 */
    frame->ib = hal_regs_current(ADC1BUF2);    /* CH2 = AN1 */
    frame->vbus = hal_regs_unipolar(ADC1BUF3); /* CH3 = AN2 */
}

/* ---- PWM --------------------------------------------------------------------- */

Q15_INLINE uint16_t hal_regs_duty_clamp(uint16_t d)
{
    return d > PWM_DUTY_MAX ? (uint16_t)PWM_DUTY_MAX : d;
}

/* The three duties under UDIS (as Microchip's code writes them): if the
 * interrupt ever ran past a period boundary mid-write, the boundary would
 * otherwise load a mix of this period's and the last one's duties. */
Q15_INLINE void hal_regs_duty_write(const hal_pwm_out_t *out)
{
    PWM1CON2bits.UDIS = 1;
    P1DC1 = hal_regs_duty_clamp(out->duty[0]);
    P1DC2 = hal_regs_duty_clamp(out->duty[1]);
    P1DC3 = hal_regs_duty_clamp(out->duty[2]);
    PWM1CON2bits.UDIS = 0;
}

/* The duties, then the pins: to the PWM, or all off. */
Q15_INLINE void hal_regs_pwm_write(const hal_pwm_out_t *out)
{
    hal_regs_duty_write(out);
    P1OVDCON = out->outputs_on ? HAL_P1OVDCON_PWM : HAL_P1OVDCON_OFF;
}

#endif /* HAL_REGS_H */
