/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_hal_dspic33f.c - what hal/dspic33f writes to the registers, against the datasheet facts. */
#include "test_support.h"

#include <math.h>
#include <stdio.h>

#include "sfr_standin.h"

#include "hal_dspic33f.h"

/*
 * Built twice (test/hal/CMakeLists.txt): with the MCLV defaults, and as
 * test_hal_dspic33f_pins with HAL_BOARD_I_SIGN = +1 (the reading as is) and the
 * optional LED and UART pins assigned, so both branches of each are run.
 * Facts quoted from docs/hardware.md (section numbers).
 */

#define FCY_HZ 40000000.0 /* 40 MIPS, docs/hardware.md 1.1 */

static int setup(void **state)
{
    (void)state;
    sfr_standin_reset();
    hal_init();
    return 0;
}

/* ---- clock ------------------------------------------------------------------ */

static void test_hal_init_should_program_the_pll_for_40_mips_from_the_8mhz_crystal(void **state)
{
    (void)state;
    unsigned m = PLLFBD + 2u;
    unsigned n1 = CLKDIVbits.PLLPRE + 2u;
    unsigned n2 = 2u * (CLKDIVbits.PLLPOST + 1u);
    double fosc = 8e6 * m / (n1 * n2);
    double vco = 8e6 / n1 * m;

    assert_int_equal(PLLFBD, 38);
    assert_int_equal(CLKDIVbits.PLLPRE, 0);
    assert_int_equal(CLKDIVbits.PLLPOST, 0);
    printf("measured: Fosc = %.0f Hz, Fcy = %.0f Hz, VCO = %.0f Hz\n", fosc, fosc / 2, vco);
    assert_cmp(fosc / 2.0, ==, FCY_HZ);
    assert_cmp(vco, >=, 100e6);
    assert_cmp(vco, <=, 200e6);
}

static void test_hal_init_should_switch_to_primary_pll_after_setting_the_dividers(void **state)
{
    (void)state;
    unsigned i;
    int h_at = -1, l_at = -1;

    for (i = 0; i < sfr_osccon_log_n && i < SFR_OSCCON_LOG_MAX; i++) {
        if (h_at < 0 && sfr_osccon_log[i].which == 'H') {
            h_at = (int)i;
        }
        if (l_at < 0 && sfr_osccon_log[i].which == 'L' && (sfr_osccon_log[i].value & 1u)) {
            l_at = (int)i;
        }
    }
    assert_cmp(h_at, >=, 0);
    assert_cmp(l_at, >, h_at);
    assert_int_equal(sfr_osccon_log[h_at].value, 3); /* NOSC = primary + PLL */
    /* The dividers were in place before the switch was requested. */
    assert_int_equal(sfr_osccon_log[l_at].pllfbd, 38);
    assert_int_equal(sfr_osccon_log[l_at].clkdiv & 0x00DFu, 0);
    assert_int_equal(OSCCONbits.COSC, 3);
    assert_int_equal(OSCCONbits.LOCK, 1);
}

static void test_hal_init_should_set_corcon_once_for_saturating_signed_fractional_dsp(void **state)
{
    (void)state;
    assert_int_equal(CORCONbits.IF, 0);
    assert_int_equal(CORCONbits.US, 0);
    assert_int_equal(CORCONbits.SATA, 1);
    assert_int_equal(CORCONbits.SATB, 0);
    assert_int_equal(CORCONbits.ACCSAT, 0);
    assert_int_equal(CORCONbits.SATDW, 1);
    assert_int_equal(CORCONbits.RND, 1);
    assert_int_equal(CORCONbits.PSV, 1); /* left as the C start-up set it */
    assert_int_equal(CORCON, 0x00A6);
}

/* ---- MCPWM1 ------------------------------------------------------------------ */

static void test_hal_init_should_run_mcpwm1_center_aligned_at_20khz(void **state)
{
    (void)state;
    double period_s = 2.0 * (P1TPER + 1.0) / FCY_HZ; /* up/down: docs/hardware.md 1.5 */

    assert_int_equal(P1TCON, 0x8002); /* PTEN, PTMOD = 10, 1:1 (docs/hardware.md 1.6) */
    assert_int_equal(P1TCONbits.PTMOD, 2);
    assert_int_equal(P1TCONbits.PTCKPS, 0);
    assert_int_equal(P1TPER, 999);
    printf("measured: PWM frequency %.3f Hz (PTPER = %u)\n", 1.0 / period_s, (unsigned)P1TPER);
    assert_cmp(fabs(1.0 / period_s - 20000.0), <, 1e-6);
}

static void test_duty_scaling_should_put_100_percent_at_pwm_duty_max(void **state)
{
    (void)state;
    /* PDCx counts Tcy/2: 100 % = 2 (PTPER + 1) (docs/hardware.md 1.5). */
    assert_int_equal(PWM_DUTY_MAX, 2000);
    assert_int_equal(2u * (P1TPER + 1u), PWM_DUTY_MAX);
}

static void test_hal_init_should_enable_three_complementary_pairs(void **state)
{
    (void)state;
    assert_int_equal(PWM1CON1, 0x0077);
    assert_int_equal(PWM1CON1bits.PMOD1 | PWM1CON1bits.PMOD2 | PWM1CON1bits.PMOD3, 0);
}

static void test_hal_init_should_load_duties_at_the_period_boundary(void **state)
{
    (void)state;
    assert_int_equal(PWM1CON2, 0x0000);
    assert_int_equal(PWM1CON2bits.UDIS, 0);
    assert_int_equal(PWM1CON2bits.IUE, 0);
}

static void test_hal_init_should_set_2us_dead_time(void **state)
{
    (void)state;
    double dt = P1DTCON1bits.DTA * 2.0 / FCY_HZ; /* DTAPS = 01: 2 Tcy per count */

    assert_int_equal(P1DTCON1, 0x0068); /* 0x40 | 40 (docs/hardware.md 1.5) */
    assert_int_equal(P1DTCON1bits.DTAPS, 1);
    assert_int_equal(P1DTCON2, 0x0000);
    printf("measured: dead time %.3f us\n", dt * 1e6);
    assert_cmp(fabs(dt - 2e-6), <, 1e-12);
}

static void
test_hal_init_should_trigger_the_adc_80_tcy_after_the_midpoint_counting_down(void **state)
{
    (void)state;
    assert_int_equal(P1SECMPbits.SEVTDIR, 1);
    assert_int_equal(P1SECMPbits.SEVTCMP, 999 - 80);
    assert_int_equal(P1SECMP, 0x8397);
}

static void test_hal_init_should_latch_the_fault_with_all_outputs_inactive(void **state)
{
    (void)state;
    assert_int_equal(P1FLTACON, 0x0007); /* FAEN1..3, FLTAM = 0, FAOV = 0 (docs/hardware.md 5) */
    assert_int_equal(P1FLTACONbits.FLTAM, 0);
    assert_int_equal(P1FLTACON & 0x3F00u, 0);
    assert_int_equal(RPINR12bits.FLTA1R, 8); /* RP8, pin 44 */
    assert_int_not_equal(TRISB & (1u << 8), 0);
    assert_int_equal(IEC3bits.FLTA1IE, 0);
    assert_int_equal(IFS3bits.FLTA1IF, 0);
}

static void test_hal_init_should_unlock_pps_and_lock_it_again(void **state)
{
    (void)state;
    unsigned i;
    int unlock_at = -1, lock_at = -1;

    for (i = 0; i < sfr_osccon_log_n && i < SFR_OSCCON_LOG_MAX; i++) {
        if (sfr_osccon_log[i].which != 'L') {
            continue;
        }
        if (!(sfr_osccon_log[i].value & 0x40u) && unlock_at < 0) {
            unlock_at = (int)i;
        }
        if ((sfr_osccon_log[i].value & 0x40u) && unlock_at >= 0) {
            lock_at = (int)i;
        }
    }
    assert_cmp(unlock_at, >=, 0);
    assert_cmp(lock_at, >, unlock_at);
    assert_int_equal(OSCCONbits.IOLOCK, 1);
}

static void test_hal_init_should_keep_the_outputs_overridden_off(void **state)
{
    (void)state;
    assert_int_equal(P1OVDCON, 0x0000);
    assert_int_equal(P1TCONbits.PTEN, 1);
    assert_int_equal(IEC3bits.PWM1IE, 0); /* the ADC interrupt is the tick */
    assert_int_equal(P1DC1, PWM_DUTY_MAX / 2);
    assert_int_equal(P1DC2, PWM_DUTY_MAX / 2);
    assert_int_equal(P1DC3, PWM_DUTY_MAX / 2);
}

/* ---- ADC1 -------------------------------------------------------------------- */

static void
test_hal_init_should_convert_four_channels_simultaneously_on_the_pwm_trigger(void **state)
{
    (void)state;
    double tad = (AD1CON3bits.ADCS + 1.0) / FCY_HZ;

    assert_int_equal(AD1CON1bits.FORM, 3);
    assert_int_equal(AD1CON1bits.SSRC, 3);
    assert_int_equal(AD1CON1bits.SIMSAM, 1);
    assert_int_equal(AD1CON1bits.ASAM, 1);
    assert_int_equal(AD1CON1bits.AD12B, 0);
    assert_int_equal(AD1CON1bits.ADON, 1);
    assert_int_equal(AD1CON2bits.CHPS, 2);
    assert_int_equal(AD1CON2bits.SMPI, 0);
    assert_int_equal(AD1CON2bits.VCFG, 0);
    assert_int_equal(AD1CON2bits.CSCNA, 0);
    assert_int_equal(AD1CON2bits.ALTS, 0);
    assert_int_equal(AD1CON3bits.ADRC, 0);
    assert_int_equal(AD1CON3bits.ADCS, 3);
    assert_int_equal(AD1CSSL, 0);
    printf("measured: TAD = %.0f ns, 4 x 12 TAD = %.1f us\n", tad * 1e9, 48.0 * tad * 1e6);
    assert_cmp(tad, >=, 76e-9);
}

static void test_hal_init_should_select_pot_ia_ib_vbus_per_the_mclv_map(void **state)
{
    (void)state;
    assert_int_equal(AD1CHS0bits.CH0SA, 8);     /* CH0 = AN8 pot */
    assert_int_equal(AD1CHS0bits.CH0NA, 0);     /* against VREF- */
    assert_int_equal(AD1CHS123bits.CH123SA, 0); /* CH1..3 = AN0, AN1, AN2 */
    assert_int_equal(AD1CHS123bits.CH123NA, 0);
    assert_int_equal(AD1PCFGL & 0x0107u, 0); /* AN0, AN1, AN2, AN8 analog */
    assert_int_equal(AD1PCFGL | 0x0107u, 0xFFFF);
}

static void test_hal_init_should_leave_the_adc_interrupt_for_motor_start(void **state)
{
    (void)state;
    assert_int_equal(IEC0bits.AD1IE, 0);
    assert_int_equal(IFS0bits.AD1IF, 0);
    assert_int_equal(IPC3bits.AD1IP, 5);
    /* The slow step's software interrupt: below the ADC, above the main loop,
     * and Timer2 never started (only software raises T2IF). */
    assert_int_equal(IEC0bits.T2IE, 0);
    assert_int_equal(IFS0bits.T2IF, 0);
    assert_int_equal(IPC1bits.T2IP, 2);
    assert_cmp(IPC1bits.T2IP, <, IPC3bits.AD1IP);
    assert_cmp(IPC1bits.T2IP, >, 0);
}

/* Raw signed-fractional word of 10-bit code n (0..1023): (n - 512) << 6. */
static uint16_t raw_of_code(unsigned n)
{
    return (uint16_t)((n ^ 0x200u) << 6);
}

static void test_adc_read_should_scale_every_code_of_every_channel_exactly(void **state)
{
    (void)state;
    err_stats_t e_i, e_u;
    unsigned n;

    err_stats_init(&e_i);
    err_stats_init(&e_u);
    for (n = 0; n < 1024u; n++) {
        hal_adc_frame_t f;
        /* References in double: a current code reads (n - 512) / 512 of
         * BOARD_I_FULLSCALE_A, a unipolar one n / 1024 of its full scale. */
        double i_ref = HAL_BOARD_I_SIGN * (n - 512.0) / 512.0 * 32768.0;
        double u_ref = n / 1024.0 * 32768.0;
        if (i_ref > 32767.0) {
            i_ref = 32767.0; /* the one saturating code: -(-1.0) */
        }
        ADC1BUF0 = raw_of_code(n);
        ADC1BUF1 = raw_of_code(n);
        ADC1BUF2 = raw_of_code(1023u - n);
        ADC1BUF3 = raw_of_code(n);
        hal_adc_read(&f);
        err_stats_add(&e_u, f.pot - u_ref, n);
        err_stats_add(&e_u, f.vbus - u_ref, n);
        err_stats_add(&e_i, f.ia - i_ref, n);
        assert_int_equal(hal_pot_read(), f.pot);
        {
            double ib_ref = HAL_BOARD_I_SIGN * (511.0 - n) / 512.0 * 32768.0;
            err_stats_add(&e_i, f.ib - (ib_ref > 32767.0 ? 32767.0 : ib_ref), n);
        }
    }
    err_stats_print("adc ia/ib vs (code-512)/512 full scale", &e_i, "LSB");
    err_stats_print("adc vbus/pot vs code/1024 full scale", &e_u, "LSB");
    assert_cmp(e_i.max_abs, ==, 0.0);
    assert_cmp(e_u.max_abs, ==, 0.0);
}

static void test_adc_read_should_map_the_rails_to_the_core_range(void **state)
{
    (void)state;
    hal_adc_frame_t f;

    ADC1BUF0 = 0x8000u; /* 0 V */
    ADC1BUF1 = 0x8000u;
    ADC1BUF2 = 0x7FC0u; /* AVDD */
    ADC1BUF3 = 0x7FC0u;
    hal_adc_read(&f);
    assert_int_equal(f.pot, 0);
    assert_int_equal(f.vbus, 32736);
#if HAL_BOARD_I_SIGN > 0
    assert_int_equal(f.ia, -32768);
    assert_int_equal(f.ib, 32704);
#else
    assert_int_equal(f.ia, 32767);
    assert_int_equal(f.ib, -32704);
#endif
    ADC1BUF1 = 0x0000u; /* mid-scale: zero current (plus offset) */
    hal_adc_read(&f);
    assert_int_equal(f.ia, 0);
}

/* ---- PWM write ----------------------------------------------------------------- */

static void test_pwm_write_should_load_the_three_duties_and_give_the_pins_to_the_pwm(void **state)
{
    (void)state;
    hal_pwm_out_t out = {{100u, 1000u, 1900u}, true};

    /* The three writes with the period-boundary update disabled, enabled
     * again after them (docs/board.md, "Bring-up facts": UDIS). */
    sfr_pdc_log_on = 1u;
    hal_pwm_write(&out);
    sfr_pdc_log_on = 0u;
    assert_int_equal(sfr_pdc_accesses, 3);
    assert_int_equal(sfr_pdc_accesses_udis0, 0);
    assert_int_equal(PWM1CON2bits.UDIS, 0);
    assert_int_equal(P1DC1, 100);
    assert_int_equal(P1DC2, 1000);
    assert_int_equal(P1DC3, 1900);
    assert_int_equal(P1OVDCON, 0x3F00);
}

static void test_pwm_write_should_override_all_six_switches_off_when_outputs_are_off(void **state)
{
    (void)state;
    hal_pwm_out_t on = {{1000u, 1000u, 1000u}, true};
    hal_pwm_out_t off = {{1000u, 1000u, 1000u}, false};

    hal_pwm_write(&on);
    hal_pwm_write(&off);
    assert_int_equal(P1OVDCON, 0x0000); /* POVD = 0, POUT = 0 */
}

static void test_pwm_write_should_clamp_duties_above_pwm_duty_max(void **state)
{
    (void)state;
    hal_pwm_out_t out = {{PWM_DUTY_MAX, PWM_DUTY_MAX + 1u, 0xFFFFu}, true};

    hal_pwm_write(&out);
    assert_int_equal(P1DC1, PWM_DUTY_MAX);
    assert_int_equal(P1DC2, PWM_DUTY_MAX);
    assert_int_equal(P1DC3, PWM_DUTY_MAX);
    out.duty[0] = 0;
    hal_pwm_write(&out);
    assert_int_equal(P1DC1, 0);
}

/* ---- fault ---------------------------------------------------------------------- */

static void test_fault_latched_should_follow_the_flta1_flag(void **state)
{
    (void)state;
    assert_false(hal_fault_latched());
    IFS3bits.FLTA1IF = 1;
    assert_true(hal_fault_latched());
}

static void test_fault_clear_should_keep_the_latch_while_the_pin_is_asserted(void **state)
{
    (void)state;
    P1OVDCON = 0x3F00u;
    IFS3bits.FLTA1IF = 1;
    PORTB = (uint16_t)(PORTB & ~(1u << 8)); /* pin low = asserted */
    assert_false(hal_fault_clear());
    assert_true(hal_fault_latched());
    assert_int_equal(P1OVDCON, 0x0000);
}

static void test_fault_clear_should_release_the_latch_with_outputs_still_off(void **state)
{
    (void)state;
    P1OVDCON = 0x3F00u;
    IFS3bits.FLTA1IF = 1;
    PORTB = (uint16_t)(PORTB | (1u << 8));
    assert_true(hal_fault_clear());
    assert_false(hal_fault_latched());
    assert_int_equal(P1OVDCON, 0x0000);
}

/* ---- buttons, LEDs ---------------------------------------------------------------- */

static void test_buttons_should_read_s2_on_ra8_and_s3_on_rb4_active_low(void **state)
{
    (void)state;
    assert_int_not_equal(TRISA & (1u << 8), 0);
    assert_int_not_equal(TRISB & (1u << 4), 0);
    PORTA = 0xFFFFu;
    PORTB = 0xFFFFu;
    assert_false(hal_button_pressed(HAL_BUTTON_S2));
    assert_false(hal_button_pressed(HAL_BUTTON_S3));
    PORTA = (uint16_t) ~(1u << 8);
    assert_true(hal_button_pressed(HAL_BUTTON_S2));
    assert_false(hal_button_pressed(HAL_BUTTON_S3));
    PORTA = 0xFFFFu;
    PORTB = (uint16_t) ~(1u << 4);
    assert_false(hal_button_pressed(HAL_BUTTON_S2));
    assert_true(hal_button_pressed(HAL_BUTTON_S3));
}

#if HAL_LED_RUN_PORT == HAL_PORT_NONE
static void test_leds_should_drive_no_pin_while_their_pins_are_unknown(void **state)
{
    (void)state;
    hal_led_set(HAL_LED_RUN, true);
    hal_led_set(HAL_LED_FAULT, true);
    assert_int_equal(LATA | LATB | LATC, 0);
    assert_int_equal(TRISA & TRISB & TRISC, 0xFFFF);
}
#else
static void test_leds_should_drive_their_assigned_pins(void **state)
{
    (void)state;
    assert_int_equal(TRISB & (1u << 9), 0);
    assert_int_equal(TRISC & (1u << 3), 0);
#if HAL_TIMING_PIN_PORT == HAL_PORT_C
    /* the bench's timing pin: an output, low until the interrupt runs */
    assert_int_equal(TRISC & (1u << HAL_TIMING_PIN_BIT), 0);
    assert_int_equal(LATC & (1u << HAL_TIMING_PIN_BIT), 0);
#endif
    hal_led_set(HAL_LED_RUN, true);
    assert_int_equal(LATB, 1u << 9);
    hal_led_set(HAL_LED_FAULT, true);
    assert_int_equal(LATC, 1u << 3);
    hal_led_set(HAL_LED_RUN, false);
    assert_int_equal(LATB, 0);
    assert_int_equal(LATC, 1u << 3);
}
#endif

/* ---- UART ---------------------------------------------------------------------------- */

static void test_hal_init_should_run_uart1_at_115200_baud_8n1_receiving_by_interrupt(void **state)
{
    (void)state;
    double baud = FCY_HZ / (4.0 * (U1BRG + 1.0)); /* BRGH = 1 */

    assert_int_equal(U1BRG, 86);
    assert_int_equal(U1MODEbits.BRGH, 1);
    assert_int_equal(U1MODEbits.PDSEL, 0);
    assert_int_equal(U1MODEbits.STSEL, 0);
    assert_int_equal(U1MODEbits.UARTEN, 1);
    assert_int_equal(U1STAbits.UTXEN, 1);
    assert_int_equal(U1STAbits.URXISEL, 0); /* an interrupt for every byte */
    assert_int_equal(IPC2bits.U1RXIP, HAL_U1RX_IRQ_PRIORITY);
    assert_cmp(IPC2bits.U1RXIP, <, IPC3bits.AD1IP); /* the ADC interrupt pre-empts it */
#if HAL_UART_RX_RP != HAL_RP_NONE
    assert_int_equal(IEC0bits.U1RXIE, 1);
#endif
    printf("measured: UART %.1f Bd, error %+.3f %%\n", baud, (baud / 115200.0 - 1.0) * 100.0);
    assert_cmp(fabs(baud / 115200.0 - 1.0), <, 0.005);
}

#if HAL_UART_TX_RP != HAL_RP_NONE
static void test_hal_init_should_map_uart1_to_its_assigned_pins(void **state)
{
    (void)state;
    assert_int_equal(RPINR18bits.U1RXR, 19);
    assert_int_equal(RPOR10 & 0x1Fu, 3); /* RP20 = U1TX */
    assert_int_equal(RPOR10 & 0x1F00u, 0);
}
#else
static void test_hal_init_should_route_uart1_nowhere_while_its_pins_are_unknown(void **state)
{
    (void)state;
    assert_int_equal(RPINR18, 0);
    assert_int_equal(RPOR0 | RPOR1 | RPOR2 | RPOR3 | RPOR4 | RPOR5 | RPOR6 | RPOR7 | RPOR8 | RPOR9 |
                         RPOR10 | RPOR11 | RPOR12,
                     0);
}
#endif

static void test_uart_put_should_refuse_a_byte_when_the_transmitter_is_full(void **state)
{
    (void)state;
    U1STAbits.UTXBF = 1;
    assert_false(hal_uart_put('x'));
    assert_int_equal(U1TXREG, 0);
    U1STAbits.UTXBF = 0;
    assert_true(hal_uart_put('x'));
    assert_int_equal(U1TXREG, 'x');
}

static void test_uart_get_should_pass_the_bytes_the_receive_interrupt_rings(void **state)
{
    (void)state;
    uint8_t b = 0;
    unsigned i, got = 0;

    assert_false(hal_uart_get(&b));
    U1STAbits.OERR = 1;
    U1STAbits.URXDA = 1; /* the stand-in's FIFO never empties: each call takes 4 */
    U1RXREG = 0x1A5u;
    IFS0bits.U1RXIF = 1;
    _U1RXInterrupt();
    assert_int_equal(U1STAbits.OERR, 0);
    assert_int_equal(IFS0bits.U1RXIF, 0);
    for (i = 0; i < 4u; i++) {
        assert_true(hal_uart_get(&b));
        assert_int_equal(b, 0xA5);
    }
    assert_false(hal_uart_get(&b));
    /* a full ring keeps what it has and drops the rest */
    for (i = 0; i < HAL_UART_RX_RING; i++) {
        _U1RXInterrupt();
    }
    while (hal_uart_get(&b)) {
        got++;
    }
    assert_int_equal(got, HAL_UART_RX_RING - 1u);
    U1STAbits.URXDA = 0;
}

/* ---- tick, critical section ------------------------------------------------------------ */

static void test_tick_should_report_each_timer1_period_once(void **state)
{
    (void)state;
    double period = 8.0 * (PR1 + 1.0) / FCY_HZ; /* TCKPS = 01: Fcy / 8 */

    assert_int_equal(PR1, 4999);
    assert_int_equal(T1CONbits.TCKPS, 1);
    assert_int_equal(T1CONbits.TON, 1);
    assert_int_equal(T1CONbits.TCS, 0);
    assert_cmp(fabs(period - 1e-3), <, 1e-12);
    assert_false(hal_tick_1ms());
    IFS0bits.T1IF = 1;
    assert_true(hal_tick_1ms());
    assert_false(hal_tick_1ms());
}

static void test_critical_section_should_raise_ipl_to_7_and_restore_it_nested(void **state)
{
    (void)state;
    hal_irq_state_t outer, inner;

    SRbits.IPL = 2;
    outer = hal_critical_enter();
    assert_int_equal(SRbits.IPL, 7);
    inner = hal_critical_enter();
    assert_int_equal(SRbits.IPL, 7);
    hal_critical_exit(inner);
    assert_int_equal(SRbits.IPL, 7);
    hal_critical_exit(outer);
    assert_int_equal(SRbits.IPL, 2);
    assert_cmp(HAL_ADC_IRQ_PRIORITY, <=, 7u);
    /* through the device header's SET_AND_SAVE_CPU_IPL / RESTORE_CPU_IPL */
    assert_int_equal(sfr_ipl_macro_uses, 4);
}

int main(void)
{
    const struct CMUnitTest tests[] =
    { cmocka_unit_test_setup(test_hal_init_should_program_the_pll_for_40_mips_from_the_8mhz_crystal,
                             setup),
      cmocka_unit_test_setup(test_hal_init_should_switch_to_primary_pll_after_setting_the_dividers,
                             setup),
      cmocka_unit_test_setup(
          test_hal_init_should_set_corcon_once_for_saturating_signed_fractional_dsp, setup),
      cmocka_unit_test_setup(test_hal_init_should_run_mcpwm1_center_aligned_at_20khz, setup),
      cmocka_unit_test_setup(test_duty_scaling_should_put_100_percent_at_pwm_duty_max, setup),
      cmocka_unit_test_setup(test_hal_init_should_enable_three_complementary_pairs, setup),
      cmocka_unit_test_setup(test_hal_init_should_load_duties_at_the_period_boundary, setup),
      cmocka_unit_test_setup(test_hal_init_should_set_2us_dead_time, setup),
      cmocka_unit_test_setup(
          test_hal_init_should_trigger_the_adc_80_tcy_after_the_midpoint_counting_down, setup),
      cmocka_unit_test_setup(test_hal_init_should_latch_the_fault_with_all_outputs_inactive, setup),
      cmocka_unit_test_setup(test_hal_init_should_unlock_pps_and_lock_it_again, setup),
      cmocka_unit_test_setup(test_hal_init_should_keep_the_outputs_overridden_off, setup),
      cmocka_unit_test_setup(
          test_hal_init_should_convert_four_channels_simultaneously_on_the_pwm_trigger, setup),
      cmocka_unit_test_setup(test_hal_init_should_select_pot_ia_ib_vbus_per_the_mclv_map, setup),
      cmocka_unit_test_setup(test_hal_init_should_leave_the_adc_interrupt_for_motor_start, setup),
      cmocka_unit_test_setup(test_adc_read_should_scale_every_code_of_every_channel_exactly, setup),
      cmocka_unit_test_setup(test_adc_read_should_map_the_rails_to_the_core_range, setup),
      cmocka_unit_test_setup(
          test_pwm_write_should_load_the_three_duties_and_give_the_pins_to_the_pwm, setup),
      cmocka_unit_test_setup(
          test_pwm_write_should_override_all_six_switches_off_when_outputs_are_off, setup),
      cmocka_unit_test_setup(test_pwm_write_should_clamp_duties_above_pwm_duty_max, setup),
      cmocka_unit_test_setup(test_fault_latched_should_follow_the_flta1_flag, setup),
      cmocka_unit_test_setup(test_fault_clear_should_keep_the_latch_while_the_pin_is_asserted,
                             setup),
      cmocka_unit_test_setup(test_fault_clear_should_release_the_latch_with_outputs_still_off,
                             setup),
      cmocka_unit_test_setup(test_buttons_should_read_s2_on_ra8_and_s3_on_rb4_active_low, setup),
#if HAL_LED_RUN_PORT == HAL_PORT_NONE
      cmocka_unit_test_setup(test_leds_should_drive_no_pin_while_their_pins_are_unknown, setup),
#else
      cmocka_unit_test_setup(test_leds_should_drive_their_assigned_pins, setup),
#endif
      cmocka_unit_test_setup(
          test_hal_init_should_run_uart1_at_115200_baud_8n1_receiving_by_interrupt, setup),
#if HAL_UART_TX_RP != HAL_RP_NONE
      cmocka_unit_test_setup(test_hal_init_should_map_uart1_to_its_assigned_pins, setup),
#else
      cmocka_unit_test_setup(test_hal_init_should_route_uart1_nowhere_while_its_pins_are_unknown,
                             setup),
#endif
      cmocka_unit_test_setup(test_uart_put_should_refuse_a_byte_when_the_transmitter_is_full,
                             setup),
      cmocka_unit_test_setup(test_uart_get_should_pass_the_bytes_the_receive_interrupt_rings,
                             setup),
      cmocka_unit_test_setup(test_tick_should_report_each_timer1_period_once, setup),
      cmocka_unit_test_setup(test_critical_section_should_raise_ipl_to_7_and_restore_it_nested,
                             setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
