/* Unit tests of auv-frontseat (c/frontseat) with Bluefin's standard payload
 * interface (Huxley BPI): the sentences as Goby3's Bluefin driver reads and
 * writes them (no example sentence with its checksum is public: these are
 * built from its field lists), the logging and heartbeat it asks, the $BPRMB
 * request, the limits (clamped, refused: each reason, and the vehicle's own
 * refusal in a $BFACK), the state ($BFMIS, $BFMSC, $BFCTL, $BFSHT, silence) and
 * the hostile corpus of tests/drivers/corpus/bluefin/ (each file: the stream,
 * and the counts it must give). */
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
        CHECK_STR(r->status.protocol, "bluefin");
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
    /* every rig speaks the BPI: --protocol bluefin first */
    rig *r = calloc(1, sizeof *r);
    drv_ctx_init(&r->ctx, "test", "AUV1", "FRONTSEAT", capture, r);
    r->ctx.quiet = 1;
    r->ctx.write = write_capture;
    r->ctx.write_user = r;
    char err[200];
    for (const drv_flag *f = frontseat_protocol.flags; f->name; f++)
        if (!strcmp(f->name, "--protocol"))
            CHECK(f->set(&r->fs, "bluefin", err, sizeof err) == 0);
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

/* 41.5 N 70.7 W, 10 m over the seabed, 3.5 m deep, heading 82.8, roll -2.6, pitch -3.9 */
#define NVG "BFNVG,221320.000,4130.0000,N,07042.0000,W,1,10.0,3.5,82.8,-2.6,-3.9,221319.900"
#define NVR "BFNVR,221320.000,1.2,0.5,0.1,0.0,0.0,0.3"

static void test_navigation(void)
{
    rig *r = rig_new((const char *const[]){"--origin", "41.5,-70.7", NULL});
    feed(r, sentence(NVR), T0);
    CHECK(r->ctx.reasons.total == 0 && r->n_nav == 0); /* velocities, no position yet */
    feed(r, sentence(NVG), T0 + 50 * MS);
    CHECK(r->ctx.reasons.total == 0);
    CHECK(r->n_nav == 1 && r->nav.utime == T0 + 50 * MS);
    CHECK(fabs(r->nav.latitude_deg - 41.5) < 1e-9 && fabs(r->nav.longitude_deg + 70.7) < 1e-9);
    CHECK(fabs(r->nav.north_m) < 1e-6 && fabs(r->nav.east_m) < 1e-6);
    CHECK(fabs(r->nav.depth_m - 3.5) < 1e-9 && fabs(r->nav.altitude_m - 10.0) < 1e-9);
    CHECK(fabs(r->nav.heading_rad - 82.8 * DEG) < 1e-9);
    CHECK(fabs(r->nav.roll_rad + 2.6 * DEG) < 1e-9 && fabs(r->nav.pitch_rad + 3.9 * DEG) < 1e-9);
    CHECK(fabs(r->nav.u_mps - 1.3) < 1e-9 && fabs(r->nav.speed_over_ground_mps - 1.3) < 1e-9);
    CHECK(isnan(r->nav.v_mps) && isnan(r->nav.r_radps) && isnan(r->nav.course_over_ground_rad));
    /* southern, eastern; no altitude (empty) */
    feed(r, sentence("BFNVG,221321.000,3330.0000,S,15115.0000,E,0,,20.0,359.9,0.0,0.0,221321.000"), T0 + 1000 * MS);
    CHECK(r->n_nav == 2 && fabs(r->nav.latitude_deg + 33.5) < 1e-9 && fabs(r->nav.longitude_deg - 151.25) < 1e-9);
    CHECK(r->nav.altitude_m == -1.0 && fabs(r->nav.depth_m - 20.0) < 1e-9);
    /* heard, it is the frontseat's own until it hands over */
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_FRONTSEAT && !r->status.has_control);
    /* others are heard, not used */
    feed(r, sentence("BFSVS,221322.000,1500.2"), T0 + 2000 * MS);
    CHECK(r->ctx.reasons.total == 0 && r->fs.last_heard == T0 + 2000 * MS && r->n_nav == 2);
    free(r);
}

/* what a stack frame left behind: a caller's local that is never set reads it */
static volatile long stack_sink;
static __attribute__((noinline)) void scribble_stack(void)
{
    volatile long junk[256];
    for (int i = 0; i < 256; i++)
        junk[i] = -1L - i;
    stack_sink = junk[255];
}

static void test_empty_quality(void)
{
    /* the quality is a field like the others: empty, it is not known, and the
     * navigation stands (it was read from an unset local: refused or not by chance) */
    rig *r = rig_new(NULL);
    for (int i = 0; i < 20; i++) {
        scribble_stack();
        feed(r, sentence("BFNVG,221320.000,4130.0000,N,07042.0000,W,,10.0,3.5,82.8,-2.6,-3.9,221319.900"),
             T0 + i * 100 * MS);
    }
    CHECK(r->n_nav == 20 && count(r, "bad position quality") == 0 && r->ctx.reasons.total == 0);
    CHECK(fabs(r->nav.latitude_deg - 41.5) < 1e-9 && fabs(r->nav.depth_m - 3.5) < 1e-9);
    free(r);
}

static void test_logging_asked_when_the_port_opens(void)
{
    /* the driver polls from its start, the port perhaps not open yet (a vehicle's
     * TCP server not up): those $BPLOG went nowhere; once it opens they are asked
     * again, the first at the next poll (else only after 300 polls: a minute) */
    rig *r = rig_new(NULL);
    for (int i = 0; i < 10; i++)
        frontseat_protocol.tick(&r->fs, &r->ctx, T0 + i * 200 * MS);
    CHECK(frontseat_protocol.opened != NULL);
    if (frontseat_protocol.opened)
        frontseat_protocol.opened(&r->fs, &r->ctx);
    const char *ids[] = {"ACK", "NVG", "NVR", "MIS", "MSC", "CTL", "SHT"};
    for (int i = 0; i < 7; i++) {
        r->written[0] = '\0';
        frontseat_protocol.tick(&r->fs, &r->ctx, T0 + (10 + i) * 200 * MS);
        char body[32];
        snprintf(body, sizeof body, "BPLOG,%s,ON", ids[i]);
        CHECK_STR(r->written, sentence(body));
    }
    free(r);
}

static void test_requests(void)
{
    rig *r = rig_new(NULL);
    /* the logging first, one $BPLOG a poll, then the heartbeat */
    const char *ids[] = {"ACK", "NVG", "NVR", "MIS", "MSC", "CTL", "SHT"};
    for (int i = 0; i < 7; i++) {
        r->written[0] = '\0';
        frontseat_protocol.tick(&r->fs, &r->ctx, T0 + i * 200 * MS);
        char body[32];
        snprintf(body, sizeof body, "BPLOG,%s,ON", ids[i]);
        CHECK_STR(r->written, sentence(body));
    }
    int heartbeats = 0;
    for (int i = 7; i < 17; i++) {
        r->written[0] = '\0';
        frontseat_protocol.tick(&r->fs, &r->ctx, T0 + i * 200 * MS);
        heartbeats += strncmp(r->written, "$BPSTS,", 7) == 0;
        CHECK(r->written[0] == '\0' || !strncmp(r->written, "$BPSTS,", 7));
    }
    CHECK(heartbeats == 2); /* 1 Hz at the default --poll-period */
    feed(r, sentence(NVG), T0 + 10 * MS);
    setpoint(r, depth_sp(T0, 1.0, 10.0, 1.5), T0 + 20 * MS);
    /* its time (of the newest sentence heard), heading [deg], depth [m], 0: a depth, speed [m/s], 1: a speed, 0: a heading */
    CHECK_STR(r->written, sentence("BPRMB,221320.010,57.3,10.0,0,1.50,1,0"));
    CHECK(r->fs.requests_sent == 1 && r->ctx.reasons.total == 0);
    /* held: asked again each --resend-period while the setpoint is fresh */
    r->written[0] = '\0';
    frontseat_protocol.tick(&r->fs, &r->ctx, T0 + 1100 * MS);
    CHECK(strstr(r->written, "$BPRMB,221320.010,57.3,10.0,0,1.50,1,0*") != NULL);
    /* the navigator stopped: no more requests */
    feed(r, sentence(NVG), T0 + 2500 * MS);
    r->written[0] = '\0';
    frontseat_protocol.tick(&r->fs, &r->ctx, T0 + 3000 * MS);
    CHECK(strstr(r->written, "$BPRMB") == NULL);
    /* a lost stream: the logging is asked again */
    frontseat_protocol.reset(&r->fs, &r->ctx);
    r->written[0] = '\0';
    frontseat_protocol.tick(&r->fs, &r->ctx, T0 + 3500 * MS);
    CHECK_STR(r->written, sentence("BPLOG,ACK,ON"));
    free(r);
    /* a stop (allowed by --min-speed 0): no rudder, pitch nor rpm; a negative heading wraps */
    rig *z = rig_new((const char *const[]){"--min-speed", "0", NULL});
    feed(z, sentence(NVG), T0);
    setpoint(z, depth_sp(T0, 0.0, 5.0, 0.0), T0);
    CHECK_STR(z->written, sentence("BPRMB,221320.000,0,0,2,0,0,1"));
    setpoint(z, depth_sp(T0, -M_PI / 2, 5.0, 1.0), T0);
    CHECK_STR(z->written, sentence("BPRMB,221320.000,270.0,5.0,0,1.00,1,0"));
    free(z);
}

static void test_limits(void)
{
    rig *r = rig_new((const char *const[]){"--max-depth", "50", "--min-speed", "0.5", "--max-speed", "2", NULL});
    feed(r, sentence(NVG), T0);
    setpoint(r, depth_sp(T0, 0.0, 80.0, 1.0), T0);
    CHECK_STR(r->written, sentence("BPRMB,221320.000,0.0,50.0,0,1.00,1,0"));
    setpoint(r, depth_sp(T0, 0.0, 10.0, 3.0), T0);
    CHECK(strstr(r->written, ",10.0,0,2.00,1,0*") != NULL);
    setpoint(r, depth_sp(T0, 0.0, -1.0, 1.0), T0);
    CHECK(strstr(r->written, "$BPRMB,221320.000,0.0,0.0,0,") != NULL);
    CHECK(r->fs.setpoints_clamped == 3);
    /* refused: never sent, each reason counted */
    setpoint(r, depth_sp(T0, NAN, 10.0, 1.0), T0);
    CHECK(r->written[0] == '\0' && count(r, "setpoint: heading not a number") == 1);
    setpoint(r, depth_sp(T0, 0.0, -INFINITY, 1.0), T0);
    CHECK(count(r, "setpoint: depth not a number") == 1);
    setpoint(r, depth_sp(T0, 0.0, 10.0, NAN), T0);
    CHECK(count(r, "setpoint: speed not a number") == 1);
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
    CHECK(r->written[0] == '\0' && r->fs.setpoints_refused == 8);
    /* absurd values: a heading of 1e300 rad and a depth of 1e12 m come out inside the limits */
    setpoint(r, depth_sp(T0, 1e300, 1e12, 1e9), T0);
    double h = -1, d = -1, v = -1;
    CHECK(sscanf(r->written, "$BPRMB,221320.000,%lf,%lf,0,%lf,1,0*", &h, &d, &v) == 3 || r->written[0] == '\0');
    if (r->written[0])
        CHECK(h >= 0.0 && h < 360.0 && d == 50.0 && v == 2.0);
    /* an altitude: the depth that puts the vehicle there (3.5 m deep, 10 m up: 5 m up is 8.5 m deep) */
    sp = depth_sp(T0, 0.0, 0.0, 1.0);
    sp.vertical_mode = AUV_SETPOINT_T_VERTICAL_ALTITUDE;
    sp.altitude_m = 5.0;
    setpoint(r, sp, T0);
    CHECK(strstr(r->written, "$BPRMB,221320.000,0.0,8.5,0,") != NULL);
    /* the vehicle refuses our request in its $BFACK: counted as a refusal, with its words */
    int64_t refused = r->fs.setpoints_refused;
    feed(r, sentence("BFACK,221320.100,RMB,221320.000,,1,,Not in a payload behavior"), T0 + 100 * MS);
    CHECK(r->fs.setpoints_refused == refused + 1);
    CHECK(count(r, "setpoint: refused by the frontseat") == 1);
    CHECK(strstr(r->fs.last_refusal, "Not in a payload behavior") != NULL);
    feed(r, sentence("BFACK,221320.200,RMB,221320.000,,2,,"), T0 + 200 * MS); /* processed */
    feed(r, sentence("BFACK,221320.300,LOG,221320.000,,0,,"), T0 + 300 * MS); /* not a request of ours */
    CHECK(r->fs.setpoints_refused == refused + 1);
    free(r);
    /* nothing heard yet: nothing asked */
    rig *q = rig_new(NULL);
    setpoint(q, depth_sp(T0, 0.0, 10.0, 1.0), T0);
    CHECK(strstr(q->written, "$BPRMB") == NULL && count(q, "setpoint: frontseat not connected") == 1);
    free(q);
}

static void test_states(void)
{
    rig *r = rig_new(NULL);
    frontseat_protocol.tick(&r->fs, &r->ctx, T0);
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_NOT_CONNECTED);
    feed(r, sentence("BFMIS,221320.000,survey.mis,Running"), T0);
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_FRONTSEAT && !r->status.has_control);
    CHECK_STR(r->mode, "Running");
    /* a payload mission command: handed over (Goby3's default trigger) */
    feed(r, sentence("BFMSC,221320.200,payload"), T0 + 200 * MS);
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_PAYLOAD && r->status.has_control);
    CHECK(r->status.control_granted == 1);
    /* the mission ended: taken back */
    feed(r, sentence("BFMIS,221320.400,survey.mis,Stopped"), T0 + 400 * MS);
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_FRONTSEAT && r->status.control_lost == 1);
    CHECK_STR(r->mode, "Stopped");
    /* $BFCTL: it alone says, from then on */
    feed(r, sentence("BFCTL,221320.600,1"), T0 + 600 * MS);
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_PAYLOAD && r->status.control_granted == 2);
    feed(r, sentence("BFCTL,221320.800,0"), T0 + 800 * MS);
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_FRONTSEAT && r->status.control_lost == 2);
    feed(r, sentence("BFMSC,221320.900,payload"), T0 + 900 * MS);
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_FRONTSEAT);
    feed(r, sentence("BFCTL,221321.000,1"), T0 + 1000 * MS);
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_PAYLOAD);
    /* silent: after --silent-after (3 s), no requests */
    feed(r, sentence(NVG), T0 + 1000 * MS);
    setpoint(r, depth_sp(T0 + 1000 * MS, 0.0, 10.0, 1.0), T0 + 1000 * MS);
    CHECK(strstr(r->written, "$BPRMB") != NULL);
    frontseat_protocol.tick(&r->fs, &r->ctx, T0 + 4100 * MS);
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_SILENT && !r->status.has_control);
    setpoint(r, depth_sp(T0 + 4200 * MS, 0.0, 10.0, 1.0), T0 + 4200 * MS);
    CHECK(strstr(r->written, "$BPRMB") == NULL && count(r, "setpoint: frontseat silent") == 1);
    feed(r, sentence(NVG), T0 + 5000 * MS);
    frontseat_protocol.tick(&r->fs, &r->ctx, T0 + 5010 * MS); /* the state published at the tick */
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_PAYLOAD);
    /* it shuts down: an error, control taken back */
    feed(r, sentence("BFSHT,221325.000"), T0 + 5200 * MS);
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_ERROR && r->status.error && !r->status.has_control);
    CHECK_STR(r->error_text, "shutdown");
    free(r);
}

static void test_refused_sentences(void)
{
    rig *r = rig_new(NULL);
    char bad[300];
    snprintf(bad, sizeof bad, "%s", sentence(NVG));
    char *digit = bad + strlen(bad) - 3; /* one checksum digit */
    *digit = *digit == '0' ? '1' : '0';
    feed(r, bad, T0);
    CHECK(count(r, "bad checksum") == 1);
    feed(r, sentence("BFNVG,221320.000,4130.0000,N,07042.0000,W,1,10.0,3.5"), T0);
    CHECK(count(r, "NVG too short") == 1);
    feed(r, sentence("BFNVG,2213,4130.0000,N,07042.0000,W,1,10.0,3.5,82.8,-2.6,-3.9,221319.900"), T0);
    feed(r, sentence("BFNVG,221320.000,4130.0000,N,07042.0000,W,1,10.0,3.5,82.8,-2.6,-3.9,noon"), T0);
    CHECK(count(r, "bad time") == 2);
    feed(r, sentence("BFNVG,221320.000,9130.0000,N,07042.0000,W,1,10.0,3.5,82.8,-2.6,-3.9,221319.900"), T0);
    feed(r, sentence("BFNVG,221320.000,4130.0000,N,07042.0000,X,1,10.0,3.5,82.8,-2.6,-3.9,221319.900"), T0);
    feed(r, sentence("BFNVG,221320.000,4130.0000,N,,,1,10.0,3.5,82.8,-2.6,-3.9,221319.900"), T0);
    feed(r, sentence("BFNVG,221320.000,4170.0000,N,07042.0000,W,1,10.0,3.5,82.8,-2.6,-3.9,221319.900"), T0);
    CHECK(count(r, "bad position") == 4);
    feed(r, sentence("BFNVG,221320.000,4130.0000,N,07042.0000,W,x,10.0,3.5,82.8,-2.6,-3.9,221319.900"), T0);
    CHECK(count(r, "bad position quality") == 1);
    feed(r, sentence("BFNVG,221320.000,4130.0000,N,07042.0000,W,1,5000,3.5,82.8,-2.6,-3.9,221319.900"), T0);
    CHECK(count(r, "altitude out of range") == 1);
    feed(r, sentence("BFNVG,221320.000,4130.0000,N,07042.0000,W,1,10.0,1e5,82.8,-2.6,-3.9,221319.900"), T0);
    feed(r, sentence("BFNVG,221320.000,4130.0000,N,07042.0000,W,1,10.0,9000,82.8,-2.6,-3.9,221319.900"), T0);
    CHECK(count(r, "depth out of range") == 2);
    feed(r, sentence("BFNVG,221320.000,4130.0000,N,07042.0000,W,1,10.0,3.5,720,-2.6,-3.9,221319.900"), T0);
    feed(r, sentence("BFNVG,221320.000,4130.0000,N,07042.0000,W,1,10.0,3.5,82.8,-2.6,nan,221319.900"), T0);
    CHECK(count(r, "attitude out of range") == 2);
    feed(r, sentence("BFNVR,221320.000,1.2,0.5"), T0);
    CHECK(count(r, "NVR too short") == 1);
    feed(r, sentence("BFNVR,221320.000,99,0.5,0.1,0.0,0.0,0.3"), T0);
    feed(r, sentence("BFNVR,221320.000,8,8,0.1,0.0,0.0,0.3"), T0);
    CHECK(count(r, "velocity out of range") == 2);
    feed(r, sentence("BFNVR,221320.000,1.2,0.5,0.1,0.0,0x10,0.3"), T0);
    CHECK(count(r, "rate out of range") == 1);
    feed(r, sentence("BFCTL,221320.000,yes"), T0);
    CHECK(count(r, "bad control field") == 1);
    feed(r, sentence("BFMIS,221320.000,survey.mis"), T0);
    CHECK(count(r, "bad mission status") == 1);
    feed(r, sentence("BFACK,221320.000,RMB,221320.000,,7,,"), T0);
    feed(r, sentence("BFACK,221320.000"), T0);
    CHECK(count(r, "bad ack") == 2);
    feed(r, sentence("BFnvg,1"), T0);
    CHECK(count(r, "bad address field") == 1);
    feed(r, "noise$BFNVG,1,2$BFCTL,1", T0);
    CHECK(count(r, "garbage") == 1 && count(r, "truncated sentence") == 1);
    char longline[800] = "$";
    memset(longline + 1, 'A', 700);
    strcpy(longline + 701, "\r\n");
    feed(r, longline, T0);
    CHECK(count(r, "line too long") == 1);
    CHECK(r->n_nav == 0 && r->fs.last_heard == -1); /* nothing refused counts as heard */
    CHECK(r->status.state == AUV_FRONTSEAT_STATUS_T_STATE_NOT_CONNECTED);
    free(r);
}

/* What a real Huxley writes beyond our emulator's lines, each read as the
 * interface's definition allows. */
static void test_real_variants(void)
{
    rig *r = rig_new(NULL);
    /* the checksum is optional: a line without one is read */
    feed(r, "$" NVG "\r\n", T0);
    CHECK(r->ctx.reasons.total == 0 && r->n_nav == 1 && count(r, "no checksum") == 0);
    /* the times as seconds since 1970 with decimals (the first field and the
     * computed time): read, and our own sentences' times written the same way */
    feed(r, sentence("BFNVG,1700000000.250,4130.0000,N,07042.0000,W,1,10.0,4.5,82.8,-2.6,-3.9,1700000000.125"),
         T0 + 10 * MS);
    CHECK(r->ctx.reasons.total == 0 && r->n_nav == 2 && fabs(r->nav.depth_m - 4.5) < 1e-9);
    setpoint(r, depth_sp(T0, 1.0, 10.0, 1.5), T0 + 20 * MS);
    CHECK_STR(r->written, sentence("BPRMB,1700000000.010,57.3,10.0,0,1.50,1,0"));
    feed(r, sentence("BFNVG,1700000000,4130.0000,N,07042.0000,W,1,10.0,4.5,82.8,-2.6,-3.9,"), T0 + 30 * MS);
    CHECK(r->ctx.reasons.total == 0 && r->n_nav == 3);
    feed(r, sentence(NVG), T0 + 40 * MS); /* hhmmss again: answered so again */
    setpoint(r, depth_sp(T0 + 40 * MS, 1.0, 10.0, 1.5), T0 + 40 * MS);
    CHECK_STR(r->written, sentence("BPRMB,221320.040,57.3,10.0,0,1.50,1,0"));
    /* no fix: the numbers empty (their hemispheres written or not): the rest read, no NAV */
    feed(r, sentence("BFNVG,221321.000,,N,,W,0,12.0,5.0,90.0,0.0,0.0,221321.000"), T0 + 50 * MS);
    feed(r, sentence("BFNVG,221321.100,,,,,,12.0,5.0,90.0,0.0,0.0,221321.100"), T0 + 60 * MS);
    CHECK(r->ctx.reasons.total == 0 && r->n_nav == 4 && fabs(r->fs.nav.depth_m - 5.0) < 1e-9);
    /* a signed heading (-180 .. 180) is the same direction */
    feed(r, sentence("BFNVG,221321.200,4130.0000,N,07042.0000,W,1,10.0,3.5,-90.0,0.0,0.0,221321.200"), T0 + 70 * MS);
    CHECK(r->ctx.reasons.total == 0 && r->n_nav == 5 && fabs(r->nav.heading_rad - 270.0 * DEG) < 1e-9);
    /* the acknowledged command written whole or in lower case is still ours */
    feed(r, sentence("BFACK,221321.300,BPRMB,221321.000,,1,,Not in a payload behavior"), T0 + 80 * MS);
    feed(r, sentence("BFACK,221321.400,bprmb,221321.000,,0,,"), T0 + 90 * MS);
    feed(r, sentence("BFACK,221321.500,rmb,221321.000,7,1,,busy"), T0 + 95 * MS);
    CHECK(count(r, "setpoint: refused by the frontseat") == 3 && strstr(r->fs.last_refusal, "busy") != NULL);
    /* the description where the field for future use would be: still its words */
    feed(r, sentence("BFACK,221321.600,RMB,221321.000,,1,Above the minimum depth"), T0 + 96 * MS);
    CHECK(count(r, "setpoint: refused by the frontseat") == 4);
    CHECK(strstr(r->fs.last_refusal, "Above the minimum depth") != NULL);
    /* what a vehicle interleaves, each in its published shape: heard, never an error */
    static const char *const others[] = {
        "BFRVL,221322.000,350.0,1.45",
        "BFSVS,221322.000,1502.3",
        "BFDVL,221322.000,1.41,0.02,-0.01,12.1,12.3,11.9,12.0,11.5,221321.950",
        "BFDVL,221322.100,,,,,,,,11.5,",
        "BFCTD,221322.000,42150.2,11.52,351.3,221321.900",
        "BFBOY,221322.000,2,0,ok,12.5",
        "BFTRM,221322.000,2,0,ok,1.5,-0.2",
        "BFTOP,221322.000,hello topside",
        "BFMBS,221322.000,survey.mis,3,7,Payload",
        "BFMBE,221322.000,survey.mis,3,7,Payload",
        "BFPLN,221322.000,1,Trackline,4131.0000,N,07043.0000,W",
        "BFVER,221322.000,1.10",
        "BFRBS,221322.000,29.8,85",
        "BFIMU,221322.000,0.01,0.02,9.81,0.0,0.0,0.1",
        "BFMSG,221322.000,a message, with, commas",
    };
    int64_t navs = r->n_nav, total = r->ctx.reasons.total;
    for (size_t i = 0; i < sizeof others / sizeof *others; i++)
        feed(r, sentence(others[i]), T0 + (100 + (int64_t)i) * MS);
    CHECK(r->ctx.reasons.total == total && r->n_nav == navs && r->fs.last_heard == T0 + 114 * MS);
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
    CHECK(corpus_check("tests/drivers/corpus/bluefin", &c) >= 3); /* reads of 13 bytes */
}

static const unit_test tests[] = {
    {"bluefin_navigation", test_navigation},
    {"bluefin_empty_quality", test_empty_quality},
    {"bluefin_logging_when_opened", test_logging_asked_when_the_port_opens},
    {"bluefin_requests", test_requests},
    {"bluefin_limits", test_limits},
    {"bluefin_states", test_states},
    {"bluefin_refused_sentences", test_refused_sentences},
    {"bluefin_real_variants", test_real_variants},
    {"bluefin_hostile_corpus", test_hostile_corpus},
    {NULL, NULL},
};

__attribute__((constructor)) static void register_tests(void) { unit_register_list(tests); }
