/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_hal_config.c - the configuration words in hal/dspic33f/config_bits.c state the settings of
 * docs/hardware.md 1.3. */
#include "test_support.h"

#include <stdio.h>
#include <string.h>

/*
 * The pragmas only exist for XC16, so this reads the file as text: every
 * setting of docs/hardware.md 1.3 must appear as one `#pragma config NAME = VALUE`
 * line inside the XC16 branch, and no setting may appear twice.
 */

static char text[8192];

static int load(void **state)
{
    (void)state;
    FILE *f = fopen(HAL_CONFIG_BITS_PATH, "r");
    size_t n;
    assert_non_null(f);
    n = fread(text, 1, sizeof text - 1, f);
    text[n] = '\0';
    fclose(f);
    return 0;
}

static unsigned count_lines(const char *line)
{
    unsigned count = 0;
    const char *p = text;
    size_t len = strlen(line);
    while ((p = strstr(p, line)) != NULL) {
        if ((p == text || p[-1] == '\n') && (p[len] == '\n' || p[len] == ' ' || p[len] == '\0')) {
            count++;
        }
        p += len;
    }
    return count;
}

static void test_config_bits_should_state_each_setting_of_the_facts_sheet_once(void **state)
{
    (void)state;
    static const char *const settings[] = {
        "#pragma config FNOSC = FRC",  "#pragma config FCKSM = CSECMD",
        "#pragma config POSCMD = XT",  "#pragma config IOL1WAY = OFF",
        "#pragma config FWDTEN = OFF", "#pragma config FPWRT = PWR128",
        "#pragma config PWMPIN = ON",  "#pragma config HPOL = ON",
        "#pragma config LPOL = ON",    "#pragma config ICS = PGD3",
        "#pragma config JTAGEN = OFF",
    };
    size_t i;
    for (i = 0; i < sizeof settings / sizeof settings[0]; i++) {
        printf("measured: %-32s x%u\n", settings[i], count_lines(settings[i]));
        assert_int_equal(count_lines(settings[i]), 1);
    }
}

static void test_config_bits_should_be_seen_only_by_xc16(void **state)
{
    (void)state;
    const char *guard = strstr(text, "#if defined(__XC16__)");
    const char *first = strstr(text, "\n#pragma config");
    assert_non_null(guard);
    assert_non_null(first);
    assert_cmp(guard - text, <, first - text); /* offsets: the guard comes first */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_config_bits_should_state_each_setting_of_the_facts_sheet_once,
                               load),
        cmocka_unit_test_setup(test_config_bits_should_be_seen_only_by_xc16, load),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
