/* Unit tests of the generated team-link codec and its bit writer/reader.
 * Run in both builds by tests/teamlink/test_team_codec.py. Prints one line per
 * failure and exits 1 if any. */
#include "team/team_codec.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The sizes the team mission is designed around (TEAM_SPEC section 2). */
_Static_assert((TEAM_STATUS_BITS + 7) / 8 <= 12, "status fits 12 bytes");
_Static_assert((TEAM_CONTACT_BITS + 7) / 8 <= 16, "contact fits 16 bytes");

static int failures;
#define CHECK(cond)                                                             \
    do {                                                                        \
        if (!(cond)) {                                                          \
            fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
            failures++;                                                         \
        }                                                                       \
    } while (0)

static team_msg_status sample_status(void)
{
    team_msg_status s = {.vehicle = 3, .time_s = 1234, .north_m = -512.4, .east_m = 1999.6,
                         .depth_m = 12.34, .heading = 6.28318, .speed = 1.54,
                         .next_line = 63, .state = 5};
    return s;
}

static void test_bits(void)
{
    uint8_t buf[3];
    team_bits w, r;
    team_bits_writer(&w, buf, sizeof buf);
    CHECK(team_bits_put(&w, 0x5, 3) == 0);      /* 101 */
    CHECK(team_bits_put(&w, 0x1ff, 9) == 0);    /* 111111111 */
    CHECK(team_bits_put(&w, 0, 0) == 0);
    CHECK(team_bits_bytes(&w) == 2);
    CHECK(team_bits_put(&w, 0x1ff, 13) == -1);  /* 12 bits left */
    CHECK(team_bits_left(&w) == 12);
    CHECK(buf[0] == 0xbf && buf[1] == 0xf0 && buf[2] == 0);
    team_bits_reader(&r, buf, sizeof buf);
    uint32_t v = 0;
    CHECK(team_bits_put(&r, 1, 1) == -1);       /* a reader does not write */
    CHECK(team_bits_get(&r, 3, &v) == 0 && v == 5);
    CHECK(team_bits_get(&r, 9, &v) == 0 && v == 0x1ff);
    CHECK(team_bits_get(&r, 13, &v) == -1 && r.pos == 12);
    CHECK(team_bits_get(&r, 12, &v) == 0 && v == 0);
    uint8_t big[5];
    team_bits_writer(&w, big, sizeof big);
    CHECK(team_bits_put(&w, 0xdeadbeefu, 32) == 0);
    team_bits_reader(&r, big, sizeof big);
    CHECK(team_bits_get(&r, 32, &v) == 0 && v == 0xdeadbeefu);
}

/* ack {to 3, number 5}: id 0011, to 0011, number 0000000101, 6 zero pad bits. */
static void test_known_bits(void)
{
    uint8_t buf[4];
    team_bits w;
    team_bits_writer(&w, buf, sizeof buf);
    team_msg_ack a = {.to = 3, .number = 5};
    CHECK(team_ack_encode(&a, &w) == TEAM_OK);
    CHECK(w.pos == TEAM_ACK_BITS && TEAM_ACK_BITS == 18);
    CHECK(team_bits_bytes(&w) == 3);
    CHECK(buf[0] == 0x33 && buf[1] == 0x01 && buf[2] == 0x40);
}

static void test_round_trip(void)
{
    uint8_t buf[32];
    team_bits w, r;
    team_bits_writer(&w, buf, sizeof buf);
    team_msg_status s = sample_status();
    team_msg_contact c = {.origin = 15, .number = 1023, .north_m = -2000, .east_m = 2000,
                          .sigma_m = 12.7, .score = 0.755, .looks = 2, .time_s = 16383};
    team_msg_ident id = {.origin = 0, .number = 7, .result = 2, .north_m = 0.124,
                         .east_m = -0.126, .time_s = 0};
    CHECK(team_status_encode(&s, &w) == TEAM_OK);
    CHECK(team_contact_encode(&c, &w) == TEAM_OK);
    CHECK(team_ident_encode(&id, &w) == TEAM_OK);
    CHECK(w.pos == TEAM_STATUS_BITS + TEAM_CONTACT_BITS + TEAM_IDENT_BITS);
    size_t n = team_bits_bytes(&w);
    team_bits_reader(&r, buf, n);
    team_msg m;
    CHECK(team_decode_next(&r, &m) == TEAM_MSG_STATUS && m.id == TEAM_MSG_STATUS);
    CHECK(m.u.status.vehicle == 3 && m.u.status.time_s == 1234 && m.u.status.next_line == 63);
    CHECK(m.u.status.state == 5);
    CHECK(fabs(m.u.status.north_m - -512.0) < 1e-9 && fabs(m.u.status.east_m - 2000.0) < 1e-9);
    CHECK(fabs(m.u.status.depth_m - 12.3) < 1e-9);
    CHECK(fabs(m.u.status.heading - 6.275) < 1e-9);  /* nearest 0.025 step */
    CHECK(fabs(m.u.status.speed - 1.5) < 1e-9);
    CHECK(team_decode_next(&r, &m) == TEAM_MSG_CONTACT);
    CHECK(m.u.contact.origin == 15 && m.u.contact.number == 1023 && m.u.contact.looks == 2);
    CHECK(m.u.contact.north_m == -2000.0 && m.u.contact.east_m == 2000.0);
    CHECK(fabs(m.u.contact.sigma_m - 12.7) < 1e-9 && fabs(m.u.contact.score - 0.76) < 1e-9);
    CHECK(team_decode_next(&r, &m) == TEAM_MSG_IDENT);
    CHECK(m.u.ident.result == 2 && m.u.ident.north_m == 0.0 && m.u.ident.east_m == -0.25);
    CHECK(team_decode_next(&r, &m) == 0);  /* padding: the end */
    /* Decoding then encoding again gives the same bits. */
    uint8_t again[32];
    team_bits w2;
    team_bits_writer(&w2, again, sizeof again);
    team_bits_reader(&r, buf, n);
    while (team_decode_next(&r, &m) > 0)
        CHECK(team_msg_encode(&m, &w2) == TEAM_OK);
    CHECK(w2.pos == w.pos && memcmp(again, buf, n) == 0);
}

static void test_refusals(void)
{
    uint8_t buf[16];
    team_bits w;
    team_bits_writer(&w, buf, sizeof buf);
    team_msg_status s = sample_status();
    s.depth_m = NAN;
    CHECK(team_status_encode(&s, &w) == TEAM_ERR_RANGE && w.pos == 0);
    s = sample_status();
    s.depth_m = 102.31;
    CHECK(team_status_encode(&s, &w) == TEAM_ERR_RANGE);
    s = sample_status();
    s.north_m = -INFINITY;
    CHECK(team_status_encode(&s, &w) == TEAM_ERR_RANGE);
    s = sample_status();
    s.heading = -1e-9;
    CHECK(team_status_encode(&s, &w) == TEAM_ERR_RANGE);
    s = sample_status();
    s.state = 8;
    CHECK(team_status_encode(&s, &w) == TEAM_ERR_RANGE);
    s = sample_status();
    s.vehicle = -1;
    CHECK(team_status_encode(&s, &w) == TEAM_ERR_RANGE);
    team_msg_ack a = {.to = 0, .number = INT32_MIN};
    CHECK(team_ack_encode(&a, &w) == TEAM_ERR_RANGE);
    CHECK(w.pos == 0);
    for (size_t i = 0; i < sizeof buf; i++)
        CHECK(buf[i] == 0);
    /* A frame of 16 bytes holds one status (78 bits) and not a second: the
     * refused one leaves the frame as it was. */
    s = sample_status();
    CHECK(team_status_encode(&s, &w) == TEAM_OK);
    uint8_t copy[16];
    memcpy(copy, buf, sizeof buf);
    CHECK(team_status_encode(&s, &w) == TEAM_ERR_FULL);
    CHECK(w.pos == TEAM_STATUS_BITS && memcmp(copy, buf, sizeof buf) == 0);
    team_msg_ack ok = {.to = 1, .number = 2};
    CHECK(team_ack_encode(&ok, &w) == TEAM_OK);  /* 78 + 18 <= 128 */
    team_msg bad = {.id = 9};
    CHECK(team_msg_encode(&bad, &w) == TEAM_ERR_UNKNOWN_ID);
    team_bits r;
    team_bits_reader(&r, buf, 4);
    CHECK(team_ack_encode(&ok, &r) == TEAM_ERR_FULL);  /* a reader refuses writes */
}

static void test_decode_faults(void)
{
    uint8_t buf[16];
    team_bits w, r;
    team_msg m;
    team_bits_writer(&w, buf, sizeof buf);
    team_msg_status s = sample_status();
    team_msg_ack a = {.to = 2, .number = 9};
    CHECK(team_ack_encode(&a, &w) == TEAM_OK);
    CHECK(team_status_encode(&s, &w) == TEAM_OK);
    /* Cut inside the status: the ack decodes, then TRUNCATED at bit 18. */
    team_bits_reader(&r, buf, 6);
    CHECK(team_decode_next(&r, &m) == TEAM_MSG_ACK && m.u.ack.number == 9);
    CHECK(team_decode_next(&r, &m) == TEAM_ERR_TRUNCATED);
    CHECK(r.pos == TEAM_ACK_BITS && team_bits_left(&r) == 48 - TEAM_ACK_BITS);
    /* Unknown id 15. */
    uint8_t unk[2] = {0xf0, 0x00};
    team_bits_reader(&r, unk, 2);
    CHECK(team_decode_next(&r, &m) == TEAM_ERR_UNKNOWN_ID && r.pos == 0);
    /* A raw value above MAX (status.north_m raw 4095 > 4000 steps). */
    uint8_t bad[12];
    memcpy(bad, buf, sizeof bad);
    team_bits_writer(&w, bad, sizeof bad);
    CHECK(team_status_encode(&s, &w) == TEAM_OK);
    w.pos = 4 + 4 + 14;
    CHECK(team_bits_put(&w, 0xfff, 12) == 0);
    team_bits_reader(&r, bad, sizeof bad);
    CHECK(team_decode_next(&r, &m) == TEAM_ERR_CORRUPT && r.pos == 0);
    /* Empty and short frames end cleanly. */
    team_bits_reader(&r, buf, 0);
    CHECK(team_decode_next(&r, &m) == 0);
    uint8_t zero[1] = {0};
    team_bits_reader(&r, zero, 1);
    CHECK(team_decode_next(&r, &m) == 0);
}

/* Random bytes and every truncation of a good frame: the decoder stops and
 * never reads outside the frame (the sanitized build checks that). */
static void test_hostile(void)
{
    uint32_t seed = 12345;
    uint8_t frame[64];
    for (int round = 0; round < 20000; round++) {
        size_t n = (size_t)(round % 65);
        uint8_t *heap = malloc(n ? n : 1);
        for (size_t i = 0; i < n; i++) {
            seed = seed * 1664525u + 1013904223u;
            heap[i] = (uint8_t)(seed >> 24);
        }
        team_bits r;
        team_msg m;
        team_bits_reader(&r, heap, n);
        int rc, count = 0;
        while ((rc = team_decode_next(&r, &m)) > 0) {
            count++;
            CHECK(team_message_by_id(rc) != NULL);
            uint8_t out[32];
            team_bits w;
            team_bits_writer(&w, out, sizeof out);
            CHECK(team_msg_encode(&m, &w) == TEAM_OK);  /* what decodes re-encodes */
        }
        CHECK(count <= (int)(8 * n / TEAM_ID_BITS));
        free(heap);
    }
    team_bits w;
    team_bits_writer(&w, frame, 32);
    team_msg_status s = sample_status();
    team_msg_ack a = {.to = 1, .number = 1};
    CHECK(team_status_encode(&s, &w) == TEAM_OK && team_ack_encode(&a, &w) == TEAM_OK);
    size_t full = team_bits_bytes(&w);
    for (size_t n = 0; n <= full; n++) {
        uint8_t *heap = malloc(n ? n : 1);
        memcpy(heap, frame, n);
        team_bits r;
        team_msg m;
        team_bits_reader(&r, heap, n);
        int got = 0, rc;
        while ((rc = team_decode_next(&r, &m)) > 0)
            got++;
        if (n == full)
            CHECK(got == 2 && rc == 0);
        else /* a cut that leaves under 4 bits after a message looks like padding */
            CHECK(rc == TEAM_ERR_TRUNCATED || (rc == 0 && 8 * n - r.pos < TEAM_ID_BITS));
        free(heap);
    }
}

static void test_tables(void)
{
    CHECK(team_message_by_name("contact")->id == TEAM_MSG_CONTACT);
    CHECK(team_message_by_name("nope") == NULL && team_message_by_id(0) == NULL);
    CHECK(team_message_by_id(TEAM_MSG_STATUS)->bits == TEAM_STATUS_BITS);
    const team_message_info *st = team_message_by_name("status");
    CHECK(st->n_fields == 9 && strcmp(st->fields[5].name, "heading") == 0);
    CHECK(st->max_bytes == 12 && team_message_by_name("contact")->max_bytes == 16);
    for (size_t i = 0; i < TEAM_N_MESSAGES; i++) {
        unsigned bits = TEAM_ID_BITS;
        for (size_t f = 0; f < team_messages[i].n_fields; f++)
            bits += team_messages[i].fields[f].bits;
        CHECK(bits == team_messages[i].bits);
        CHECK((bits + 7) / 8 <= team_messages[i].max_bytes);
    }
    CHECK(strcmp(team_strerror(TEAM_ERR_TRUNCATED), "frame ends inside a message") == 0);
}

int main(void)
{
    test_bits();
    test_known_bits();
    test_round_trip();
    test_refusals();
    test_decode_faults();
    test_hostile();
    test_tables();
    if (failures) {
        fprintf(stderr, "%d check(s) failed\n", failures);
        return 1;
    }
    printf("team codec: all checks passed\n");
    return 0;
}
