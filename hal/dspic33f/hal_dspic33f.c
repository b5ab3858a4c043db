/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* hal_dspic33f.c - hal.h for the dsPIC33FJ32MC204: clock, MCPWM1, ADC1, fault, pins, UART1, tick.
 */
#include <xc.h>

#include "hal_dspic33f.h"
#include "hal_regs.h"

/* ---- init ------------------------------------------------------------------ */

/* 40 MIPS: the configuration starts the chip on the FRC; set the PLL
 * dividers, then switch to the crystal through the PLL and wait for the
 * switch and the lock (docs/hardware.md 1.2, AN1078's sequence). */
static void clock_init(void)
{
    PLLFBD = HAL_PLLFBD;
    CLKDIVbits.PLLPRE = HAL_CLKDIV_PLLPRE;
    CLKDIVbits.PLLPOST = HAL_CLKDIV_PLLPOST;

    __builtin_write_OSCCONH(HAL_OSC_PRIPLL);            /* NOSC = primary + PLL */
    __builtin_write_OSCCONL((uint8_t)(OSCCON | 0x01u)); /* OSWEN: request the switch */
    while (OSCCONbits.COSC != HAL_OSC_PRIPLL) {
    }
    while (OSCCONbits.LOCK != 1u) {
    }
}

/* See HAL_CORCON_SET in hal_dspic33f.h for what each bit is for. */
static void corcon_init(void)
{
    CORCON = (uint16_t)(((unsigned)CORCON & ~HAL_CORCON_CLEAR) | HAL_CORCON_SET);
}

/* The RPORx word holding the output function of RPn. */
static volatile uint16_t *rpor_word(unsigned rp)
{
    switch (rp / 2u) {
        case 0u:
            return &RPOR0;
        case 1u:
            return &RPOR1;
        case 2u:
            return &RPOR2;
        case 3u:
            return &RPOR3;
        case 4u:
            return &RPOR4;
        case 5u:
            return &RPOR5;
        case 6u:
            return &RPOR6;
        case 7u:
            return &RPOR7;
        case 8u:
            return &RPOR8;
        case 9u:
            return &RPOR9;
        case 10u:
            return &RPOR10;
        case 11u:
            return &RPOR11;
        default:
            return &RPOR12;
    }
}

/* Output function fn on pin RPrp: RPORn holds RP(2n) in bits 0-4 and
 * RP(2n+1) in bits 8-12. */
static void pps_output(unsigned rp, unsigned fn)
{
    volatile uint16_t *w = rpor_word(rp);
    unsigned shift = (rp & 1u) ? 8u : 0u;
    *w = (uint16_t)(((unsigned)*w & ~(0x1Fu << shift)) | ((fn & 0x1Fu) << shift));
}

static volatile uint16_t *lat_of(unsigned port)
{
    return port == HAL_PORT_A ? &LATA : port == HAL_PORT_B ? &LATB : &LATC;
}

static volatile uint16_t *tris_of(unsigned port)
{
    return port == HAL_PORT_A ? &TRISA : port == HAL_PORT_B ? &TRISB : &TRISC;
}

static void led_pin_init(unsigned port, unsigned bit)
{
    if (port != HAL_PORT_NONE) {
        *lat_of(port) = (uint16_t)((unsigned)*lat_of(port) & ~(1u << bit));
        *tris_of(port) = (uint16_t)((unsigned)*tris_of(port) & ~(1u << bit));
    }
}

static void pins_init(void)
{
    /* AN0, AN1, AN2, AN8 analog; every other ANx pin digital. */
    AD1PCFGL = HAL_AD1PCFGL_ANALOG;

    /* Buttons and the fault pin are inputs (they are after reset; say so). */
    TRISA = (uint16_t)(TRISA | (1u << HAL_S2_PORTA_BIT));
    TRISB = (uint16_t)(TRISB | (1u << HAL_S3_PORTB_BIT) | (1u << HAL_FLTA1_PORTB_BIT));

    led_pin_init(HAL_LED_RUN_PORT, HAL_LED_RUN_BIT);
    led_pin_init(HAL_LED_FAULT_PORT, HAL_LED_FAULT_BIT);
    led_pin_init(HAL_TIMING_PIN_PORT, HAL_TIMING_PIN_BIT); /* an output, low */

    /* Peripheral pin select: unlock, map, lock. FLTA1 must be on its pin
     * before P1FLTACON enables the fault (docs/hardware.md 5). */
    __builtin_write_OSCCONL((uint8_t)(OSCCON & ~HAL_OSCCON_IOLOCK));
    RPINR12bits.FLTA1R = HAL_FLTA1_RP;
#if HAL_UART_RX_RP != HAL_RP_NONE
    RPINR18bits.U1RXR = HAL_UART_RX_RP;
#endif
#if HAL_UART_TX_RP != HAL_RP_NONE
    pps_output(HAL_UART_TX_RP, HAL_PPS_FN_U1TX);
#else
    (void)pps_output;
#endif
    __builtin_write_OSCCONL((uint8_t)(OSCCON | HAL_OSCCON_IOLOCK));
}

/* AN1078's order (docs/hardware.md 1.6), with the fault latched instead of off
 * and the outputs overridden off until the core turns them on. */
static void pwm_init(void)
{
    P1TCONbits.PTEN = 0;
    P1OVDCON = HAL_P1OVDCON_OFF;
    P1DC1 = PWM_DUTY_MAX / 2u;
    P1DC2 = PWM_DUTY_MAX / 2u;
    P1DC3 = PWM_DUTY_MAX / 2u;
    P1TPER = HAL_PTPER;
    PWM1CON1 = HAL_PWM1CON1_COMPL_ALL;
    PWM1CON2 = HAL_PWM1CON2_SYNC;
    P1DTCON1 = HAL_P1DTCON1;
    P1DTCON2 = 0x0000u; /* dead-time unit A on every edge */
    P1FLTACON = HAL_P1FLTACON_LATCHED;
    IEC3bits.FLTA1IE = 0; /* the latch is polled: hal_fault_latched() */
    IFS3bits.FLTA1IF = 0;
    IEC3bits.PWM1IE = 0; /* the ADC interrupt is the control tick */
    IFS3bits.PWM1IF = 0;
    P1SECMP = HAL_P1SECMP;
    P1TCON = HAL_P1TCON_PTEN_UPDOWN;
}

static void adc_init(void)
{
    AD1CON1 = 0x0000u; /* ADON = 0 while configuring */
    AD1CON1bits.FORM = HAL_AD1_FORM_SFRACT;
    AD1CON1bits.SSRC = HAL_AD1_SSRC_PWM;
    AD1CON1bits.SIMSAM = 1;
    AD1CON1bits.ASAM = 1;
    AD1CON1bits.AD12B = 0;

    AD1CON2 = 0x0000u; /* VCFG = AVDD/AVSS, no scan, SMPI = 0, one buffer */
    AD1CON2bits.CHPS = HAL_AD1_CHPS_4CH;

    AD1CON3 = 0x0000u; /* ADRC = 0: TAD from Tcy */
    AD1CON3bits.ADCS = HAL_AD1_ADCS;

    AD1CHS0 = 0x0000u; /* negative inputs VREF- */
    AD1CHS0bits.CH0SA = HAL_AD1_CH0SA_POT;
    AD1CHS123 = 0x0000u;
    AD1CHS123bits.CH123SA = HAL_AD1_CH123SA_IAB;
    AD1CSSL = 0x0000u;

    IEC0bits.AD1IE = 0; /* hal_control_start() enables it */
    IFS0bits.AD1IF = 0;
    IPC3bits.AD1IP = HAL_ADC_IRQ_PRIORITY;
    AD1CON1bits.ADON = 1;
}

static void uart_init(void)
{
    U1MODE = 0x0000u; /* 8N1, UEN = 00 (RX/TX only) */
    U1MODEbits.BRGH = 1;
    U1STA = 0x0000u; /* URXISEL = 00: an interrupt for every byte received */
    U1BRG = HAL_U1BRG;
    IEC0bits.U1TXIE = 0;
    IPC2bits.U1RXIP = HAL_U1RX_IRQ_PRIORITY;
    IFS0bits.U1RXIF = 0;
#if HAL_UART_RX_RP != HAL_RP_NONE
    IEC0bits.U1RXIE = 1;
#else
    IEC0bits.U1RXIE = 0; /* nothing to receive (hal_uart_get) */
#endif
    U1MODEbits.UARTEN = 1;
    U1STAbits.UTXEN = 1; /* after UARTEN, as the module requires */
}

static void tick_init(void)
{
    T1CON = 0x0000u;
    TMR1 = 0u;
    PR1 = HAL_PR1;
    T1CONbits.TCKPS = HAL_T1_TCKPS_8;
    IEC0bits.T1IE = 0; /* polled */
    IFS0bits.T1IF = 0;
    T1CONbits.TON = 1;
}

/* The slow step's interrupt: Timer2's vector, with Timer2 itself never
 * started, so only the ADC interrupt's software write to T2IF raises it. */
static void slow_irq_init(void)
{
    IEC0bits.T2IE = 0; /* hal_control_start() enables it */
    IFS0bits.T2IF = 0;
    IPC1bits.T2IP = HAL_SLOW_IRQ_PRIORITY;
}

void hal_init(void)
{
    clock_init();
    corcon_init();
    pins_init();
    pwm_init();
    adc_init();
    slow_irq_init();
    uart_init();
    tick_init();
}

/* ---- ADC --------------------------------------------------------------------- */

void hal_adc_read(hal_adc_frame_t *frame)
{
    hal_regs_adc_read(frame);
}

int16_t hal_pot_read(void)
{
    return hal_regs_unipolar(ADC1BUF0);
}

/* ---- PWM --------------------------------------------------------------------- */

void hal_pwm_write(const hal_pwm_out_t *out)
{
    hal_regs_pwm_write(out);
}

void hal_pwm_off(void)
{
    P1OVDCON = HAL_P1OVDCON_OFF;
}

/* ---- fault --------------------------------------------------------------------- */

bool hal_fault_latched(void)
{
    return IFS3bits.FLTA1IF != 0u;
}

static bool fault_pin_asserted(void)
{
    return (PORTB & (1u << HAL_FLTA1_PORTB_BIT)) == 0u; /* active low */
}

/* In latched mode the outputs resume once the pin is released and FLTA1IF
 * is clear (docs/hardware.md 5): override them off first, and keep the flag
 * while the pin is still low so the latch cannot end behind our back. */
bool hal_fault_clear(void)
{
    P1OVDCON = HAL_P1OVDCON_OFF;
    if (fault_pin_asserted()) {
        return false;
    }
    IFS3bits.FLTA1IF = 0;
    return true;
}

/* ---- buttons, LEDs --------------------------------------------------------------- */

bool hal_button_pressed(hal_button_t button)
{
    if (button == HAL_BUTTON_S2) {
        return (PORTA & (1u << HAL_S2_PORTA_BIT)) == 0u;
    }
    return (PORTB & (1u << HAL_S3_PORTB_BIT)) == 0u;
}

static void led_pin_write(unsigned port, unsigned bit, bool on)
{
    if (port != HAL_PORT_NONE) {
        volatile uint16_t *lat = lat_of(port);
        *lat = (uint16_t)(on ? ((unsigned)*lat | (1u << bit)) : ((unsigned)*lat & ~(1u << bit)));
    }
}

void hal_led_set(hal_led_t led, bool on)
{
    if (led == HAL_LED_RUN) {
        led_pin_write(HAL_LED_RUN_PORT, HAL_LED_RUN_BIT, on);
    } else {
        led_pin_write(HAL_LED_FAULT_PORT, HAL_LED_FAULT_BIT, on);
    }
}

/* ---- UART ------------------------------------------------------------------------ */

bool hal_uart_put(uint8_t byte)
{
    if (U1STAbits.UTXBF) {
        return false;
    }
    U1TXREG = byte;
    return true;
}

/* The receive ring: head written by the U1RX interrupt only, tail by
 * hal_uart_get only (main loop); each one byte, so atomic. */
static volatile uint8_t rx_ring[HAL_UART_RX_RING];
static volatile uint8_t rx_head;
static volatile uint8_t rx_tail;
Q15_STATIC_ASSERT((HAL_UART_RX_RING & (HAL_UART_RX_RING - 1u)) == 0u && HAL_UART_RX_RING <= 256u,
                  "the ring's indices wrap by mask in one byte");

/* Every received byte into the ring; a byte the full ring cannot take is
 * dropped (the LNet receiver resynchronises on the next frame). */
void HAL_ISR _U1RXInterrupt(void)
{
    uint8_t n;
    /* at most the receiver's 4-deep FIFO: a bounded handler */
    for (n = 0; n < 4u && U1STAbits.URXDA; n++) {
        uint8_t b = (uint8_t)(U1RXREG & 0xFFu);
        uint8_t next = (uint8_t)((rx_head + 1u) & (HAL_UART_RX_RING - 1u));
        if (next != rx_tail) {
            rx_ring[rx_head] = b;
            rx_head = next;
        }
    }
    if (U1STAbits.OERR) {
        U1STAbits.OERR = 0; /* the receiver stops until this is cleared */
    }
    IFS0bits.U1RXIF = 0;
}

bool hal_uart_get(uint8_t *byte)
{
    uint8_t t = rx_tail;
    if (t == rx_head) {
        return false;
    }
    *byte = rx_ring[t];
    rx_tail = (uint8_t)((t + 1u) & (HAL_UART_RX_RING - 1u));
    return true;
}

/* ---- tick, critical section --------------------------------------------------- */

bool hal_tick_1ms(void)
{
    if (!IFS0bits.T1IF) {
        return false;
    }
    IFS0bits.T1IF = 0;
    return true;
}

/* Microchip's idiom from the device header: the IPL is written inside a
 * DISI window, so no interrupt slips in while SR is being changed. */
hal_irq_state_t hal_critical_enter(void)
{
    hal_irq_state_t saved;
    SET_AND_SAVE_CPU_IPL(saved, 7);
    return saved;
}

void hal_critical_exit(hal_irq_state_t saved)
{
    RESTORE_CPU_IPL(saved);
}
