/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* xc.h (host stand-in) - the dsPIC33FJ32MC204 SFRs the HAL touches, as plain variables. */
#ifndef SFR_STANDIN_XC_H
#define SFR_STANDIN_XC_H

/*
 * This header replaces XC16's <xc.h> when the hal/dspic33f sources are compiled on
 * the PC (gcc, for the tests) or with avr-gcc (check-16bit, compile only).
 * It declares the register names exactly as XC16 spells them, so the HAL
 * compiles unchanged:
 *
 *   - every register is one variable (sfr_<NAME>), a union of its 16-bit
 *     word and its bit-field struct, and the XC16 names are macros onto the
 *     two views: `P1TCON` is the word, `P1TCONbits.PTEN` a field of the same
 *     storage, as on the chip where both names sit at one address;
 *   - bit-fields are uint16_t, allocated from bit 0 upwards (gcc, avr-gcc and
 *     XC16 all do so on these little-endian targets), so `PWM1CON1 == 0x0077`
 *     and the field view agree bit for bit;
 *   - bit positions are those of docs/hardware.md sections 1.4/1.7 (the
 *     dsPIC33FJ128MC804 header, same family) where it gives them; the others
 *     are marked [MEM] beside the field and only matter to the tests that
 *     read the word instead of the field;
 *   - the XC16 built-ins the HAL uses (__builtin_write_OSCCONH/L) are
 *     functions here that record their calls and emulate the clock switch
 *     (COSC follows NOSC, LOCK sets) so the HAL's wait loops end.
 *
 * The stand-in's storage and helpers are in sfr_standin.c, linked only into
 * the HAL tests; check-16bit compiles against this header and links nothing.
 * __XC16__ is never defined here, which is how the HAL's few XC16-only lines
 * (interrupt attributes, configuration pragmas) stay out of the host build.
 */

#include <stdint.h>

#define SFR_STANDIN 1

/* Declares the union type, its storage and the two XC16 names of one register. */
#define SFR_DECLARE(name, bitstype)                                                                \
    typedef union {                                                                                \
        uint16_t w;                                                                                \
        bitstype bits;                                                                             \
    } sfr_##name##_t;                                                                              \
    extern volatile sfr_##name##_t sfr_##name

/* A register whose fields the HAL never names: word view only. */
typedef struct {
    uint16_t b : 16;
} SFR_PLAINBITS;

/* ---- CPU ----------------------------------------------------------------- */

typedef struct {
    uint16_t C : 1;
    uint16_t Z : 1;
    uint16_t OV : 1;
    uint16_t N : 1;
    uint16_t RA : 1;
    uint16_t IPL : 3; /* CPU interrupt priority level, bits 5-7 [MEM] */
    uint16_t DC : 1;
    uint16_t : 7;
} SRBITS;
SFR_DECLARE(SR, SRBITS);
#define SR     sfr_SR.w
#define SRbits sfr_SR.bits

/* The device header's IPL macros: on the chip SET_CPU_IPL writes SR.IPL
 * inside a DISI window; here they write it and count their uses
 * (sfr_standin.h), so a test can see the HAL goes through them. */
extern unsigned sfr_ipl_macro_uses;
#define SET_CPU_IPL(ipl)                                                                           \
    do {                                                                                           \
        sfr_ipl_macro_uses++;                                                                      \
        SRbits.IPL = (uint16_t)((ipl)&7u);                                                         \
    } while (0)
#define SET_AND_SAVE_CPU_IPL(save_to, ipl)                                                         \
    do {                                                                                           \
        (save_to) = SRbits.IPL;                                                                    \
        SET_CPU_IPL(ipl);                                                                          \
    } while (0)
#define RESTORE_CPU_IPL(saved_to) SET_CPU_IPL(saved_to)

typedef struct { /* docs/hardware.md 4.6 */
    uint16_t IF : 1;
    uint16_t RND : 1;
    uint16_t PSV : 1;
    uint16_t IPL3 : 1;
    uint16_t ACCSAT : 1;
    uint16_t SATDW : 1;
    uint16_t SATB : 1;
    uint16_t SATA : 1;
    uint16_t DL : 3;
    uint16_t EDT : 1;
    uint16_t US : 1;
    uint16_t : 3;
} CORCONBITS;
SFR_DECLARE(CORCON, CORCONBITS);
#define CORCON     sfr_CORCON.w
#define CORCONbits sfr_CORCON.bits

/* ---- oscillator ------------------------------------------------------------ */

typedef struct { /* positions [MEM] (dsPIC33F FRM section 7) */
    uint16_t OSWEN : 1;
    uint16_t LPOSCEN : 1;
    uint16_t : 1;
    uint16_t CF : 1;
    uint16_t : 1;
    uint16_t LOCK : 1;
    uint16_t IOLOCK : 1;
    uint16_t CLKLOCK : 1;
    uint16_t NOSC : 3;
    uint16_t : 1;
    uint16_t COSC : 3;
    uint16_t : 1;
} OSCCONBITS;
SFR_DECLARE(OSCCON, OSCCONBITS);
#define OSCCON     sfr_OSCCON.w
#define OSCCONbits sfr_OSCCON.bits

typedef struct { /* positions [MEM] */
    uint16_t PLLPRE : 5;
    uint16_t : 1;
    uint16_t PLLPOST : 2;
    uint16_t FRCDIV : 3;
    uint16_t DOZEN : 1;
    uint16_t DOZE : 3;
    uint16_t ROI : 1;
} CLKDIVBITS;
SFR_DECLARE(CLKDIV, CLKDIVBITS);
#define CLKDIV     sfr_CLKDIV.w
#define CLKDIVbits sfr_CLKDIV.bits

typedef struct {
    uint16_t PLLDIV : 9;
    uint16_t : 7;
} PLLFBDBITS;
SFR_DECLARE(PLLFBD, PLLFBDBITS);
#define PLLFBD     sfr_PLLFBD.w
#define PLLFBDbits sfr_PLLFBD.bits

/* The unlock-and-write built-ins: recorded and emulated by sfr_standin.c. */
void __builtin_write_OSCCONH(uint8_t value);
void __builtin_write_OSCCONL(uint8_t value);
#define Nop() ((void)0)

/* ---- interrupts ------------------------------------------------------------ */

typedef struct { /* IFS0/IEC0: docs/hardware.md 1.7 (AD1 bit 13); the rest [MEM] */
    uint16_t INT0IF : 1;
    uint16_t IC1IF : 1;
    uint16_t OC1IF : 1;
    uint16_t T1IF : 1;
    uint16_t : 1;
    uint16_t IC2IF : 1;
    uint16_t OC2IF : 1;
    uint16_t T2IF : 1;
    uint16_t T3IF : 1;
    uint16_t SPI1EIF : 1;
    uint16_t SPI1IF : 1;
    uint16_t U1RXIF : 1;
    uint16_t U1TXIF : 1;
    uint16_t AD1IF : 1;
    uint16_t : 2;
} IFS0BITS;
SFR_DECLARE(IFS0, IFS0BITS);
#define IFS0     sfr_IFS0.w
#define IFS0bits sfr_IFS0.bits

typedef struct {
    uint16_t INT0IE : 1;
    uint16_t IC1IE : 1;
    uint16_t OC1IE : 1;
    uint16_t T1IE : 1;
    uint16_t : 1;
    uint16_t IC2IE : 1;
    uint16_t OC2IE : 1;
    uint16_t T2IE : 1;
    uint16_t T3IE : 1;
    uint16_t SPI1EIE : 1;
    uint16_t SPI1IE : 1;
    uint16_t U1RXIE : 1;
    uint16_t U1TXIE : 1;
    uint16_t AD1IE : 1;
    uint16_t : 2;
} IEC0BITS;
SFR_DECLARE(IEC0, IEC0BITS);
#define IEC0     sfr_IEC0.w
#define IEC0bits sfr_IEC0.bits

typedef struct { /* IFS3: PWM1IF bit 9, FLTA1IF bit 15 (docs/hardware.md 1.4) */
    uint16_t : 9;
    uint16_t PWM1IF : 1;
    uint16_t : 5;
    uint16_t FLTA1IF : 1;
} IFS3BITS;
SFR_DECLARE(IFS3, IFS3BITS);
#define IFS3     sfr_IFS3.w
#define IFS3bits sfr_IFS3.bits

typedef struct {
    uint16_t : 9;
    uint16_t PWM1IE : 1;
    uint16_t : 5;
    uint16_t FLTA1IE : 1;
} IEC3BITS;
SFR_DECLARE(IEC3, IEC3BITS);
#define IEC3     sfr_IEC3.w
#define IEC3bits sfr_IEC3.bits

typedef struct { /* IPC1: T2IP at bits 12-14 [MEM] */
    uint16_t : 12;
    uint16_t T2IP : 3;
    uint16_t : 1;
} IPC1BITS;
SFR_DECLARE(IPC1, IPC1BITS);
#define IPC1     sfr_IPC1.w
#define IPC1bits sfr_IPC1.bits

typedef struct { /* IPC2: U1RXIP at bits 12-14 [MEM] */
    uint16_t : 12;
    uint16_t U1RXIP : 3;
    uint16_t : 1;
} IPC2BITS;
SFR_DECLARE(IPC2, IPC2BITS);
#define IPC2     sfr_IPC2.w
#define IPC2bits sfr_IPC2.bits

typedef struct { /* IPC3: AD1IP at bits 4-6 [MEM] */
    uint16_t : 4;
    uint16_t AD1IP : 3;
    uint16_t : 9;
} IPC3BITS;
SFR_DECLARE(IPC3, IPC3BITS);
#define IPC3     sfr_IPC3.w
#define IPC3bits sfr_IPC3.bits

/* ---- MCPWM1 (docs/hardware.md 1.4) ----------------------------------------- */

typedef struct {
    uint16_t PTMOD : 2;
    uint16_t PTCKPS : 2;
    uint16_t PTOPS : 4;
    uint16_t : 5;
    uint16_t PTSIDL : 1;
    uint16_t : 1;
    uint16_t PTEN : 1;
} P1TCONBITS;
SFR_DECLARE(P1TCON, P1TCONBITS);
#define P1TCON     sfr_P1TCON.w
#define P1TCONbits sfr_P1TCON.bits

typedef struct {
    uint16_t PTMR : 15;
    uint16_t PTDIR : 1;
} P1TMRBITS;
SFR_DECLARE(P1TMR, P1TMRBITS);
#define P1TMR     sfr_P1TMR.w
#define P1TMRbits sfr_P1TMR.bits

typedef struct {
    uint16_t PTPER : 15;
    uint16_t : 1;
} P1TPERBITS;
SFR_DECLARE(P1TPER, P1TPERBITS);
#define P1TPER     sfr_P1TPER.w
#define P1TPERbits sfr_P1TPER.bits

typedef struct {
    uint16_t SEVTCMP : 15;
    uint16_t SEVTDIR : 1;
} P1SECMPBITS;
SFR_DECLARE(P1SECMP, P1SECMPBITS);
#define P1SECMP     sfr_P1SECMP.w
#define P1SECMPbits sfr_P1SECMP.bits

typedef struct {
    uint16_t PEN1L : 1;
    uint16_t PEN2L : 1;
    uint16_t PEN3L : 1;
    uint16_t : 1;
    uint16_t PEN1H : 1;
    uint16_t PEN2H : 1;
    uint16_t PEN3H : 1;
    uint16_t : 1;
    uint16_t PMOD1 : 1;
    uint16_t PMOD2 : 1;
    uint16_t PMOD3 : 1;
    uint16_t : 5;
} PWM1CON1BITS;
SFR_DECLARE(PWM1CON1, PWM1CON1BITS);
#define PWM1CON1     sfr_PWM1CON1.w
#define PWM1CON1bits sfr_PWM1CON1.bits

typedef struct {
    uint16_t UDIS : 1;
    uint16_t OSYNC : 1;
    uint16_t IUE : 1;
    uint16_t : 5;
    uint16_t SEVOPS : 4;
    uint16_t : 4;
} PWM1CON2BITS;
SFR_DECLARE(PWM1CON2, PWM1CON2BITS);
#define PWM1CON2     sfr_PWM1CON2.w
#define PWM1CON2bits sfr_PWM1CON2.bits

typedef struct {
    uint16_t DTA : 6;
    uint16_t DTAPS : 2;
    uint16_t DTB : 6;
    uint16_t DTBPS : 2;
} P1DTCON1BITS;
SFR_DECLARE(P1DTCON1, P1DTCON1BITS);
#define P1DTCON1     sfr_P1DTCON1.w
#define P1DTCON1bits sfr_P1DTCON1.bits

typedef struct {
    uint16_t DTS1I : 1;
    uint16_t DTS1A : 1;
    uint16_t DTS2I : 1;
    uint16_t DTS2A : 1;
    uint16_t DTS3I : 1;
    uint16_t DTS3A : 1;
    uint16_t : 10;
} P1DTCON2BITS;
SFR_DECLARE(P1DTCON2, P1DTCON2BITS);
#define P1DTCON2     sfr_P1DTCON2.w
#define P1DTCON2bits sfr_P1DTCON2.bits

typedef struct {
    uint16_t FAEN1 : 1;
    uint16_t FAEN2 : 1;
    uint16_t FAEN3 : 1;
    uint16_t : 4;
    uint16_t FLTAM : 1;
    uint16_t FAOV1L : 1;
    uint16_t FAOV1H : 1;
    uint16_t FAOV2L : 1;
    uint16_t FAOV2H : 1;
    uint16_t FAOV3L : 1;
    uint16_t FAOV3H : 1;
    uint16_t : 2;
} P1FLTACONBITS;
SFR_DECLARE(P1FLTACON, P1FLTACONBITS);
#define P1FLTACON     sfr_P1FLTACON.w
#define P1FLTACONbits sfr_P1FLTACON.bits

typedef struct {
    uint16_t POUT1L : 1;
    uint16_t POUT1H : 1;
    uint16_t POUT2L : 1;
    uint16_t POUT2H : 1;
    uint16_t POUT3L : 1;
    uint16_t POUT3H : 1;
    uint16_t : 2;
    uint16_t POVD1L : 1;
    uint16_t POVD1H : 1;
    uint16_t POVD2L : 1;
    uint16_t POVD2H : 1;
    uint16_t POVD3L : 1;
    uint16_t POVD3H : 1;
    uint16_t : 2;
} P1OVDCONBITS;
SFR_DECLARE(P1OVDCON, P1OVDCONBITS);
#define P1OVDCON     sfr_P1OVDCON.w
#define P1OVDCONbits sfr_P1OVDCON.bits

SFR_DECLARE(P1DC1, SFR_PLAINBITS);
SFR_DECLARE(P1DC2, SFR_PLAINBITS);
SFR_DECLARE(P1DC3, SFR_PLAINBITS);
/* The duty registers go through an accessor that notes PWM1CON2.UDIS at
 * each access (sfr_standin.h), so a test can see that the three writes
 * happen with the update disabled. */
volatile uint16_t *sfr_pdc_access(volatile uint16_t *reg);
#define P1DC1 (*sfr_pdc_access(&sfr_P1DC1.w))
#define P1DC2 (*sfr_pdc_access(&sfr_P1DC2.w))
#define P1DC3 (*sfr_pdc_access(&sfr_P1DC3.w))

/* ---- ADC1 (docs/hardware.md 1.7; positions [MEM] except where it gives them) */

typedef struct {
    uint16_t DONE : 1;
    uint16_t SAMP : 1;
    uint16_t ASAM : 1;
    uint16_t SIMSAM : 1;
    uint16_t : 1;
    uint16_t SSRC : 3;
    uint16_t FORM : 2;
    uint16_t AD12B : 1;
    uint16_t : 2;
    uint16_t ADSIDL : 1;
    uint16_t : 1;
    uint16_t ADON : 1;
} AD1CON1BITS;
SFR_DECLARE(AD1CON1, AD1CON1BITS);
#define AD1CON1     sfr_AD1CON1.w
#define AD1CON1bits sfr_AD1CON1.bits

typedef struct {
    uint16_t ALTS : 1;
    uint16_t BUFM : 1;
    uint16_t SMPI : 4;
    uint16_t : 1;
    uint16_t BUFS : 1;
    uint16_t CHPS : 2;
    uint16_t CSCNA : 1;
    uint16_t : 2;
    uint16_t VCFG : 3;
} AD1CON2BITS;
SFR_DECLARE(AD1CON2, AD1CON2BITS);
#define AD1CON2     sfr_AD1CON2.w
#define AD1CON2bits sfr_AD1CON2.bits

typedef struct {
    uint16_t ADCS : 8;
    uint16_t SAMC : 5;
    uint16_t : 2;
    uint16_t ADRC : 1;
} AD1CON3BITS;
SFR_DECLARE(AD1CON3, AD1CON3BITS);
#define AD1CON3     sfr_AD1CON3.w
#define AD1CON3bits sfr_AD1CON3.bits

typedef struct {
    uint16_t CH123SA : 1;
    uint16_t CH123NA : 2;
    uint16_t : 5;
    uint16_t CH123SB : 1;
    uint16_t CH123NB : 2;
    uint16_t : 5;
} AD1CHS123BITS;
SFR_DECLARE(AD1CHS123, AD1CHS123BITS);
#define AD1CHS123     sfr_AD1CHS123.w
#define AD1CHS123bits sfr_AD1CHS123.bits

typedef struct {
    uint16_t CH0SA : 5;
    uint16_t : 2;
    uint16_t CH0NA : 1;
    uint16_t CH0SB : 5;
    uint16_t : 2;
    uint16_t CH0NB : 1;
} AD1CHS0BITS;
SFR_DECLARE(AD1CHS0, AD1CHS0BITS);
#define AD1CHS0     sfr_AD1CHS0.w
#define AD1CHS0bits sfr_AD1CHS0.bits

SFR_DECLARE(AD1PCFGL, SFR_PLAINBITS); /* bit n = 1: ANn digital, 0: analog */
SFR_DECLARE(AD1CSSL, SFR_PLAINBITS);
#define AD1PCFGL sfr_AD1PCFGL.w
#define AD1CSSL  sfr_AD1CSSL.w

SFR_DECLARE(ADC1BUF0, SFR_PLAINBITS);
SFR_DECLARE(ADC1BUF1, SFR_PLAINBITS);
SFR_DECLARE(ADC1BUF2, SFR_PLAINBITS);
SFR_DECLARE(ADC1BUF3, SFR_PLAINBITS);
#define ADC1BUF0 sfr_ADC1BUF0.w
#define ADC1BUF1 sfr_ADC1BUF1.w
#define ADC1BUF2 sfr_ADC1BUF2.w
#define ADC1BUF3 sfr_ADC1BUF3.w

/* ---- ports and peripheral pin select --------------------------------------- */

SFR_DECLARE(TRISA, SFR_PLAINBITS);
SFR_DECLARE(TRISB, SFR_PLAINBITS);
SFR_DECLARE(TRISC, SFR_PLAINBITS);
SFR_DECLARE(PORTA, SFR_PLAINBITS);
SFR_DECLARE(PORTB, SFR_PLAINBITS);
SFR_DECLARE(PORTC, SFR_PLAINBITS);
SFR_DECLARE(LATA, SFR_PLAINBITS);
SFR_DECLARE(LATB, SFR_PLAINBITS);
SFR_DECLARE(LATC, SFR_PLAINBITS);
#define TRISA sfr_TRISA.w
#define TRISB sfr_TRISB.w
#define TRISC sfr_TRISC.w
#define PORTA sfr_PORTA.w
#define PORTB sfr_PORTB.w
#define PORTC sfr_PORTC.w
#define LATA  sfr_LATA.w
#define LATB  sfr_LATB.w
#define LATC  sfr_LATC.w

typedef struct { /* RPINR12: FLTA1R<4:0> (docs/hardware.md 1.4 / SINBLDC-204) */
    uint16_t FLTA1R : 5;
    uint16_t : 11;
} RPINR12BITS;
SFR_DECLARE(RPINR12, RPINR12BITS);
#define RPINR12     sfr_RPINR12.w
#define RPINR12bits sfr_RPINR12.bits

typedef struct { /* RPINR18: U1RXR<4:0>, U1CTSR<12:8> [MEM] */
    uint16_t U1RXR : 5;
    uint16_t : 3;
    uint16_t U1CTSR : 5;
    uint16_t : 3;
} RPINR18BITS;
SFR_DECLARE(RPINR18, RPINR18BITS);
#define RPINR18     sfr_RPINR18.w
#define RPINR18bits sfr_RPINR18.bits

/* RPORn holds the output function of RP(2n) in bits 0-4 and RP(2n+1) in
 * bits 8-12 [MEM]. The 32MC204 has RP0..RP25, so RPOR0..RPOR12. The HAL
 * writes them through a pointer table, so only the words are declared. */
SFR_DECLARE(RPOR0, SFR_PLAINBITS);
SFR_DECLARE(RPOR1, SFR_PLAINBITS);
SFR_DECLARE(RPOR2, SFR_PLAINBITS);
SFR_DECLARE(RPOR3, SFR_PLAINBITS);
SFR_DECLARE(RPOR4, SFR_PLAINBITS);
SFR_DECLARE(RPOR5, SFR_PLAINBITS);
SFR_DECLARE(RPOR6, SFR_PLAINBITS);
SFR_DECLARE(RPOR7, SFR_PLAINBITS);
SFR_DECLARE(RPOR8, SFR_PLAINBITS);
SFR_DECLARE(RPOR9, SFR_PLAINBITS);
SFR_DECLARE(RPOR10, SFR_PLAINBITS);
SFR_DECLARE(RPOR11, SFR_PLAINBITS);
SFR_DECLARE(RPOR12, SFR_PLAINBITS);
#define RPOR0  sfr_RPOR0.w
#define RPOR1  sfr_RPOR1.w
#define RPOR2  sfr_RPOR2.w
#define RPOR3  sfr_RPOR3.w
#define RPOR4  sfr_RPOR4.w
#define RPOR5  sfr_RPOR5.w
#define RPOR6  sfr_RPOR6.w
#define RPOR7  sfr_RPOR7.w
#define RPOR8  sfr_RPOR8.w
#define RPOR9  sfr_RPOR9.w
#define RPOR10 sfr_RPOR10.w
#define RPOR11 sfr_RPOR11.w
#define RPOR12 sfr_RPOR12.w

/* ---- UART1 (positions [MEM], dsPIC33F FRM section 17) --------------------- */

typedef struct {
    uint16_t STSEL : 1;
    uint16_t PDSEL : 2;
    uint16_t BRGH : 1;
    uint16_t URXINV : 1;
    uint16_t ABAUD : 1;
    uint16_t LPBACK : 1;
    uint16_t WAKE : 1;
    uint16_t UEN : 2;
    uint16_t : 1;
    uint16_t RTSMD : 1;
    uint16_t IREN : 1;
    uint16_t USIDL : 1;
    uint16_t : 1;
    uint16_t UARTEN : 1;
} U1MODEBITS;
SFR_DECLARE(U1MODE, U1MODEBITS);
#define U1MODE     sfr_U1MODE.w
#define U1MODEbits sfr_U1MODE.bits

typedef struct {
    uint16_t URXDA : 1;
    uint16_t OERR : 1;
    uint16_t FERR : 1;
    uint16_t PERR : 1;
    uint16_t RIDLE : 1;
    uint16_t ADDEN : 1;
    uint16_t URXISEL : 2;
    uint16_t TRMT : 1;
    uint16_t UTXBF : 1;
    uint16_t UTXEN : 1;
    uint16_t UTXBRK : 1;
    uint16_t : 1;
    uint16_t UTXISEL0 : 1;
    uint16_t UTXINV : 1;
    uint16_t UTXISEL1 : 1;
} U1STABITS;
SFR_DECLARE(U1STA, U1STABITS);
#define U1STA     sfr_U1STA.w
#define U1STAbits sfr_U1STA.bits

SFR_DECLARE(U1BRG, SFR_PLAINBITS);
SFR_DECLARE(U1TXREG, SFR_PLAINBITS);
SFR_DECLARE(U1RXREG, SFR_PLAINBITS);
#define U1BRG   sfr_U1BRG.w
#define U1TXREG sfr_U1TXREG.w
#define U1RXREG sfr_U1RXREG.w

/* ---- Timer1 (positions [MEM]) ---------------------------------------------- */

typedef struct {
    uint16_t : 1;
    uint16_t TCS : 1;
    uint16_t TSYNC : 1;
    uint16_t : 1;
    uint16_t TCKPS : 2;
    uint16_t TGATE : 1;
    uint16_t : 6;
    uint16_t TSIDL : 1;
    uint16_t : 1;
    uint16_t TON : 1;
} T1CONBITS;
SFR_DECLARE(T1CON, T1CONBITS);
#define T1CON     sfr_T1CON.w
#define T1CONbits sfr_T1CON.bits

SFR_DECLARE(TMR1, SFR_PLAINBITS);
SFR_DECLARE(PR1, SFR_PLAINBITS);
#define TMR1 sfr_TMR1.w
#define PR1  sfr_PR1.w

#endif /* SFR_STANDIN_XC_H */
