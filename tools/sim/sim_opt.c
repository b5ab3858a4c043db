/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_opt.c - the command-line options of the simulator's programs (sim_opt.h). */
#include "sim_opt.h"

#include <string.h>

static const sim_opt_t *find(const sim_opt_t *opts, size_t n, const char *a)
{
    size_t k;
    for (k = 0; k < n; k++) {
        if (strcmp(opts[k].name, a) == 0) {
            return &opts[k];
        }
    }
    return NULL;
}

/* Checks the value v of option o; *x the number it stands for. Returns 0,
 * or -1 with the reason in why. */
static int check_value(const sim_opt_t *o, const char *v, double *x, char *why, size_t len)
{
    switch (o->type) {
        case SIM_OPT_NUMBER:
            return sim_parse_number(v, &o->range, x, why, len);
        case SIM_OPT_NAME:
            return sim_parse_name(v, why, len);
        case SIM_OPT_WORD: {
            char q[48], words[96];
            if (sim_parse_word(v, o->words, x)) {
                return 0;
            }
            sim_parse_msg(why, len, "'%s' is not %s", sim_parse_quote(v, q, sizeof(q)),
                          sim_parse_words(o->words, ", ", " or ", words, sizeof(words)));
            return -1;
        }
        default:
            return 0;
    }
}

const sim_opt_t *sim_opt_read(const char *prog, const sim_opt_t *opts, size_t n, int argc,
                              char **argv, int *i, const char **v, double *x)
{
    const char *a = argv[*i];
    const sim_opt_t *o = find(opts, n, a);
    char why[320];
    *v = NULL;
    *x = 0.0;
    if (o == NULL) {
        char q[48];
        sim_parse_msg(why, sizeof(why), "unknown option (%s --help lists them)", prog);
        (void)sim_refuse(prog, sim_parse_quote(a, q, sizeof(q)), why);
        return NULL;
    }
    if (o->type == SIM_OPT_FLAG) {
        return o;
    }
    if (*i + 1 >= argc) {
        (void)sim_refuse(prog, a, "needs a value");
        return NULL;
    }
    *i += 1;
    *v = argv[*i];
    if (check_value(o, *v, x, why, sizeof(why)) != 0) {
        (void)sim_refuse(prog, a, why);
        return NULL;
    }
    return o;
}

void sim_opt_usage(FILE *f, const sim_opt_t *opts, size_t n)
{
    size_t k;
    for (k = 0; k < n; k++) {
        const sim_opt_t *o = &opts[k];
        char head[48], words[96];
        snprintf(head, sizeof(head), "%s%s%s", o->name, (o->value != NULL) ? " " : "",
                 (o->value != NULL) ? o->value : "");
        fprintf(f, "  %-19s %s", head, o->help);
        if (o->type == SIM_OPT_NUMBER) {
            const sim_range_t *r = &o->range;
            const char *sp = (r->unit[0] != '\0') ? " " : "";
            if ((r->flags & SIM_RANGE_LO_OPEN) != 0u) {
                fprintf(f, " [more than %.10g, up to %.10g%s%s]", r->lo, r->hi, sp, r->unit);
            } else {
                fprintf(f, " [%.10g..%.10g%s%s%s]", r->lo, r->hi, sp, r->unit,
                        ((r->flags & SIM_RANGE_INTEGER) != 0u) ? ", whole" : "");
            }
        } else if (o->type == SIM_OPT_WORD) {
            fprintf(f, " [%s]", sim_parse_words(o->words, "|", "|", words, sizeof(words)));
        }
        fprintf(f, "\n");
    }
}
