/* hal.h - the hardware seam of the firmware: everything main loop and ISR need from the chip. */
#ifndef HAL_H
#define HAL_H

/*
 * One header is the whole hardware contract; hal/dspic33f/ implements it for
 * the dsPIC33FJ32MC204 and is the only code that includes the device header.
 * Plain C types only (the two frame types are the core's, from mc.h), so the
 * host can fake or mock every function.
 *
 * Who calls what:
 *   main()        hal_init(), then hal_motor_start(), then polls forever;
 *   ADC interrupt hal_adc_read() -> mc_step() -> hal_pwm_write(), inside
 *                 hal/dspic33f/ (the trampoline owns the one mc_t);
 *   main loop     buttons, LEDs, UART, the 1 ms tick, the fault latch, and the
 *                 motor mailbox (hal_motor_*), never the PWM or ADC directly.
 *
 * Nothing here blocks, except hal_init() while the PLL locks.
 */

#include <stdbool.h>
#include <stdint.h>

#include "mc.h"

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
void hal_adc_read(mc_adc_frame_t *frame);

/* The pot alone, 0..32767, as hal_adc_read() would give it: for the main
 * loop (one buffer register, read atomically, at most one period old). */
int16_t hal_pot_read(void);

/* Duties for the next PWM period (loaded by the hardware at the period
 * boundary), each clamped to 0..PWM_DUTY_MAX; outputs_on = false overrides
 * all six switches off at once, true hands the pins back to the PWM. */
void hal_pwm_write(const mc_pwm_out_t *out);

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

/* One received byte, if any; false when nothing is waiting. A receive
 * overrun is cleared here (the lost bytes are gone). */
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

/* ---- the running motor ----------------------------------------------------- *
 * The one mc_t lives with the ADC interrupt that steps it. The main loop
 * reaches it only through this mailbox: each call wraps the core's function
 * in hal_critical_enter/exit, so a status is one period's snapshot. */

/* mc_init() on the motor, then enable the ADC interrupt: from here on
 * mc_step() runs every PWM period. */
void hal_motor_start(void);

void hal_motor_request(mc_request_t request);
void hal_motor_set_reference(int16_t ref);
void hal_motor_status(mc_status_t *status);

/* An observer of the running motor (e.g. the data monitor's recorder,
 * firmware/monitor): called by the ADC interrupt once per period, after the
 * duties are written, so it never delays them. It runs in the interrupt:
 * constant time, no waiting, no UART. NULL removes it. */
typedef void (*hal_motor_observer_t)(void *ctx, const mc_t *mc);
void hal_motor_observe(hal_motor_observer_t fn, void *ctx);

/* The running motor itself, for code that calls the core's own lock-free
 * entry points from the main loop (mc.h note 1), such as the monitor.
 * Everything else uses the hal_motor_* calls above. */
mc_t *hal_motor_core(void);

#endif /* HAL_H */
