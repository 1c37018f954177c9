/* Unit tests of auv-frontseat (c/frontseat) with the Iver3 Remote Helm
 * protocol: the sentences as Goby3's Iver driver and the ACFR UVC driver read
 * and write them, the setpoint's limits (clamped, refused: each reason), the
 * state (control, manual, error, silence) and the hostile corpus of
 * tests/drivers/corpus/iver3/ (each file: the stream, and the counts it must
 * give). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "auv/auv_frontseat_status_t.h"
#include "auv/auv_nav_solution_t.h"
#include "common/lcm_rx.h"
#include "drivers/common/nmea.h"
#include "frontseat/frontseat.h"
#include "../harness/unit.h"
#include "corpus_expect.h"

#define T0 INT64_C(1700000000000000)
#define MS INT64_C(1000)
#define DEG (M_PI / 180.0)
#define FT 0.3048

typedef struct {
    fs_state fs;
    drv_ctx ctx;
    int n_nav, n_status;
    auv_nav_solution_t nav;        /* the newest */
    auv_frontseat_status_t status; /* the newest, strings copied below */
    char mode[16], error_text[32], last_refusal[160];
    char written[4096]; /* what went to the frontseat */
} rig;

static void capture(void *user, const char *channel, const auv_type_entry_t *type, const void *data, int len)
{
    rig *r = user;
    if (!strcmp(channel, "AUV1.NAV")) {
        CHECK(rx_decode(type, data, len, &r->nav) == 0);
        CHECK_STR(r->nav.vehicle, "AUV1");
        auv_nav_solution_t_decode_cleanup(&r->nav);
        r->n_nav++;
    } else {
        CHECK_STR(channel, "AUV1.FRONTSEAT");
        CHECK(rx_decode(type, data, len, &r->status) == 0);
        snprintf(r->mode, sizeof r->mode, "%s", r->status.mode);
        snprintf(r->error_text, sizeof r->error_text, "%s", r->status.error_text);
        snprintf(r->last_refusal, sizeof r->last_refusal, "%s", r->status.last_refusal);
        CHECK_STR(r->status.protocol, "iver3");
        auv_frontseat_status_t_decode_cleanup(&r->status);
        r->n_status++;
    }
}

static int write_capture(void *user, const uint8_t *data, size_t n)
{
    rig *r = user;
    size_t used = strlen(r->written);
    if (used + n < sizeof r->written) {
        memcpy(r->written + used, data, n);
        r->written[used + n] = '\0';
    }
    return 0;
}

static rig *rig_new(const char *const *flags)
{
    rig *r = calloc(1, sizeof *r);
    drv_ctx_init(&r->ctx, "test", "AUV1", "FRONTSEAT", capture, r);
    r->ctx.quiet = 1;
    r->ctx.write = write_capture;
    r->ctx.write_user = r;
    char err[200];
    for (int i = 0; flags && flags[i]; i += 2) {
        int found = 0;
        for (const drv_flag *f = frontseat_protocol.flags; f->name; f++)
            if (!strcmp(f->name, flags[i])) {
                CHECK(f->set(&r->fs, flags[i + 1], err, sizeof err) == 0);
                found = 1;
            }
        CHECK(found);
    }
    CHECK(frontseat_protocol.init(&r->fs, &r->ctx) == 0);
    return r;
}

static void feed(rig *r, const char *text, int64_t stamp)
{
    frontseat_protocol.tick(&r->fs, &r->ctx, stamp);
    frontseat_protocol.feed(&r->fs, &r->ctx, (const uint8_t *)text, strlen(text), stamp);
}

static const char *sentence(const char *body)
{
    static char buf[8][300];
    static int k;
    char *out = buf[k++ % 8];
    CHECK(nmea_format(out, 300, body) > 0);
    return out;
}

static int64_t count(const rig *r, const char *reason) { return drv_reasons_get(&r->ctx.reasons, reason); }

static void setpoint(rig *r, auv_setpoint_t sp, int64_t now)
{
    r->written[0] = '\0';
    frontseat_protocol.subscriptions[0].handler(&r->fs, &r->ctx, &sp, now);
}

static auv_setpoint_t depth_sp(int64_t utime, double heading, double depth, double speed)
{
    auv_setpoint_t sp;
    memset(&sp, 0, sizeof sp);
    sp.utime = utime;
    sp.heading_rad = heading;
    sp.vertical_mode = AUV_SETPOINT_T_VERTICAL_DEPTH;
    sp.depth_m = depth;
    sp.speed_mode = AUV_SETPOINT_T_SPEED_MPS;
    sp.speed_mps = speed;
    return sp;
}

/* an OSI of mode `mode`, error `err`, at 41.5 N 70.7 W, 2.9 kn, 32.8 ft over
 * the seabed, heading 82.8, 3.2 ft deep (Remote Helm 4's 15 fields) */
static const char *osi(const char *mode, const char *err)
{
    static char body[200];
    snprintf(body, sizeof body, "OSI,8080808080,%s,0,41.5000000,-70.7000000,2.9,0.0,%s,32.8,P0,-15.0,m1,0.0,82.8,3.2",
             mode, err);
    return sentence(body);
}

static void test_published_examples(void)
{
    rig *r = rig_new((const char *const[]){"--origin", "41.5,-70.7", NULL});
    /* Goby3's example compass sentence, its checksum as published */
    feed(r, "$C82.8P-3.89R-2.63T20.3D3.2*78\r\n", T0);
    CHECK(r->ctx.reasons.total == 0);
    CHECK(r->n_nav == 0); /* no position yet */
    feed(r, osi("A", "N"), T0 + 50 * MS);
    CHECK(r->n_nav == 1);
    CHECK(r->nav.utime == T0 + 50 * MS);
    CHECK(fabs(r->nav.latitude_deg - 41.5) < 1e-9 && fabs(r->nav.longitude_deg + 70.7) < 1e-9);
    CHECK(fabs(r->nav.north_m) < 1e-6 && fabs(r->nav.east_m) < 1e-6);
    CHECK(fabs(r->nav.depth_m - 3.2 * FT) < 1e-9);
    CHECK(fabs(r->nav.altitude_m - 32.8 * FT) < 1e-9);
    CHECK(fabs(r->nav.heading_rad - 82.8 * DEG) < 1e-9);
    CHECK(fabs(r->nav.pitch_rad + 3.89 * DEG) < 1e-9 && fabs(r->nav.roll_rad + 2.63 * DEG) < 1e-9);
    CHECK(fabs(r->nav.u_mps - 2.9 * 1852.0 / 3600.0) < 1e-9);
    CHECK(isnan(r->nav.v_mps) && isnan(r->nav.r_radps) && isnan(r->nav.course_over_ground_rad));
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_PAYLOAD && r->status.has_control);
    CHECK_STR(r->mode, "A");
    CHECK(r->status.control_granted == 1);
    /* the poll it writes on its tick: Goby3's data request */
    CHECK(strstr(r->written, "$OSD,G,C,S,P,,,,*") != NULL);
    /* without --origin: no local position */
    rig *q = rig_new(NULL);
    feed(q, "$C82.8P-3.89R-2.63T20.3D3.2*78\r\n", T0);
    feed(q, osi("N", "N"), T0);
    CHECK(q->n_nav == 1 && isnan(q->nav.north_m) && isnan(q->nav.east_m));
    CHECK(q->status.state == AUV_FRONTSEAT_STATUS_T_STATE_FRONTSEAT && !q->status.has_control);
    free(q);
    free(r);
}

static void test_request_sentence(void)
{
    rig *r = rig_new(NULL);
    feed(r, osi("N", "N"), T0);
    setpoint(r, depth_sp(T0, 1.0, 10.0, 1.5), T0 + 10 * MS);
    /* heading [deg], depth [m] (Remote Helm 5), max pitch [deg], speed [kn], timeout [s] */
    CHECK_STR(r->written, sentence("OMS,57.3,10.0,30.0,2.9,5"));
    CHECK(r->fs.requests_sent == 1 && r->ctx.reasons.total == 0);
    /* held: asked again each --resend-period while the setpoint is fresh */
    r->written[0] = '\0';
    frontseat_protocol.tick(&r->fs, &r->ctx, T0 + 1100 * MS);
    CHECK(strstr(r->written, "$OMS,57.3,10.0,") != NULL);
    /* a setpoint the navigator stopped sending: no more requests */
    feed(r, osi("N", "N"), T0 + 2500 * MS);
    r->written[0] = '\0';
    frontseat_protocol.tick(&r->fs, &r->ctx, T0 + 3000 * MS);
    CHECK(strstr(r->written, "$OMS") == NULL);
    free(r);
    /* Remote Helm 4 takes feet; a negative heading wraps */
    rig *v4 = rig_new((const char *const[]){"--helm-version", "4", "--request-timeout", "10", NULL});
    feed(v4, osi("N", "N"), T0);
    setpoint(v4, depth_sp(T0, -M_PI / 2, 3.048, 1.0), T0);
    CHECK_STR(v4->written, sentence("OMS,270.0,10.0,30.0,1.9,10"));
    /* a heading a hair under north is north (0.0), never 360.0, out of the range */
    setpoint(v4, depth_sp(T0, 359.97 * M_PI / 180.0, 3.048, 1.0), T0);
    CHECK_STR(v4->written, sentence("OMS,0.0,10.0,30.0,1.9,10"));
    free(v4);
}

static void test_limits(void)
{
    rig *r = rig_new((const char *const[]){"--max-depth", "50", "--min-speed", "0.5", "--max-speed", "2", NULL});
    feed(r, osi("N", "N"), T0);
    feed(r, sentence("C10.0P0.0R0.0T15.0D32.8"), T0);
    setpoint(r, depth_sp(T0, 0.0, 80.0, 1.0), T0);
    CHECK_STR(r->written, sentence("OMS,0.0,50.0,30.0,1.9,5"));
    CHECK(r->fs.setpoints_clamped == 1);
    setpoint(r, depth_sp(T0, 0.0, 10.0, 3.0), T0);
    CHECK(strstr(r->written, ",3.9,5*") != NULL); /* 2 m/s */
    setpoint(r, depth_sp(T0, 0.0, -1.0, 1.0), T0);
    CHECK(strstr(r->written, "$OMS,0.0,0.0,") != NULL);
    CHECK(r->fs.setpoints_clamped == 3);
    /* refused: never sent, each reason counted */
    setpoint(r, depth_sp(T0, NAN, 10.0, 1.0), T0);
    CHECK(r->written[0] == '\0');
    CHECK(count(r, "setpoint: heading not a number") == 1);
    setpoint(r, depth_sp(T0, 0.0, INFINITY, 1.0), T0);
    CHECK(count(r, "setpoint: depth not a number") == 1);
    setpoint(r, depth_sp(T0, 0.0, 10.0, 0.2), T0);
    CHECK(count(r, "setpoint: speed under the minimum") == 1);
    auv_setpoint_t sp = depth_sp(T0, 0.0, 10.0, 1.0);
    sp.vertical_mode = AUV_SETPOINT_T_VERTICAL_PITCH;
    setpoint(r, sp, T0);
    CHECK(count(r, "setpoint: pitch setpoint (the frontseat holds a depth)") == 1);
    sp = depth_sp(T0, 0.0, 10.0, 1.0);
    sp.speed_mode = AUV_SETPOINT_T_SPEED_RPM;
    setpoint(r, sp, T0);
    CHECK(count(r, "setpoint: rpm setpoint (the frontseat holds a speed)") == 1);
    setpoint(r, depth_sp(0, 0.0, 10.0, 1.0), T0);
    CHECK(count(r, "setpoint: setpoint without a time") == 1);
    setpoint(r, depth_sp(T0, 0.0, 10.0, 1.0), T0 + 2500 * MS);
    CHECK(count(r, "setpoint: stale setpoint") == 1);
    CHECK(r->written[0] == '\0');
    CHECK(r->fs.setpoints_refused == 7);
    /* an altitude: the depth that puts the vehicle there (10 m deep, 32.8 ft = 10 m up: 5 m up is 15 m deep) */
    sp = depth_sp(T0, 0.0, 0.0, 1.0);
    sp.vertical_mode = AUV_SETPOINT_T_VERTICAL_ALTITUDE;
    sp.altitude_m = 5.0;
    setpoint(r, sp, T0);
    CHECK(strstr(r->written, "$OMS,0.0,15.0,") != NULL);
    frontseat_protocol.tick(&r->fs, &r->ctx, T0 + 100 * MS);
    CHECK(strstr(r->last_refusal, "refused: stale setpoint") != NULL || r->n_status > 0);
    free(r);
    /* nothing heard yet: nothing asked */
    rig *q = rig_new(NULL);
    setpoint(q, depth_sp(T0, 0.0, 10.0, 1.0), T0);
    CHECK(q->written[0] == '\0' && count(q, "setpoint: frontseat not connected") == 1);
    free(q);
}

static void test_states(void)
{
    rig *r = rig_new(NULL);
    frontseat_protocol.tick(&r->fs, &r->ctx, T0);
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_NOT_CONNECTED && r->status.last_message_age_s == -1.0);
    feed(r, osi("N", "N"), T0);
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_FRONTSEAT);
    feed(r, osi("A", "N"), T0 + 200 * MS);
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_PAYLOAD && r->status.control_granted == 1);
    /* an operator takes it */
    feed(r, osi("M", "N"), T0 + 400 * MS);
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_MANUAL && !r->status.has_control);
    CHECK(r->status.control_lost == 1);
    feed(r, osi("mP", "N"), T0 + 500 * MS);
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_MANUAL);
    /* its safety rule: stopped, with its error word (ACFR's list: Stl time limit) */
    feed(r, osi("S", "Stl"), T0 + 600 * MS);
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_ERROR && r->status.error);
    CHECK_STR(r->error_text, "Stl");
    /* silent: after --silent-after (3 s), no requests */
    feed(r, osi("A", "N"), T0 + 1000 * MS);
    setpoint(r, depth_sp(T0 + 1000 * MS, 0.0, 10.0, 1.0), T0 + 1000 * MS);
    CHECK(strstr(r->written, "$OMS") != NULL);
    frontseat_protocol.tick(&r->fs, &r->ctx, T0 + 3900 * MS);
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_PAYLOAD);
    frontseat_protocol.tick(&r->fs, &r->ctx, T0 + 4100 * MS);
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_SILENT && !r->status.has_control);
    CHECK(fabs(r->status.last_message_age_s - 3.1) < 1e-9 && !r->status.requesting);
    setpoint(r, depth_sp(T0 + 4200 * MS, 0.0, 10.0, 1.0), T0 + 4200 * MS);
    CHECK(strstr(r->written, "$OMS") == NULL && count(r, "setpoint: frontseat silent") == 1);
    /* back */
    feed(r, osi("A", "N"), T0 + 5000 * MS);
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_PAYLOAD);
    free(r);
}

static void test_refused_sentences(void)
{
    rig *r = rig_new(NULL);
    feed(r, "$C82.8P-3.89R-2.63T20.3D3.2*79\r\n", T0);
    CHECK(count(r, "bad checksum") == 1);
    feed(r, "$C82.8P-3.89R-2.63T20.3D3.2*7\r\n", T0); /* a '*' without its two digits */
    CHECK(count(r, "bad checksum") == 2 && count(r, "no checksum") == 0);
    feed(r, sentence("C400.0P0R0T0D1"), T0);
    CHECK(count(r, "compass out of range") == 1);
    feed(r, sentence("C1.0P0R0T1D"), T0);      /* a letter without its number */
    feed(r, sentence("C1.0P0P1R0T1D1"), T0);   /* a field twice */
    feed(r, sentence("C1.0P0,R0T1D1"), T0);    /* a comma: not a compass sentence */
    CHECK(count(r, "bad compass sentence") == 3);
    feed(r, osi("X", "N"), T0);
    CHECK(count(r, "unknown mode") == 1);
    feed(r, sentence("OSI,8080808080,N,0,91.0,-70.7,2.9,0.0,N,32.8,P0,-15.0,m1,0.0,82.8,3.2"), T0);
    feed(r, sentence("OSI,8080808080,N,0,0x10,-70.7,2.9,0.0,N,32.8,P0,-15.0,m1,0.0,82.8,3.2"), T0);
    CHECK(count(r, "bad position") == 2);
    feed(r, sentence("OSI,8080808080,N,0,41.5,-70.7,99,0.0,N,32.8,P0,-15.0,m1,0.0,82.8,3.2"), T0);
    CHECK(count(r, "speed out of range") == 1);
    feed(r, sentence("OSI,8080808080,N,0,41.5,-70.7,2.9,0.0,N,32.8,P0"), T0);
    CHECK(count(r, "OSI too short") == 1);
    feed(r, sentence("OSI,8080808080,N,0,41.5,-70.7,2.9,0.0,N,32.8,P0,-15.0,m1,0.0,720,3.2"), T0);
    CHECK(count(r, "heading out of range") == 1);
    feed(r, "noise$OSI,1,2$C1", T0);
    CHECK(count(r, "garbage") == 1 && count(r, "truncated") == 1);
    char longline[400] = "$";
    memset(longline + 1, 'A', 300);
    strcpy(longline + 301, "\r\n");
    feed(r, longline, T0);
    CHECK(count(r, "too long") == 1);
    CHECK(r->n_nav == 0 && r->fs.last_heard == -1); /* nothing refused counts as heard */
    feed(r, sentence("ACK,1,0,0"), T0); /* ACFR's $ACK: heard, not used */
    CHECK(r->fs.last_heard == T0);
    free(r);
}

/* What a real Remote Helm writes beyond our emulator's lines, each read as
 * the protocol's definition allows (Goby3's Iver driver reads them so). */
static void test_real_variants(void)
{
    rig *r = rig_new(NULL);
    /* the checksum is optional (NMEA 0183): a line without one is read */
    feed(r, "$C82.8P-3.89R-2.63T20.3D3.2\r\n", T0);
    feed(r, "$OSI,8080808080,N,0,41.5000000,-70.7000000,2.9,0.0,N,32.8,P0,-15.0,m1,0.0,82.8,3.2\r\n", T0);
    CHECK(r->ctx.reasons.total == 0 && r->n_nav == 1 && fabs(r->nav.latitude_deg - 41.5) < 1e-9);
    /* whole sentences run together without their CR LF (a full output buffer): each read */
    feed(r, "$C82.8P-3.89R-2.63T20.3D3.2*78$C82.8P-3.89R-2.63T20.3D3.2*78", T0 + 1 * MS);
    feed(r, "$OSI,8080808080,N,0,41.5000000,-70.7000000,2.9,0.0,N,32.8,P0,-15.0,m1,0.0,82.8,3.2*66\r\n", T0 + 2 * MS);
    CHECK(r->ctx.reasons.total == 0 && r->n_nav == 2 && r->ctx.frames_decoded == 5);
    /* the compass writes what it is set to: more outputs after D (skipped), or fewer fields */
    feed(r, sentence("C90.5P1.5R-2.5T20.1D6.4M51.2Mx12.3My-4.5Mz48.9A1.0Ax0.01Ay0.02Az0.99"), T0 + 10 * MS);
    CHECK(r->ctx.reasons.total == 0);
    CHECK(fabs(r->fs.nav.heading_rad - 90.5 * DEG) < 1e-9 && fabs(r->fs.nav.pitch_rad - 1.5 * DEG) < 1e-9);
    CHECK(fabs(r->fs.nav.roll_rad + 2.5 * DEG) < 1e-9 && fabs(r->fs.nav.depth_m - 6.4 * FT) < 1e-9);
    feed(r, sentence("C91.0P2.0R-3.0"), T0 + 20 * MS); /* no temperature, no depth: the depth held */
    CHECK(r->ctx.reasons.total == 0 && fabs(r->fs.nav.heading_rad - 91.0 * DEG) < 1e-9);
    CHECK(fabs(r->fs.nav.depth_m - 6.4 * FT) < 1e-9);
    /* no fix yet: the position empty; the state is read, no NAV with an old position */
    feed(r, sentence("OSI,8080808080,N,0,,,,,N,,,,,,,"), T0 + 30 * MS);
    CHECK(r->ctx.reasons.total == 0 && r->n_nav == 2 && r->fs.last_heard == T0 + 30 * MS);
    /* an empty speed or altimeter: not known, the rest stands */
    feed(r, sentence("OSI,8080808080,N,0,41.5001000,-70.7000000,,0.0,N,,P0,-15.0,m1,0.0,82.8,3.2"), T0 + 40 * MS);
    CHECK(r->ctx.reasons.total == 0 && r->n_nav == 3 && fabs(r->nav.latitude_deg - 41.5001) < 1e-9);
    CHECK(r->nav.altitude_m == -1.0 && fabs(r->nav.u_mps - 2.9 * 1852.0 / 3600.0) < 1e-9);
    /* the mode's first letter decides (Goby3): mP and Mp are an operator's parking */
    feed(r, osi("mP", "N"), T0 + 50 * MS);
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_MANUAL && !r->status.has_control);
    feed(r, osi("Mp", "N"), T0 + 60 * MS);
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_MANUAL);
    /* several error codes run together: the whole word */
    feed(r, osi("S", "SopStlSle"), T0 + 70 * MS);
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_ERROR && r->status.error);
    CHECK_STR(r->error_text, "SopStlSle");
    CHECK(r->ctx.reasons.total == 0);
    /* binary between the lines with a '$' in it: one run of garbage, not a broken sentence */
    feed(r, "$\x01\xb5\x62\x01\x02$C82.8P-3.89R-2.63T20.3D3.2*78\r\n", T0 + 80 * MS);
    CHECK(count(r, "garbage") == 1 && count(r, "bad character") == 0 && r->ctx.reasons.total == 1);
    CHECK(r->fs.last_heard == T0 + 80 * MS); /* the compass after it was read */
    free(r);
}

static long expected(const rig *r, const char *name)
{
    if (!strcmp(name, "navs"))
        return r->n_nav;
    if (!strcmp(name, "total"))
        return (long)r->ctx.reasons.total;
    return (long)count(r, name);
}

static void *corpus_open(void) { return rig_new(NULL); }

static void corpus_read(void *p, const uint8_t *data, size_t n, size_t k)
{
    rig *r = p;
    (void)k;
    frontseat_protocol.feed(&r->fs, &r->ctx, data, n, T0);
}

static long corpus_figure(void *p, const char *name) { return expected(p, name); }

static const char *corpus_last_error(void *p) { return ((rig *)p)->ctx.last_error; }

static void test_hostile_corpus(void)
{
    const corpus_rig c = {13, corpus_open, corpus_read, NULL, corpus_figure, corpus_last_error};
    CHECK(corpus_check("tests/drivers/corpus/iver3", &c) >= 3); /* reads of 13 bytes */
}

static const unit_test tests[] = {
    {"iver3_published_examples", test_published_examples},
    {"iver3_request_sentence", test_request_sentence},
    {"iver3_limits", test_limits},
    {"iver3_states", test_states},
    {"iver3_refused_sentences", test_refused_sentences},
    {"iver3_real_variants", test_real_variants},
    {"iver3_hostile_corpus", test_hostile_corpus},
    {NULL, NULL},
};

__attribute__((constructor)) static void register_tests(void) { unit_register_list(tests); }
