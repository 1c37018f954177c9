/* Unit tests of auv-payload's protocol (c/drivers/payload): the lcmframe
 * layout and its CRC, a contact and a look framed and published byte for
 * byte on their channels from reads cut anywhere, each refusal reason (bad
 * crc, bad header, too long, unknown topic, undecodable, truncated frame,
 * garbage), a frame found inside a refused one, and the hostile corpus
 * tests/drivers/corpus/payload/ (each file: a first line "# expect:
 * reason=count ...", then the stream). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "auv/auv_reacquire_look_t.h"
#include "auv/auv_sidescan_contact_t.h"
#include "common/lcm_rx.h"
#include "drivers/payload/payload.h"
#include "../harness/unit.h"
#include "corpus_expect.h"

#define STAMP0 INT64_C(1700000000000000)
#define MAX_OUT 16

typedef struct {
    payload_state s;
    drv_ctx ctx;
    char channel[MAX_OUT][64];
    uint8_t data[MAX_OUT][512];
    int len[MAX_OUT];
    int n;
} rig;

static void capture(void *user, const char *channel, const auv_type_entry_t *type, const void *data, int len)
{
    rig *r = user;
    (void)type;
    if (r->n < MAX_OUT && len <= 512) {
        snprintf(r->channel[r->n], 64, "%s", channel);
        memcpy(r->data[r->n], data, (size_t)len);
        r->len[r->n++] = len;
    }
}

static rig *rig_new(void)
{
    rig *r = calloc(1, sizeof *r);
    drv_ctx_init(&r->ctx, "test", "AUV1", "PAYLOAD", capture, r);
    r->ctx.quiet = 1;
    CHECK(payload_protocol.init(&r->s, &r->ctx) == 0);
    return r;
}

static void feed(rig *r, const uint8_t *b, size_t n, int64_t t)
{
    payload_protocol.tick(&r->s, &r->ctx, t);
    payload_protocol.feed(&r->s, &r->ctx, b, n, t);
}

static int64_t count(const rig *r, const char *reason) { return drv_reasons_get(&r->ctx.reasons, reason); }

/* A contact as the simulator encodes it: its LCM bytes, fingerprint first. */
static int contact_bytes(uint8_t *out, int cap)
{
    auv_sidescan_contact_t c = {
        .utime = 123456789, .vehicle = "AUV1", .contact_id = 7, .side = 1, .slant_range_m = 21.5,
        .ground_range_m = 20.0, .vehicle_altitude_m = 8.0, .north_m = 101.25, .east_m = -42.0,
        .position_sigma_m = 0.6, .confidence = 0.75f, .classification = "mine_like",
    };
    int n = auv_sidescan_contact_t_encoded_size(&c);
    CHECK(n <= cap && auv_sidescan_contact_t_encode(out, 0, cap, &c) == n);
    return n;
}

static int look_bytes(uint8_t *out, int cap)
{
    auv_reacquire_look_t m = {.utime = 5000000, .vehicle = "AUV1", .look_id = 3, .north_m = 1, .east_m = 2,
                              .position_sigma_m = 0.5, .range_m = 4, .result = 1, .confidence = 0.9f};
    int n = auv_reacquire_look_t_encoded_size(&m);
    CHECK(n <= cap && auv_reacquire_look_t_encode(out, 0, cap, &m) == n);
    return n;
}

static int frame(uint8_t *out, const char *topic, const uint8_t *payload, int n)
{
    int k = lcmframe_encode(out, LCMFRAME_MAX, topic, payload, (size_t)n);
    CHECK(k == LCMFRAME_OVERHEAD + (int)strlen(topic) + n);
    return k;
}

static void test_layout_and_crc(void)
{
    CHECK(lcmframe_crc16((const uint8_t *)"123456789", 9) == 0x29B1); /* CRC-16/CCITT-FALSE's check value */
    uint8_t f[LCMFRAME_MAX];
    const uint8_t p[3] = {1, 2, 3};
    int k = lcmframe_encode(f, sizeof f, "AB", p, 3);
    const uint8_t head[] = {0xA5, 0x4C, 2, 'A', 'B', 0, 3, 1, 2, 3};
    CHECK(k == 12 && !memcmp(f, head, sizeof head));
    uint16_t crc = lcmframe_crc16(f, 10);
    CHECK(f[10] == crc >> 8 && f[11] == (crc & 0xFF));
    CHECK(lcmframe_encode(f, sizeof f, "", p, 3) < 0 && lcmframe_encode(f, sizeof f, "lower", p, 3) < 0);
    CHECK(lcmframe_encode(f, sizeof f, "AB", p, 0) < 0 && lcmframe_encode(f, 11, "AB", p, 3) < 0);
}

static void test_contact_and_look_byte_for_byte(void)
{
    uint8_t c[512], l[512], f[2 * LCMFRAME_MAX];
    int nc = contact_bytes(c, sizeof c), nl = look_bytes(l, sizeof l);
    int k = frame(f, "CONTACTS", c, nc);
    k += frame(f + k, "LOOKS", l, nl);
    /* every read size: a frame cut anywhere between reads */
    for (int step = 1; step <= k; step += step < 8 ? 1 : 17) {
        rig *r = rig_new();
        for (int i = 0; i < k; i += step)
            feed(r, f + i, (size_t)(k - i < step ? k - i : step), STAMP0 + i);
        CHECK(r->n == 2 && r->ctx.reasons.total == 0 && r->ctx.frames_decoded == 2);
        CHECK_STR(r->channel[0], "AUV1.CONTACTS");
        CHECK(r->len[0] == nc && !memcmp(r->data[0], c, (size_t)nc));
        CHECK_STR(r->channel[1], "AUV1.LOOKS");
        CHECK(r->len[1] == nl && !memcmp(r->data[1], l, (size_t)nl));
        free(r);
    }
}

static void test_refusals(void)
{
    uint8_t c[512], l[512], f[LCMFRAME_MAX], good[LCMFRAME_MAX];
    int nc = contact_bytes(c, sizeof c), nl = look_bytes(l, sizeof l);
    int ng = frame(good, "CONTACTS", c, nc);
    rig *r = rig_new();
    int64_t t = STAMP0;
    /* a bad CRC */
    int k = frame(f, "CONTACTS", c, nc);
    f[20] ^= 0x40;
    feed(r, f, (size_t)k, t += 1000);
    CHECK(count(r, "bad crc") == 1 && r->n == 0);
    /* a topic not in the table */
    k = frame(f, "SONAR", c, nc);
    feed(r, f, (size_t)k, t += 1000);
    CHECK(count(r, "unknown topic") == 1);
    /* another type under the topic, and the right type cut short (its CRC good) */
    k = frame(f, "CONTACTS", l, nl);
    feed(r, f, (size_t)k, t += 1000);
    k = frame(f, "CONTACTS", c, nc - 1);
    feed(r, f, (size_t)k, t += 1000);
    CHECK(count(r, "undecodable") == 2 && r->n == 0);
    /* a length over the bound: refused at its header, the next frame found */
    const uint8_t huge[] = {0xA5, 0x4C, 1, 'X', 0x13, 0x88};
    feed(r, huge, sizeof huge, t += 1000);
    CHECK(count(r, "too long") == 1);
    feed(r, good, (size_t)ng, t += 1000);
    CHECK(r->n == 1);
    /* headers: topic length 0, a lower-case topic, a payload of 0 bytes */
    const uint8_t bad1[] = {0xA5, 0x4C, 0}, bad2[] = {0xA5, 0x4C, 2, 'a', 'b'}, bad3[] = {0xA5, 0x4C, 1, 'X', 0, 0};
    feed(r, bad1, sizeof bad1, t += 1000);
    feed(r, bad2, sizeof bad2, t += 1000);
    feed(r, bad3, sizeof bad3, t += 1000);
    CHECK(count(r, "bad header") == 3);
    /* garbage: one count per run, a frame between two runs (the bytes right
     * after a refused frame are its rest, not garbage of their own) */
    CHECK(count(r, "garbage") == 0);
    feed(r, good, (size_t)ng, t += 1000);
    const uint8_t junk[] = {0x00, 0xFF, 0xA5, 0x00, 'x', 'y'};
    feed(r, junk, sizeof junk, t += 1000);
    feed(r, junk, sizeof junk, t += 1000);
    feed(r, good, (size_t)ng, t += 1000);
    feed(r, junk, sizeof junk, t += 1000);
    CHECK(count(r, "garbage") == 2 && r->n == 3);
    /* a frame the link stopped sending: cut by the silence */
    feed(r, good, 30, t += 1000);
    payload_protocol.tick(&r->s, &r->ctx, t + 400000);
    CHECK(count(r, "truncated frame") == 0);
    payload_protocol.tick(&r->s, &r->ctx, t + 600000);
    CHECK(count(r, "truncated frame") == 1);
    feed(r, good, (size_t)ng, t += 700000);
    CHECK(r->n == 4 && r->ctx.frames_decoded == 4);
    for (int i = 0; i < r->n; i++)
        CHECK(r->len[i] == nc && !memcmp(r->data[i], c, (size_t)nc));
    free(r);
}

static void test_a_frame_inside_a_refused_one(void)
{
    uint8_t c[512], f[2 * LCMFRAME_MAX];
    int nc = contact_bytes(c, sizeof c);
    /* a header whose claimed frame swallows the start of a good one: its
     * CRC fails, and the search from the byte after its sync finds the good
     * frame, whose rest is still to come from the stream */
    const uint8_t head[] = {0xA5, 0x4C, 1, 'X', 0x00, 0x40}; /* 64 bytes of payload claimed */
    memcpy(f, head, sizeof head);
    int k = (int)sizeof head;
    k += frame(f + k, "CONTACTS", c, nc);
    rig *r = rig_new();
    feed(r, f, (size_t)k, STAMP0);
    CHECK(count(r, "bad crc") == 1);
    CHECK(r->n == 1 && r->len[0] == nc && !memcmp(r->data[0], c, (size_t)nc));
    CHECK_STR(r->channel[0], "AUV1.CONTACTS");
    free(r);
}

static void test_a_lost_port_forgets_the_half_frame(void)
{
    uint8_t c[512], f[LCMFRAME_MAX];
    int nc = contact_bytes(c, sizeof c), k = frame(f, "CONTACTS", c, nc);
    rig *r = rig_new();
    feed(r, f, 25, STAMP0);
    payload_protocol.reset(&r->s, &r->ctx);
    feed(r, f, (size_t)k, STAMP0 + 1000);
    CHECK(r->n == 1 && r->ctx.reasons.total == 0);
    free(r);
}

static long expected(rig *r, const char *name)
{
    if (!strcmp(name, "messages"))
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
    feed(r, data, n, STAMP0 + (int64_t)k * 1000); /* 1 ms apart */
}

static void corpus_end(void *p, size_t reads)
{
    rig *r = p;
    payload_protocol.tick(&r->s, &r->ctx, STAMP0 + (int64_t)reads * 1000 + 1000000); /* the end: a half frame is cut */
}

static long corpus_figure(void *p, const char *name) { return expected(p, name); }

static const char *corpus_last_error(void *p) { return ((rig *)p)->ctx.last_error; }

static void test_hostile_corpus(void)
{
    const corpus_rig c = {13, corpus_open, corpus_read, corpus_end, corpus_figure, corpus_last_error};
    CHECK(corpus_check("tests/drivers/corpus/payload", &c) >= 3); /* reads of 13 bytes */
}

static const unit_test tests[] = {
    {"payload_layout_and_crc", test_layout_and_crc},
    {"payload_contact_and_look_byte_for_byte", test_contact_and_look_byte_for_byte},
    {"payload_refusals", test_refusals},
    {"payload_a_frame_inside_a_refused_one", test_a_frame_inside_a_refused_one},
    {"payload_a_lost_port_forgets_the_half_frame", test_a_lost_port_forgets_the_half_frame},
    {"payload_hostile_corpus", test_hostile_corpus},
    {NULL, NULL},
};

__attribute__((constructor)) static void register_tests(void) { unit_register_list(tests); }
