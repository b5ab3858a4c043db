/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sfr_standin.c - storage of the stand-in registers and the emulated XC16 clock built-ins. */
#include "sfr_standin.h"

/* clang-format off */
#define SFR_LIST(X) \
    X(SR) X(CORCON) X(OSCCON) X(CLKDIV) X(PLLFBD) X(IFS0) X(IEC0) X(IFS3) X(IEC3) X(IPC1) X(IPC2) X(IPC3) \
    X(P1TCON) X(P1TMR) X(P1TPER) X(P1SECMP) X(PWM1CON1) X(PWM1CON2) X(P1DTCON1) X(P1DTCON2) \
    X(P1FLTACON) X(P1OVDCON) X(P1DC1) X(P1DC2) X(P1DC3) X(AD1CON1) X(AD1CON2) X(AD1CON3) \
    X(AD1CHS123) X(AD1CHS0) X(AD1PCFGL) X(AD1CSSL) X(ADC1BUF0) X(ADC1BUF1) X(ADC1BUF2) \
    X(ADC1BUF3) X(TRISA) X(TRISB) X(TRISC) X(PORTA) X(PORTB) X(PORTC) X(LATA) X(LATB) X(LATC) \
    X(RPINR12) X(RPINR18) X(RPOR0) X(RPOR1) X(RPOR2) X(RPOR3) X(RPOR4) X(RPOR5) X(RPOR6) \
    X(RPOR7) X(RPOR8) X(RPOR9) X(RPOR10) X(RPOR11) X(RPOR12) X(U1MODE) X(U1STA) X(U1BRG) \
    X(U1TXREG) X(U1RXREG) X(T1CON) X(TMR1) X(PR1)
/* clang-format on */

#define SFR_DEFINE(name) volatile sfr_##name##_t sfr_##name;
SFR_LIST(SFR_DEFINE)

unsigned sfr_ipl_macro_uses;
unsigned sfr_pdc_log_on;
unsigned sfr_pdc_accesses;
unsigned sfr_pdc_accesses_udis0;

volatile uint16_t *sfr_pdc_access(volatile uint16_t *reg)
{
    if (sfr_pdc_log_on != 0u) {
        sfr_pdc_accesses++;
        if (PWM1CON2bits.UDIS == 0u) {
            sfr_pdc_accesses_udis0++;
        }
    }
    return reg;
}

sfr_osccon_write_t sfr_osccon_log[SFR_OSCCON_LOG_MAX];
unsigned sfr_osccon_log_n;

void sfr_standin_reset(void)
{
#define SFR_ZERO(name) sfr_##name.w = 0u;
    SFR_LIST(SFR_ZERO)
#undef SFR_ZERO
    TRISA = 0xFFFFu;
    TRISB = 0xFFFFu;
    TRISC = 0xFFFFu;
    U1STA = 0x0100u;  /* TRMT */
    CORCON = 0x0024u; /* SATDW | PSV */
    sfr_osccon_log_n = 0;
    sfr_ipl_macro_uses = 0u;
    sfr_pdc_log_on = 0u;
    sfr_pdc_accesses = 0u;
    sfr_pdc_accesses_udis0 = 0u;
}

static void log_write(char which, uint8_t value)
{
    if (sfr_osccon_log_n < SFR_OSCCON_LOG_MAX) {
        sfr_osccon_write_t *e = &sfr_osccon_log[sfr_osccon_log_n];
        e->which = which;
        e->value = value;
        e->pllfbd = PLLFBD;
        e->clkdiv = CLKDIV;
    }
    sfr_osccon_log_n++;
}

/* The high byte holds NOSC<2:0> (bits 8-10 of OSCCON); the rest of the high
 * byte (COSC) is read-only. */
void __builtin_write_OSCCONH(uint8_t value)
{
    log_write('H', value);
    OSCCON = (uint16_t)((OSCCON & 0xF8FFu) | (((unsigned)value & 0x07u) << 8));
}

/* The low byte: OSWEN (bit 0) requests the switch to NOSC, which the
 * stand-in completes at once: COSC = NOSC, OSWEN back to 0, LOCK = 1 when
 * the new source uses the PLL (NOSC = 001 FRC+PLL or 011 primary+PLL). */
void __builtin_write_OSCCONL(uint8_t value)
{
    log_write('L', value);
    /* Writable: OSWEN, LPOSCEN, CF, IOLOCK, CLKLOCK; LOCK (bit 5) is read-only. */
    OSCCON = (uint16_t)((OSCCON & ~0x00CBu) | (value & 0x00CBu));
    if (OSCCONbits.OSWEN) {
        unsigned nosc = OSCCONbits.NOSC;
        OSCCONbits.COSC = nosc & 7u;
        OSCCONbits.LOCK = (nosc == 1u || nosc == 3u) ? 1u : 0u;
        OSCCONbits.OSWEN = 0;
    }
}
