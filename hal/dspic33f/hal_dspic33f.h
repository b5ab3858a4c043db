/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* hal_dspic33f.h - register values of the dsPIC33FJ32MC204 HAL, derived at compile time from the
 * profiles. */
#ifndef HAL_DSPIC33F_H
#define HAL_DSPIC33F_H

/*
 * Every number written to a register is a macro here, computed from the
 * engineering units of boards/board.h (BOARD_FCY_HZ, PWM_FREQUENCY_HZ,
 * PWM_DEADTIME_NS, PWM_DUTY_MAX, PWM_ADC_TRIGGER_TCY), with a compile-time
 * check on every range. The tests pin the resulting register values, and
 * docs/board.md lists them.
 *
 * Confidence (docs/hardware.md tags): register layouts and the AN1078 values are
 * [SRC]. Each fact that is only [MEM] or [NOT FOUND] lives in ONE macro
 * below whose comment says so; the HAL code uses the macro, never the
 * number, so correcting a fact is a one-line change.
 */

#include <stdint.h>

#include "../../boards/board.h"
#include "hal.h"
#include "q15.h"

/* Pin designators for the board headers below. */
#define HAL_PORT_NONE 0u
#define HAL_PORT_A    1u
#define HAL_PORT_B    2u
#define HAL_PORT_C    3u
#define HAL_RP_NONE   0xFFu /* RPn not mapped (the 32MC204 has RP0..RP25) */

/* HAL-side board facts (current sign, LED and UART pins) for the board the
 * core was built for; the scalings themselves are in the core's profile. */
#if defined(MC_BOARD_MCHV)
#include "board_mchv_hal.h"
#else
#include "board_mclv_hal.h"
#endif

#ifndef BOARD_FCY_HZ
#error "BOARD_FCY_HZ missing: the board profile (boards/board_<BOARD>.h) must define it"
#endif

/* ---- interrupt attributes ------------------------------------------------- *
 * auto_psv: the ISRs run the core, which reads const tables (the sine
 * table, gains) that XC16 places in program memory and reads through PSV;
 * auto_psv makes each ISR set PSVPAG for them (a few cycles), instead of
 * trusting that nothing ever changed it (docs/board.md). shadow, on the ADC
 * interrupt alone: W0-W3 and SR go to the one set of shadow registers
 * (push.s / pop.s) instead of the stack; no other code may use them, which
 * is why the slow step's interrupt, which the ADC interrupt pre-empts, does
 * not. On the PC and with avr-gcc the vectors are ordinary functions the
 * tests call. */
#if defined(__XC16__)
#define HAL_ISR      __attribute__((interrupt, auto_psv))
#define HAL_ISR_FAST __attribute__((interrupt, auto_psv, shadow))
#else
#define HAL_ISR
#define HAL_ISR_FAST
#endif

/* ---- clock (docs/hardware.md 1.2) ----------------------------------------- *
 * Fosc = Fin * M / (N1 * N2), Fcy = Fosc / 2, M = PLLFBD + 2,
 * N1 = PLLPRE + 2, N2 = 2 * (PLLPOST + 1). */
#define HAL_FIN_HZ         8000000L /* MCLV crystal, 8 MHz (AN1078 PLLIN) [SRC] */
#define HAL_PLL_N1         2L       /* PLLPRE = 0 [SRC] */
#define HAL_PLL_N2         2L       /* PLLPOST = 0 [SRC] */
#define HAL_PLL_M          (2L * BOARD_FCY_HZ * HAL_PLL_N1 * HAL_PLL_N2 / HAL_FIN_HZ)
#define HAL_PLLFBD         ((uint16_t)(HAL_PLL_M - 2L))
#define HAL_CLKDIV_PLLPRE  ((unsigned)(HAL_PLL_N1 - 2L))
#define HAL_CLKDIV_PLLPOST ((unsigned)(HAL_PLL_N2 / 2L - 1L))
/* PLL input and VCO limits of the dsPIC33F: 0.8..8 MHz after N1, 100..200 MHz
 * at the VCO [MEM: docs/hardware.md 1.2, check DS70283]. */
#define HAL_PLL_VCO_MIN_HZ 100000000L
#define HAL_PLL_VCO_MAX_HZ 200000000L
#define HAL_PLL_PFD_MIN_HZ 800000L
#define HAL_PLL_PFD_MAX_HZ 8000000L
#define HAL_PLL_VCO_HZ     (HAL_FIN_HZ / HAL_PLL_N1 * HAL_PLL_M)
/* OSCCON.NOSC/COSC code of "primary oscillator (XT) with PLL" [SRC: AN1078]. */
#define HAL_OSC_PRIPLL 3u

/* HAL_CHECK(PARAM, cond, "why"): the build stops at this line naming the
 * user's parameter the condition is about ("PARAM__out_of_range" in the
 * first error line, as the core's MC_CHECK does; the pasted name is used
 * in place, not handed to another macro, which cppcheck cannot expand). */
#define HAL_CHECK(param, cond, msg)                                                                \
    extern char q15_check_[1 + (int)(0 * sizeof(struct {                                           \
                                         unsigned param##__out_of_range : Q15_CHECK_WIDTH_(cond);  \
                                     }))]

HAL_CHECK(BOARD_FCY_HZ, HAL_PLL_M *HAL_FIN_HZ == 2L * BOARD_FCY_HZ * HAL_PLL_N1 * HAL_PLL_N2,
          "BOARD_FCY_HZ is not reachable from the 8 MHz crystal with N1 = N2 = 2");
HAL_CHECK(BOARD_FCY_HZ, HAL_PLL_M >= 2L && HAL_PLL_M <= 513L, "PLLFBD out of its 9-bit range");
HAL_CHECK(BOARD_FCY_HZ,
          HAL_FIN_HZ / HAL_PLL_N1 >= HAL_PLL_PFD_MIN_HZ &&
              HAL_FIN_HZ / HAL_PLL_N1 <= HAL_PLL_PFD_MAX_HZ,
          "PLL input after N1 outside 0.8..8 MHz");
HAL_CHECK(BOARD_FCY_HZ,
          HAL_PLL_VCO_HZ >= HAL_PLL_VCO_MIN_HZ && HAL_PLL_VCO_HZ <= HAL_PLL_VCO_MAX_HZ,
          "PLL VCO outside 100..200 MHz");
HAL_CHECK(BOARD_FCY_HZ, BOARD_FCY_HZ <= 40000000L, "the dsPIC33F runs at most 40 MIPS");

/* ---- MCPWM1 (docs/hardware.md 1.4-1.6) ------------------------------------ *
 * Center-aligned (PTMOD = 10): one period = 2 * (PTPER + 1) Tcy, so
 * PTPER = Fcy / (2 Fpwm) - 1 (the textbook value; AN1078 writes Fcy/Fpwm/2,
 * one count more, docs/hardware.md 0.2). Duty registers count Tcy/2, so 100 %
 * duty is 2 * (PTPER + 1) = PWM_DUTY_MAX: the core's duties go to PDCx
 * unscaled. */
#define HAL_PTPER ((uint16_t)(BOARD_FCY_HZ / (2L * (long)PWM_FREQUENCY_HZ) - 1L))
HAL_CHECK(PWM_FREQUENCY_HZ, BOARD_FCY_HZ % (2L * (long)PWM_FREQUENCY_HZ) == 0,
          "PWM_FREQUENCY_HZ does not divide Fcy / 2: the period would not be exact");
HAL_CHECK(PWM_FREQUENCY_HZ, BOARD_FCY_HZ / (2L * (long)PWM_FREQUENCY_HZ) - 1L <= 0x7FFFL,
          "PTPER is 15 bits: PWM_FREQUENCY_HZ too low");
HAL_CHECK(PWM_DUTY_MAX, 2L * (BOARD_FCY_HZ / (2L * (long)PWM_FREQUENCY_HZ)) == (long)PWM_DUTY_MAX,
          "PWM_DUTY_MAX must be 2 * (PTPER + 1), the PDCx count of 100 % duty");

#define HAL_P1TCON_PTEN_UPDOWN 0x8002u /* PTEN = 1, PTMOD = 10 (center-aligned), 1:1 [SRC] */
#define HAL_PWM1CON1_COMPL_ALL 0x0077u /* PEN1H..3H, PEN1L..3L, PMOD = 0 complementary [SRC] */
#define HAL_PWM1CON2_SYNC      0x0000u /* UDIS = 0, IUE = 0: PDCx load at the period boundary */

/* Dead time: DTAPS = 01 counts 2 Tcy [SRC: AN1078 writes 0x40 | (Tcy / 2)];
 * the 00/10/11 codes are [MEM] and unused. */
#define HAL_DTAPS_2TCY   1u
#define HAL_DEADTIME_TCY ((PWM_DEADTIME_NS * (BOARD_FCY_HZ / 1000L) + 500000L) / 1000000L)
#define HAL_DTA          ((uint16_t)(HAL_DEADTIME_TCY / 2L))
#define HAL_P1DTCON1     ((uint16_t)((HAL_DTAPS_2TCY << 6) | HAL_DTA))
HAL_CHECK(PWM_DEADTIME_NS, HAL_DEADTIME_TCY % 2L == 0,
          "dead time is not a whole number of 2-Tcy units");
HAL_CHECK(PWM_DEADTIME_NS, HAL_DEADTIME_TCY / 2L >= 1L && HAL_DEADTIME_TCY / 2L <= 63L,
          "dead time outside DTA's 1..63 units of 2 Tcy");
/* BOARD_DEADTIME_NS: the least the power stage needs (its profile). */
HAL_CHECK(PWM_DEADTIME_NS, PWM_DEADTIME_NS >= BOARD_DEADTIME_NS,
          "dead time below the power stage's BOARD_DEADTIME_NS (shoot-through)");

/* Special event: ADC start 80 Tcy after the period's midpoint (PTMR =
 * PTPER, all low switches on), counting down: "80 offset ... to avoid
 * ripple on the current measurement" [SRC: AN1078]. */
#define HAL_ADC_TRIGGER_OFFSET_TCY                                                                 \
    ((unsigned)PWM_ADC_TRIGGER_TCY) /* boards/board.h: the core knows it */
#define HAL_P1SECMP ((uint16_t)(0x8000u | (unsigned)(HAL_PTPER - HAL_ADC_TRIGGER_OFFSET_TCY)))

/* Fault A: FAEN1..3 = 1, FLTAM = 0 (latched), FAOVxx = 0 (inactive) [SRC]. */
#define HAL_P1FLTACON_LATCHED 0x0007u
/* Override: POVDxx = 1 gives the pins to the PWM; 0 with POUT = 0 = off [SRC]. */
#define HAL_P1OVDCON_PWM 0x3F00u
#define HAL_P1OVDCON_OFF 0x0000u
/* Bootstrap precharge: every pin overridden, the three low switches on
 * (POUT1L, POUT2L, POUT3L), so the high-side drivers' bootstrap capacitors
 * charge before the PWM first switches the high sides [SRC: docs/board.md,
 * "Bring-up facts": Microchip's MCLV code, OVDCON = 0x0015 for 10 ms]. */
#define HAL_P1OVDCON_PRECHARGE 0x0015u
/* Its length after hal_control_start(), in PWM periods: 10 ms. */
#define HAL_PRECHARGE_PERIODS ((uint16_t)(PWM_FREQUENCY_HZ / 100L))

/* ---- ADC1 (docs/hardware.md 1.7, 1.8) --------------------------------------- *
 * Four sample-and-holds sampled together at the special event, converted
 * CH0..CH3 into ADC1BUF0..3:
 *   CH0 = AN8 pot, CH1 = AN0 IA, CH2 = AN1 IB, CH3 = AN2 VBUS [SRC]. */
#define HAL_AD1_FORM_SFRACT 3u /* signed fractional [SRC] */
#define HAL_AD1_SSRC_PWM    3u /* MCPWM special event ends sampling, starts conversion [SRC] */
#define HAL_AD1_CHPS_4CH    2u /* CH0..CH3 [SRC] */
#define HAL_AD1_CH0SA_POT   8u /* AN8 [SRC] */
#define HAL_AD1_CH123SA_IAB 0u /* CH1..3 = AN0, AN1, AN2 [SRC] */
/* ANx pins used as analog inputs: AN0, AN1, AN2, AN8. */
#define HAL_AD1PCFGL_ANALOG ((uint16_t) ~(uint16_t)((1u << 0) | (1u << 1) | (1u << 2) | (1u << 8)))
/* TAD = (ADCS + 1) Tcy. [MEM] the dsPIC33F 10-bit minimum TAD is about 76 ns
 * and a conversion takes 12 TAD: ADCS = 3 gives TAD = 100 ns, 4 channels in
 * 4.8 us, so the ISR starts about 6.8 us after the midpoint, 18.2 us (728
 * Tcy) before the period boundary where the duties load (docs/design.md timing
 * contract; docs/board.md "Timing" says what the interrupt's length does to
 * it).
 * AN1078 used ADCS = 15 (400 ns, 19.2 us for 4 channels) [SRC], which leaves
 * too little time before the boundary. */
#define HAL_AD1_ADCS 3u
/* ADC interrupt priority (1..7; the critical section masks up to 7). */
#define HAL_ADC_IRQ_PRIORITY 5u
/* The slow hook (hal_hook_slow) runs in Timer2's interrupt, raised in
 * software by the ADC interrupt every slow_periods periods (Timer2 stays off): below
 * the ADC interrupt, which pre-empts it, above the main loop (0).
 * T2IF/T2IE are IFS0/IEC0 bit 7, T2IP is IPC1<14:12> [MEM: the dsPIC33F
 * interrupt vector table, DS70283 / FRM section 6]. */
#define HAL_SLOW_IRQ_PRIORITY 2u

/* ---- pins (docs/hardware.md 1.8) ----------------------------------------- */
#define HAL_S2_PORTA_BIT    8u /* S2 on RA8, active low [SRC] */
#define HAL_S3_PORTB_BIT    4u /* S3 on RB4, active low [SRC] */
#define HAL_FLTA1_RP        8u /* FLTA1 on RP8 = RB8 (RPINR12.FLTA1R = 8) [SRC] */
#define HAL_FLTA1_PORTB_BIT 8u
/* OSCCON.IOLOCK, bit 6: PPS registers writable while 0 [MEM]. */
#define HAL_OSCCON_IOLOCK 0x40u
/* PPS output function number of U1TX [MEM: dsPIC33F FRM/DS70283 table]. */
#define HAL_PPS_FN_U1TX 3u

/* ---- UART1: 8N1, BRGH = 1, BRG = Fcy / (4 baud) - 1, rounded [MEM: FRM section 17] ----
 * 115200 Bd, X2Cscope's default: BRG 86, 114,943 Bd at 40 MIPS (-0.22 %); with
 * BRGH = 0 the nearest rate is 5.6 % off, more than a receiver forgives. */
#ifndef HAL_UART_BAUD
#define HAL_UART_BAUD 115200L
#endif
#define HAL_U1BRG ((uint16_t)((BOARD_FCY_HZ + 2L * HAL_UART_BAUD) / (4L * HAL_UART_BAUD) - 1L))
/* The receive ring the U1RX interrupt fills, bytes (a power of two, <= 256):
 * the bytes wait here while the main loop is busy elsewhere; 32 are 2.8 ms
 * at 115200 Bd, far above the main loop's longest pass. */
#define HAL_UART_RX_RING 32u
/* U1RX's priority: above the slow step (2), below the ADC interrupt (5),
 * which pre-empts it; the handler is a few cycles a byte. */
#define HAL_U1RX_IRQ_PRIORITY 3u

/* ---- 1 ms tick: Timer1, Fcy / 8, period 1 ms --------------------------------- */
#define HAL_T1_TCKPS_8 1u /* TCKPS = 01: 1:8 [MEM] */
#define HAL_PR1        ((uint16_t)(BOARD_FCY_HZ / 8L / 1000L - 1L))
Q15_STATIC_ASSERT(BOARD_FCY_HZ / 8L / 1000L - 1L <= 0xFFFFL, "PR1 is 16 bits");

/* ---- CORCON (docs/board.md), set once in hal_init() ------------------------ *
 * The DSP engine serves the core's accumulator primitives (foc/q15_dsp.h),
 * which rely on exactly these modes:
 *   IF = 0      fractional multiplies (1.15 x 1.15 -> 1.31);
 *   US = 0      signed operands;
 *   SATA = 1, ACCSAT = 0   A saturates at 1.31, like q31_add_sat;
 *   SATB = 0    B is unsaturated (8 guard bits): the PI's Kp Err 2^shift is
 *               formed there before the sum in A saturates;
 *   SATDW = 1   accumulator stores saturate to 16 bits, like q15_sat;
 *   RND = 1     conventional (biased) rounding in sac.r, the ties-up rule
 *               of q15_mul.
 * No other code changes CORCON, so it is set once and never saved; XC16
 * saves and restores both accumulators around the ADC interrupt (a
 * non-leaf interrupt function), so the core may use them in every context.
 * PSV, IPL3 and the DO-loop bits are left as the C start-up set them. */
#define HAL_CORCON_SET   0x00A2u /* SATA | SATDW | RND */
#define HAL_CORCON_CLEAR 0x1051u /* US | SATB | ACCSAT | IF */

/* The ADC interrupt vector and the slow step's (hal_isr.c); the tests call
 * them as functions. */
void HAL_ISR_FAST _ADC1Interrupt(void);
void HAL_ISR _T2Interrupt(void);
void HAL_ISR _U1RXInterrupt(void);

#endif /* HAL_DSPIC33F_H */
