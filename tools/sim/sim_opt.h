/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_opt.h - the command-line options of the simulator's programs: one table per program. */
#ifndef SIM_OPT_H
#define SIM_OPT_H

#include <stddef.h>
#include <stdio.h>

#include "sim_parse.h"

/*
 * A program lists every option it takes once, in a table of sim_opt_t: its
 * name, what its value is (and so how it is checked), its usage line. The
 * same table recognises the options, checks their values (one line on
 * stderr and exit status 2 for anything else, sim_refuse) and prints the
 * usage; the program acts on the entry's id.
 */
typedef enum {
    SIM_OPT_FLAG,   /* no value */
    SIM_OPT_NUMBER, /* a number inside range (sim_parse_number) */
    SIM_OPT_NAME,   /* a profile name (sim_parse_name) */
    SIM_OPT_WORD,   /* one of words */
    SIM_OPT_TEXT    /* any text: a path, or a value the program checks itself */
} sim_opt_type_t;

typedef struct {
    int id;           /* the program's own code for it */
    const char *name; /* "--rpm0" */
    sim_opt_type_t type;
    const char *value;       /* the value in the usage, "RPM" (NULL for a flag) */
    sim_range_t range;       /* SIM_OPT_NUMBER (range.name unused: messages name the option) */
    const sim_word_t *words; /* SIM_OPT_WORD */
    const char *help;        /* the usage line */
} sim_opt_t;

/* A seed: a uint32_t, written in decimal. */
#define SIM_OPT_SEED_MAX 4294967295.0
#define SIM_OPT_SEED_RANGE                                                                         \
    {                                                                                              \
        "seed", "", 0.0, SIM_OPT_SEED_MAX, SIM_RANGE_INTEGER                                       \
    }

/* The option argv[*i] names, with its value (*i moved past it): *v its text
 * and, for a number, *x its value. Returns its entry, or NULL after
 * refusing it in one line (unknown, without its value, a bad value). */
const sim_opt_t *sim_opt_read(const char *prog, const sim_opt_t *opts, size_t n, int argc,
                              char **argv, int *i, const char **v, double *x);

/* One usage line per option: name, value, help, and the range or the words. */
void sim_opt_usage(FILE *f, const sim_opt_t *opts, size_t n);

#endif /* SIM_OPT_H */
