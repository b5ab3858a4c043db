/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* probe_main.c - prints what probe_values.c holds, as lines tools/tune reads (motortune/probe.py).
 */

/*
 * Never compiled with a profile: it includes the core's headers only for
 * the type of the observer's parameters (smc.h) and the list of names
 * (probe_facts.h). Every line is tab-separated:
 *   fact <name> <value>              a number (%.17g: read back exactly)
 *   text <name> <text>               a string, bytes outside ' '..'~' and
 *                                    the backslash as \xHH
 *   row  <name> <value> <unit> <integer or -> <decoded or -> <note>
 *                                    a line of tools/tune --check's table:
 *                                    the value, the integer the core holds
 *                                    and that integer back in the unit
 * The rows decode the core's integers with its own scales; nothing here
 * computes a constant the core uses.
 */

#include <stdio.h>

#include "probe_facts.h"
#ifndef TUNE_PROBE_BOARD
#include "smc.h"
#endif

#define TUNE_INDEX_(name, expr) F_##name,
#define TUNE_NAME_(name, expr)  #name,
#ifdef TUNE_PROBE_BOARD
enum { TUNE_PROBE_BOARD_FACTS(TUNE_INDEX_) F_COUNT_ };
static const char *const names[] = {TUNE_PROBE_BOARD_FACTS(TUNE_NAME_) ""};
#else
enum { TUNE_PROBE_PROFILE_FACTS(TUNE_INDEX_) F_COUNT_ };
static const char *const names[] = {TUNE_PROBE_PROFILE_FACTS(TUNE_NAME_) ""};
extern const smc_params_t tune_probe_smc;
extern const double tune_probe_fw_amps[];
extern const double tune_probe_fw_q15[];
extern const char tune_probe_motor_name[];
extern const char tune_probe_tune_board[];
#endif
extern const double tune_probe_facts[];
extern const unsigned tune_probe_nfacts;
extern const char tune_probe_board_name[];

static void text(const char *name, const char *s)
{
    printf("text\t%s\t", name);
    for (; *s != '\0'; s++) {
        unsigned char c = (unsigned char)*s;
        if (c < 0x20U || c > 0x7eU || c == '\\') {
            printf("\\x%02x", c);
        } else {
            putchar(c);
        }
    }
    putchar('\n');
}

#ifndef TUNE_PROBE_BOARD
#define V(name) tune_probe_facts[F_##name]
#define NO_Q    (-1.0e300)

/* One row of the table: q == NO_Q for a value the core holds no integer for. */
static void row(const char *name, double eng, const char *unit, double q, double decoded,
                const char *note)
{
    printf("row\t%s\t%.17g\t%s\t", name, eng, unit);
    if (q == NO_Q) {
        printf("-\t-\t%s\n", note);
    } else {
        printf("%.0f\t%.17g\t%s\n", q, decoded, note);
    }
}

static void plain(const char *name, double eng, const char *unit, const char *note)
{
    row(name, eng, unit, NO_Q, 0.0, note);
}

static double pow2(double shift)
{
    double p = 1.0;
    int k;
    for (k = 0; k < (int)shift; k++) {
        p *= 2.0;
    }
    return p;
}

static void table(void)
{
    const double q = 32768.0;
    const double i_fs = V(BOARD_I_FULLSCALE_A);
    const double v_fs = V(MC_VOLTAGE_FULLSCALE_V);
    const double fs = V(MC_SPEED_FULLSCALE_RPM);
    const double ts = V(MC_TS_S);
    const double fpwm = V(PWM_FREQUENCY_HZ);
    const double loop = V(MC_SPEED_LOOP_HZ);
    const double irp = V(IRP_PERCALC);
    const double pp = V(MOTOR_POLE_PAIRS);
    const double e_fs = V(SMC_EMF_FS_RATIO) * v_fs;
    const double turn32 = 4294967296.0;
    const smc_params_t *s = &tune_probe_smc;
    char note[96];
    int k;

    plain("PWM_DUTY_MAX", V(PWM_DUTY_MAX), "counts", "BOARD_FCY_HZ / PWM_FREQUENCY_HZ");
    plain("IRP_PERCALC", irp, "periods", "PWM periods per speed-loop run");
    plain("scale: current", i_fs, "A", "Q15 full scale (BOARD_I_FULLSCALE_A)");
    plain("scale: voltage", v_fs, "V", "Q15 full scale, BOARD_VBUS_NOMINAL_V / sqrt 3");
    plain("scale: speed", fs, "rpm", "Q15 full scale (MC_SPEED_FULLSCALE_RPM)");

    row("SPEED_REF_MIN_RPM", V(SPEED_REF_MIN_RPM), "rpm", V(MC_SPEED_REF_MIN_Q15),
        V(MC_SPEED_REF_MIN_Q15) / q * fs, "pot at 0");
    row("SPEED_REF_MAX_RPM", V(SPEED_REF_MAX_RPM), "rpm", V(MC_SPEED_REF_MAX_Q15),
        V(MC_SPEED_REF_MAX_Q15) / q * fs, "pot at full travel");
    row("MOTOR_SPEED_NOMINAL_RPM", V(MOTOR_SPEED_NOMINAL_RPM), "rpm", V(MC_SPEED_NOMINAL_Q15),
        V(MC_SPEED_NOMINAL_Q15) / q * fs, "field weakening starts above");
    row("MOTOR_SPEED_FW_MAX_RPM", V(MOTOR_SPEED_FW_MAX_RPM), "rpm", V(MC_SPEED_FW_MAX_Q15),
        V(MC_SPEED_FW_MAX_Q15) / q * fs, "top of the field-weakening table");
    row("MC_SPEED_RAMP_STEP", V(MC_SPEED_RAMP_RPM_PER_S), "rpm/s", V(MC_SPEED_RAMP_STEP),
        V(MC_SPEED_RAMP_STEP) / q * fs * loop, "speed-reference slew, counts per speed-loop run");

    row("MOTOR_CURRENT_MAX_A", V(MOTOR_CURRENT_MAX_A), "A", V(MC_IQ_MAX_Q15),
        V(MC_IQ_MAX_Q15) / q * i_fs, "|Iq| limit of the speed loop");
    row("MC_OVERCURRENT_A", V(MC_OVERCURRENT_A), "A", V(MC_OVERCURRENT_Q15),
        V(MC_OVERCURRENT_Q15) / q * i_fs, "software trip, any phase");
    row("MOTOR_LOCK_CURRENT_A", V(MOTOR_LOCK_CURRENT_A), "A", V(MC_LOCK_CURRENT_Q15),
        V(MC_LOCK_CURRENT_Q15) / q * i_fs, "Iq during the lock");
    row("MOTOR_RAMP_CURRENT_A", V(MOTOR_RAMP_CURRENT_A), "A", V(MC_RAMP_CURRENT_Q15),
        V(MC_RAMP_CURRENT_Q15) / q * i_fs, "Iq during the open-loop ramp");
    row("MOTOR_OL_DAMP_S", V(MOTOR_OL_DAMP_S), "s", V(MC_OL_DAMP_K),
        V(MC_OL_DAMP_K) / V(MC_OL_DAMP_COUNTS_PER_PERIOD) * ts,
        "open-loop damping, MC_OL_DAMP_K (Q4 periods)");
    row("MC_VOLTAGE_LIMIT_FRACTION", V(MC_VOLTAGE_LIMIT_FRACTION) * v_fs, "V", V(MC_VMAX_Q15),
        V(MC_VMAX_Q15) / q * v_fs, "largest |V|, phase peak");

    (void)snprintf(note, sizeof note, "MC_CUR_KP, shift %.0f", V(MC_CUR_KP_SHIFT));
    row("MOTOR_CURRENT_KP_V_PER_A", V(MOTOR_CURRENT_KP_V_PER_A), "V/A", V(MC_CUR_KP),
        V(MC_CUR_KP) * pow2(V(MC_CUR_KP_SHIFT)) / q * v_fs / i_fs, note);
    row("MOTOR_CURRENT_KI_V_PER_AS", V(MOTOR_CURRENT_KI_V_PER_AS), "V/(A s)", V(MC_CUR_KI),
        V(MC_CUR_KI) / q * v_fs / i_fs / ts, "MC_CUR_KI, per period");
    (void)snprintf(note, sizeof note, "MC_SPD_KP, shift %.0f", V(MC_SPD_KP_SHIFT));
    row("MOTOR_SPEED_KP_A_PER_RPM", V(MOTOR_SPEED_KP_A_PER_RPM), "A/rpm", V(MC_SPD_KP),
        V(MC_SPD_KP) * pow2(V(MC_SPD_KP_SHIFT)) / q * i_fs / fs, note);
    row("MOTOR_SPEED_KI_A_PER_RPM_S", V(MOTOR_SPEED_KI_A_PER_RPM_S), "A/(rpm s)", V(MC_SPD_KI),
        V(MC_SPD_KI) / q * i_fs / fs * loop, "MC_SPD_KI, per speed-loop run");
    row("MOTOR_SPEED_KP_FULL_RPM", V(MOTOR_SPEED_KP_FULL_RPM), "rpm", V(MC_SPEED_KP_FULL_Q15),
        V(MC_SPEED_KP_FULL_Q15) / q * fs, "speed-PI Kp full above, scaled down below");
    row("MC_SPEED_KP_MIN_FRACTION", V(MC_SPEED_KP_MIN_FRACTION), "", V(MC_SPEED_KP_MIN_Q15),
        V(MC_SPEED_KP_MIN_Q15) / q, "smallest scheduled Kp fraction");

    row("MOTOR_LOCK_TIME_S", V(MOTOR_LOCK_TIME_S), "s", V(MC_LOCK_PERIODS), V(MC_LOCK_PERIODS) * ts,
        "MC_LOCK_PERIODS (periods)");
    row("MOTOR_RAMP_TIME_S", V(MOTOR_RAMP_TIME_S), "s", V(MC_RAMP_PERIODS), V(MC_RAMP_PERIODS) * ts,
        "ramp periods");
    row("MOTOR_RAMP_END_RPM", V(MOTOR_RAMP_END_RPM), "rpm", V(MC_RAMP_STEP_END),
        V(MC_RAMP_STEP_END) * fpwm * 60.0 / (turn32 * pp), "MC_RAMP_STEP_END (32-bit angle step)");
    row("ramp acceleration", V(MOTOR_RAMP_END_RPM) / V(MOTOR_RAMP_TIME_S), "rpm/s",
        V(MC_RAMP_STEP_INC), V(MC_RAMP_STEP_INC) * fpwm * fpwm * 60.0 / (turn32 * pp),
        "MC_RAMP_STEP_INC per period");

    plain("F (AN1078 Eq. 2: 1 - Ts R/L)", 1.0 - ts * V(MOTOR_RS_OHM) / V(MOTOR_LS_H), "",
          "the Euler form of AN1078");
    row("smc F = exp(-Ts R/L)", V(SMC_F), "", s->f, s->f / q,
        "the core's exact discretisation (Pade 3,3)");
    plain("G (AN1078 Eq. 2: Ts/L)", ts / V(MOTOR_LS_H), "A/(V period)", "in amps per volt");
    plain("G = (1-F)/R * V_FS/I_FS", V(SMC_G), "I_FS/V_FS",
          "in the core's current and voltage scales");
    (void)snprintf(note, sizeof note, "g_shift %u", (unsigned)s->g_shift);
    row("smc G = (1-F)/R * 2V_FS/I_FS", V(SMC_GE), "I_FS/E_FS", s->g, s->g * pow2(s->g_shift) / q,
        note);
    row("MOTOR_SMC_GAIN_V", V(MOTOR_SMC_GAIN_V), "V", s->kslide, s->kslide / q * e_fs,
        "Kslide, Q15 of E_FS = 2 V_FS");
    row("MOTOR_SMC_LINEAR_BAND_A", V(MOTOR_SMC_LINEAR_BAND_A), "A", s->max_err,
        s->max_err / q * i_fs, "MaxSMCError");
    (void)snprintf(note, sizeof note, "kz_shift %u", (unsigned)s->kz_shift);
    row("smc Kz = Kslide / MaxSMCError", V(SMC_KZ), "E_FS/I_FS", s->kz,
        s->kz * pow2(s->kz_shift) / q, note);
    plain("smc loop gain c = G Kz", V(SMC_C), "",
          "linear band dead-beat at c = F; relay (chattering) mode above 1 + F");
    row("smc K per unit speed", V(SMC_KPW), "rad/period", s->k_per_omega, s->k_per_omega / q,
        "Kslf at full-scale speed (AN1078 Eq. 7)");
    row("smc K floor (filter floor)", V(MC_ESTIMATOR_MIN_RPM), "rpm", s->k_min,
        s->k_min / q / (6.283185307179586 * ts) * 60.0 / pp, "Kslf floor at MC_ESTIMATOR_MIN_RPM");
    row("MC_SPEED_FILTER_HZ", V(MC_SPEED_FILTER_HZ), "Hz", s->k_speed_lpf,
        s->k_speed_lpf / q / (6.283185307179586 * irp * ts), "speed filter");

    row("PWM_DEADTIME_NS", V(PWM_DEADTIME_NS), "ns", V(MC_DT_COUNTS),
        V(MC_DT_COUNTS) / V(BOARD_FCY_HZ) * 1e9, "MC_DT_COUNTS (duty counts)");
    row("MC_DEADTIME_BAND_A", V(MC_DEADTIME_BAND_A), "A", V(MC_DT_BAND_Q15),
        V(MC_DT_BAND_Q15) / q * i_fs, "dead-time compensation band");
    plain("MC_DUTY_SAMPLE_MAX", V(MC_DUTY_SAMPLE_MAX), "counts",
          "largest duty of a measured phase (shunt window)");

    for (k = 0; k < 16; k++) {
        double n = V(MOTOR_SPEED_NOMINAL_RPM) +
                   (V(MOTOR_SPEED_FW_MAX_RPM) - V(MOTOR_SPEED_NOMINAL_RPM)) * k / 15.0;
        char name[40];
        (void)snprintf(name, sizeof name, "FW Id[%2d] at %7.0f rpm", k, n);
        row(name, tune_probe_fw_amps[k], "A", tune_probe_fw_q15[k], tune_probe_fw_q15[k] / q * i_fs,
            "");
    }
}
#endif

int main(void)
{
    unsigned k;
    if (tune_probe_nfacts != (unsigned)F_COUNT_ + 1U) {
        fprintf(stderr, "probe: %u values for %u names\n", tune_probe_nfacts, (unsigned)F_COUNT_);
        return 1;
    }
    for (k = 0; k < (unsigned)F_COUNT_; k++) {
        printf("fact\t%s\t%.17g\n", names[k], tune_probe_facts[k]);
    }
    text("BOARD_NAME", tune_probe_board_name);
#ifndef TUNE_PROBE_BOARD
    text("MOTOR_NAME", tune_probe_motor_name);
    text("MOTOR_TUNE_BOARD", tune_probe_tune_board);
    table();
#endif
    return 0;
}
