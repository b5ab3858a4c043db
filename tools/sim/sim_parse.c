/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_parse.c - strict numbers for the simulator's inputs (sim_parse.h). */
#include "sim_parse.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int is_digit(char c)
{
    return c >= '0' && c <= '9';
}

/* [+-] digits [. digits] [e [+-] digits], at least one mantissa digit; with
 * whole_only no '.' and no exponent. strtod alone would also take hex
 * ("0x10"), "inf", "nan(...)" and leading blanks, none of which a scenario
 * or an option means. */
static int is_decimal(const char *s, int whole_only)
{
    int digits = 0;
    if (*s == '+' || *s == '-') {
        s++;
    }
    while (is_digit(*s)) {
        s++;
        digits++;
    }
    if (!whole_only && *s == '.') {
        s++;
        while (is_digit(*s)) {
            s++;
            digits++;
        }
    }
    if (digits == 0) {
        return 0;
    }
    if (!whole_only && (*s == 'e' || *s == 'E')) {
        s++;
        if (*s == '+' || *s == '-') {
            s++;
        }
        if (!is_digit(*s)) {
            return 0;
        }
        while (is_digit(*s)) {
            s++;
        }
    }
    return *s == '\0';
}

const char *sim_parse_quote(const char *tok, char *buf, size_t len)
{
    size_t i, n = strlen(tok);
    /* all of it when it fits, else as much as leaves room for "..." */
    size_t keep = (n + 1 <= len) ? n : ((len > 4) ? len - 4 : 0);
    if (len == 0) {
        return "";
    }
    for (i = 0; i < keep; i++) {
        unsigned char c = (unsigned char)tok[i];
        /* one line on any terminal and in any decoder: no control bytes,
         * no bytes of multi-byte characters (U+2028 is a line break too) */
        buf[i] = (c >= 0x20u && c < 0x7fu) ? (char)c : '?';
    }
    if (keep < n) {
        for (; i < len - 1; i++) {
            buf[i] = '.';
        }
    }
    buf[i] = '\0';
    return buf;
}

int sim_parse_number(const char *tok, const sim_range_t *r, double *out, char *why, size_t why_len)
{
    char q[48]; /* a bad number echoed back: 44 characters, then "..." */
    double v;
    int whole = (r->flags & SIM_RANGE_INTEGER) != 0u;
    int lo_open = (r->flags & SIM_RANGE_LO_OPEN) != 0u;
    const char *sp = (r->unit[0] != '\0') ? " " : "";

    sim_parse_quote(tok, q, sizeof(q));
    if (!is_decimal(tok, whole)) {
        sim_parse_msg(why, why_len, "'%s' is not %s", q,
                      whole ? "a whole number" : "a decimal number");
        return -1;
    }
    v = strtod(tok, NULL);
    /* an overflowing token comes back as +-HUGE_VAL: outside every range */
    if (!isfinite(v) || v > r->hi || v < r->lo || (lo_open && v == r->lo)) {
        sim_parse_msg(why, why_len, "'%s' is outside %.10g..%.10g%s%s%s", q, r->lo, r->hi, sp,
                      r->unit, lo_open ? " (lower end excluded)" : "");
        return -1;
    }
    *out = v;
    return 0;
}

static int name_ok(const char *s)
{
    size_t n = 0;
    for (; s[n] != '\0'; n++) {
        char c = s[n];
        /* no leading '-': "--motor --board" is a forgotten value, not a name */
        int ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || is_digit(c) || c == '_' ||
                 (c == '-' && n > 0);
        if (!ok || n >= 32) {
            return 0;
        }
    }
    return n > 0;
}

int sim_parse_name(const char *s, char *why, size_t why_len)
{
    char q[64];
    if (name_ok(s)) {
        return 0;
    }
    sim_parse_msg(why, why_len, "'%s' is not a profile name (1 to 32 letters, digits, _ or -)",
                  sim_parse_quote(s, q, sizeof(q)));
    return -1;
}

int sim_parse_word(const char *tok, const sim_word_t *words, double *out)
{
    for (; words->word != NULL; words++) {
        if (strcmp(tok, words->word) == 0) {
            *out = words->value;
            return 1;
        }
    }
    return 0;
}

const char *sim_parse_words(const sim_word_t *words, const char *sep, const char *last, char *buf,
                            size_t len)
{
    int k;
    if (len == 0) {
        return "";
    }
    buf[0] = '\0';
    for (k = 0; words[k].word != NULL; k++) {
        const char *join = (k == 0) ? "" : ((words[k + 1].word == NULL) ? last : sep);
        size_t n = strlen(buf);
        sim_parse_msg(buf + n, len - n, "%s%s", join, words[k].word);
    }
    return buf;
}

int sim_refuse(const char *prog, const char *field, const char *why)
{
    fprintf(stderr, "%s: %s: %s\n", prog, field, why);
    return 2;
}

void sim_parse_msg(char *buf, size_t len, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    (void)vsnprintf(buf, len, fmt, ap);
    va_end(ap);
}
