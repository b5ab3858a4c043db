/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* hal.h - the hardware seam of the firmware: everything main loop and ISR need from the chip. */
#ifndef HAL_H
#define HAL_H

/*
 * One header is the whole hardware contract; hal/dspic33f/ implements it for
 * the dsPIC33FJ32MC204 and is the only code that includes the device header.
 * Plain C types only, so the host can fake or mock every function. The HAL
 * knows the chip and the board (boards/board.h) and nothing of the
 * application: it includes no firmware/ header and owns no application
 * object.
 *
 * Who calls what:
 *   main()         hal_init(), then (through firmware/motor.c)
 *                  hal_control_start(), then polls forever;
 *   ADC interrupt  a trampoline in hal/dspic33f/: it reads the conversion
 *                  set, hands it to hal_hook_control(), writes the duties
 *                  it gets back, then calls hal_hook_finish(); every
 *                  slow_periods-th period it raises the slow interrupt,
 *                  whose trampoline calls hal_hook_slow(). The three hooks
 *                  are the firmware's (firmware/motor.c);
 *   main loop      buttons, LEDs, UART, the 1 ms tick, the fault latch,
 *                  never the PWM or ADC directly.
 *
 * Nothing here blocks, except hal_init() while the PLL locks.
 */

#include <stdbool.h>
#include <stdint.h>

#include "hal_frame.h"

/* ---- init ------------------------------------------------------------------ */

/* Clock (40 MIPS from the 8 MHz crystal via the PLL), CORCON, pins, MCPWM1
 * (running, 20 kHz center-aligned, all six outputs overridden off), ADC1
 * (converting on the PWM special event, its interrupt still disabled), the
 * fault input (latched), UART1 and the 1 ms tick. Call once, first. */
void hal_init(void);

/* ---- the fast path (ADC interrupt) -------------------------------------- */

/* The four results of the last conversion set, in the core's units:
 * ia, ib  Q15 of BOARD_I_FULLSCALE_A, + = into the motor (the board's
 *         amplifier sign is applied here; offset still included);
 * vbus    0..32767 of BOARD_VBUS_FULLSCALE_V;
 * pot     0..32767 over the travel. */
void hal_adc_read(hal_adc_frame_t *frame);

/* The pot alone, 0..32767, as hal_adc_read() would give it: for the main
 * loop (one buffer register, read atomically, at most one period old). */
int16_t hal_pot_read(void);

/* Duties for the next PWM period (loaded by the hardware at the period
 * boundary), each clamped to 0..PWM_DUTY_MAX; outputs_on = false overrides
 * all six switches off at once, true hands the pins back to the PWM. */
void hal_pwm_write(const hal_pwm_out_t *out);

/* All six switches overridden off at once, the duties untouched: for a
 * hook that turns the outputs off after the duties were written. */
void hal_pwm_off(void);

/* ---- fault input (FLTA1, latched) ----------------------------------------- */

/* True once the fault pin has tripped: the hardware has already driven every
 * output inactive and holds them so until hal_fault_clear(). */
bool hal_fault_latched(void);

/* Leave the latch: overrides the outputs off (so nothing restarts before the
 * core asks) and clears it. If the pin is still asserted the latch stays set
 * and this returns false. */
bool hal_fault_clear(void);

/* ---- buttons, LEDs ---------------------------------------------------------- */

typedef enum {
    HAL_BUTTON_S2, /* start / stop */
    HAL_BUTTON_S3  /* AN1078's second button: double / normal speed */
} hal_button_t;

/* Raw level, true while held down. Debouncing is the caller's. */
bool hal_button_pressed(hal_button_t button);

typedef enum {
    HAL_LED_RUN,  /* motor state */
    HAL_LED_FAULT /* fault code */
} hal_led_t;

void hal_led_set(hal_led_t led, bool on);

/* ---- UART1 (8N1, HAL_UART_BAUD) ------------------------------------------- */

/* Queue one byte; false (and nothing sent) when the transmitter is full. */
bool hal_uart_put(uint8_t byte);

/* One received byte, if any; false when nothing is waiting. The UART's
 * receive interrupt keeps the bytes in a ring until they are taken; what a
 * full ring cannot take is lost. */
bool hal_uart_get(uint8_t *byte);

/* ---- time --------------------------------------------------------------------- */

/* True once for every millisecond elapsed since the previous true (a
 * free-running timer's flag, polled and cleared: ticks are skipped, never
 * queued, if the caller is late). */
bool hal_tick_1ms(void);

/* ---- critical section ------------------------------------------------------- */

/* Masks the interrupts that share data with the main loop (on the dsPIC:
 * raises the CPU priority to 7) and returns what to restore. Pairs nest. */
typedef uint16_t hal_irq_state_t;
hal_irq_state_t hal_critical_enter(void);
void hal_critical_exit(hal_irq_state_t saved);

/* ---- the control interrupts ---------------------------------------------- */

/* Enable the ADC interrupt and the slow interrupt: from the next
 * conversion set on, the control and finish hooks below run every PWM
 * period and the slow hook after every slow_periods-th (1..65535, counted
 * from here), each given ctx (the firmware's object; the HAL only hands it
 * back). The first 10 ms the bootstrap capacitors precharge (the low
 * switches on while the hooks keep the outputs off). */
void hal_control_start(void *ctx, uint16_t slow_periods);

/* Disable both interrupts (a conversion set that completes meanwhile is
 * dropped): the hooks no longer run. */
void hal_control_stop(void);

/* ---- hooks: implemented by the firmware, called by the HAL's interrupts --- */

/* The ADC interrupt, once per PWM period: the duties for the next period
 * from this period's conversion set. The HAL writes them as soon as this
 * returns, before the period boundary that loads them. Constant time, no
 * waiting, no UART. */
void hal_hook_control(void *ctx, const hal_adc_frame_t *frame, hal_pwm_out_t *out);

/* The same interrupt, after the duties are in the registers: the rest of
 * the period's work. out is what hal_hook_control() returned; to turn the
 * outputs off now, call hal_pwm_off(). */
void hal_hook_finish(void *ctx, hal_pwm_out_t *out);

/* The slow interrupt (lower priority, pre-empted by the ADC interrupt). */
void hal_hook_slow(void *ctx);

#endif /* HAL_H */
