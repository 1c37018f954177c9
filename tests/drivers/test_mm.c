/* Unit tests of the Micro-Modem's NMEA subset (c/drivers/modem/mm_msg.c) and
 * its bridge (mm_bridge.c, mm_table.c): published example sentences of each
 * kind, every refusal, whole exchanges (a frame sent, a frame received, an
 * error, timeouts, a reboot) and the hostile corpus tests/drivers/corpus/mm. */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "drivers/modem/mm_bridge.h"
#include "../harness/unit.h"

/* A body ("CARXD,...") through nmea_format and the strict parser, then mm_parse. */
static int parse_body(const char *body, mm_msg *m, const char **why)
{
    char line[NMEA_MAX_SENTENCE + 8];
    nmea_sentence s;
    if (nmea_format(line, sizeof line, body) < 0 || nmea_parse_line(line, strlen(line), 0, &s) != NMEA_OK) {
        *why = "framing";
        return -2;
    }
    return mm_parse(&s, m, why);
}

static const char *refusal(const char *body)
{
    mm_msg m;
    const char *why = NULL;
    int rc = parse_body(body, &m, &why);
    if (rc != -1)
        UNIT_FAIL("%s: accepted (rc %d), expected a refusal", body, rc);
    return why ? why : "";
}

/* Parses, formats back, and checks the body comes out the same. */
static void round_trip(const char *body, mm_msg *m)
{
    const char *why = NULL;
    if (parse_body(body, m, &why) != 0) {
        UNIT_FAIL("%s: refused: %s", body, why ? why : "?");
        return;
    }
    if (m->kind == MM_CAXST || m->kind == MM_CACST)
        return; /* read only */
    char out[MM_BODY_MAX];
    CHECK(mm_format(m, out, sizeof out) > 0);
    CHECK_STR(out, body);
}

static void test_rates(void)
{
    int bytes[] = {32, 64, 64, 256, 256, 256}, frames[] = {1, 3, 3, 2, 2, 8};
    for (int r = 0; r <= MM_MAX_RATE; r++) {
        CHECK(mm_rate_frame_bytes(r) == bytes[r]);
        CHECK(mm_rate_frames(r) == frames[r]);
    }
    CHECK(mm_rate_frame_bytes(6) == -1 && mm_rate_frames(-1) == -1);
}

static void test_host_sentences(void)
{
    mm_msg m;
    round_trip("CCCFG,SRC,1", &m);
    CHECK(m.kind == MM_CCCFG);
    CHECK_STR(m.u.cfg.name, "SRC");
    CHECK_STR(m.u.cfg.value, "1");
    round_trip("CCCFQ,ALL", &m);
    CHECK(m.kind == MM_CCCFQ);
    CHECK_STR(m.u.cfg.name, "ALL");
    round_trip("CCCYC,0,1,2,0,0,1", &m);
    CHECK(m.kind == MM_CCCYC && m.u.cyc.src == 1 && m.u.cyc.dest == 2 && m.u.cyc.rate == 0 && m.u.cyc.nframes == 1);
    round_trip("CCCYC,0,3,0,5,0,8", &m);
    CHECK(m.u.cyc.rate == 5 && m.u.cyc.nframes == 8 && m.u.cyc.dest == MM_BROADCAST);
    round_trip("CCTXD,1,2,1,48656C6C6F", &m);
    CHECK(m.kind == MM_CCTXD && m.u.data.ack == 1 && m.u.data.n == 5 && !memcmp(m.u.data.data, "Hello", 5));
    round_trip("CCMPC,1,2", &m);
    CHECK(m.kind == MM_CCMPC && m.u.ping.dest == 2);
    /* lower-case hex is read, upper case written */
    const char *why;
    CHECK(parse_body("CCTXD,1,2,0,0a0b", &m, &why) == 0 && m.u.data.n == 2 && m.u.data.data[0] == 10);
}

static void test_modem_sentences(void)
{
    mm_msg m;
    round_trip("CACFG,SRC,1", &m);
    CHECK(m.kind == MM_CACFG);
    round_trip("CACYC,0,2,1,1,1,3", &m);
    CHECK(m.kind == MM_CACYC && m.u.cyc.rate == 1 && m.u.cyc.nframes == 3);
    round_trip("CADRQ,123456,1,2,0,32,1", &m);
    CHECK(m.kind == MM_CADRQ && m.u.drq.nbytes == 32 && m.u.drq.frame == 1);
    CHECK_NEAR(m.u.drq.time_s, 12 * 3600 + 34 * 60 + 56, 1e-9);
    round_trip("CATXD,1,2,0,5", &m);
    CHECK(m.kind == MM_CATXD && m.u.data.n == 5);
    round_trip("CARXD,2,1,0,1,48656C6C6F", &m);
    CHECK(m.kind == MM_CARXD && m.u.data.src == 2 && m.u.data.frame == 1 && m.u.data.n == 5);
    round_trip("CAACK,2,1,1", &m);
    CHECK(m.kind == MM_CAACK && m.u.ack.src == 2 && m.u.ack.dest == 1 && m.u.ack.frame == 1 && m.u.ack.ack == -1);
    round_trip("CAACK,2,1,3,1", &m);
    CHECK(m.u.ack.frame == 3 && m.u.ack.ack == 1);
    round_trip("CAERR,010203,NMEA,2,bad NMEA sentence", &m);
    CHECK(m.kind == MM_CAERR && m.u.err.number == 2);
    CHECK_STR(m.u.err.module, "NMEA");
    CHECK_STR(m.u.err.text, "bad NMEA sentence");
    const char *why;
    CHECK(parse_body("CAERR,010203,CYC,,timeout, no data", &m, &why) == 0 && m.u.err.number == -1);
    CHECK_STR(m.u.err.text, "timeout, no data");
    round_trip("CAREV,000102,AUV,0.93.0.52", &m);
    CHECK(m.kind == MM_CAREV);
    CHECK_STR(m.u.rev.ident, "AUV");
    CHECK_STR(m.u.rev.version, "0.93.0.52");
    round_trip("CAREV,000102,INIT,", &m);
    CHECK_STR(m.u.rev.ident, "INIT");
    /* statistics: a published version-0 CACST (rate 1 from 7 to 6, 3 frames), and version 6 */
    round_trip("CACST,0,223413.0000,0,1440,25,0175,0166,75,01,01,01,03,1,007,006,0,3,3,0,146,03,04,-100,-1,000,-1.2,45,"
               "10000,2000",
               &m);
    CHECK(m.kind == MM_CACST && m.u.cst.version == 0 && m.u.cst.mode == 0 && m.u.cst.rate == 1);
    CHECK(m.u.cst.src == 7 && m.u.cst.dest == 6 && m.u.cst.nframes == 3 && m.u.cst.nbad == 0);
    CHECK_NEAR(m.u.cst.snr_in, 3, 0);
    CHECK_NEAR(m.u.cst.snr_out, 4, 0);
    CHECK_NEAR(m.u.cst.doppler, -1.2, 1e-12);
    round_trip("CACST,6,1,223413.0000,0,1440,25,0175,0166,75,01,01,01,03,0,3,1,0,1,1,1,146,12.5,14,-100,-1,000,0,45,"
               "25000,5000,6,20240101,1",
               &m);
    CHECK(m.u.cst.version == 6 && m.u.cst.mode == 1 && m.u.cst.rate == 0 && m.u.cst.nbad == 1);
    CHECK_NEAR(m.u.cst.snr_in, 12.5, 1e-12);
    round_trip("CAXST,20081212,123456.0000,3,0,200,4000,25000,0,1,2,0,1,1,1,32", &m);
    CHECK(m.kind == MM_CAXST && m.u.xst.version == 0 && m.u.xst.src == 1 && m.u.xst.nbytes == 32);
    round_trip("CAXST,6,20081212,123456.0000,3,0,200,4000,25000,5,1,2,0,8,8,5,2048", &m);
    CHECK(m.u.xst.version == 6 && m.u.xst.rate == 5 && m.u.xst.nframes_sent == 8);
    /* other sentences are not refusals: they are not ours */
    CHECK(parse_body("GPGGA,1,2", &m, &why) == 1 && m.kind == MM_NONE);
    CHECK(parse_body("CAMSG,BAD_CRC,4", &m, &why) == 1);
}

static void test_refusals(void)
{
    CHECK_STR(refusal("CCTXD,1,2,0,4865ZZ"), "bad hex");
    CHECK_STR(refusal("CCTXD,1,2,0,486"), "odd hex length");
    CHECK_STR(refusal("CARXD,2,1,0,1,4"), "odd hex length");
    char big[MM_BODY_MAX + 16] = "CARXD,2,1,0,1,";
    for (int i = 0; i < 257; i++)
        strcat(big, "AB");
    CHECK_STR(refusal(big), "data longer than any frame");
    CHECK_STR(refusal("CATXD,1,2,0,300"), "data longer than any frame");
    CHECK_STR(refusal("CADRQ,123456,1,2,0,999,1"), "data longer than any frame");
    CHECK_STR(refusal("CCCYC,0,1,2,6,0,1"), "unknown rate");
    CHECK_STR(refusal("CCCYC,0,1,2,-1,0,1"), "unknown rate");
    CHECK_STR(refusal("CACST,0,223413.0000,0,1440,25,0175,0166,75,01,01,01,03,9,007,006,0,3,3,0,146,03,04,-100,-1,000,"
                      "-1.2,45,10000,2000"),
              "unknown rate");
    CHECK_STR(refusal("CCCYC,0,1,2,0,0,2"), "bad frame count"); /* rate 0 has one frame */
    CHECK_STR(refusal("CCCYC,0,1,2,0,0"), "missing fields");
    CHECK_STR(refusal("CCCYC,0,1,,0,0,1"), "missing fields");
    CHECK_STR(refusal("CARXD,2,1,0,48656C"), "missing fields");
    CHECK_STR(refusal("CCTXD,1,2,0,AB,CD"), "too many fields");
    CHECK_STR(refusal("CACFG,SRC"), "missing fields");
    CHECK_STR(refusal("CAREV,000102"), "missing fields");
    CHECK_STR(refusal("CCCYC,0,128,2,0,0,1"), "bad address");
    CHECK_STR(refusal("CCTXD,1,-2,0,AB"), "bad address");
    CHECK_STR(refusal("CAACK,x,1,1"), "bad address");
    CHECK_STR(refusal("CCTXD,1,2,2,AB"), "bad flag");
    CHECK_STR(refusal("CARXD,2,1,0,9,AB"), "bad frame number");
    CHECK_STR(refusal("CADRQ,123456,1,2,0,32,0"), "bad frame number");
    CHECK_STR(refusal("CADRQ,256060,1,2,0,32,1"), "bad time");
    CHECK_STR(refusal("CCCFG,1SRC,1"), "bad name");
    CHECK_STR(refusal("CCCFG,S-C,1"), "bad name");
    CHECK_STR(refusal("CAREV,2025-06-06T23:01:23.3x,AUV,2.0.27087"), "bad time");
    CHECK_STR(refusal("CAREV,2025-06-06 23:01:23,AUV,2.0.27087"), "bad time");
    CHECK_STR(refusal("CAXST,100,20250606,230103.000935,3,0,200,5000,25000,1,0,1,0,0,1,5,2,25000"),
              "unknown version");
    CHECK_STR(refusal("CAXST,7,1,2"), "missing fields");
    /* formatting refuses what parsing would */
    mm_msg m = {.kind = MM_CCCYC};
    m.u.cyc = (mm_cyc){0, 1, 2, 7, 0, 1};
    char out[MM_BODY_MAX];
    CHECK(mm_format(&m, out, sizeof out) == -1);
    m.u.cyc = (mm_cyc){0, 1, 200, 0, 0, 1};
    CHECK(mm_format(&m, out, sizeof out) == -1);
    m.u.cyc = (mm_cyc){0, 1, 2, 0, 0, 1};
    CHECK(mm_format(&m, out, 8) == -1); /* does not fit */
    m.kind = MM_CAERR;
    m.u.err = (mm_err){.time_s = -1, .module = "NMEA", .number = 1, .text = "a*b"};
    CHECK(mm_format(&m, out, sizeof out) == -1);
}

static void test_table(void)
{
    mm_table t;
    const char *why = NULL;
    CHECK(mm_table_parse(&t, "AUV1=1,AUV2=2,SHIP_A=10", &why) == 0);
    CHECK(t.n == 3 && mm_table_address(&t, "SHIP_A") == 10 && mm_table_address(&t, "AUV3") == -1);
    CHECK_STR(mm_table_vehicle(&t, 2), "AUV2");
    CHECK(mm_table_vehicle(&t, 3) == NULL);
    const char *bad[] = {"", "AUV1", "AUV1=", "=1", "AUV1=0", "AUV1=128", "AUV1=1x", "AUV1=1,AUV2=1", "AUV1=1,AUV1=2",
                         "AUV1=1,", "AU V=1", "AUV1=99999999999999999999"};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++)
        if (mm_table_parse(&t, bad[i], &why) != -1)
            UNIT_FAIL("table '%s' accepted", bad[i]);
}

/* ---- bridge exchanges */

static mm_bridge B;
static mm_out O;

static void setup(int ack, int cst)
{
    mm_table t;
    const char *why;
    CHECK(mm_table_parse(&t, "AUV1=1,AUV2=2,AUV3=3", &why) == 0);
    mm_options o;
    mm_options_default(&o);
    o.vehicle = "AUV1";
    o.ack = ack;
    o.cst = cst;
    CHECK(mm_bridge_init(&B, &o, &t, &why) == 0);
    mm_out_clear(&O);
}

static void modem_says(const char *body, int64_t t)
{
    mm_msg m;
    const char *why;
    if (parse_body(body, &m, &why) != 0) {
        UNIT_FAIL("%s: %s", body, why);
        return;
    }
    mm_out_clear(&O);
    mm_bridge_input(&B, &m, t, &O);
}

static void test_bridge_start(void)
{
    setup(0, 1);
    mm_bridge_start(&B, 0, &O);
    CHECK(O.n_sentences == 3);
    CHECK_STR(O.sentence[0], "CCCFG,SRC,1");
    CHECK_STR(O.sentence[1], "CCCFG,CST,1");
    CHECK_STR(O.sentence[2], "CCCFQ,SRC");
    modem_says("CACFG,SRC,1", 1000);
    CHECK(B.status.modem_errors == 0);
    modem_says("CACFG,SRC,5", 2000);
    CHECK(B.status.modem_errors == 1);
    CHECK_HAS(B.status.last_error, "the modem's address is 5");
    modem_says("CAREV,000102,AUV,0.93.0.52", 3000);
    CHECK(B.status.heartbeat_utime == 3000);
    CHECK_STR(B.status.revision, "0.93.0.52");
    /* a reboot: configured again */
    modem_says("CAREV,000103,INIT,", 4000);
    CHECK(O.n_sentences == 3 && B.status.heartbeat_utime == 4000);
    mm_table t;
    mm_options o;
    const char *why;
    mm_options_default(&o);
    o.vehicle = "AUV9";
    CHECK(mm_table_parse(&t, "AUV1=1", &why) == 0);
    CHECK(mm_bridge_init(&B, &o, &t, &why) == -1);
    o.vehicle = "AUV1";
    o.rate = 6;
    CHECK(mm_bridge_init(&B, &o, &t, &why) == -1);
}

static void test_bridge_sends_one_frame(void)
{
    setup(1, 1);
    const uint8_t frame[] = {0x12, 0x34, 0xAB};
    CHECK(mm_bridge_send(&B, 7, "AUV2", 2, frame, 3, 1000000, &O) == 0);
    CHECK(O.n_sentences == 1);
    CHECK_STR(O.sentence[0], "CCCYC,0,1,2,0,1,1");
    CHECK(B.status.busy_until_utime == 6000000);
    /* a second frame while this one is on its way: refused, not queued */
    mm_out_clear(&O);
    CHECK(mm_bridge_send(&B, 8, "", 2, frame, 3, 1100000, &O) == 1);
    CHECK(B.status.refused_rate == 1 && B.status.last_refused_seq == 8 && O.n_sentences == 0);
    CHECK_HAS(B.status.last_refusal, "busy: frame 7");
    modem_says("CACYC,0,1,2,0,1,1", 1200000); /* the echo of our cycle */
    CHECK(O.n_sentences == 0);
    modem_says("CADRQ,000001,1,2,1,32,1", 1300000);
    CHECK(O.n_sentences == 1);
    CHECK_STR(O.sentence[0], "CCTXD,1,2,1,1234AB");
    modem_says("CATXD,1,2,1,3", 1400000);
    CHECK(B.status.sent == 1 && B.state == MM_WAIT_ACK);
    modem_says("CAACK,3,1,1", 1500000); /* not from the addressee */
    CHECK(B.status.acked == 0);
    modem_says("CAACK,2,1,1", 1600000);
    CHECK(B.status.acked == 1 && B.state == MM_IDLE && B.status.busy_until_utime == 0);
    /* a broadcast never asks for an ack */
    mm_out_clear(&O);
    CHECK(mm_bridge_send(&B, 9, "", 2, frame, 3, 2000000, &O) == 0);
    CHECK_STR(O.sentence[0], "CCCYC,0,1,0,0,0,1");
    modem_says("CADRQ,000002,1,0,0,32,1", 2100000);
    CHECK_STR(O.sentence[0], "CCTXD,1,0,0,1234AB");
    modem_says("CATXD,1,0,0,3", 2200000);
    CHECK(B.status.sent == 2 && B.state == MM_IDLE);
}

static void test_bridge_refusals(void)
{
    setup(0, 1);
    uint8_t big[40] = {0};
    CHECK(mm_bridge_send(&B, 1, "AUV2", 2, big, 33, 0, &O) == 1);
    CHECK(B.status.refused_size == 1);
    CHECK_HAS(B.status.last_refusal, "33 bytes is over rate 0's 32-byte frame");
    CHECK(mm_bridge_send(&B, 2, "AUV7", 2, big, 3, 0, &O) == 1);
    CHECK(B.status.refused_invalid == 1);
    CHECK_HAS(B.status.last_refusal, "no modem address for AUV7");
    CHECK(mm_bridge_send(&B, 3, "AUV1", 2, big, 3, 0, &O) == 1);
    CHECK(mm_bridge_send(&B, 4, "", 1, big, 3, 0, &O) == 1);
    CHECK(mm_bridge_send(&B, 5, "", 2, big, 0, 0, &O) == 1);
    CHECK(B.status.refused_invalid == 4 && B.state == MM_IDLE);
    /* the modem asks for fewer bytes than the frame has */
    mm_out_clear(&O);
    CHECK(mm_bridge_send(&B, 6, "AUV2", 2, big, 20, 0, &O) == 0);
    modem_says("CADRQ,000001,1,2,0,16,1", 100);
    CHECK_STR(O.sentence[0], "CCTXD,1,2,0,");
    CHECK(B.status.refused_size == 2 && B.state == MM_IDLE);
    /* a request for data we have not got: an empty frame */
    modem_says("CADRQ,000001,1,3,0,32,1", 200);
    CHECK_STR(O.sentence[0], "CCTXD,1,3,0,");
}

static void test_bridge_receives_one_frame(void)
{
    setup(0, 1);
    modem_says("CACYC,0,2,0,0,0,1", 5000000);
    modem_says("CARXD,2,0,0,1,0102030405", 5100000);
    CHECK(O.n_frames == 0); /* held for its CACST */
    modem_says("CACST,0,223413.0000,0,1440,25,0175,0166,75,01,01,01,03,0,2,0,0,1,1,0,146,9.5,04,-100,-1,000,-1.2,45,"
               "25000,5000",
               5200000);
    CHECK(O.n_frames == 1 && B.status.received == 1);
    mm_rx_frame *f = &O.frame[0];
    CHECK(f->utime == 5100000 && f->kind == 2 && f->n_bytes == 5 && f->payload[4] == 5);
    CHECK_STR(f->src_vehicle, "AUV2");
    CHECK_STR(f->dst_vehicle, "");
    CHECK(f->src_address == 2 && f->dst_address == 0 && f->rate == 0);
    CHECK_NEAR(f->snr_db, 9.5, 1e-12);
    /* unicast to us, no CACST: delivered after the hold, without an SNR */
    modem_says("CARXD,3,1,0,1,AA", 6000000);
    mm_out_clear(&O);
    mm_bridge_tick(&B, 7999999, &O);
    CHECK(O.n_frames == 0);
    mm_bridge_tick(&B, 8000000, &O);
    CHECK(O.n_frames == 1 && isnan(O.frame[0].snr_db) && O.frame[0].rate == -1);
    CHECK_STR(O.frame[0].dst_vehicle, "AUV1");
    /* dropped: unknown sender, another's frame, too long for the cycle's rate */
    modem_says("CARXD,9,1,0,1,AA", 9000000);
    modem_says("CARXD,2,3,0,1,AA", 9000000);
    modem_says("CACYC,0,2,1,0,0,1", 9000000);
    char body[200] = "CARXD,2,1,0,1,";
    for (int i = 0; i < 33; i++)
        strcat(body, "00");
    modem_says(body, 9000000);
    CHECK(B.status.rx_dropped == 3 && B.status.received == 2);
    CHECK_HAS(B.status.last_error, "33-byte frame is over rate 0's 32 bytes");
    /* a bad-CRC packet counts as lost */
    modem_says("CACST,0,223413.0000,1,1440,25,0175,0166,75,01,01,01,03,0,2,1,0,1,1,1,146,03,04,-100,-1,000,-1.2,45,"
               "25000,5000",
               9100000);
    CHECK(B.status.lost == 1);
    /* without CST, frames go straight out */
    setup(0, 0);
    modem_says("CARXD,2,0,0,1,AA", 100);
    CHECK(O.n_frames == 1 && B.status.received == 1);
}

static void test_bridge_error_and_timeouts(void)
{
    setup(1, 1);
    const uint8_t frame[] = {1};
    CHECK(mm_bridge_send(&B, 1, "AUV2", 2, frame, 1, 0, &O) == 0);
    modem_says("CAERR,000001,CYC,5,no data", 100);
    CHECK(B.status.modem_errors == 1 && B.state == MM_IDLE);
    CHECK_HAS(B.status.last_error, "CAERR CYC 5: no data");
    /* the modem never asks for the data */
    mm_out_clear(&O);
    CHECK(mm_bridge_send(&B, 2, "AUV2", 2, frame, 1, 1000000, &O) == 0);
    mm_bridge_tick(&B, 5999999, &O);
    CHECK(B.state == MM_WAIT_DRQ);
    mm_bridge_tick(&B, 6000000, &O);
    CHECK(B.status.timeouts == 1 && B.state == MM_IDLE && O.status_changed);
    CHECK_HAS(B.status.last_error, "no CADRQ within 5.0 s for frame 2");
    /* sent, never acknowledged */
    mm_out_clear(&O);
    CHECK(mm_bridge_send(&B, 3, "AUV2", 2, frame, 1, 7000000, &O) == 0);
    modem_says("CADRQ,000001,1,2,1,32,1", 7100000);
    modem_says("CATXD,1,2,1,1", 7200000);
    mm_out_clear(&O);
    mm_bridge_tick(&B, 27200000, &O);
    CHECK(B.status.ack_timeouts == 1 && B.status.sent == 1 && B.state == MM_IDLE);
    /* a reboot in the middle of a cycle */
    mm_out_clear(&O);
    CHECK(mm_bridge_send(&B, 4, "AUV2", 2, frame, 1, 30000000, &O) == 0);
    modem_says("CAREV,000001,INIT,", 30100000);
    CHECK(B.state == MM_IDLE && B.status.timeouts == 2 && O.n_sentences == 3);
}

/* What Micro-Modem 2 firmware prints (our own sentences in its shapes, as
 * public host code quotes them): statistics of versions 7 and 8
 * with version 6's fields first, ISO date-times, hierarchical parameter
 * names, a CAREV without its time; and the many sentences the bridge does
 * not use, which are not refusals. */
static void test_later_firmware(void)
{
    mm_msg m;
    const char *why;
    CHECK(parse_body("CACST,8,0,20250606230123.348554,06,32767,45,0102,0123,07,00,00,00,00,1,001,002,0,5,3,1,150,"
                     "26.0,9.48,-100,-6.48,-01,0.01,51,25000,5000,0,-1,-1,00",
                     &m, &why) == 0);
    CHECK(m.kind == MM_CACST && m.u.cst.version == 8 && m.u.cst.mode == 0 && m.u.cst.rate == 1);
    CHECK(m.u.cst.src == 1 && m.u.cst.dest == 2 && m.u.cst.nframes == 3 && m.u.cst.nbad == 1);
    CHECK_NEAR(m.u.cst.snr_in, 26.0, 1e-12);
    CHECK_NEAR(m.u.cst.doppler, 0.01, 1e-12);
    CHECK(parse_body("CACST,7,0,20250606230123.348554,06,32767,45,0102,0123,07,00,00,00,00,3,002,001,0,3,2,0,150,"
                     "14.5,9.48,-100,-6.48,-01,0.01,51,25000,5000,0",
                     &m, &why) == 0);
    CHECK(m.u.cst.version == 7 && m.u.cst.rate == 3 && m.u.cst.src == 2);
    CHECK(parse_body("CAXST,7,20250606,230117.336548,3,0,200,5000,25000,1,2,1,0,3,3,5,192,25000", &m, &why) == 0);
    CHECK(m.kind == MM_CAXST && m.u.xst.version == 7 && m.u.xst.rate == 1 && m.u.xst.src == 2);
    CHECK(m.u.xst.dest == 1 && m.u.xst.nframes_sent == 3 && m.u.xst.nbytes == 192);
    CHECK(parse_body("CAREV,2025-06-06T23:01:03.000935,AUV,2.0.27087", &m, &why) == 0);
    CHECK_NEAR(m.u.rev.time_s, 23 * 3600 + 60 + 3.000935, 1e-6);
    CHECK_STR(m.u.rev.version, "2.0.27087");
    CHECK(parse_body("CAREV,181807,COPROC,0.20.0.56", &m, &why) == 0);
    CHECK_STR(m.u.rev.ident, "COPROC");
    CHECK(parse_body("CAREV,INIT,2.0.27087", &m, &why) == 0 && m.u.rev.time_s == -1);
    CHECK_STR(m.u.rev.ident, "INIT");
    CHECK_STR(m.u.rev.version, "2.0.27087");
    CHECK(parse_body("CADRQ,2025-06-06T23:01:03.5,1,2,1,64,1", &m, &why) == 0 && m.u.drq.nbytes == 64);
    CHECK(parse_body("CAERR,2025-06-06T23:01:03,DTO,4,Data timeout", &m, &why) == 0 && m.u.err.number == 4);
    round_trip("CACFG,xst.version,7", &m);
    CHECK_STR(m.u.cfg.name, "xst.version");
    round_trip("CACFG,pwramp.txlevel,3", &m);
    /* not used by the bridge, not refusals */
    const char *others[] = {"CATXP,32", "CATXF,32", "CAMSG,BAD_CRC,4", "CAMPR,2,1,1.2345", "CATMS,0,2025-06-06T23:01:03Z",
                            "CACLK,2025,06,06,23,01,03", "CAMUC,1,2,0F0F", "CATMG,2025-06-06T23:01:03,1,3",
                            "CACMD,PNG,0,1,1,0,3", "SNTTA,1.2,,,,230103"};
    for (size_t k = 0; k < sizeof others / sizeof others[0]; k++)
        CHECK(parse_body(others[k], &m, &why) == 1 && m.kind == MM_NONE);
    /* the bridge: a reboot announced without a time still reconfigures */
    setup(0, 1);
    modem_says("CAREV,INIT,2.0.27087", 1000);
    CHECK(O.n_sentences == 3);
    CHECK_STR(O.sentence[0], "CCCFG,SRC,1");
    /* a frame received with version-8 statistics: its SNR */
    modem_says("CACYC,0,2,1,1,0,1", 5000000);
    modem_says("CARXD,2,1,0,1,0102", 5100000);
    modem_says("CACST,8,0,20250606230123.348554,06,32767,45,0102,0123,07,00,00,00,00,1,002,001,0,5,1,0,150,12.25,"
               "9.48,-100,-6.48,-01,0.01,51,25000,5000,0,-1,-1,00",
               5200000);
    CHECK(O.n_frames == 1 && B.status.received == 1 && B.status.lost == 0);
    CHECK_NEAR(O.frame[0].snr_db, 12.25, 1e-12);
    CHECK(O.frame[0].rate == 1);
}

/* Every file of the hostile corpus through the framer, the parser and a
 * bridge: no crash, no sanitizer report; bad_* files' sentences are all
 * refused (by the framer or the parser), ok_* files' all accepted. */
static void test_corpus(void)
{
    const char *dir = getenv("MM_CORPUS") ? getenv("MM_CORPUS") : "tests/drivers/corpus/mm";
    DIR *d = opendir(dir);
    if (!d) {
        UNIT_FAIL("cannot open %s (run from the repository's root, or set MM_CORPUS)", dir);
        return;
    }
    struct dirent *e;
    int files = 0;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.')
            continue;
        char path[512];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        FILE *f = fopen(path, "rb");
        if (!f)
            continue;
        files++;
        setup(1, 1);
        nmea_framer fr;
        nmea_framer_init(&fr, 0);
        nmea_sentence s;
        int accepted = 0, refused = 0, c;
        int64_t t = 0;
        while ((c = fgetc(f)) != EOF) {
            int r = nmea_framer_push(&fr, (uint8_t)c, &s);
            if (r > 0)
                refused++;
            if (r != NMEA_OK)
                continue;
            mm_msg m;
            const char *why;
            int rc = mm_parse(&s, &m, &why);
            if (rc == 0) {
                accepted++;
                mm_out_clear(&O);
                mm_bridge_input(&B, &m, t += 100000, &O);
                mm_bridge_tick(&B, t, &O);
            } else {
                refused++;
            }
        }
        fclose(f);
        if (!strncmp(e->d_name, "bad_", 4) && (accepted || !refused))
            UNIT_FAIL("%s: %d accepted, %d refused: expected only refusals", path, accepted, refused);
        if (!strncmp(e->d_name, "ok_", 3) && (refused || !accepted))
            UNIT_FAIL("%s: %d accepted, %d refused: expected only accepted sentences", path, accepted, refused);
    }
    closedir(d);
    CHECK(files >= 3);
}

static const unit_test tests[] = {
    {"mm_rates", test_rates},
    {"mm_host_sentences", test_host_sentences},
    {"mm_modem_sentences", test_modem_sentences},
    {"mm_later_firmware", test_later_firmware},
    {"mm_refusals", test_refusals},
    {"mm_table", test_table},
    {"mm_bridge_start", test_bridge_start},
    {"mm_bridge_sends_one_frame", test_bridge_sends_one_frame},
    {"mm_bridge_refusals", test_bridge_refusals},
    {"mm_bridge_receives_one_frame", test_bridge_receives_one_frame},
    {"mm_bridge_error_and_timeouts", test_bridge_error_and_timeouts},
    {"mm_corpus", test_corpus},
    {NULL, NULL},
};

__attribute__((constructor)) static void register_tests(void) { unit_register_list(tests); }
