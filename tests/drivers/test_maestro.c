/* Unit tests of the Maestro protocol (c/drivers/servo/maestro.c) and the
 * channel table (actuator_map.c, am_config.c): the published command
 * examples byte for byte, replies good and bad, limits, neutral, reversed
 * channels, the watchdog's timing, the table's errors, and the hostile corpus
 * (tests/drivers/corpus/maestro) through the fuzz target's own check. */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "drivers/fuzz/fuzz_maestro.h"
#include "drivers/servo/actuator_map.h"
#include "../harness/unit.h"

static const maestro_framing COMPACT = {0, 0};
static const maestro_framing POLOLU = {1, 12};

static int bytes_are(const uint8_t *got, size_t n, const uint8_t *want, size_t wn)
{
    return n == wn && !memcmp(got, want, n);
}
#define BYTES(got, n, ...) bytes_are(got, n, (const uint8_t[]){__VA_ARGS__}, sizeof((const uint8_t[]){__VA_ARGS__}))

static void test_published_examples(void)
{
    uint8_t b[MAESTRO_MAX_COMMAND];
    /* channel 2 to 1500 us (6000 quarter-us): low 7 bits 0x70, high 7 bits 0x2E */
    CHECK(BYTES(b, maestro_set_target(&COMPACT, b, 2, 6000), 0x84, 0x02, 0x70, 0x2E));
    CHECK(BYTES(b, maestro_set_target(&POLOLU, b, 2, 6000), 0xAA, 0x0C, 0x04, 0x02, 0x70, 0x2E));
    /* channel 5's speed to 140 (17.5 us/ms), its acceleration to 4 */
    CHECK(BYTES(b, maestro_set_speed(&COMPACT, b, 5, 140), 0x87, 0x05, 0x0C, 0x01));
    CHECK(BYTES(b, maestro_set_acceleration(&COMPACT, b, 5, 4), 0x89, 0x05, 0x04, 0x00));
    CHECK(BYTES(b, maestro_set_acceleration(&POLOLU, b, 5, 4), 0xAA, 0x0C, 0x09, 0x05, 0x04, 0x00));
    /* channel 3 off (0) and channel 4 to 1500 us in one command */
    uint16_t two[2] = {0, 6000};
    CHECK(BYTES(b, maestro_set_multiple_targets(&COMPACT, b, 3, 2, two), 0x9F, 0x02, 0x03, 0x00, 0x00, 0x70, 0x2E));
    CHECK(BYTES(b, maestro_get_position(&COMPACT, b, 0), 0x90, 0x00));
    CHECK(BYTES(b, maestro_get_position(&POLOLU, b, 0), 0xAA, 0x0C, 0x10, 0x00));
    CHECK(BYTES(b, maestro_get_moving_state(&COMPACT, b), 0x93));
    CHECK(BYTES(b, maestro_get_errors(&COMPACT, b), 0xA1));
    CHECK(BYTES(b, maestro_get_errors(&POLOLU, b), 0xAA, 0x0C, 0x21));
    CHECK(BYTES(b, maestro_go_home(&COMPACT, b), 0xA2));
    CHECK(BYTES(b, maestro_go_home(&POLOLU, b), 0xAA, 0x0C, 0x22));
    /* the baud rate indication 0xAA, as a whole Pololu Get Errors in either framing */
    CHECK(BYTES(b, maestro_baud_indication(&COMPACT, b), 0xAA, 0x0C, 0x21));
    maestro_framing dev3 = {1, 3};
    CHECK(BYTES(b, maestro_baud_indication(&dev3, b), 0xAA, 0x03, 0x21));
    /* the extremes of a 14-bit number, and what the protocol cannot say */
    CHECK(BYTES(b, maestro_set_target(&COMPACT, b, 23, 16383), 0x84, 0x17, 0x7F, 0x7F));
    CHECK(maestro_set_target(&COMPACT, b, 24, 6000) == 0);
    CHECK(maestro_set_target(&COMPACT, b, 0, 16384) == 0);
    CHECK(maestro_set_acceleration(&COMPACT, b, 0, 256) == 0);
    CHECK(maestro_set_multiple_targets(&COMPACT, b, 23, 2, two) == 0);
    CHECK(maestro_set_multiple_targets(&COMPACT, b, 0, 0, two) == 0);
    maestro_framing bad = {1, 128};
    CHECK(maestro_go_home(&bad, b) == 0);
    uint16_t all[MAESTRO_MAX_CHANNELS] = {0};
    CHECK(maestro_set_multiple_targets(&POLOLU, b, 0, MAESTRO_MAX_CHANNELS, all) <= MAESTRO_MAX_COMMAND);
    CHECK_STR(maestro_error_name(4), "serial protocol error");
    CHECK(maestro_error_name(9) == NULL);
}

static void test_replies(void)
{
    maestro_rx rx;
    maestro_rx_event ev;
    maestro_rx_init(&rx);
    /* a byte nobody asked for */
    CHECK(maestro_rx_push(&rx, 0x55, &ev) == MRX_UNEXPECTED);
    /* a position of 1500 us is 0x70 0x17: full bytes, low first */
    maestro_rx_expect(&rx, MAESTRO_Q_POSITION, 7);
    maestro_rx_expect(&rx, MAESTRO_Q_ERRORS, 0);
    maestro_rx_expect(&rx, MAESTRO_Q_MOVING, 0);
    CHECK(maestro_rx_push(&rx, 0x70, &ev) == MRX_NONE);
    CHECK(maestro_rx_push(&rx, 0x17, &ev) == MRX_POSITION && ev.channel == 7 && ev.value == 6000);
    CHECK(maestro_rx_push(&rx, 0x10, &ev) == MRX_NONE);
    CHECK(maestro_rx_push(&rx, 0x01, &ev) == MRX_ERRORS && ev.value == 0x110);
    CHECK(maestro_rx_push(&rx, 0x01, &ev) == MRX_MOVING && ev.value == 1);
    CHECK(rx.replies == 3 && rx.refused_bytes == 1);
    /* impossible replies */
    maestro_rx_expect(&rx, MAESTRO_Q_POSITION, 0);
    maestro_rx_expect(&rx, MAESTRO_Q_ERRORS, 0);
    maestro_rx_expect(&rx, MAESTRO_Q_MOVING, 0);
    maestro_rx_push(&rx, 0x00, &ev);
    CHECK(maestro_rx_push(&rx, 0x40, &ev) == MRX_BAD_POSITION); /* 16384 */
    maestro_rx_push(&rx, 0x00, &ev);
    CHECK(maestro_rx_push(&rx, 0x02, &ev) == MRX_BAD_ERRORS); /* bit 9: no meaning */
    CHECK(maestro_rx_push(&rx, 0x07, &ev) == MRX_BAD_MOVING);
    CHECK(rx.refused_bytes == 6);
    /* a reply cut by the deadline; the next one starts clean */
    maestro_rx_expect(&rx, MAESTRO_Q_POSITION, 1);
    maestro_rx_expect(&rx, MAESTRO_Q_POSITION, 2);
    maestro_rx_push(&rx, 0x70, &ev);
    CHECK(maestro_rx_timeout(&rx) == 2 && rx.refused[MRX_TIMEOUT] == 2 && rx.refused_bytes == 7);
    maestro_rx_expect(&rx, MAESTRO_Q_POSITION, 3);
    maestro_rx_push(&rx, 0xA0, &ev);
    CHECK(maestro_rx_push(&rx, 0x0F, &ev) == MRX_POSITION && ev.channel == 3 && ev.value == 4000);
    /* a host that never reads: the queue does not grow past its size */
    for (int i = 0; i < MAESTRO_RX_PENDING; i++)
        CHECK(maestro_rx_expect(&rx, MAESTRO_Q_MOVING, 0) == MRX_NONE);
    CHECK(maestro_rx_expect(&rx, MAESTRO_Q_MOVING, 0) == MRX_QUEUE_FULL);
    CHECK_STR(maestro_rx_result_name(MRX_TIMEOUT), "reply timeout");
}

static const char TABLE[] = "# AUV1's fins and thruster\n"
                            "protocol compact\n"
                            "watchdog 0.5   # s\n"
                            "channel 0 rudder      1500 500 1100 1900\n"
                            "channel 1 stern_plane 1500 500 1100 1900 reversed speed 100 accel 4\n"
                            "channel 4 prop        1490 0.25 1000 2000\n";

static void load(am_config *cfg, const char *text)
{
    char err[256] = "";
    if (am_config_parse(cfg, text, strlen(text), "t.cfg", err, sizeof err))
        UNIT_FAIL("%s", err);
}

static void test_table_and_limits(void)
{
    am_config cfg;
    load(&cfg, TABLE);
    CHECK(cfg.n == 3 && cfg.watchdog_us == 500000 && !cfg.framing.pololu);
    CHECK(cfg.ch[1].reversed && cfg.ch[1].speed == 100 && cfg.ch[1].accel == 4 && cfg.ch[2].channel == 4);
    am_state st;
    am_state_init(&st);
    uint16_t t[MAESTRO_MAX_CHANNELS];
    /* zero is neutral; +0.2 rad is +100 us, reversed on the stern plane; 400 rpm is +100 us */
    am_command c = {1000, 0.0, 0.0, 0.0};
    CHECK(am_apply(&cfg, &st, &c, 1000, t) == AM_OK);
    CHECK(t[0] == 6000 && t[1] == 6000 && t[2] == 5960);
    c = (am_command){2000, 0.2, 0.2, 400.0};
    CHECK(am_apply(&cfg, &st, &c, 2000, t) == AM_OK);
    CHECK(t[0] == 6400 && t[1] == 5600 && t[2] == 6360);
    CHECK(st.clamped == 0);
    /* past the limits: clamped, and each clamp counted */
    c = (am_command){3000, 2.0, -2.0, -1e6};
    CHECK(am_apply(&cfg, &st, &c, 3000, t) == AM_OK);
    CHECK(t[0] == 7600 && t[1] == 7600 && t[2] == 4000 && st.clamped == 3);
    /* non-finite values move nothing, and do not count as fresh */
    uint16_t before[MAESTRO_MAX_CHANNELS];
    memcpy(before, t, sizeof t);
    c = (am_command){4000, NAN, 0.0, 0.0};
    CHECK(am_apply(&cfg, &st, &c, 4000, t) == AM_NON_FINITE);
    c = (am_command){4000, 0.0, 0.0, INFINITY};
    CHECK(am_apply(&cfg, &st, &c, 4000, t) == AM_NON_FINITE);
    CHECK(!memcmp(before, t, sizeof t) && st.refused[AM_NON_FINITE] == 2 && st.in.newest == 3000);
    /* the time rule: invalid, from the future, out of order; and stale */
    c = (am_command){-1, 0, 0, 0};
    CHECK(am_apply(&cfg, &st, &c, 4000, t) == AM_INVALID_TIME);
    c = (am_command){4000 + TP_FUTURE_TOLERANCE_US + 1, 0, 0, 0};
    CHECK(am_apply(&cfg, &st, &c, 4000, t) == AM_FUTURE);
    c = (am_command){2500, 0, 0, 0};
    CHECK(am_apply(&cfg, &st, &c, 4000, t) == AM_OUT_OF_ORDER);
    c = (am_command){3500, 0, 0, 0};
    CHECK(am_apply(&cfg, &st, &c, 3500 + 500001, t) == AM_STALE);
    c = (am_command){INT64_MAX, 0, 0, 0};
    CHECK(am_apply(&cfg, &st, &c, INT64_MAX, t) == AM_INVALID_TIME);
    CHECK(!memcmp(before, t, sizeof t) && st.applied == 3);
    CHECK_STR(am_verdict_name(AM_STALE), "stale");
}

static void test_watchdog(void)
{
    am_config cfg;
    load(&cfg, TABLE);
    am_state st;
    am_state_init(&st);
    uint16_t t[MAESTRO_MAX_CHANNELS] = {0};
    /* at the start: neutral once, saying no command came */
    CHECK(am_watchdog(&cfg, &st, 0, t) == AM_WD_NO_COMMAND);
    CHECK(t[0] == 6000 && t[1] == 6000 && t[2] == 5960);
    CHECK(am_watchdog(&cfg, &st, 10, t) == AM_WD_QUIET);
    am_command c = {1000000, 0.1, 0.1, 100};
    CHECK(am_apply(&cfg, &st, &c, 1000000, t) == AM_OK && st.resumed);
    /* fresh up to the timeout (0.5 s after the newest command's stamp), stale past it */
    CHECK(am_watchdog(&cfg, &st, 1500000, t) == AM_WD_QUIET);
    c.utime = 1400000;
    CHECK(am_apply(&cfg, &st, &c, 1500000, t) == AM_OK && !st.resumed);
    CHECK(am_watchdog(&cfg, &st, 1900000, t) == AM_WD_QUIET);
    t[0] = 0;
    CHECK(am_watchdog(&cfg, &st, 1900001, t) == AM_WD_TIMEOUT && t[0] == 6000);
    /* once: the loop turning again says nothing more */
    CHECK(am_watchdog(&cfg, &st, 5000000, t) == AM_WD_QUIET && st.watchdog_trips == 2);
    /* commands again: resumed */
    c.utime = 5000000;
    CHECK(am_apply(&cfg, &st, &c, 5000000, t) == AM_OK && st.resumed && t[0] == 6200);
    CHECK(am_watchdog(&cfg, &st, 5000001, t) == AM_WD_QUIET);
    /* a clock that jumps to the far end cannot overflow the age */
    CHECK(am_watchdog(&cfg, &st, INT64_MAX, t) == AM_WD_TIMEOUT);
    CHECK_HAS(am_watchdog_name(AM_WD_TIMEOUT), "neutral");
}

static void test_encode_from_table(void)
{
    am_config cfg;
    load(&cfg, TABLE);
    uint8_t out[AM_MAX_OUT];
    uint16_t t[MAESTRO_MAX_CHANNELS];
    am_neutral(&cfg, t);
    CHECK(BYTES(out, am_encode_targets(&cfg, t, out), 0x84, 0, 0x70, 0x2E, 0x84, 1, 0x70, 0x2E, 0x84, 4, 0x48, 0x2E));
    CHECK(BYTES(out, am_encode_limits(&cfg, out), 0x87, 0, 0, 0, 0x89, 0, 0, 0, 0x87, 1, 100, 0, 0x89, 1, 4, 0, 0x87,
                4, 0, 0, 0x89, 4, 0, 0));
    load(&cfg, "protocol pololu 3\nwatchdog 1\nchannel 23 prop 1500 1 1000 2000\n");
    am_neutral(&cfg, t);
    CHECK(BYTES(out, am_encode_targets(&cfg, t, out), 0xAA, 3, 0x04, 23, 0x70, 0x2E));
}

static void refused(const char *text, const char *where, const char *what)
{
    am_config cfg;
    char err[256] = "";
    if (am_config_parse(&cfg, text, strlen(text), "t.cfg", err, sizeof err) == 0) {
        UNIT_FAIL("accepted: %s", text);
        return;
    }
    CHECK_HAS(err, where);
    CHECK_HAS(err, what);
}

static void test_table_errors(void)
{
    refused("watchdog 1\nchannel 0 rudder 1500 500 1100 1900\nchannel 0 prop 1500 1 1000 2000\n", "t.cfg:3:9:",
            "already in the table");
    refused("watchdog 1\nchannel 24 rudder 1500 500 1100 1900\n", "t.cfg:2:9:", "outside 0..23");
    refused("watchdog 1\nchannel 0 aileron 1500 500 1100 1900\n", "t.cfg:2:11:", "unknown actuator");
    refused("watchdog 1\nchannel 0 rudder 1500 -500 1100 1900\n", "t.cfg:2:23:", "outside");
    refused("watchdog 1\nchannel 0 rudder 1000 500 1100 1900\n", "t.cfg:2:18:", "neutral 1000 us is outside");
    refused("watchdog 1\nchannel 0 rudder 1500 500 1900 1100\n", "t.cfg:2:27:", "not below max");
    refused("watchdog 1\nchannel 0 rudder 1500 500 1100 5000\n", "t.cfg:2:32:", "max [us]");
    refused("watchdog 1\nchannel 0 rudder 1500 nan 1100 1900\n", "t.cfg:2:23:", "not a number");
    refused("watchdog 1\nchannel 0 rudder 1500 500 1100\n", "t.cfg:2:27:", "missing");
    refused("watchdog 1\nchannel 0 rudder 1500 500 1100 1900 speed 1.5\n", "t.cfg:2:43:", "not a whole number");
    refused("watchdog 1\nchannel 0 rudder 1500 500 1100 1900 upside_down\n", "t.cfg:2:37:", "unexpected");
    refused("watchdog 1\nwatchdog 2\n", "t.cfg:2:1:", "already set");
    refused("watchdog 0\n", "t.cfg:1:10:", "watchdog [s]");
    refused("watchdog 0x10\n", "t.cfg:1:10:", "not a number");
    refused("watchdog 1\nchannel 0 rudder 1500 500 1100 1900 speed inf\n", "t.cfg:2:43:", "not a number");
    refused("channel 0 rudder 1500 500 1100 1900\n", "t.cfg:1:1:", "no 'watchdog");
    refused("watchdog 1\n", "t.cfg:1:1:", "table is empty");
    refused("watchdog 1\nprotocol serial\n", "t.cfg:2:10:", "protocol");
    refused("watchdog 1\nprotocol pololu 200\n", "t.cfg:2:17:", "device number");
    refused("watchdog 1\n  rudder 0\n", "t.cfg:2:3:", "unknown keyword");
    refused("watchdog 1\nchannel 0 rudder\x01 1500\n", "t.cfg:2:17:", "printable ASCII");
    char nul[] = "watchdog 1\nchannel\0 0 rudder 1500 500 1100 1900\n";
    am_config cfg;
    char err[256];
    CHECK(am_config_parse(&cfg, nul, sizeof nul - 1, "t.cfg", err, sizeof err) == -1);
    CHECK_HAS(err, "t.cfg:2:8:");
    CHECK(am_config_load(&cfg, "/nonexistent/table", err, sizeof err) == -1);
    CHECK_HAS(err, "cannot open");
}

/* Every file of the hostile corpus passes the fuzz target's check (no byte
 * unaccounted for), and together they hit every refusal. */
static void test_hostile_corpus(void)
{
    const char *dir = getenv("MAESTRO_CORPUS");
    if (!dir)
        dir = "tests/drivers/corpus/maestro"; /* the tests run from the checkout's root */
    DIR *d = opendir(dir);
    if (!d) {
        UNIT_FAIL("cannot open %s (run from the checkout's root, or set MAESTRO_CORPUS)", dir);
        return;
    }
    uint64_t seen[MRX_N_RESULTS] = {0};
    int files = 0, tables_refused = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.')
            continue;
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        static uint8_t buf[65536];
        FILE *f = fopen(path, "rb");
        if (!f)
            continue;
        size_t n = fread(buf, 1, sizeof buf, f);
        fclose(f);
        maestro_rx rx;
        memset(&rx, 0, sizeof rx);
        tables_refused += maestro_fuzz_one(buf, n, &rx) != 0;
        for (int r = 0; r < MRX_N_RESULTS; r++)
            seen[r] += rx.refused[r];
        files++;
    }
    closedir(d);
    CHECK(files >= 8);
    CHECK(tables_refused >= 2);
    for (int r = MRX_UNEXPECTED; r < MRX_N_RESULTS; r++)
        if (!seen[r])
            UNIT_FAIL("no corpus file is refused as '%s'", maestro_rx_result_name((maestro_rx_result)r));
}

static const unit_test tests[] = {
    {"maestro_published_examples", test_published_examples},
    {"maestro_replies", test_replies},
    {"maestro_table_and_limits", test_table_and_limits},
    {"maestro_watchdog", test_watchdog},
    {"maestro_encode_from_table", test_encode_from_table},
    {"maestro_table_errors", test_table_errors},
    {"maestro_hostile_corpus", test_hostile_corpus},
    {NULL, NULL},
};

__attribute__((constructor)) static void register_tests(void) { unit_register_list(tests); }
