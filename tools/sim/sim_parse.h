/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_parse.h - strict numbers for the simulator's inputs (scenario files and command lines). */
#ifndef SIM_PARSE_H
#define SIM_PARSE_H

#include <stddef.h>

/*
 * Every number a user gives the simulator (a scenario value, a command-line
 * option) goes through sim_parse_number(): the whole token must be a plain
 * decimal number (no hex, no "inf" or "nan", nothing after it), finite, and
 * inside the field's stated range. Anything else is refused with a reason
 * that names the range, so a typo never turns into a silent nonsense run or
 * into undefined behaviour further down (a NaN cast to an integer, a loop
 * bound of 1e300 periods).
 */

#define SIM_RANGE_INTEGER 1u /* whole numbers only, written without '.' or exponent */
#define SIM_RANGE_LO_OPEN 2u /* lo itself is excluded: (lo, hi] */

typedef struct {
    const char *name; /* the field as the user knows it: "--rpm0", "speed rpm" */
    const char *unit; /* "rpm", "s", "" */
    double lo, hi;    /* inclusive unless SIM_RANGE_LO_OPEN */
    unsigned flags;
} sim_range_t;

/* Parses tok into *out. Returns 0, or -1 with why set to one line such as
 * "'1e300' is outside 0..3600 s" (the token quoted by sim_parse_quote). */
int sim_parse_number(const char *tok, const sim_range_t *r, double *out, char *why, size_t why_len);

/* The token made safe to print on one line: bytes outside printable ASCII
 * become '?'; a token longer than buf ends in "...". Returns buf. */
const char *sim_parse_quote(const char *tok, char *buf, size_t len);

/* snprintf for messages that may be cut at len on purpose (a long token in
 * a fixed buffer): the cut is the intent, so no -Wformat-truncation. */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
void sim_parse_msg(char *buf, size_t len, const char *fmt, ...);

/* A profile name (--motor, --board): 1 to 32 letters, digits, '_' or '-'.
 * Returns 0, or -1 with the one-line reason in why. */
int sim_parse_name(const char *s, char *why, size_t why_len);

/* A word a value may be instead of a number ("max", "switching", "a") and
 * the number it stands for. A list of them ends with {NULL, 0}: the one
 * place its words are written, for parsing and for messages alike. */
typedef struct {
    const char *word;
    double value;
} sim_word_t;

/* Returns 1 with *out set when tok is one of words, else 0. */
int sim_parse_word(const char *tok, const sim_word_t *words, double *out);

/* The words for a message, joined by sep and by last before the last one
 * ("max|min" with "|", "|"; "linear, hard or ripple" with ", ", " or ").
 * Returns buf. */
const char *sim_parse_words(const sim_word_t *words, const char *sep, const char *last, char *buf,
                            size_t len);

/* A refusal, the one way every program of the simulator refuses its input:
 * one line on stderr, "<prog>: <field>: <why>". Returns 2, their exit status
 * for bad input. */
int sim_refuse(const char *prog, const char *field, const char *why);

#endif /* SIM_PARSE_H */
