/* sim_inverter.h - averaged three-phase inverter with dead time and a DC bus with ripple. */
#ifndef SIM_INVERTER_H
#define SIM_INVERTER_H

#include <stdbool.h>
#include <stdint.h>

/*
 * Averaged model (no switching ripple): over one integration sub-step the pin
 * of phase k sits, on average, at
 *
 *   V_k = (d_k - Td/Ts * s(i_k)) * Vbus,  clamped to [0, Vbus]
 *
 * versus the negative rail, with d_k = duty[k] / duty_max. s(i) is the sign of
 * the phase current (+ = into the motor), made linear inside +-i_band: while the
 * current is smaller than the PWM current ripple it changes sign inside the
 * period and the dead-time error fades (note 1 in sim_inverter.c). A duty of
 * exactly 0 or duty_max has no switching edge, hence no dead time.
 * The star point floats: phase-to-neutral voltages are the pin voltages minus
 * their mean. With all switches off the pins are set by the free-wheeling
 * diodes (handled by sim_rig.c).
 */

typedef struct {
    double vbus_v;     /* DC bus level, V */
    double ripple_v;   /* peak of a sinusoidal bus ripple, V (0 = none) */
    double ripple_hz;  /* its frequency, Hz */
    double deadtime_s; /* Td, s (the boards: 2e-6) */
    double pwm_hz;     /* 1/Ts, Hz */
    double duty_max;   /* duty count of 100 % (PWM_DUTY_MAX) */
    double i_band_a;   /* dead-time linear band, A; <= 0: automatic, see sim_inverter_init */
} sim_inverter_params_t;

typedef struct {
    sim_inverter_params_t prm;
    double i_band_a;  /* band in use, A */
    uint16_t duty[3]; /* latched duties, applied during the present period */
    bool on;          /* latched output enable */
} sim_inverter_t;

/* Outputs off, duties 0. l_h: motor inductance used for the automatic band
 * Vbus / (12 L fpwm), about half the peak PWM current ripple. */
void sim_inverter_init(sim_inverter_t *inv, const sim_inverter_params_t *prm, double l_h);

/* Latches the duties and enable that apply from now on (next period). */
void sim_inverter_latch(sim_inverter_t *inv, const uint16_t duty[3], bool on);

/* Bus voltage at time t (s), V, never negative. */
double sim_inverter_vbus(const sim_inverter_t *inv, double t_s);

/* Pin voltages vs the negative rail (V) with the outputs on. */
void sim_inverter_pins(const sim_inverter_t *inv, double vbus, const double i_abc[3],
                       double v_pin[3]);

/* Phase-to-neutral alpha-beta voltage of three pin voltages (floating star). */
void sim_pins_to_ab(const double v_pin[3], double *v_alpha, double *v_beta);

#endif /* SIM_INVERTER_H */
