/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_sim_parse.c - the strict number parser (sim_parse.h) and the scenario parser's value
 * checks: every bad number is refused in one line that names its field and line. */
#include "test_support.h"

#include <stdio.h>
#include <string.h>

#include "sim_parse.h"
#include "sim_scenario.h"

static const sim_range_t R_0_10 = {"x", "V", 0.0, 10.0, 0u};

static void test_number_should_take_plain_decimals_in_range(void **state)
{
    static const char *const ok[] = {"0",  "-0",  "+3",   "10",     "0.5",   ".5",
                                     "5.", "1e1", "1E-3", "2.5e+0", "1e-400"};
    static const double want[] = {0.0, 0.0, 3.0, 10.0, 0.5, 0.5, 5.0, 10.0, 1e-3, 2.5, 0.0};
    char why[160];
    size_t k;
    (void)state;
    for (k = 0; k < sizeof(ok) / sizeof(ok[0]); k++) {
        double v = -1.0;
        if (sim_parse_number(ok[k], &R_0_10, &v, why, sizeof(why)) != 0) {
            fail_msg("'%s' refused: %s", ok[k], why);
        }
        assert_cmp(v, ==, want[k]);
    }
}

static void test_number_should_refuse_non_decimals_non_finite_and_out_of_range(void **state)
{
    /* what strtod alone would have taken (hex, inf, nan, blanks, a prefix) and the rest */
    static const char *const bad[] = {"",    " 1",    "1 ",     "0x10", "inf",  "-inf",  "nan",
                                      "NAN", "1e",    "e3",     ".",    "-",    "1.2.3", "1,5",
                                      "5V",  "1e300", "-1e300", "11",   "-0.1", "1e309"};
    char why[160];
    double v0 = 0.0;
    size_t k;
    (void)state;
    for (k = 0; k < sizeof(bad) / sizeof(bad[0]); k++) {
        double v = 42.0;
        if (sim_parse_number(bad[k], &R_0_10, &v, why, sizeof(why)) == 0) {
            fail_msg("'%s' taken as %g", bad[k], v);
        }
        assert_cmp(v, ==, 42.0); /* untouched */
        assert_null(strchr(why, '\n'));
    }
    assert_int_equal(sim_parse_number("1e300", &R_0_10, &v0, why, sizeof(why)), -1);
    assert_string_equal(why, "'1e300' is outside 0..10 V");
    assert_int_equal(sim_parse_number("nan", &R_0_10, &v0, why, sizeof(why)), -1);
    assert_string_equal(why, "'nan' is not a decimal number");
}

static void test_number_should_honour_whole_and_open_ranges(void **state)
{
    static const sim_range_t whole = {"n", "", 1.0, 64.0, SIM_RANGE_INTEGER};
    static const sim_range_t open = {"k", "", 0.0, 100.0, SIM_RANGE_LO_OPEN};
    static const sim_range_t seed = {"seed", "", 0.0, 4294967295.0, SIM_RANGE_INTEGER};
    char why[160];
    double v = 0.0;
    (void)state;
    assert_int_equal(sim_parse_number("64", &whole, &v, why, sizeof(why)), 0);
    assert_cmp(v, ==, 64.0);
    assert_int_equal(sim_parse_number("65", &whole, &v, why, sizeof(why)), -1);
    assert_int_equal(sim_parse_number("1000000", &whole, &v, why, sizeof(why)), -1);
    assert_int_equal(sim_parse_number("4.0", &whole, &v, why, sizeof(why)), -1);
    assert_string_equal(why, "'4.0' is not a whole number");
    assert_int_equal(sim_parse_number("1e1", &whole, &v, why, sizeof(why)), -1);
    assert_int_equal(sim_parse_number("0", &open, &v, why, sizeof(why)), -1);
    assert_non_null(strstr(why, "lower end excluded"));
    assert_int_equal(sim_parse_number("1e-9", &open, &v, why, sizeof(why)), 0);
    assert_int_equal(sim_parse_number("4294967295", &seed, &v, why, sizeof(why)), 0);
    assert_cmp(v, ==, 4294967295.0);
    assert_int_equal(sim_parse_number("4294967296", &seed, &v, why, sizeof(why)), -1);
    assert_int_equal(sim_parse_number("010", &seed, &v, why, sizeof(why)), 0);
    assert_cmp(v, ==, 10.0); /* decimal, never octal */
}

static void test_quote_should_keep_a_message_on_one_printable_line(void **state)
{
    char buf[16];
    (void)state;
    assert_string_equal(sim_parse_quote("1\n2\r3\x0b\xe2\x80\xa8", buf, sizeof(buf)), "1?2?3????");
    assert_string_equal(sim_parse_quote("abcdefghijklmnopqrstuvwxyz", buf, sizeof(buf)),
                        "abcdefghijkl..."); /* 15 characters and the NUL */
    assert_string_equal(sim_parse_quote("fits", buf, sizeof(buf)), "fits");
    char why[128];
    assert_int_equal(sim_parse_name("hurst075", why, sizeof(why)), 0);
    assert_int_equal(sim_parse_name("hs2p-x_1", why, sizeof(why)), 0);
    assert_int_equal(sim_parse_name("", why, sizeof(why)), -1);
    assert_int_equal(sim_parse_name("--board", why, sizeof(why)), -1);
    assert_int_equal(sim_parse_name("a b", why, sizeof(why)), -1);
    assert_non_null(strstr(why, "'a b' is not a profile name"));
    assert_int_equal(sim_parse_name("a/../b", why, sizeof(why)), -1);
    assert_int_equal(sim_parse_name("abcdefghijklmnopqrstuvwxyz0123456789", why, sizeof(why)), -1);
}

/* A scenario "0 start", the line, "4 end": refused at line 2, naming want. */
static void refused_at_line_2(const char *line, const char *want)
{
    static sim_scenario_t sc;
    char text[300], err[300];
    snprintf(text, sizeof(text), "0 start\n%s\n4 end\n", line);
    if (sim_scenario_parse(text, &sc, err, sizeof(err)) == 0) {
        fail_msg("'%s' was taken", line);
    }
    if (strncmp(err, "line 2: ", 8) != 0 || strstr(err, want) == NULL ||
        strchr(err, '\n') != NULL) {
        fail_msg("'%s': got \"%s\", want \"line 2: ...%s...\" on one line", line, err, want);
    }
}

static void test_scenario_should_refuse_bad_values_naming_event_field_and_line(void **state)
{
    (void)state;
    refused_at_line_2("nan stop", "time: 'nan' is not a decimal number");
    refused_at_line_2("inf stop", "time: 'inf'");
    refused_at_line_2("1e300 stop", "time: '1e300' is outside 0..3600 s");
    refused_at_line_2("-1 stop", "time: '-1' is outside");
    refused_at_line_2("0x1p3 stop", "time: '0x1p3' is not");
    refused_at_line_2("1 speed nan", "speed rpm: 'nan'");
    refused_at_line_2("1 speed inf", "speed rpm: 'inf'");
    refused_at_line_2("1 speed -1", "speed rpm: '-1' is outside 0..100000 rpm");
    refused_at_line_2("1 speed 100001", "speed rpm: '100001' is outside");
    refused_at_line_2("1 speed_ramp max 1e300", "speed_ramp ramp time: '1e300' is outside");
    refused_at_line_2("1 pot 1.5", "pot position: '1.5' is outside 0..1");
    refused_at_line_2("1 pot_ramp 0.5 nan", "pot_ramp ramp time: 'nan'");
    refused_at_line_2("1 load 1e300", "load torque: '1e300' is outside 0..10 N m");
    refused_at_line_2("1 load -0.1", "load torque: '-0.1' is outside");
    refused_at_line_2("1 load_active -11", "load_active torque: '-11' is outside -10..10 N m");
    refused_at_line_2("1 load_fan inf", "load_fan torque at rated speed: 'inf'");
    refused_at_line_2("1 vbus nan", "vbus voltage: 'nan'");
    refused_at_line_2("1 vbus 1001", "vbus voltage: '1001' is outside 0..1000 V");
    refused_at_line_2("1 vbus_ripple -3 100", "vbus_ripple amplitude: '-3' is outside");
    refused_at_line_2("1 vbus_ripple 3 1e9", "vbus_ripple frequency: '1e9' is outside 0..10000 Hz");
    refused_at_line_2("1 current_spike 1e300", "current_spike current: '1e300' is outside");
    refused_at_line_2("1 current_spike 6 1e300", "current_spike periods: '1e300' is not a whole");
    refused_at_line_2("1 current_spike 6 0", "current_spike periods: '0' is outside 1..20000");
    refused_at_line_2("1 current_spike 6 2.5", "current_spike periods: '2.5' is not a whole");
    refused_at_line_2("1 deadtime 21", "deadtime dead time: '21' is outside 0..20 us");
    refused_at_line_2("1 noise -1", "noise sigma: '-1' is outside 0..100 codes");
    refused_at_line_2("1 zoom 0", "zoom length: '0' is outside 0..10 s (lower end excluded)");
    refused_at_line_2("1 zoom 1e9", "zoom length: '1e9'");
    refused_at_line_2("1 inverter nan", "inverter model: 'nan' is not one of averaged|switching");
    refused_at_line_2("1 deadtime_shape 1", "deadtime_shape shape: '1' is not one of");
    refused_at_line_2("1 pot 0.5x", "pot position: '0.5x' is not a decimal number");
    refused_at_line_2("1 vbus 24 12", "'vbus' takes 1 value, got 2");
    refused_at_line_2("1 vbus_ripple 1 2 3 4 5", "'vbus_ripple' takes 2 values, got 4 or more");
    refused_at_line_2("1 mark now", "'mark' takes 0 values, got 1");
    refused_at_line_2("1 start\x0b", "control character 0x0b");
    refused_at_line_2("1 sp\x01"
                      "eed 1000",
                      "control character 0x01");
    /* U+2028, a line break to some decoders: echoed as three '?' */
    refused_at_line_2("1 speed \xe2\x80\xa8", "speed rpm: '?"
                                              "?"
                                              "?' is not");
}

static void test_scenario_should_take_every_range_end(void **state)
{
    static sim_scenario_t sc;
    char err[300];
    const char *text = "0 speed 0\n"
                       "0 speed 100000\n"
                       "0 speed_ramp min 3600\n"
                       "0 pot 0\n"
                       "0 pot_ramp 1 0\n"
                       "0 load 10\n"
                       "0 load_active -10\n"
                       "0 load_fan 10\n"
                       "0 vbus 0\n"
                       "0 vbus 1000\n"
                       "0 vbus_ripple 1000 10000\n"
                       "0 current_spike -100 20000\n"
                       "0 current_spike 100 1\n"
                       "0 deadtime 20\n"
                       "0 noise 100\n"
                       "0 zoom 10\n"
                       "0 inverter switching\n"
                       "0 deadtime_shape ripple\n"
                       "3600 end\n";
    (void)state;
    if (sim_scenario_parse(text, &sc, err, sizeof(err)) != 0) {
        fail_msg("%s", err);
    }
    assert_int_equal(sc.n, 19);
    assert_cmp(sc.end_s, ==, 3600.0);
    assert_cmp(sc.ev[11].v2, ==, 20000.0);
}

static void test_every_event_value_should_have_a_range(void **state)
{
    char err[200] = "";
    (void)state;
    if (sim_scenario_check_rules(err, sizeof(err)) != 0) {
        fail_msg("%s", err);
    }
}

static void test_load_should_name_the_file_and_refuse_binary_and_huge_files(void **state)
{
    static sim_scenario_t sc;
    char err[400], path[64], big[80];
    FILE *f;
    long k;
    (void)state;
    snprintf(path, sizeof(path), "test_sim_parse_%ld.txt", (long)sizeof(sc));
    f = fopen(path, "wb");
    assert_non_null(f);
    fputs("0 start\n0.5 load 1e300\n1 end\n", f);
    fclose(f);
    assert_int_equal(sim_scenario_load(path, &sc, err, sizeof(err)), -1);
    assert_non_null(strstr(err, ":2: load torque: '1e300' is outside"));
    assert_int_equal(strncmp(err, path, strlen(path)), 0);

    f = fopen(path, "wb");
    assert_non_null(f);
    fwrite("0 start\n1 end\n\0 junk\n", 1, 21, f); /* an 'end' and then a NUL */
    fclose(f);
    assert_int_equal(sim_scenario_load(path, &sc, err, sizeof(err)), -1);
    assert_non_null(strstr(err, ":3: NUL byte"));

    snprintf(big, sizeof(big), "%s.big", path);
    f = fopen(big, "wb");
    assert_non_null(f);
    for (k = 0; k < 300000; k++) {
        fputs("# pad\n", f);
    }
    fputs("1 end\n", f);
    fclose(f);
    assert_int_equal(sim_scenario_load(big, &sc, err, sizeof(err)), -1);
    assert_non_null(strstr(err, "larger than"));

    assert_int_equal(sim_scenario_load(".", &sc, err, sizeof(err)), -1);
    assert_int_equal(sim_scenario_load("no/such/file.txt", &sc, err, sizeof(err)), -1);
    assert_non_null(strstr(err, "no/such/file.txt: cannot open"));
    remove(path);
    remove(big);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_number_should_take_plain_decimals_in_range),
        cmocka_unit_test(test_number_should_refuse_non_decimals_non_finite_and_out_of_range),
        cmocka_unit_test(test_number_should_honour_whole_and_open_ranges),
        cmocka_unit_test(test_quote_should_keep_a_message_on_one_printable_line),
        cmocka_unit_test(test_scenario_should_refuse_bad_values_naming_event_field_and_line),
        cmocka_unit_test(test_scenario_should_take_every_range_end),
        cmocka_unit_test(test_every_event_value_should_have_a_range),
        cmocka_unit_test(test_load_should_name_the_file_and_refuse_binary_and_huge_files),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
