/* Unit tests of auv-timesync's protocol (c/drivers/timesync): the $PAUVT
 * sentence as the emulator writes it, each accepted sentence as SIM.CLOCK
 * (mode, warp, server, term), the time rule (backwards refused, a jump
 * confirmed by a second sentence), each refusal reason, --clock sim refused,
 * and the hostile corpus tests/drivers/corpus/timesync/ (each file: a first
 * line "# expect: reason=count ...", then the stream). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "auv/auv_sim_clock_t.h"
#include "common/lcm_rx.h"
#include "drivers/common/drv_options.h"
#include "drivers/timesync/timesync.h"
#include "../harness/unit.h"
#include "corpus_expect.h"

#define STAMP0 INT64_C(1700000000000000)
#define MAX_CLOCKS 64

typedef struct {
    timesync_state s;
    drv_ctx ctx;
    auv_sim_clock_t clock[MAX_CLOCKS];
    int n;
} rig;

static void capture(void *user, const char *channel, const auv_type_entry_t *type, const void *data, int len)
{
    rig *r = user;
    CHECK_STR(channel, "SIM.CLOCK"); /* unprefixed: the world's clock, not the vehicle's topic */
    if (r->n < MAX_CLOCKS) {
        auv_sim_clock_t *m = &r->clock[r->n++];
        CHECK(rx_decode(type, data, len, m) == 0);
        CHECK_STR(m->server_id, "AUV1-timelink");
        auv_sim_clock_t_decode_cleanup(m);
        m->server_id = NULL;
    }
}

static rig *rig_new(void)
{
    rig *r = calloc(1, sizeof *r);
    drv_ctx_init(&r->ctx, "test", "AUV1", "TIMESYNC", capture, r);
    r->ctx.quiet = 1;
    CHECK(timesync_protocol.init(&r->s, &r->ctx) == 0);
    return r;
}

static void feed(rig *r, const char *text)
{
    timesync_protocol.feed(&r->s, &r->ctx, (const uint8_t *)text, strlen(text), STAMP0);
}

static const char *sentence(int64_t utime, double warp)
{
    static char buf[4][96];
    static int k;
    char *out = buf[k++ % 4];
    CHECK(pauvt_format(out, 96, utime, warp) > 0);
    return out;
}

static const char *raw(const char *body)
{
    static char buf[4][160];
    static int k;
    char *out = buf[k++ % 4];
    CHECK(nmea_format(out, 160, body) > 0);
    return out;
}

static int64_t count(const rig *r, const char *reason) { return drv_reasons_get(&r->ctx.reasons, reason); }

static void test_the_sentence(void)
{
    /* the checksum is NMEA's: XOR of "PAUVT,12500000,1" */
    CHECK_STR(sentence(12500000, 1.0), "$PAUVT,12500000,1*71\r\n");
    CHECK_STR(sentence(0, 10.0), "$PAUVT,0,10*77\r\n");
    CHECK_STR(sentence(7, 0.25), "$PAUVT,7,0.25*68\r\n");
}

static void test_accepted_sentences_are_the_clock(void)
{
    rig *r = rig_new();
    feed(r, sentence(12500000, 1.0));
    feed(r, sentence(12550000, 10.0));
    /* cut anywhere between reads */
    const char *s = sentence(12600000, 0.5);
    for (size_t i = 0; s[i]; i++)
        timesync_protocol.feed(&r->s, &r->ctx, (const uint8_t *)s + i, 1, STAMP0 + (int64_t)i);
    CHECK(r->n == 3);
    CHECK(r->clock[0].utime == 12500000 && r->clock[0].mode == AUV_SIM_CLOCK_T_MODE_REALTIME);
    CHECK(r->clock[0].warp == 1.0 && r->clock[0].term == 0 && r->clock[0].step == 0);
    CHECK(r->clock[1].utime == 12550000 && r->clock[1].mode == AUV_SIM_CLOCK_T_MODE_SCALED);
    CHECK(r->clock[1].warp == 10.0);
    CHECK(r->clock[2].utime == 12600000 && r->clock[2].warp == 0.5);
    CHECK(r->ctx.frames_decoded == 3 && r->ctx.reasons.total == 0);
    /* the same time again is no step back (a repeated sentence) */
    feed(r, sentence(12600000, 1.0));
    CHECK(r->n == 4 && r->ctx.reasons.total == 0);
    free(r);
}

static void test_the_time_rule(void)
{
    rig *r = rig_new();
    feed(r, sentence(100000000, 1.0));
    feed(r, sentence(99000000, 1.0));
    CHECK(count(r, "clock backwards") == 1 && r->n == 1);
    /* a jump over 60 s: refused until a second sentence confirms it */
    feed(r, sentence(200000000, 1.0));
    CHECK(count(r, "unconfirmed clock jump") == 1 && r->n == 1);
    feed(r, sentence(200050000, 1.0));
    CHECK(r->n == 2 && r->clock[1].utime == 200050000);
    /* a lone wild value between good ones is refused and forgotten */
    feed(r, sentence(900000000, 1.0));
    feed(r, sentence(200100000, 1.0));
    CHECK(count(r, "unconfirmed clock jump") == 2 && r->n == 3 && r->clock[2].utime == 200100000);
    free(r);
}

static void test_refusals(void)
{
    rig *r = rig_new();
    feed(r, "$PAUVT,1000,1*00\r\n");
    CHECK(count(r, "bad checksum") == 1);
    feed(r, "$PAUVT,1000,1\r\n");
    CHECK(count(r, "no checksum") == 1);
    feed(r, raw("PAUVT,12a,1"));
    feed(r, raw("PAUVT,-5,1"));
    feed(r, raw("PAUVT,,1"));
    feed(r, raw("PAUVT,1.5,1"));
    feed(r, raw("PAUVT,99999999999999999999,1")); /* 20 digits: over int64 */
    CHECK(count(r, "malformed time") == 5);
    feed(r, raw("PAUVT,4102444800000001,1"));
    CHECK(count(r, "time out of range") == 1);
    feed(r, raw("PAUVT,1000,x"));
    feed(r, raw("PAUVT,1000,"));
    feed(r, raw("PAUVT,1000,1e3"));
    CHECK(count(r, "malformed warp") == 3);
    feed(r, raw("PAUVT,1000,-1"));
    feed(r, raw("PAUVT,1000,2000000"));
    CHECK(count(r, "warp out of range") == 2);
    feed(r, raw("PAUVT,1000"));
    feed(r, raw("PAUVT,1000,1,2"));
    CHECK(count(r, "malformed sentence") == 2);
    feed(r, raw("GPZDA,120000.00,01,06,2025,00,00"));
    feed(r, raw("PAUVX,1000,1"));
    CHECK(count(r, "unknown sentence") == 2);
    feed(r, "\x01\x02junk");
    CHECK(count(r, "garbage") == 1);
    CHECK(r->n == 0 && r->ctx.frames_decoded == 0);
    feed(r, sentence(1000, 1.0)); /* and the link goes on */
    CHECK(r->n == 1);
    free(r);
}

static void test_a_lost_port_keeps_the_rule(void)
{
    rig *r = rig_new();
    feed(r, sentence(5000000, 1.0));
    feed(r, "$PAUVT,600"); /* cut by the loss */
    timesync_protocol.reset(&r->s, &r->ctx);
    feed(r, sentence(4000000, 1.0)); /* a simulator restarted: still no step back */
    feed(r, sentence(5100000, 1.0));
    CHECK(r->n == 2 && count(r, "clock backwards") == 1 && count(r, "truncated sentence") == 0);
    free(r);
}

static void test_clock_sim_is_refused(void)
{
    drv_options o;
    timesync_state s;
    char *argv[] = {"auv-timesync", "--device", "/dev/null", "--vehicle", "AUV1", "--clock", "sim", NULL};
    /* the usage error goes to stderr: expected */
    CHECK(drv_options_parse(&o, &timesync_protocol, &s, 7, argv) == 2);
    argv[6] = "system";
    CHECK(drv_options_parse(&o, &timesync_protocol, &s, 7, argv) == 0);
    CHECK(timesync_protocol.link_time && timesync_protocol.clock_source);
}

static long expected(rig *r, const char *name)
{
    if (!strcmp(name, "clocks"))
        return r->n;
    if (!strcmp(name, "total"))
        return (long)r->ctx.reasons.total;
    return (long)count(r, name);
}

static void *corpus_open(void) { return rig_new(); }

static void corpus_read(void *p, const uint8_t *data, size_t n, size_t k)
{
    rig *r = p;
    (void)k;
    timesync_protocol.feed(&r->s, &r->ctx, data, n, STAMP0);
}

static long corpus_figure(void *p, const char *name) { return expected(p, name); }

static const char *corpus_last_error(void *p) { return ((rig *)p)->ctx.last_error; }

static void test_hostile_corpus(void)
{
    const corpus_rig c = {11, corpus_open, corpus_read, NULL, corpus_figure, corpus_last_error};
    CHECK(corpus_check("tests/drivers/corpus/timesync", &c) >= 3); /* reads of 11 bytes */
}

static const unit_test tests[] = {
    {"timesync_the_sentence", test_the_sentence},
    {"timesync_accepted_sentences_are_the_clock", test_accepted_sentences_are_the_clock},
    {"timesync_the_time_rule", test_the_time_rule},
    {"timesync_refusals", test_refusals},
    {"timesync_a_lost_port_keeps_the_rule", test_a_lost_port_keeps_the_rule},
    {"timesync_clock_sim_is_refused", test_clock_sim_is_refused},
    {"timesync_hostile_corpus", test_hostile_corpus},
    {NULL, NULL},
};

__attribute__((constructor)) static void register_tests(void) { unit_register_list(tests); }
