/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_scenario.c - scenario text parser. */
#include "sim_scenario.h"

#include "sim_inverter.h"
#include "sim_parse.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const char *name;
    sim_event_kind_t kind;
    int min_args, max_args;
} ev_desc_t;

static const ev_desc_t EVENTS[] = {
    {"start", SIM_EV_START, 0, 0},
    {"stop", SIM_EV_STOP, 0, 0},
    {"button", SIM_EV_BUTTON, 0, 0},
    {"identify", SIM_EV_IDENTIFY, 0, 0},
    {"pot", SIM_EV_POT, 1, 1},
    {"pot_ramp", SIM_EV_POT_RAMP, 2, 2},
    {"speed", SIM_EV_SPEED, 1, 1},
    {"speed_ramp", SIM_EV_SPEED_RAMP, 2, 2},
    {"load", SIM_EV_LOAD, 1, 1},
    {"load_active", SIM_EV_LOAD_ACTIVE, 1, 1},
    {"load_fan", SIM_EV_LOAD_FAN, 1, 1},
    {"vbus", SIM_EV_VBUS, 1, 1},
    {"vbus_ripple", SIM_EV_VBUS_RIPPLE, 2, 2},
    {"lock_rotor", SIM_EV_LOCK_ROTOR, 0, 0},
    {"unlock_rotor", SIM_EV_UNLOCK_ROTOR, 0, 0},
    {"open_lead", SIM_EV_OPEN_LEAD, 1, 1},
    {"close_lead", SIM_EV_CLOSE_LEAD, 0, 0},
    {"current_spike", SIM_EV_CURRENT_SPIKE, 1, 2},
    {"hw_fault", SIM_EV_HW_FAULT, 0, 0},
    {"deadtime", SIM_EV_DEADTIME, 1, 1},
    {"inverter", SIM_EV_INVERTER, 1, 1},
    {"deadtime_shape", SIM_EV_DEADTIME_SHAPE, 1, 1},
    {"noise", SIM_EV_NOISE, 1, 1},
    {"sensor_stuck", SIM_EV_SENSOR_STUCK, 2, 2},
    {"sensor_open", SIM_EV_SENSOR_OPEN, 1, 1},
    {"sensor_gain", SIM_EV_SENSOR_GAIN, 2, 2},
    {"sensor_drift", SIM_EV_SENSOR_DRIFT, 2, 2},
    {"sensor_ok", SIM_EV_SENSOR_OK, 1, 1},
    {"zoom", SIM_EV_ZOOM, 0, 1},
    {"mark", SIM_EV_MARK, 0, 0},
    {"end", SIM_EV_END, 0, 0},
};

#define N_EVENTS (sizeof(EVENTS) / sizeof(EVENTS[0]))

const char *sim_event_name(sim_event_kind_t k)
{
    size_t i;
    for (i = 0; i < N_EVENTS; i++) {
        if (EVENTS[i].kind == k) {
            return EVENTS[i].name;
        }
    }
    return "?";
}

/*
 * Value rules: what each value of each event may be. A row names the value
 * as an error message shows it, its unit and its range (sim_parse.h), and
 * the words it takes instead of a number (the words' one list, also what
 * the message names). Every value of every event in EVENTS needs its row:
 * a value with none is refused when parsed, and sim_scenario_check_rules()
 * (run by test_sim_parse) names the event that lacks one. The ranges are
 * physical or sane bounds, wide enough for every shipped scenario and test,
 * narrow enough that no value makes the run unbounded or overflows a
 * conversion (a periods count cast to long). They cannot stop a load the
 * motor cannot hold from driving the plant out of its model's range over a
 * long run (docs/sim.md, "Input checking").
 */
#define T_MAX_S       3600.0   /* event times and ramps: one simulated hour, ~72 M periods */
#define RPM_MAX       100000.0 /* pot speeds: far above any profile's top (17,000 rpm) */
#define TORQUE_MAX    10.0     /* N m: 15 x the most any profile's board drives (hispeed, 0.66) */
#define VBUS_MAX      1000.0   /* V: three times the MCHV's 320 V bus */
#define CURRENT_MAX   100.0    /* A: beyond both boards' ADC full scale (4.4 A, 8 A) */
#define DEADTIME_MAX  20.0     /* us: 40 % of a 50 us PWM period */
#define NOISE_MAX     100.0    /* ADC codes (sigma): a tenth of the 10-bit range */
#define RIPPLE_HZ     10000.0  /* bus ripple: up to half the 20 kHz PWM rate */
#define SPIKE_PERIODS 20000.0  /* one second of PWM periods at 20 kHz */
#define ZOOM_MAX_S    10.0     /* full-rate trace: 200,000 rows at 20 kHz */

/* The pot's ends instead of a speed. */
static const sim_word_t SPEED_WORDS[] = {
    {"max", SIM_SPEED_MAX}, {"min", SIM_SPEED_MIN}, {NULL, 0.0}};
/* The measured phase of a sensor event (0 = A, 1 = B). */
static const sim_word_t PHASE_WORDS[] = {{"a", 0.0}, {"b", 1.0}, {NULL, 0.0}};
/* A motor lead (0 = A, 1 = B, 2 = C). */
static const sim_word_t LEAD_WORDS[] = {{"a", 0.0}, {"b", 1.0}, {"c", 2.0}, {NULL, 0.0}};

typedef struct {
    sim_event_kind_t kind;
    int argi;
    sim_range_t r;           /* r.name: the value's name in messages */
    const sim_word_t *words; /* the words taken instead of a number, or NULL */
    int words_only;          /* 1: one of the words, never a number */
} value_rule_t;

static const value_rule_t RULES[] = {
    {SIM_EV_POT, 0, {"position", "", 0.0, 1.0, 0u}, NULL, 0},
    {SIM_EV_POT_RAMP, 0, {"position", "", 0.0, 1.0, 0u}, NULL, 0},
    {SIM_EV_POT_RAMP, 1, {"ramp time", "s", 0.0, T_MAX_S, 0u}, NULL, 0},
    {SIM_EV_SPEED, 0, {"rpm", "rpm", 0.0, RPM_MAX, 0u}, SPEED_WORDS, 0},
    {SIM_EV_SPEED_RAMP, 0, {"rpm", "rpm", 0.0, RPM_MAX, 0u}, SPEED_WORDS, 0},
    {SIM_EV_SPEED_RAMP, 1, {"ramp time", "s", 0.0, T_MAX_S, 0u}, NULL, 0},
    {SIM_EV_LOAD, 0, {"torque", "N m", 0.0, TORQUE_MAX, 0u}, NULL, 0},
    {SIM_EV_LOAD_ACTIVE, 0, {"torque", "N m", -TORQUE_MAX, TORQUE_MAX, 0u}, NULL, 0},
    {SIM_EV_LOAD_FAN, 0, {"torque at rated speed", "N m", 0.0, TORQUE_MAX, 0u}, NULL, 0},
    {SIM_EV_VBUS, 0, {"voltage", "V", 0.0, VBUS_MAX, 0u}, NULL, 0},
    {SIM_EV_VBUS_RIPPLE, 0, {"amplitude", "V", 0.0, VBUS_MAX, 0u}, NULL, 0},
    {SIM_EV_VBUS_RIPPLE, 1, {"frequency", "Hz", 0.0, RIPPLE_HZ, 0u}, NULL, 0},
    {SIM_EV_CURRENT_SPIKE, 0, {"current", "A", -CURRENT_MAX, CURRENT_MAX, 0u}, NULL, 0},
    {SIM_EV_CURRENT_SPIKE, 1, {"periods", "", 1.0, SPIKE_PERIODS, SIM_RANGE_INTEGER}, NULL, 0},
    {SIM_EV_DEADTIME, 0, {"dead time", "us", 0.0, DEADTIME_MAX, 0u}, NULL, 0},
    {SIM_EV_INVERTER, 0, {"model", "", 0.0, 0.0, 0u}, sim_inverter_models, 1},
    {SIM_EV_DEADTIME_SHAPE, 0, {"shape", "", 0.0, 0.0, 0u}, sim_inverter_shapes, 1},
    {SIM_EV_NOISE, 0, {"sigma", "codes", 0.0, NOISE_MAX, 0u}, NULL, 0},
    {SIM_EV_OPEN_LEAD, 0, {"lead", "", 0.0, 0.0, 0u}, LEAD_WORDS, 1},
    {SIM_EV_SENSOR_STUCK, 0, {"phase", "", 0.0, 0.0, 0u}, PHASE_WORDS, 1},
    {SIM_EV_SENSOR_STUCK, 1, {"current", "A", -CURRENT_MAX, CURRENT_MAX, 0u}, NULL, 0},
    {SIM_EV_SENSOR_OPEN, 0, {"phase", "", 0.0, 0.0, 0u}, PHASE_WORDS, 1},
    {SIM_EV_SENSOR_GAIN, 0, {"phase", "", 0.0, 0.0, 0u}, PHASE_WORDS, 1},
    {SIM_EV_SENSOR_GAIN, 1, {"gain", "", -10.0, 10.0, 0u}, NULL, 0},
    {SIM_EV_SENSOR_DRIFT, 0, {"phase", "", 0.0, 0.0, 0u}, PHASE_WORDS, 1},
    {SIM_EV_SENSOR_DRIFT, 1, {"drift", "A/s", -CURRENT_MAX, CURRENT_MAX, 0u}, NULL, 0},
    {SIM_EV_SENSOR_OK, 0, {"phase", "", 0.0, 0.0, 0u}, PHASE_WORDS, 1},
    {SIM_EV_ZOOM, 0, {"length", "s", 0.0, ZOOM_MAX_S, SIM_RANGE_LO_OPEN}, NULL, 0},
};

#define N_RULES (sizeof(RULES) / sizeof(RULES[0]))

static const sim_range_t TIME_RANGE = {"time", "s", 0.0, T_MAX_S, 0u};

static const value_rule_t *find_rule(sim_event_kind_t kind, int argi)
{
    size_t i;
    for (i = 0; i < N_RULES; i++) {
        if (RULES[i].kind == kind && RULES[i].argi == argi) {
            return &RULES[i];
        }
    }
    return NULL;
}

int sim_scenario_check_rules(char *err, size_t err_len)
{
    size_t i;
    int a;
    for (i = 0; i < N_EVENTS; i++) {
        for (a = 0; a < EVENTS[i].max_args; a++) {
            if (find_rule(EVENTS[i].kind, a) == NULL) {
                sim_parse_msg(err, err_len,
                              "event '%s' value %d has no row in RULES (sim_scenario.c)",
                              EVENTS[i].name, a + 1);
                return -1;
            }
        }
    }
    return 0;
}

/* One value: one of its rule's words, or a number inside its range. */
static int parse_number(const char *tok, sim_event_kind_t kind, int argi, double *out, char *why,
                        size_t why_len)
{
    const value_rule_t *rule = find_rule(kind, argi);
    char words[64] = "", msg[160];
    if (rule == NULL) {
        sim_parse_msg(why, why_len, "value %d has no range (RULES in sim_scenario.c)", argi + 1);
        return -1;
    }
    if (rule->words != NULL) {
        if (sim_parse_word(tok, rule->words, out)) {
            return 0;
        }
        sim_parse_words(rule->words, "|", "|", words, sizeof(words));
    }
    if (rule->words_only) {
        char q[48];
        sim_parse_msg(why, why_len, "%s: '%s' is not one of %s", rule->r.name,
                      sim_parse_quote(tok, q, sizeof(q)), words);
        return -1;
    }
    if (sim_parse_number(tok, &rule->r, out, msg, sizeof(msg)) == 0) {
        return 0;
    }
    sim_parse_msg(why, why_len, "%s: %s%s%s", rule->r.name, msg,
                  (rule->words != NULL) ? ", or one of " : "", (rule->words != NULL) ? words : "");
    return -1;
}

typedef struct {
    const char *src; /* file name for messages, or NULL: "line N" */
    int lineno;
    char *err;
    size_t err_len;
} ctx_t;

/* One-line message "FILE:LINE: what" (or "line LINE: what"); returns -1. */
static int fail(const ctx_t *c, const char *what)
{
    if (c->src != NULL) {
        sim_parse_msg(c->err, c->err_len, "%s:%d: %s", c->src, c->lineno, what);
    } else {
        sim_parse_msg(c->err, c->err_len, "line %d: %s", c->lineno, what);
    }
    return -1;
}

/* time, event and up to three values; a line with more is counted past
 * this and refused by its event's value count */
#define MAX_TOKENS 5

static int parse_line(char *line, const ctx_t *c, sim_scenario_t *sc)
{
    char *tok[MAX_TOKENS];
    int ntok = 0;
    char *save = line;
    char *t;
    char msg[200];
    size_t i;
    sim_event_t ev;
    const ev_desc_t *d = NULL;
    int a;

    t = strchr(line, '#');
    if (t != NULL) {
        *t = '\0';
    }
    for (t = line; *t != '\0'; t++) {
        unsigned char ch = (unsigned char)*t;
        if (ch < 0x20u && ch != '\t' && ch != '\r') {
            sim_parse_msg(msg, sizeof(msg), "control character 0x%02x outside a comment", ch);
            return fail(c, msg);
        }
    }
    while (*save != '\0') {
        while (*save == ' ' || *save == '\t' || *save == '\r') {
            save++;
        }
        if (*save == '\0') {
            break;
        }
        if (ntok == MAX_TOKENS) {
            ntok++; /* counted, not kept: the event's own check names it */
            break;
        }
        tok[ntok++] = save;
        while (*save != '\0' && *save != ' ' && *save != '\t' && *save != '\r') {
            save++;
        }
        if (*save != '\0') {
            *save++ = '\0';
        }
    }
    if (ntok == 0) {
        return 0;
    }
    {
        char why[160];
        if (sim_parse_number(tok[0], &TIME_RANGE, &ev.t_s, why, sizeof(why)) != 0) {
            sim_parse_msg(msg, sizeof(msg), "time: %s", why);
            return fail(c, msg);
        }
    }
    if (ntok < 2) {
        return fail(c, "missing event name");
    }
    for (i = 0; i < N_EVENTS; i++) {
        if (strcmp(EVENTS[i].name, tok[1]) == 0) {
            d = &EVENTS[i];
        }
    }
    if (d == NULL) {
        char q[48];
        sim_parse_msg(msg, sizeof(msg), "unknown event '%s'",
                      sim_parse_quote(tok[1], q, sizeof(q)));
        return fail(c, msg);
    }
    if (ntok - 2 < d->min_args || ntok - 2 > d->max_args) {
        const char *more = (ntok > MAX_TOKENS) ? " or more" : "";
        if (d->min_args == d->max_args) {
            sim_parse_msg(msg, sizeof(msg), "'%s' takes %d value%s, got %d%s", d->name, d->min_args,
                          (d->min_args == 1) ? "" : "s", ntok - 2, more);
        } else {
            sim_parse_msg(msg, sizeof(msg), "'%s' takes %d to %d values, got %d%s", d->name,
                          d->min_args, d->max_args, ntok - 2, more);
        }
        return fail(c, msg);
    }
    ev.kind = d->kind;
    ev.v1 = 0.0;
    ev.v2 = 0.0;
    for (a = 0; a < ntok - 2; a++) {
        double v = 0.0;
        char why[160];
        if (parse_number(tok[2 + a], d->kind, a, &v, why, sizeof(why)) != 0) {
            sim_parse_msg(msg, sizeof(msg), "%s %s", d->name, why);
            return fail(c, msg);
        }
        if (a == 0) {
            ev.v1 = v;
        } else {
            ev.v2 = v;
        }
    }
    if (sc->n > 0 && ev.t_s < sc->ev[sc->n - 1].t_s) {
        sim_parse_msg(msg, sizeof(msg),
                      "time: %.10g s goes backwards (the event before is at %.10g s)", ev.t_s,
                      sc->ev[sc->n - 1].t_s);
        return fail(c, msg);
    }
    if (sc->n > 0 && sc->ev[sc->n - 1].kind == SIM_EV_END) {
        return fail(c, "event after 'end'");
    }
    if (sc->n >= SIM_SCENARIO_MAX_EVENTS) {
        sim_parse_msg(msg, sizeof(msg), "more than %d events", SIM_SCENARIO_MAX_EVENTS);
        return fail(c, msg);
    }
    sc->ev[sc->n++] = ev;
    if (ev.kind == SIM_EV_END) {
        sc->end_s = ev.t_s;
    }
    return 0;
}

static int parse_text(const char *text, size_t len, const char *src, sim_scenario_t *sc, char *err,
                      size_t err_len)
{
    char line[256];
    ctx_t c;
    size_t pos = 0;
    c.src = src;
    c.lineno = 0;
    c.err = err;
    c.err_len = err_len;
    sc->n = 0;
    sc->end_s = -1.0;
    while (pos < len) {
        const char *p = text + pos;
        const char *nl = memchr(p, '\n', len - pos);
        size_t n = (nl != NULL) ? (size_t)(nl - p) : len - pos;
        c.lineno++;
        if (memchr(p, '\0', n) != NULL) {
            return fail(&c, "NUL byte: not a text file");
        }
        if (n >= sizeof(line)) {
            sim_parse_msg(line, sizeof(line), "longer than %d characters", (int)sizeof(line) - 1);
            return fail(&c, line);
        }
        memcpy(line, p, n);
        line[n] = '\0';
        if (parse_line(line, &c, sc) != 0) {
            return -1;
        }
        pos += n + ((nl != NULL) ? 1u : 0u);
    }
    if (sc->end_s < 0.0) {
        if (src != NULL) {
            sim_parse_msg(err, err_len, "%s: no 'end' event", src);
        } else {
            sim_parse_msg(err, err_len, "no 'end' event");
        }
        return -1;
    }
    return 0;
}

int sim_scenario_parse(const char *text, sim_scenario_t *sc, char *err, size_t err_len)
{
    return parse_text(text, strlen(text), NULL, sc, err, err_len);
}

/* A scenario is a page of text: anything larger is the wrong file. */
#define SCENARIO_MAX_BYTES (1L << 20)

int sim_scenario_load(const char *path, sim_scenario_t *sc, char *err, size_t err_len)
{
    FILE *f = fopen(path, "rb");
    char *buf;
    char q[256]; /* the path, as messages name it */
    size_t len;
    int rc;
    sim_parse_quote(path, q, sizeof(q));
    if (f == NULL) {
        sim_parse_msg(err, err_len, "%s: cannot open (%s)", q, strerror(errno));
        return -1;
    }
    buf = malloc((size_t)SCENARIO_MAX_BYTES + 1u);
    if (buf == NULL) {
        fclose(f);
        sim_parse_msg(err, err_len, "%s: out of memory", q);
        return -1;
    }
    /* read, not fseek/ftell: a directory, a pipe or /dev/zero must end in
     * a message, not in a huge allocation or an endless read */
    len = fread(buf, 1, (size_t)SCENARIO_MAX_BYTES + 1u, f);
    if (ferror(f)) {
        free(buf);
        fclose(f);
        sim_parse_msg(err, err_len, "%s: cannot read (not a file?)", q);
        return -1;
    }
    fclose(f);
    if (len > (size_t)SCENARIO_MAX_BYTES) {
        free(buf);
        sim_parse_msg(err, err_len, "%s: larger than %ld bytes: not a scenario", q,
                      SCENARIO_MAX_BYTES);
        return -1;
    }
    rc = parse_text(buf, len, q, sc, err, err_len);
    free(buf);
    return rc;
}
