/* Unit tests of the driver framework (c/drivers/common/drv_*.c): drop reasons,
 * the common flags and a driver's own, the context's publish path, the
 * port on a pseudo-terminal: raw mode, reads, a hangup, the reopening, and a
 * protocol's LCM subscriptions on an in-process LCM (memq://). */
#define _GNU_SOURCE /* posix_openpt & co. */
#include <fcntl.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <unistd.h>

#include "auv/auv_actuators_t.h"
#include "auv/auv_gps_fix_t.h"
#include "drivers/common/drv_clock.h"
#include "drivers/common/drv_options.h"
#include "drivers/common/drv_port.h"
#include "drivers/common/drv_protocol.h"
#include "drivers/common/drv_subs.h"
#include "../harness/unit.h"

static void test_reasons(void)
{
    drv_reasons r;
    drv_reasons_init(&r);
    CHECK(drv_reasons_count(&r, "bad checksum") == 1); /* first: the caller logs it */
    CHECK(drv_reasons_count(&r, "bad checksum") == 0);
    CHECK(drv_reasons_count(&r, "garbage") == 1);
    CHECK(drv_reasons_get(&r, "bad checksum") == 2 && drv_reasons_get(&r, "nope") == 0);
    CHECK(r.total == 3 && r.n == 2);
    /* more reasons than slots: none goes uncounted */
    char name[32];
    for (int i = 0; i < 100; i++) {
        snprintf(name, sizeof name, "reason %d", i);
        drv_reasons_count(&r, name);
    }
    CHECK(r.total == 103 && r.n == DRV_MAX_REASONS);
    int64_t sum = 0;
    for (int i = 0; i < r.n; i++)
        sum += r.count[i];
    CHECK(sum == 103);
}

typedef struct {
    double gain;
    int verbose;
} toy_state;

static int set_gain(void *state, const char *v, char *err, size_t n)
{
    char *end;
    ((toy_state *)state)->gain = strtod(v, &end);
    if (*end) {
        snprintf(err, n, "--gain wants a number, not '%s'", v);
        return -1;
    }
    return 0;
}

static int set_verbose(void *state, const char *v, char *err, size_t n)
{
    (void)v;
    (void)err;
    (void)n;
    ((toy_state *)state)->verbose = 1;
    return 0;
}

static const drv_flag toy_flags[] = {
    {"--gain", "G", "a gain", set_gain},
    {"--verbose", NULL, "say more", set_verbose},
    {0},
};
static const drv_protocol toy = {
    .device = "TOY", .program = "auv-toy", .summary = "a toy", .default_baud = 4800, .flags = toy_flags};

static int parse(drv_options *o, toy_state *s, const char *const *args)
{
    char *argv[32] = {"auv-toy"};
    int argc = 1;
    for (; args[argc - 1]; argc++)
        argv[argc] = (char *)args[argc - 1];
    memset(s, 0, sizeof *s);
    /* usage errors print on stderr: keep the test's output readable */
    fflush(stderr);
    int saved = dup(2), null = open("/dev/null", O_WRONLY);
    dup2(null, 2);
    int r = drv_options_parse(o, &toy, s, argc, argv);
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
    close(null);
    return r;
}

static void test_options(void)
{
    drv_options o;
    toy_state s;
    CHECK(parse(&o, &s, (const char *const[]){"--device", "/dev/ttyS0", "--vehicle", "AUV1", NULL}) == 0);
    CHECK(o.baud == 4800 && !o.tcp && !o.raw && o.clock == DRV_CLOCK_SYSTEM);
    CHECK(parse(&o, &s,
                (const char *const[]){"--tcp", "10.0.0.2:4001", "--vehicle", "AUV1", "--raw", "--clock", "sim",
                                      "--gain", "2.5", "--verbose", "--url", "udpm://x", NULL}) == 0);
    CHECK(o.raw && o.clock == DRV_CLOCK_SIM && s.gain == 2.5 && s.verbose && !strcmp(o.lcm_url, "udpm://x"));
    CHECK(parse(&o, &s, (const char *const[]){"--device", "/dev/ttyS0", "--baud", "115200", "--vehicle", "A", NULL}) ==
          0);
    CHECK(o.baud == 115200);
    /* refusals: each a usage error (2) */
    const char *const *bad[] = {
        (const char *const[]){"--vehicle", "A", NULL},
        (const char *const[]){"--device", "/dev/x", "--tcp", "h:1", "--vehicle", "A", NULL},
        (const char *const[]){"--device", "/dev/x", "--baud", "1000", "--vehicle", "A", NULL},
        (const char *const[]){"--tcp", "h:1", "--baud", "9600", "--vehicle", "A", NULL},
        (const char *const[]){"--device", "/dev/x", NULL},
        (const char *const[]){"--device", "/dev/x", "--vehicle", "A.B", NULL},
        (const char *const[]){"--device", "/dev/x", "--vehicle", "A", "--clock", "gps", NULL},
        (const char *const[]){"--device", "/dev/x", "--vehicle", "A", "--gain", "x", NULL},
        (const char *const[]){"--device", "/dev/x", "--vehicle", "A", "--gain", NULL},
        (const char *const[]){"--device", "/dev/x", "--vehicle", "A", "--what", "1", NULL},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        CHECK(parse(&o, &s, bad[i]) == 2);
    drv_port p;
    char err[200];
    CHECK(drv_port_tcp(&p, "host:4001", "t", err, sizeof err) == 0 && !strcmp(p.host, "host"));
    CHECK(drv_port_tcp(&p, "[::1]:4001", "t", err, sizeof err) == 0 && !strcmp(p.host, "::1"));
    CHECK(drv_port_tcp(&p, "host", "t", err, sizeof err) < 0);
    CHECK(drv_port_tcp(&p, "host:http", "t", err, sizeof err) < 0);
    CHECK(drv_port_tcp(&p, ":4001", "t", err, sizeof err) < 0);
}

static int sunk;
static void count_sink(void *user, const char *channel, const auv_type_entry_t *type, const void *data, int len)
{
    (void)user;
    (void)data;
    CHECK_STR(channel, "AUV7.GPS");
    CHECK(!strcmp(type->lcm_name, "auv.gps_fix_t") && len > 8);
    sunk++;
}

static void test_ctx(void)
{
    drv_ctx c;
    drv_ctx_init(&c, "t", "AUV7", "GPS", count_sink, NULL);
    c.quiet = 1;
    auv_gps_fix_t m;
    memset(&m, 0, sizeof m);
    m.vehicle = "AUV7";
    CHECK(drv_publish(&c, "GPS", auv_type_find("gps_fix_t"), &m) == 0);
    CHECK(sunk == 1 && c.messages_published == 1);
    drv_drop(&c, "bad thing", "detail %d", 42);
    CHECK_STR(c.last_error, "bad thing: detail 42");
    CHECK(drv_write(&c, (const uint8_t *)"x", 1) == -1); /* no device */
    drv_frame_ok(&c, 123);
    CHECK(c.frames_decoded == 1 && c.last_frame_utime == 123);
}

static long read_all(drv_port *p, uint8_t *buf, size_t cap, int64_t now)
{
    struct pollfd fd = {.fd = drv_port_fd(p), .events = drv_port_events(p)};
    if (fd.fd < 0 || poll(&fd, 1, 2000) <= 0)
        return 0;
    return drv_port_ready(p, fd.revents, buf, cap, now);
}

static void test_port_on_a_pty(void)
{
    int master = posix_openpt(O_RDWR | O_NOCTTY);
    CHECK(master >= 0 && grantpt(master) == 0 && unlockpt(master) == 0);
    char path[128];
    snprintf(path, sizeof path, "%s", ptsname(master));
    /* close stderr's noise of the port's log lines */
    drv_port p;
    drv_port_serial(&p, path, 57600, "test-port");
    int64_t now = 1000;
    drv_port_service(&p, now);
    CHECK(p.state == DRV_PORT_OPEN && p.reopens == 0);
    struct termios t;
    CHECK(tcgetattr(p.fd, &t) == 0);
    CHECK(cfgetispeed(&t) == B57600 && !(t.c_lflag & (ICANON | ECHO)) && !(t.c_iflag & ICRNL));
    CHECK(write(master, "ab\r\ncd", 6) == 6);
    uint8_t buf[64];
    long n = read_all(&p, buf, sizeof buf, now);
    CHECK(n == 6 && !memcmp(buf, "ab\r\ncd", 6)); /* raw: CR LF untouched */
    CHECK(drv_port_write(&p, (const uint8_t *)"hi", 2, now) == 0 && p.bytes_written == 2);
    /* the device hangs up: lost, closed, a retry scheduled within the backoff */
    close(master);
    n = read_all(&p, buf, sizeof buf, now);
    CHECK(n == -1 && p.state == DRV_PORT_CLOSED && p.retry_at_ms > now);
    CHECK(p.retry_at_ms - now <= DRV_PORT_MAX_BACKOFF_MS);
    CHECK(p.last_error[0] != '\0');
    /* it is gone for good: retries fail, the backoff grows to its cap */
    for (int i = 0; i < 10; i++) {
        now = p.retry_at_ms;
        drv_port_service(&p, now);
    }
    CHECK(p.state == DRV_PORT_CLOSED && p.backoff_ms == DRV_PORT_MAX_BACKOFF_MS);
    /* another device behind the same name would be a reopen: a new pty at a
     * symlink stands for it */
    master = posix_openpt(O_RDWR | O_NOCTTY);
    CHECK(master >= 0 && grantpt(master) == 0 && unlockpt(master) == 0);
    char link[] = "/tmp/drv_test_pty_XXXXXX";
    int lf = mkstemp(link);
    CHECK(lf >= 0);
    close(lf);
    unlink(link);
    CHECK(symlink(ptsname(master), link) == 0);
    snprintf(p.path, sizeof p.path, "%s", link);
    now = p.retry_at_ms;
    drv_port_service(&p, now);
    CHECK(p.state == DRV_PORT_OPEN && p.reopens == 1);
    drv_port_close(&p);
    close(master);
    unlink(link);
}

static void test_clock(void)
{
    drv_clock c;
    CHECK(drv_clock_init(&c, DRV_CLOCK_SYSTEM, NULL) == 0);
    int64_t t = drv_clock_now(&c);
    CHECK(t > INT64_C(1600000000000000) && t < TP_UTIME_MAX);
    c.mode = DRV_CLOCK_SIM; /* no SIM.CLOCK yet: no time */
    CHECK(drv_clock_now(&c) == -1);
    CHECK(tp_clock_offer(&c.sim, 5000000) == TP_OK && drv_clock_now(&c) == 5000000);
}

typedef struct {
    int calls;
    double rudder;
    int64_t now;
} sub_state;

static void on_toy_actuators(void *state, drv_ctx *ctx, const void *msg, int64_t now)
{
    (void)ctx;
    sub_state *s = state;
    s->calls++;
    s->rudder = ((const auv_actuators_t *)msg)->rudder_rad;
    s->now = now;
}

static const drv_subscription toy_subs[] = {{"ACTUATORS", "actuators_t", on_toy_actuators}, {0}};
static const drv_subscription bad_subs[] = {{"ACTUATORS", "no_such_t", on_toy_actuators}, {0}};

/* one pending message of the in-process LCM, then the drops it caused */
static void handle(lcm_t *lcm, drv_subs *s)
{
    CHECK(rx_handle_timeout(lcm, 100) == 1);
    drv_subs_account(s);
}

static void test_subscriptions(void)
{
    lcm_t *lcm = lcm_create("memq://");
    CHECK(lcm != NULL);
    if (!lcm)
        return;
    drv_clock clock;
    CHECK(drv_clock_init(&clock, DRV_CLOCK_SYSTEM, NULL) == 0);
    clock.mode = DRV_CLOCK_SIM; /* no SIM.CLOCK yet */
    drv_ctx c;
    drv_ctx_init(&c, "t", "AUV7", "TOY", count_sink, NULL);
    c.quiet = 1;
    sub_state st = {0};
    drv_protocol p = {.device = "TOY", .program = "t", .subscriptions = bad_subs};
    drv_subs subs;
    char err[128] = "";
    CHECK(drv_subs_init(&subs, lcm, &p, &st, &c, &clock, err, sizeof err) == -1);
    CHECK_STR(err, "subscription ACTUATORS: no such message type");
    p.subscriptions = toy_subs;
    CHECK(drv_subs_init(&subs, lcm, &p, &st, &c, &clock, err, sizeof err) == 0 && subs.n == 1);

    auv_actuators_t m = {.utime = 1000, .vehicle = "AUV7", .rudder_rad = 0.25, .seq = 1};
    auv_actuators_t_publish(lcm, "AUV7.ACTUATORS", &m);
    handle(lcm, &subs); /* before the first clock: no time rule can judge it */
    CHECK(st.calls == 0 && drv_reasons_get(&c.reasons, "no clock yet") == 1);

    CHECK(tp_clock_offer(&clock.sim, 5000) == TP_OK);
    auv_actuators_t_publish(lcm, "AUV7.ACTUATORS", &m);
    handle(lcm, &subs);
    CHECK(st.calls == 1 && st.rudder == 0.25 && st.now == 5000); /* stamped with the driver's clock */

    /* garbage, a truncated actuators_t and another type: counted, never handled */
    lcm_publish(lcm, "AUV7.ACTUATORS", "junk", 4);
    handle(lcm, &subs);
    uint8_t buf[256];
    int n = auv_actuators_t_encode(buf, 0, sizeof buf, &m);
    CHECK(n > 10);
    lcm_publish(lcm, "AUV7.ACTUATORS", buf, (unsigned)n - 3);
    handle(lcm, &subs);
    auv_gps_fix_t g;
    memset(&g, 0, sizeof g);
    g.vehicle = "AUV7";
    auv_gps_fix_t_publish(lcm, "AUV7.ACTUATORS", &g);
    handle(lcm, &subs);
    CHECK(st.calls == 1 && drv_reasons_get(&c.reasons, "undecodable ACTUATORS") == 3);
    drv_subs_account(&subs); /* accounting again counts nothing twice */
    CHECK(drv_reasons_get(&c.reasons, "undecodable ACTUATORS") == 3 && c.reasons.total == 4);

    /* another vehicle's commands are not this driver's */
    auv_actuators_t_publish(lcm, "AUV8.ACTUATORS", &m);
    rx_handle_timeout(lcm, 50);
    CHECK(st.calls == 1);
    drv_subs_close(&subs, lcm);
    lcm_destroy(lcm);
}

static const unit_test tests[] = {
    {"framework_reasons", test_reasons},
    {"framework_options", test_options},
    {"framework_ctx", test_ctx},
    {"framework_port_on_a_pty", test_port_on_a_pty},
    {"framework_clock", test_clock},
    {"framework_subscriptions", test_subscriptions},
    {NULL, NULL},
};

__attribute__((constructor)) static void register_tests(void) { unit_register_list(tests); }
