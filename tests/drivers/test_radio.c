/* Unit tests of auv-radio (c/drivers/radio): the byte pipe's framing in
 * noise, and the chunk reassembly's every bad input (docs/radio.md,
 * "Transfers"): out of order, duplicated, another transfer's chunk, a wrong
 * digest, too many (past the count, past the size, more chunks than the size
 * allows), a transfer that never ends, a flood; a restart resuming from the
 * spool; the whole published byte for byte through the protocol, with its
 * acknowledgement on the pipe; acoustic commands run once. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "auv/auv_mission_command_t.h"
#include "auv/auv_modem_rx_t.h"
#include "auv/auv_radio_ack_t.h"
#include "auv/auv_radio_chunk_t.h"
#include "auv/auv_radio_frame_t.h"
#include "auv/auv_radio_report_t.h"
#include "common/auth_mac.h"
#include "common/crc32.h"
#include "common/lcm_rx.h"
#include "drivers/radio/radio.h"
#include "drivers/radio/radio_spool.h"
#include "team/team_codec.h"
#include "../harness/unit.h"

#define T0 1700000000.0
#define DATA_LEN 5000
#define CHUNK 512
#define N_CHUNKS 10

static char spool[256];
static uint8_t DATA[DATA_LEN];

static void spool_new(void)
{
    snprintf(spool, sizeof spool, "/tmp/test_radio.XXXXXX");
    CHECK(mkdtemp(spool) != NULL);
}

static int files(const char *ext)
{
    DIR *d = opendir(spool);
    int n = 0;
    struct dirent *e;
    while (d && (e = readdir(d)) != NULL) {
        size_t k = strlen(e->d_name), m = strlen(ext);
        n += k > m && !strcmp(e->d_name + k - m, ext);
    }
    if (d)
        closedir(d);
    return n;
}

static void spool_remove(void)
{
    DIR *d = opendir(spool);
    struct dirent *e;
    char path[600];
    while (d && (e = readdir(d)) != NULL)
        if (e->d_name[0] != '.') {
            snprintf(path, sizeof path, "%s/%s", spool, e->d_name);
            unlink(path);
        }
    if (d)
        closedir(d);
    rmdir(spool);
}

typedef struct {
    auv_radio_chunk_t c;
    char sha[65];
} chunk;

/* Chunk i of DATA's transfer tid, CHUNK bytes each (the last shorter). */
static chunk make(int64_t tid, int i)
{
    chunk k;
    memset(&k, 0, sizeof k);
    auth_sha256_hex(DATA, DATA_LEN, k.sha);
    k.c.transfer_id = tid;
    k.c.vehicle = "AUV1";
    k.c.channel = "PLUGIN_UPLOAD";
    k.c.index = i;
    k.c.count = N_CHUNKS;
    k.c.total_bytes = DATA_LEN;
    k.c.n_bytes = i < N_CHUNKS - 1 ? CHUNK : DATA_LEN - CHUNK * (N_CHUNKS - 1);
    k.c.data = DATA + (i < N_CHUNKS ? i : 0) * CHUNK;
    return k;
}

typedef struct {
    drv_ctx ctx;
    ra_assembler a;
} rig;

static rig *rig_open(double expiry)
{
    rig *r = calloc(1, sizeof *r);
    char err[200];
    drv_ctx_init(&r->ctx, "test", "AUV1", "RADIO", NULL, NULL);
    r->ctx.quiet = 1;
    CHECK(ra_open(&r->a, &r->ctx, "AUV1", spool, expiry, err, sizeof err) == 0);
    return r;
}

static ra_offer offer(rig *r, chunk *k, double t)
{
    k->c.sha256_hex = k->sha;
    ra_offer o;
    ra_offer_chunk(&r->a, &r->ctx, &k->c, t, &o);
    return o;
}

static int64_t reason(rig *r, const char *why) { return drv_reasons_get(&r->ctx.reasons, why); }

static void test_in_order_gives_the_whole_once(void)
{
    spool_new();
    rig *r = rig_open(3600);
    for (int i = 0; i < N_CHUNKS; i++) {
        chunk k = make(7, i);
        ra_offer o = offer(r, &k, T0);
        CHECK(o.next_index == i + 1);
        CHECK(o.state == (i < N_CHUNKS - 1 ? RA_HOLDING : RA_DONE));
        if (i == N_CHUNKS - 1) {
            CHECK(o.data && o.len == DATA_LEN && !memcmp(o.data, DATA, DATA_LEN));
            CHECK_STR(o.channel, "PLUGIN_UPLOAD");
        }
        ra_offer_free(&o);
    }
    CHECK(files(".part") == 0 && files(".json") == 1); /* done.json only */
    chunk last = make(7, N_CHUNKS - 1);
    ra_offer o = offer(r, &last, T0 + 1); /* repeated: never handed on twice */
    CHECK(o.state == RA_DONE && !o.data && reason(r, "duplicate") == 1);
    free(r);
    r = rig_open(3600); /* nor after a restart: done.json */
    o = offer(r, &last, T0 + 2);
    CHECK(o.state == RA_DONE && !o.data);
    free(r);
    spool_remove();
}

static void test_out_of_order_duplicated_and_another_transfer(void)
{
    spool_new();
    rig *r = rig_open(3600);
    for (int i = 0; i < 3; i++) {
        chunk k = make(7, i);
        offer(r, &k, T0);
    }
    chunk k = make(7, 5);
    ra_offer o = offer(r, &k, T0);
    CHECK(o.state == RA_HOLDING && o.next_index == 3);
    CHECK_HAS(o.reason, "out of order: expected 3");
    k = make(7, 1);
    o = offer(r, &k, T0);
    CHECK(o.next_index == 3);
    CHECK_HAS(o.reason, "duplicate chunk 1");
    k = make(7, 3);
    k.sha[0] = k.sha[0] == 'a' ? 'b' : 'a'; /* the same id, another transfer's header */
    o = offer(r, &k, T0);
    CHECK(o.next_index == 3);
    CHECK_HAS(o.reason, "does not match");
    k = make(7, 3);
    k.c.index = N_CHUNKS; /* past the count */
    o = offer(r, &k, T0);
    CHECK_STR(o.reason, "chunk 10 of 10");
    int64_t ids[4];
    int32_t next[4];
    CHECK(ra_holding(&r->a, ids, next, 4) == 1 && ids[0] == 7 && next[0] == 3); /* the transfer is kept */
    for (int i = 3; i < N_CHUNKS; i++) {
        k = make(7, i);
        o = offer(r, &k, T0);
    }
    CHECK(o.data && !memcmp(o.data, DATA, DATA_LEN));
    ra_offer_free(&o);
    CHECK(reason(r, "out of order") == 1 && reason(r, "duplicate") == 1 && reason(r, "another transfer") == 1 &&
          reason(r, "too many") == 1 && r->a.refused == 4);
    free(r);
    spool_remove();
}

static void test_bad_first_chunks_keep_nothing(void)
{
    static const struct {
        const char *field;
        const char *key, *text;
    } cases[] = {
        {"index", "unknown transfer", "not held"},       {"channel", "channel", "is not carried"},
        {"vehicle", "wrong vehicle", "addressed to"},     {"sha", "bad digest", "64 lowercase hex"},
        {"total", "too large", "at most"},                {"count", "too many", "chunks for"},
        {"count1", "too few", "cannot hold"},             {"index-1", "too many", "chunk -1 of"},
        {"n_bytes", "bad chunk", "0 bytes"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        spool_new();
        rig *r = rig_open(3600);
        chunk k = make(7, 0);
        const char *f = cases[i].field;
        if (!strcmp(f, "index"))
            k.c.index = 5;
        else if (!strcmp(f, "channel"))
            k.c.channel = "CHASM.NAVIGATOR";
        else if (!strcmp(f, "vehicle"))
            k.c.vehicle = "AUV2";
        else if (!strcmp(f, "sha"))
            snprintf(k.sha, sizeof k.sha, "XYZ");
        else if (!strcmp(f, "total"))
            k.c.total_bytes = RA_MAX_BYTES + 1;
        else if (!strcmp(f, "count"))
            k.c.count = 1000000000;
        else if (!strcmp(f, "count1"))
            k.c.count = 1;
        else if (!strcmp(f, "index-1"))
            k.c.index = -1;
        else
            k.c.n_bytes = 0;
        ra_offer o = offer(r, &k, T0);
        CHECK(!o.data && reason(r, cases[i].key) == 1);
        CHECK_HAS(o.reason, cases[i].text);
        int64_t ids[4];
        int32_t next[4];
        /* a chunk 0 of zero bytes opened its transfer: it is held, empty, and nothing else */
        CHECK(ra_holding(&r->a, ids, next, 4) == (strcmp(f, "n_bytes") ? 0 : 1));
        CHECK(files(".part") == (strcmp(f, "n_bytes") ? 0 : 1));
        free(r);
        spool_remove();
    }
}

static void test_a_wrong_digest_drops_the_whole(void)
{
    spool_new();
    rig *r = rig_open(3600);
    ra_offer o;
    for (int i = 0; i < N_CHUNKS; i++) {
        chunk k = make(7, i);
        auth_sha256_hex("something else", 14, k.sha);
        o = offer(r, &k, T0);
    }
    CHECK(o.state == RA_REFUSED && !o.data && reason(r, "wrong digest") == 1);
    CHECK_HAS(o.reason, "does not match its SHA-256");
    CHECK(files(".part") == 0 && ra_holding(&r->a, NULL, NULL, 0) == 0);
    free(r);
    spool_remove();
}

static void test_chunks_past_the_declared_size(void)
{
    spool_new();
    rig *r = rig_open(3600);
    for (int i = 0; i < N_CHUNKS - 1; i++) {
        chunk k = make(7, i);
        offer(r, &k, T0);
    }
    chunk big = make(7, N_CHUNKS - 1);
    big.c.n_bytes = 4096; /* more than the 392 bytes left */
    big.c.data = DATA;
    ra_offer o = offer(r, &big, T0);
    CHECK_HAS(o.reason, "goes past the declared 5000 bytes");
    CHECK(o.next_index == N_CHUNKS - 1 && !o.data);
    chunk small = make(7, N_CHUNKS - 1);
    small.c.n_bytes = 10; /* the last chunk, short of the size */
    o = offer(r, &small, T0);
    CHECK_HAS(o.reason, "at the last chunk");
    CHECK(reason(r, "too many") == 1 && reason(r, "too few") == 1);
    free(r);
    spool_remove();
}

static void test_bounded_and_never_ending_transfers_expire(void)
{
    spool_new();
    rig *r = rig_open(60);
    for (int tid = 1; tid <= RA_MAX_TRANSFERS; tid++) {
        chunk k = make(tid, 0);
        offer(r, &k, T0);
    }
    chunk k = make(99, 0);
    ra_offer o = offer(r, &k, T0 + 1);
    CHECK(o.state == RA_REFUSED && reason(r, "busy") == 1);
    CHECK_HAS(o.reason, "already in progress");
    CHECK(files(".part") == RA_MAX_TRANSFERS);
    o = offer(r, &k, T0 + 100); /* the others never ended: expired first */
    CHECK(o.state == RA_HOLDING && o.next_index == 1);
    CHECK(reason(r, "never ended: expired") == RA_MAX_TRANSFERS && files(".part") == 1);
    CHECK(ra_expire(&r->a, &r->ctx, T0 + 1000) == 1 && files(".part") == 0 && files(".json") == 0);
    free(r);
    spool_remove();
}

static void test_a_flood_keeps_nothing(void)
{
    spool_new();
    rig *r = rig_open(3600);
    for (int i = 0; i < 5000; i++) {
        chunk k = make(1000 + i, 1 + i % 3);
        offer(r, &k, T0 + i);
    }
    CHECK(reason(r, "unknown transfer") == 5000 && files(".part") == 0);
    free(r);
    spool_remove();
}

static void test_a_restart_resumes_from_the_spool(void)
{
    spool_new();
    rig *r = rig_open(3600);
    for (int i = 0; i < 4; i++) {
        chunk k = make(7, i);
        offer(r, &k, T0);
    }
    free(r);
    char path[600];
    snprintf(path, sizeof path, "%s/7.part", spool);
    FILE *f = fopen(path, "ab");
    fputs("half a chunk written when the power went", f);
    fclose(f);
    snprintf(path, sizeof path, "%s/8.json", spool); /* and a meta file that is not one */
    f = fopen(path, "w");
    fputs("{\"header\": {\"transfer_id\": 8}}", f);
    fclose(f);
    char orphan[600];
    snprintf(orphan, sizeof orphan, "%s/5.part", spool); /* bytes whose meta was never written */
    f = fopen(orphan, "wb");
    fputs("x", f);
    fclose(f);
    r = rig_open(3600);
    int64_t ids[4];
    int32_t next[4];
    CHECK(ra_holding(&r->a, ids, next, 4) == 1 && ids[0] == 7 && next[0] == 4);
    CHECK(reason(r, "spool: unreadable partial transfer") == 1 && access(path, F_OK) != 0);
    CHECK(reason(r, "spool: bytes without meta") == 1 && access(orphan, F_OK) != 0 && files(".part") == 1);
    ra_offer o;
    for (int i = 4; i < N_CHUNKS; i++) {
        chunk k = make(7, i);
        o = offer(r, &k, T0);
    }
    CHECK(o.state == RA_DONE && o.data && !memcmp(o.data, DATA, DATA_LEN));
    ra_offer_free(&o);
    free(r);
    spool_remove();
}

static void test_the_spool_reads_the_python_format(void)
{
    spool_new();
    char path[600];
    snprintf(path, sizeof path, "%s/done.json", spool);
    FILE *f = fopen(path, "w");
    fputs("[3, 4, 5]", f);
    fclose(f);
    int64_t ids[2];
    CHECK(rsp_load_done(path, ids, 2) == 2 && ids[0] == 4 && ids[1] == 5); /* the newest kept */
    ra_partial p;
    snprintf(path, sizeof path, "%s/9.json", spool);
    f = fopen(path, "w");
    fprintf(f, "{\"header\": {\"transfer_id\": 9, \"vehicle\": \"AUV1\", \"channel\": \"MISSION_CMD\", \"count\": 2, "
               "\"total_bytes\": 600, \"sha256_hex\": \"%064d\"}, \"next_index\": 1, \"held\": 512}",
            0);
    fclose(f);
    CHECK(rsp_load_meta(path, &p) == 0 && p.h.transfer_id == 9 && p.h.count == 2 && p.h.total_bytes == 600 &&
          p.next_index == 1 && p.held_bytes == 512);
    CHECK_STR(p.h.channel, "MISSION_CMD");
    f = fopen(path, "w");
    fputs("{\"header\": {\"transfer_id\": 9, \"vehicle\": \"A\\\"\", \"channel\": \"MISSION_CMD\"}}", f);
    fclose(f);
    CHECK(rsp_load_meta(path, &p) < 0);
    spool_remove();
}

/* ------------------------------------------------------------ the pipe */
typedef struct {
    int seqs[16];
    int n;
} seen;

static void on_frame(void *user, const uint8_t *frame, size_t n)
{
    seen *s = user;
    auv_radio_frame_t f;
    if (rx_decode(auv_type_find("radio_frame_t"), frame, (int)n, &f) == 0) {
        s->seqs[s->n++] = f.seq;
        auv_radio_frame_t_decode_cleanup(&f);
    }
}

static size_t framed(int seq, uint8_t *out, size_t cap)
{
    uint8_t payload[400], enc[600];
    memset(payload, seq, sizeof payload);
    auv_radio_frame_t f = {.utime = seq, .src = "SHORE", .dst = "AUV1", .seq = seq, .n_bytes = 10 + 37 * seq,
                           .payload = payload};
    int n = auv_radio_frame_t_encode(enc, 0, sizeof enc, &f);
    return rp_encode(enc, (size_t)n, out, cap);
}

static void test_the_pipe_finds_every_good_frame_in_noise(void)
{
    static uint8_t stream[8192];
    uint8_t fr[700];
    size_t k = 0, n;
    memcpy(stream, "noise", 5);
    k = 5;
    k += framed(0, stream + k, sizeof stream - k);
    stream[k++] = 0xA5; /* a lone half marker */
    k += framed(1, stream + k, sizeof stream - k);
    n = framed(2, fr, sizeof fr);
    fr[n - 1] ^= 0xFF; /* a bad CRC */
    memcpy(stream + k, fr, n);
    k += n;
    const uint8_t too_long[] = {0xA5, 0x5A, 0x00, 0x00, 0x40, 0x01};
    memcpy(stream + k, too_long, sizeof too_long);
    k += sizeof too_long;
    n = framed(3, fr, sizeof fr);
    memcpy(stream + k, fr, n - 7); /* cut by a dive */
    k += n - 7;
    k += framed(4, stream + k, sizeof stream - k);
    k += framed(5, stream + k, sizeof stream - k);
    drv_ctx ctx;
    drv_ctx_init(&ctx, "test", "AUV1", "RADIO", NULL, NULL);
    ctx.quiet = 1;
    rp_deframer *d = calloc(1, sizeof *d);
    seen s = {{0}, 0};
    for (size_t i = 0; i < k; i += 7) /* as the bytes trickle in */
        rp_feed(d, &ctx, stream + i, k - i < 7 ? k - i : 7, on_frame, &s);
    CHECK(s.n == 4 && s.seqs[0] == 0 && s.seqs[1] == 1 && s.seqs[2] == 4 && s.seqs[3] == 5);
    CHECK(drv_reasons_get(&ctx.reasons, "bad CRC") >= 1 && drv_reasons_get(&ctx.reasons, "too long") >= 1);
    CHECK(d->noise_bytes >= 5);
    CHECK(crc32_update(0, "123456789", 9) == 0xCBF43926u); /* the standard check value */
    free(d);
}

/* ------------------------------------------------------------ the protocol */
typedef struct {
    char channel[8][64];
    uint8_t *data[8];
    int len[8];
    int n;
    uint8_t wrote[65536];
    size_t n_wrote;
} outbox;

static void capture(void *user, const char *channel, const auv_type_entry_t *type, const void *data, int len)
{
    outbox *o = user;
    (void)type;
    if (o->n < 8) {
        snprintf(o->channel[o->n], 64, "%s", channel);
        o->data[o->n] = malloc((size_t)len);
        memcpy(o->data[o->n], data, (size_t)len);
        o->len[o->n++] = len;
    }
}

static int pipe_write(void *user, const uint8_t *data, size_t n)
{
    outbox *o = user;
    if (o->n_wrote + n > sizeof o->wrote)
        return -1;
    memcpy(o->wrote + o->n_wrote, data, n);
    o->n_wrote += n;
    return 0;
}

static int acks_seen;
static void count_acks(void *user, const uint8_t *frame, size_t n)
{
    (void)user;
    auv_radio_frame_t f;
    auv_radio_ack_t a;
    if (rx_decode(auv_type_find("radio_frame_t"), frame, (int)n, &f) != 0)
        return;
    if (rx_decode(auv_type_find("radio_ack_t"), f.payload, f.n_bytes, &a) == 0) {
        acks_seen++;
        auv_radio_ack_t_decode_cleanup(&a);
    }
    auv_radio_frame_t_decode_cleanup(&f);
}

static void test_a_command_crosses_byte_for_byte(void)
{
    spool_new();
    outbox *out = calloc(1, sizeof *out);
    radio_state *s = calloc(1, sizeof *s);
    drv_ctx ctx;
    drv_ctx_init(&ctx, "test", "AUV1", "RADIO", capture, out);
    ctx.quiet = 1;
    ctx.write = pipe_write;
    ctx.write_user = out;
    s->spool = spool;
    CHECK(radio_protocol.init(s, &ctx) == 0);
    /* a signed command: bytes appended after the encoded message must cross untouched */
    uint8_t cmd[300];
    auv_mission_command_t m = {.vehicle = "AUV1", .manager = "", .seq = 7, .command = 1, .plan_name = "",
                               .plan_text = "", .reason = "test", .auth = {.key_id = "", .sender = ""}};
    int n = auv_mission_command_t_encode(cmd, 0, sizeof cmd, &m);
    memcpy(cmd + n, "HMAC-and-then-some", 18);
    n += 18;
    char sha[65];
    auth_sha256_hex(cmd, (size_t)n, sha);
    int count = (n + 63) / 64;
    for (int i = 0; i < count; i++) {
        auv_radio_chunk_t c = {.transfer_id = 42, .vehicle = "AUV1", .channel = "MISSION_CMD", .index = i,
                               .count = count, .total_bytes = n, .sha256_hex = sha,
                               .n_bytes = i < count - 1 ? 64 : n - 64 * (count - 1), .data = cmd + 64 * i};
        uint8_t enc[600], frame_enc[800], pipe[900];
        int k = auv_radio_chunk_t_encode(enc, 0, sizeof enc, &c);
        auv_radio_frame_t f = {.utime = 1, .src = "SHORE", .dst = "AUV1", .seq = i, .n_bytes = k, .payload = enc};
        int fk = auv_radio_frame_t_encode(frame_enc, 0, sizeof frame_enc, &f);
        size_t pk = rp_encode(frame_enc, (size_t)fk, pipe, sizeof pipe);
        for (size_t j = 0; j < pk; j += 5) /* cut anywhere */
            radio_protocol.feed(s, &ctx, pipe + j, pk - j < 5 ? pk - j : 5, 1000000 + i);
    }
    CHECK(out->n == 1 && out->len[0] == n && !memcmp(out->data[0], cmd, (size_t)n));
    CHECK_STR(out->channel[0], "AUV1.MISSION_CMD");
    rp_deframer *d = calloc(1, sizeof *d);
    acks_seen = 0;
    rp_feed(d, &ctx, out->wrote, out->n_wrote, count_acks, NULL);
    CHECK(acks_seen == count); /* every chunk answered */
    CHECK(s->delivered == 1);
    free(d);
    for (int i = 0; i < out->n; i++)
        free(out->data[i]);
    free(out);
    free(s);
    spool_remove();
}

static void test_acoustic_commands_run_once_from_the_shore_to_their_target(void)
{
    outbox *out = calloc(1, sizeof *out);
    radio_state *s = calloc(1, sizeof *s);
    drv_ctx ctx;
    drv_ctx_init(&ctx, "test", "AUV1", "RADIO", capture, out);
    ctx.quiet = 1;
    s->team_index = 2;
    s->given = RADIO_GIVEN_TEAM;
    CHECK(radio_protocol.init(s, &ctx) == 0);
    const int heard[][4] = {{15, 2, 1, 500}, {15, 2, 1, 500}, {3, 2, 1, 501}, {15, 1, 1, 502}, {15, 2, 6, 503},
                            {15, 2, 3, 504}};
    for (size_t i = 0; i < sizeof heard / sizeof heard[0]; i++) {
        team_msg_command c = {.origin = heard[i][0], .target = heard[i][1], .kind = heard[i][2],
                              .counter = heard[i][3]};
        uint8_t buf[TEAM_COMMAND_MAX_BYTES];
        team_bits w;
        team_bits_writer(&w, buf, sizeof buf);
        CHECK(team_command_encode(&c, &w) == TEAM_OK);
        radio_acoustic_heard(s, buf, (int)team_bits_bytes(&w), 5000000);
    }
    CHECK(out->n == 2);
    auv_mission_command_t m;
    CHECK(rx_decode(auv_type_find("mission_command_t"), out->data[0], out->len[0], &m) == 0);
    CHECK(m.command == AUV_MISSION_COMMAND_T_CMD_ABORT && m.seq == 500 && !strcmp(m.manager, ""));
    CHECK_HAS(m.reason, "acoustic abort #500");
    auv_mission_command_t_decode_cleanup(&m);
    CHECK(rx_decode(auv_type_find("mission_command_t"), out->data[1], out->len[1], &m) == 0);
    CHECK(m.command == AUV_MISSION_COMMAND_T_CMD_RESUME && m.seq == 504);
    auv_mission_command_t_decode_cleanup(&m);
    for (int i = 0; i < out->n; i++)
        free(out->data[i]);
    free(out);
    free(s);
}

/* A frame from vehicle src to AUV1 carrying payload, through the protocol's pipe. */
static void hear_from(radio_state *s, drv_ctx *ctx, const char *src, const uint8_t *payload, int len)
{
    uint8_t frame_enc[1200], pipe[1300];
    auv_radio_frame_t f = {.utime = 1, .src = (char *)src, .dst = "AUV1", .seq = 1, .n_bytes = len,
                           .payload = (uint8_t *)payload};
    int fk = auv_radio_frame_t_encode(frame_enc, 0, sizeof frame_enc, &f);
    size_t pk = rp_encode(frame_enc, (size_t)fk, pipe, sizeof pipe);
    radio_protocol.feed(s, ctx, pipe, pk, 2000000);
}

static void test_a_peers_status_is_published_and_nothing_else_from_a_vehicle(void)
{
    outbox *out = calloc(1, sizeof *out);
    radio_state *s = calloc(1, sizeof *s);
    drv_ctx ctx;
    drv_ctx_init(&ctx, "test", "AUV1", "RADIO", capture, out);
    ctx.quiet = 1;
    char err[200];
    CHECK(radio_peers_parse(s, "AUV2,AUV3", err, sizeof err) == 0 && s->n_peers == 2);
    CHECK(radio_peers_parse(s, "AUV2,,AUV3", err, sizeof err) < 0 && radio_peers_parse(s, "SHORE", err, sizeof err) < 0);
    CHECK(radio_peers_parse(s, "AUV2,AUV3", err, sizeof err) == 0);
    CHECK(radio_protocol.init(s, &ctx) == 0);
    uint8_t rep[600];
    auv_radio_report_t r = {.vehicle = "AUV2", .mission = "RUNNING survey", .n_transfers = 0};
    int n = auv_radio_report_t_encode(rep, 0, sizeof rep, &r);
    hear_from(s, &ctx, "AUV2", rep, n);       /* a teammate's status: published as it came */
    hear_from(s, &ctx, "AUV9", rep, n);       /* not a teammate */
    hear_from(s, &ctx, "AUV3", rep, n);       /* a teammate speaking for another */
    uint8_t chunk[600];
    auv_radio_chunk_t c = {.transfer_id = 1, .vehicle = "AUV1", .channel = "MISSION_CMD", .count = 1,
                           .total_bytes = 3, .sha256_hex = "", .n_bytes = 3, .data = (uint8_t *)"abc"};
    int k = auv_radio_chunk_t_encode(chunk, 0, sizeof chunk, &c);
    hear_from(s, &ctx, "AUV2", chunk, k);     /* a command from a vehicle: never */
    CHECK(out->n == 1 && out->len[0] == n && !memcmp(out->data[0], rep, (size_t)n));
    CHECK_STR(out->channel[0], "AUV1.PEER_RADIO_REPORT");
    CHECK(s->peer_reports == 1 && s->frames_dropped == 3);
    CHECK(drv_reasons_get(&ctx.reasons, "not a peer") == 1 &&
          drv_reasons_get(&ctx.reasons, "another vehicle's status") == 1 &&
          drv_reasons_get(&ctx.reasons, "not a peer's status") == 1);
    for (int i = 0; i < out->n; i++)
        free(out->data[i]);
    free(out);
    free(s);
}

static const unit_test tests[] = {
    {"radio_in_order_gives_the_whole_once", test_in_order_gives_the_whole_once},
    {"radio_out_of_order_duplicated_and_another_transfer", test_out_of_order_duplicated_and_another_transfer},
    {"radio_bad_first_chunks_keep_nothing", test_bad_first_chunks_keep_nothing},
    {"radio_a_wrong_digest_drops_the_whole", test_a_wrong_digest_drops_the_whole},
    {"radio_chunks_past_the_declared_size", test_chunks_past_the_declared_size},
    {"radio_bounded_and_never_ending_transfers_expire", test_bounded_and_never_ending_transfers_expire},
    {"radio_a_flood_keeps_nothing", test_a_flood_keeps_nothing},
    {"radio_a_restart_resumes_from_the_spool", test_a_restart_resumes_from_the_spool},
    {"radio_the_spool_reads_the_python_format", test_the_spool_reads_the_python_format},
    {"radio_the_pipe_finds_every_good_frame_in_noise", test_the_pipe_finds_every_good_frame_in_noise},
    {"radio_a_command_crosses_byte_for_byte", test_a_command_crosses_byte_for_byte},
    {"radio_acoustic_commands_run_once", test_acoustic_commands_run_once_from_the_shore_to_their_target},
    {"radio_a_peers_status_is_published", test_a_peers_status_is_published_and_nothing_else_from_a_vehicle},
    {NULL, NULL},
};

__attribute__((constructor)) static void register_tests(void) { unit_register_list(tests); }
