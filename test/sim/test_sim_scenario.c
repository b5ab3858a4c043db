/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* test_sim_scenario.c - the scenario parser, and every shipped scenario file. */
#include "test_support.h"

#include <dirent.h>
#include <stdio.h>
#include <string.h>

#include "sim_scenario.h"

static void test_parser_should_read_events_values_and_comments(void **state)
{
    static sim_scenario_t sc;
    char err[128];
    const char *text = "# a comment\n"
                       "\n"
                       "0.0 speed 2000   # trailing comment\n"
                       "0.1 start\n"
                       "1.5 speed_ramp max 2.5\n"
                       "2 vbus_ripple 3 100\n"
                       "2.5 current_spike 6\n"
                       "3 zoom\n"
                       "4.0 end\n";
    (void)state;
    assert_int_equal(sim_scenario_parse(text, &sc, err, sizeof(err)), 0);
    assert_int_equal(sc.n, 7);
    assert_int_equal(sc.ev[0].kind, SIM_EV_SPEED);
    assert_cmp(sc.ev[0].v1, ==, 2000.0);
    assert_int_equal(sc.ev[1].kind, SIM_EV_START);
    assert_cmp(sc.ev[1].t_s, ==, 0.1);
    assert_int_equal(sc.ev[2].kind, SIM_EV_SPEED_RAMP);
    assert_cmp(sc.ev[2].v1, ==, SIM_SPEED_MAX);
    assert_cmp(sc.ev[2].v2, ==, 2.5);
    assert_cmp(sc.ev[3].v1, ==, 3.0);
    assert_cmp(sc.ev[3].v2, ==, 100.0);
    assert_int_equal(sc.ev[4].kind, SIM_EV_CURRENT_SPIKE);
    assert_int_equal(sc.ev[5].kind, SIM_EV_ZOOM);
    assert_cmp(sc.end_s, ==, 4.0);
    assert_string_equal(sim_event_name(SIM_EV_LOAD_FAN), "load_fan");
}

static void test_parser_should_reject_bad_lines_naming_the_line(void **state)
{
    static sim_scenario_t sc;
    char err[128];
    (void)state;
    assert_int_equal(sim_scenario_parse("0 frobnicate\n1 end\n", &sc, err, sizeof(err)), -1);
    assert_non_null(strstr(err, "line 1"));
    assert_int_equal(sim_scenario_parse("0 start\n0 pot\n1 end\n", &sc, err, sizeof(err)), -1);
    assert_non_null(strstr(err, "line 2"));
    assert_int_equal(sim_scenario_parse("1 start\n0.5 stop\n2 end\n", &sc, err, sizeof(err)), -1);
    assert_non_null(strstr(err, "backwards"));
    assert_int_equal(sim_scenario_parse("0 start\n", &sc, err, sizeof(err)), -1);
    assert_non_null(strstr(err, "end"));
    assert_int_equal(sim_scenario_parse("0 load abc\n1 end\n", &sc, err, sizeof(err)), -1);
    assert_int_equal(sim_scenario_parse("x start\n1 end\n", &sc, err, sizeof(err)), -1);
    assert_int_equal(sim_scenario_parse("1 end\n2 start\n", &sc, err, sizeof(err)), -1);
}

static void test_every_shipped_scenario_should_parse_and_end(void **state)
{
    static sim_scenario_t sc;
    char err[128], path[512];
    DIR *d = opendir(SIM_SCENARIO_DIR);
    struct dirent *e;
    int n = 0;
    (void)state;
    assert_non_null(d);
    while ((e = readdir(d)) != NULL) {
        size_t len = strlen(e->d_name);
        if (len < 5 || strcmp(e->d_name + len - 4, ".txt") != 0) {
            continue;
        }
        snprintf(path, sizeof(path), "%s/%s", SIM_SCENARIO_DIR, e->d_name);
        if (sim_scenario_load(path, &sc, err, sizeof(err)) != 0) {
            fail_msg("%s: %s", e->d_name, err);
        }
        assert_cmp(sc.end_s, >, 0.0);
        printf("measured: scenario %s: %d events, %.2f s\n", e->d_name, sc.n, sc.end_s);
        n++;
    }
    closedir(d);
    assert_cmp(n, >=, 8);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_parser_should_read_events_values_and_comments),
        cmocka_unit_test(test_parser_should_reject_bad_lines_naming_the_line),
        cmocka_unit_test(test_every_shipped_scenario_should_parse_and_end),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
