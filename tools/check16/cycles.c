/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* cycles.c - AVR clock cycles of mc_step and mc_slow_step over check16's recorded start, per frame.
 */
/* check16-cflags: -DMOTOR_LOCK_TIME_S=0.02 -DMOTOR_RAMP_TIME_S=0.15 -DMC_HANDOFF_WAIT_S=0.05 */
/* check16-cflags: -DMC_HANDOFF_AGREE_S=0.005 */
#include <stdint.h>

#include "emit.h"
#include "mc.h"
#if defined(CYCLES_ID)
#include "id_frames.h"
#include "vec_id_frames.h"
#define CYCLES_FRAMES          (ID_FRAMES_N < ID_FRAMES_RECORDED_N ? ID_FRAMES_N : ID_FRAMES_RECORDED_N)
#define cycles_input(m, n, in) id_frames_input(m, n, in)
#else
#include "mc_frames.h"
#include "vec_mc_frames.h"
#define CYCLES_FRAMES          (MC_FRAMES_N < MC_FRAMES_RECORDED_N ? MC_FRAMES_N : MC_FRAMES_RECORDED_N)
#define cycles_input(m, n, in) mc_frames_input(m, n, in)
#endif

/*
 * The cycle guard of make test (tools/check16/cycles runs it): the same
 * frames vec_mc.c replays (a Hurst start through calibration, lock, ramp,
 * hand-off, closed loop and the pot to full travel), or with CYCLES_ID the
 * first stages of an identification (vec_id_frames.h), built with avr-gcc
 * for the ATmega2560 and run under simavr, which executes every instruction
 * with the AVR's exact cycle count. Timer 1 runs at the CPU clock; its
 * overflows are counted in an interrupt (a few dozen cycles per 65,536,
 * included in the figure, the same every run). The count of an empty
 * interval is measured first and subtracted, so each figure is the call
 * alone, argument set-up included.
 *
 * AVR only (tools/check16/cycles builds it with avr-gcc).
 *
 * One line per frame: state at the step's start, whether the step ended a
 * speed-loop window (so this mc_slow_step call has the window's work) |
 * mc_step cycles, mc_slow_step cycles.
 */

#include <avr/interrupt.h>
#include <avr/io.h>

static volatile uint16_t t1_overflows;

ISR(TIMER1_OVF_vect)
{
    t1_overflows++;
}

/* The 32-bit cycle count: Timer 1 low word, overflow count high word. An
 * overflow pending but not yet counted (interrupts off here) belongs to
 * this reading when the low word has already wrapped. */
static uint32_t cycles_now(void)
{
    uint8_t sreg = SREG;
    uint16_t lo;
    uint16_t hi;
    cli();
    lo = TCNT1;
    hi = t1_overflows;
    if ((TIFR1 & (1U << TOV1)) != 0U && lo < 0x8000U) {
        hi++;
    }
    SREG = sreg;
    return ((uint32_t)hi << 16) | lo;
}

static mc_t mc; /* static: off the AVR stack */

int main(void)
{
    uint32_t n;
    uint32_t t0;
    uint32_t empty;

    platform_init();
    TCCR1A = 0U;
    TCCR1B = (uint8_t)(1U << CS10); /* clk/1 */
    TIMSK1 = (uint8_t)(1U << TOIE1);
    sei();

    t0 = cycles_now();
    empty = cycles_now() - t0;

    emit_text("cycles begin");
    emit_section("mc_cycles");
    mc_init(&mc);
    for (n = 0U; n < CYCLES_FRAMES; n++) {
        mc_adc_frame_t in;
        mc_pwm_out_t out;
        mc_status_t st;
        uint32_t t_step;
        uint32_t t_slow;
        cycles_input(&mc, n, &in);
        mc_status(&mc, &st); /* the state the step starts in */
        t0 = cycles_now();
        mc_step(&mc, &in, &out);
        t_step = cycles_now() - t0 - empty;
        t0 = cycles_now();
        mc_slow_step(&mc);
        t_slow = cycles_now() - t0 - empty;
        emit_u8((uint8_t)st.state);
        emit_bool(((n + 1U) % MC_SLOW_STEP_PERIODS) == 0U);
        emit_sep();
        emit_u32(t_step);
        emit_u32(t_slow);
        emit_end();
    }
    emit_text("cycles end");
    platform_exit();
    return 0;
}
