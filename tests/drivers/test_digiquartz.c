/* Unit tests of the Digiquartz-style pressure protocol (c/drivers/pressure/
 * digiquartz.c): commands, answers, units, depth, and every refusal. */
#include <math.h>
#include <string.h>

#include "drivers/pressure/digiquartz.h"
#include "../harness/unit.h"

/* Feeds a string; returns the answers decoded and counts refusals. */
static int feed(dq_framer *f, const char *bytes, int refused[DQ_RESULT_COUNT], dq_answer *last)
{
    int ok = 0;
    for (const char *p = bytes; *p; p++) {
        int r = dq_framer_push(f, (uint8_t)*p, 0, 1, last);
        if (r == DQ_OK)
            ok++;
        else if (r > 0)
            refused[r]++;
    }
    return ok;
}

static void test_dq_commands_and_answers(void)
{
    char cmd[32];
    CHECK(dq_format_command(cmd, sizeof cmd, 1, 0, "P3") == 9);
    CHECK_STR(cmd, "*0100P3\r\n");
    CHECK(dq_format_command(cmd, sizeof cmd, 1, 0, "UN=2") > 0);
    CHECK_STR(cmd, "*0100UN=2\r\n");
    CHECK(dq_format_command(cmd, sizeof cmd, 100, 0, "P3") == -1);
    CHECK(dq_format_command(cmd, 4, 1, 0, "P3") == -1);
    dq_framer f;
    dq_framer_init(&f);
    dq_answer a;
    int refused[DQ_RESULT_COUNT] = {0};
    CHECK(feed(&f, "*000114.7069\r\n", refused, &a) == 1);
    CHECK(a.host == 0 && a.sensor == 1);
    CHECK_NEAR(a.value, 14.7069, 1e-12);
    /* garbage, another sensor's answer, a bad value, a bad byte, an endless line, then a good one */
    char endless[200];
    memset(endless, '1', sizeof endless - 1);
    endless[0] = '*';
    endless[sizeof endless - 1] = '\0';
    CHECK(feed(&f, "xyz*000214.7\r\n*00011a.0\r\n*0001\x01" "2\r\n", refused, &a) == 0);
    CHECK(feed(&f, endless, refused, &a) == 0);
    CHECK(feed(&f, "\r\n*00011013.25\r\n", refused, &a) == 1);
    CHECK_NEAR(a.value, 1013.25, 1e-12);
    CHECK(f.garbage_bytes == 3);
    CHECK(refused[DQ_WRONG_ADDRESS] == 1 && refused[DQ_BAD_VALUE] == 1 && refused[DQ_BAD_CHAR] == 1);
    CHECK(refused[DQ_TOO_LONG] == 1);
    CHECK(feed(&f, "*AB01\r\n*00\r\n", refused, &a) == 0 && refused[DQ_NOT_AN_ANSWER] == 2);
    /* real lines: spaces and a unit word around the number; the host's own
     * commands read back on a two-wire RS-485 line are not answers nor errors */
    memset(refused, 0, sizeof refused);
    CHECK(feed(&f, "*0001 14.7069 psia\r\n", refused, &a) == 1);
    CHECK_NEAR(a.value, 14.7069, 1e-12);
    CHECK(feed(&f, "*0001-1.25 C\r\n*000122.031\r\n", refused, &a) == 2);
    CHECK_NEAR(a.value, 22.031, 1e-12);
    CHECK(feed(&f, "*0100P3\r\n*0100EW\r\n", refused, &a) == 0 && refused[DQ_OWN_COMMAND] == 2);
    CHECK(refused[DQ_BAD_VALUE] == 0 && refused[DQ_WRONG_ADDRESS] == 0);
    CHECK(feed(&f, "*000114.7 psia psia\r\n*000114.7psia\r\n", refused, &a) == 0 && refused[DQ_BAD_VALUE] == 2);
}

static void test_dq_units_and_depth(void)
{
    double pa;
    CHECK(dq_pressure_pa(14.6959, DQ_PSI, &pa) == DQ_OK);
    CHECK_NEAR(pa, 101325.0, 1.0);
    CHECK(dq_pressure_pa(1013.25, DQ_HPA, &pa) == DQ_OK && fabs(pa - 101325.0) < 1e-6);
    CHECK(dq_pressure_pa(10.0, DQ_MH2O, &pa) == DQ_OK && fabs(pa - 98066.5) < 1e-6);
    CHECK(dq_pressure_pa(1.0, 9, &pa) == DQ_BAD_VALUE);
    CHECK(dq_pressure_pa(-0.1, DQ_BAR, &pa) == DQ_VALUE_RANGE);
    CHECK(dq_pressure_pa(2001.0, DQ_BAR, &pa) == DQ_VALUE_RANGE);
    dq_depth_model m = DQ_DEPTH_DEFAULTS;
    CHECK_NEAR(dq_depth_m(&m, 101325.0), 0.0, 1e-12);
    /* 10 m of sea water at 1025 kg/m^3 */
    CHECK_NEAR(dq_depth_m(&m, 101325.0 + 1025.0 * 9.81 * 10.0), 10.0, 1e-9);
    CHECK(dq_depth_m(&m, 100000.0) < 0.0); /* out of the water */
    double t;
    CHECK(dq_temperature_c(12.5, &t) == DQ_OK && t == 12.5);
    CHECK(dq_temperature_c(80.0, &t) == DQ_VALUE_RANGE);
    CHECK(dq_temperature_c(NAN, &t) == DQ_BAD_VALUE);
}

static const unit_test tests[] = {
    {"dq_commands_and_answers", test_dq_commands_and_answers},
    {"dq_units_and_depth", test_dq_units_and_depth},
    {NULL, NULL},
};

__attribute__((constructor)) static void register_tests(void) { unit_register_list(tests); }
