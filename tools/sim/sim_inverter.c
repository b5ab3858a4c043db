/* sim_inverter.c - averaged inverter: duty to pin voltage, dead time, bus ripple. */
#include "sim_inverter.h"

#include <math.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

void sim_inverter_init(sim_inverter_t *inv, const sim_inverter_params_t *prm, double l_h)
{
    inv->prm = *prm;
    inv->i_band_a = prm->i_band_a;
    if (inv->i_band_a <= 0.0) {
        inv->i_band_a = prm->vbus_v / (12.0 * l_h * prm->pwm_hz);
        if (inv->i_band_a < 1e-3) {
            inv->i_band_a = 1e-3;
        }
    }
    inv->duty[0] = 0;
    inv->duty[1] = 0;
    inv->duty[2] = 0;
    inv->on = false;
}

void sim_inverter_latch(sim_inverter_t *inv, const uint16_t duty[3], bool on)
{
    inv->duty[0] = duty[0];
    inv->duty[1] = duty[1];
    inv->duty[2] = duty[2];
    inv->on = on;
}

double sim_inverter_vbus(const sim_inverter_t *inv, double t_s)
{
    double v = inv->prm.vbus_v;
    if (inv->prm.ripple_v != 0.0) {
        v += inv->prm.ripple_v * sin(2.0 * M_PI * inv->prm.ripple_hz * t_s);
    }
    return (v > 0.0) ? v : 0.0;
}

void sim_inverter_pins(const sim_inverter_t *inv, double vbus, const double i_abc[3],
                       double v_pin[3])
{
    double td_frac = inv->prm.deadtime_s * inv->prm.pwm_hz;
    int k;
    for (k = 0; k < 3; k++) {
        double d = (double)inv->duty[k] / inv->prm.duty_max;
        if (d <= 0.0) {
            v_pin[k] = 0.0;
        } else if (d >= 1.0) {
            v_pin[k] = vbus;
        } else {
            double s = i_abc[k] / inv->i_band_a;
            if (s > 1.0) {
                s = 1.0;
            } else if (s < -1.0) {
                s = -1.0;
            }
            /* Current out of the pin (s > 0): the low-side diode carries it
             * during the dead time, so the pin loses Td/Ts of Vbus. */
            d -= td_frac * s;
            if (d < 0.0) {
                d = 0.0;
            } else if (d > 1.0) {
                d = 1.0;
            }
            v_pin[k] = d * vbus;
        }
    }
}

void sim_pins_to_ab(const double v_pin[3], double *v_alpha, double *v_beta)
{
    double vn = (v_pin[0] + v_pin[1] + v_pin[2]) / 3.0;
    *v_alpha = v_pin[0] - vn;
    *v_beta = (v_pin[1] - v_pin[2]) / sqrt(3.0);
}

/*
 * Notes
 * 1. The band: a phase current smaller than the PWM ripple around it reverses
 *    inside each period, so the dead-time interval is spent partly on either
 *    diode and the mean error is proportional to the mean current. The peak
 *    ripple of one phase is about Vbus Ts / (8 L) at 50 % duty; a band of
 *    Vbus / (12 L fpwm) is about two thirds of it (space-vector modulation
 *    shares the ripple between phases). It also keeps the explicit treatment
 *    stable: the band acts as a resistance Td/Ts Vbus / i_band whose time
 *    constant is >= 2 sub-steps for any motor as long as N >= 1.
 */
