/* sim_scenario.c - scenario text parser. */
#include "sim_scenario.h"

#include "sim_inverter.h"

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
    {"current_spike", SIM_EV_CURRENT_SPIKE, 1, 2},
    {"hw_fault", SIM_EV_HW_FAULT, 0, 0},
    {"deadtime", SIM_EV_DEADTIME, 1, 1},
    {"inverter", SIM_EV_INVERTER, 1, 1},
    {"deadtime_shape", SIM_EV_DEADTIME_SHAPE, 1, 1},
    {"noise", SIM_EV_NOISE, 1, 1},
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

static int parse_number(const char *tok, sim_event_kind_t kind, int argi, double *out)
{
    char *endp;
    if ((kind == SIM_EV_SPEED || kind == SIM_EV_SPEED_RAMP) && argi == 0) {
        if (strcmp(tok, "max") == 0) {
            *out = SIM_SPEED_MAX;
            return 0;
        }
        if (strcmp(tok, "min") == 0) {
            *out = SIM_SPEED_MIN;
            return 0;
        }
    }
    if (kind == SIM_EV_INVERTER || kind == SIM_EV_DEADTIME_SHAPE) {
        int k;
        int bad = (kind == SIM_EV_INVERTER) ? sim_inverter_model_parse(tok, &k)
                                            : sim_inverter_shape_parse(tok, &k);
        *out = (double)k;
        return bad;
    }
    *out = strtod(tok, &endp);
    return (endp == tok || *endp != '\0') ? -1 : 0;
}

static int parse_line(char *line, int lineno, sim_scenario_t *sc, char *err, size_t err_len)
{
    char *tok[5] = {NULL, NULL, NULL, NULL, NULL};
    int ntok = 0;
    char *save = line;
    char *t;
    char *endp;
    size_t i;
    sim_event_t ev;
    const ev_desc_t *d = NULL;
    int a;

    t = strchr(line, '#');
    if (t != NULL) {
        *t = '\0';
    }
    while (ntok < 5) {
        while (*save == ' ' || *save == '\t' || *save == '\r') {
            save++;
        }
        if (*save == '\0' || *save == '\n') {
            break;
        }
        tok[ntok++] = save;
        while (*save != '\0' && *save != ' ' && *save != '\t' && *save != '\r' && *save != '\n') {
            save++;
        }
        if (*save != '\0') {
            *save++ = '\0';
        }
    }
    if (ntok == 0) {
        return 0;
    }
    ev.t_s = strtod(tok[0], &endp);
    if (endp == tok[0] || *endp != '\0' || ev.t_s < 0.0) {
        snprintf(err, err_len, "line %d: bad time '%s'", lineno, tok[0]);
        return -1;
    }
    if (ntok < 2) {
        snprintf(err, err_len, "line %d: missing event name", lineno);
        return -1;
    }
    for (i = 0; i < N_EVENTS; i++) {
        if (strcmp(EVENTS[i].name, tok[1]) == 0) {
            d = &EVENTS[i];
        }
    }
    if (d == NULL) {
        snprintf(err, err_len, "line %d: unknown event '%s'", lineno, tok[1]);
        return -1;
    }
    if (ntok - 2 < d->min_args || ntok - 2 > d->max_args) {
        snprintf(err, err_len, "line %d: '%s' takes %d to %d values", lineno, d->name, d->min_args,
                 d->max_args);
        return -1;
    }
    ev.kind = d->kind;
    ev.v1 = 0.0;
    ev.v2 = 0.0;
    for (a = 0; a < ntok - 2; a++) {
        double v;
        if (parse_number(tok[2 + a], d->kind, a, &v) != 0) {
            snprintf(err, err_len, "line %d: bad value '%s'", lineno, tok[2 + a]);
            return -1;
        }
        if (a == 0) {
            ev.v1 = v;
        } else {
            ev.v2 = v;
        }
    }
    if (sc->n > 0 && ev.t_s < sc->ev[sc->n - 1].t_s) {
        snprintf(err, err_len, "line %d: time goes backwards", lineno);
        return -1;
    }
    if (sc->n > 0 && sc->ev[sc->n - 1].kind == SIM_EV_END) {
        snprintf(err, err_len, "line %d: event after 'end'", lineno);
        return -1;
    }
    if (sc->n >= SIM_SCENARIO_MAX_EVENTS) {
        snprintf(err, err_len, "line %d: more than %d events", lineno, SIM_SCENARIO_MAX_EVENTS);
        return -1;
    }
    sc->ev[sc->n++] = ev;
    if (ev.kind == SIM_EV_END) {
        sc->end_s = ev.t_s;
    }
    return 0;
}

int sim_scenario_parse(const char *text, sim_scenario_t *sc, char *err, size_t err_len)
{
    char line[256];
    int lineno = 0;
    const char *p = text;
    sc->n = 0;
    sc->end_s = -1.0;
    while (*p != '\0') {
        size_t len = strcspn(p, "\n");
        lineno++;
        if (len >= sizeof(line)) {
            snprintf(err, err_len, "line %d: too long", lineno);
            return -1;
        }
        memcpy(line, p, len);
        line[len] = '\0';
        if (parse_line(line, lineno, sc, err, err_len) != 0) {
            return -1;
        }
        p += len;
        if (*p == '\n') {
            p++;
        }
    }
    if (sc->end_s < 0.0) {
        snprintf(err, err_len, "no 'end' event");
        return -1;
    }
    return 0;
}

int sim_scenario_load(const char *path, sim_scenario_t *sc, char *err, size_t err_len)
{
    FILE *f = fopen(path, "rb");
    char *buf;
    long len;
    int rc;
    if (f == NULL) {
        snprintf(err, err_len, "cannot open %s", path);
        return -1;
    }
    if (fseek(f, 0, SEEK_END) != 0 || (len = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
        fclose(f);
        snprintf(err, err_len, "cannot read %s", path);
        return -1;
    }
    buf = malloc((size_t)len + 1);
    if (buf == NULL || fread(buf, 1, (size_t)len, f) != (size_t)len) {
        free(buf);
        fclose(f);
        snprintf(err, err_len, "cannot read %s", path);
        return -1;
    }
    buf[len] = '\0';
    fclose(f);
    rc = sim_scenario_parse(buf, sc, err, err_len);
    free(buf);
    return rc;
}
