/* Bluefin's standard payload interface (the Huxley "BPI"), the payload's side
 * (docs/frontseat.md, "Bluefin": the sentences, their fields, the sources and
 * what is not used). NMEA 0183 lines "$BODY*hh" CR LF (the common framer,
 * c/drivers/common/nmea.c), the payload's sentences $BP..., the vehicle's
 * $BF...:
 *
 *   payload -> vehicle  $BPLOG,ID,ON                 send me sentence ID (once each,
 *                                                    when the port opens and every
 *                                                    minute)
 *                       $BPSTS,TIME,1,TEXT           the payload's heartbeat
 *                       $BPRMB,TIME,HDG,DEPTH,0,SPEED,1,0
 *                                                    fly this heading [deg], depth [m]
 *                                                    (0: a depth), speed [m/s] (1: a
 *                                                    speed), 0: a heading
 *   vehicle -> payload  $BFNVG  navigation           $BFNVR  velocities and rates
 *                       $BFMIS  mission status       $BFMSC  payload mission command
 *                       $BFCTL  backseat control     $BFSHT  shutting down
 *                       $BFACK  acknowledgement      others: heard, not used
 *
 * TIME is hhmmss.sss of the newest stamp heard (the vehicle's clock is not
 * ours to set; before anything is heard nothing is asked but the logging), or
 * seconds since 1970 with three decimals once the vehicle's own times are
 * written so (Huxley writes either: both are read, and answered in kind).
 * The checksum is optional, as in NMEA 0183 (Goby3 checks it when present). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "drivers/common/nmea.h"
#include "frontseat/frontseat.h"

#define HEARTBEAT_EVERY 5    /* polls: 1 Hz at the default --poll-period of 0.2 s */
#define RELOG_EVERY 300      /* polls: the logging asked again (a restarted vehicle) */
#define MAX_DEPTH_M 6000.0   /* a depth past this is not a vehicle's */
#define MAX_ALTITUDE_M 1000.0
#define MAX_SPEED_MPS 10.0

/* what the payload asks the vehicle to send (Goby3's list, the ones used here) */
static const char *const log_ids[] = {"ACK", "NVG", "NVR", "MIS", "MSC", "CTL", "SHT"};
#define N_LOG ((int)(sizeof log_ids / sizeof *log_ids))

typedef struct {
    nmea_framer framer;
    uint64_t garbage_seen;
    int in_garbage;
    int64_t stamp;        /* newest stamp fed: the time in our sentences */
    int polls;            /* since the logging was asked */
    int log_next;         /* the next $BPLOG to send; N_LOG: all sent */
    /* the vehicle's state */
    char mission[16];     /* the $BFMIS status word */
    int heard_ctl;        /* a $BFCTL was heard: it alone grants control */
    int epoch_times;      /* the vehicle writes its times as seconds since 1970 */
    int control, shutdown;
} bluefin_state;

static void time_of(const bluefin_state *s, int64_t stamp, char *out, size_t n)
{
    if (s->epoch_times) {
        int64_t ms = stamp > 0 ? stamp / 1000 : 0;
        snprintf(out, n, "%lld.%03d", (long long)(ms / 1000), (int)(ms % 1000));
        return;
    }
    int64_t ms = stamp > 0 ? (stamp / 1000) % (86400 * INT64_C(1000)) : 0;
    snprintf(out, n, "%02d%02d%02d.%03d", (int)(ms / 3600000), (int)(ms / 60000 % 60), (int)(ms / 1000 % 60),
             (int)(ms % 1000));
}

static void report(bluefin_state *s, fs_state *fs, drv_ctx *ctx, int64_t stamp)
{
    fs_report r = {0};
    snprintf(r.mode, sizeof r.mode, "%s", s->mission);
    r.has_control = s->control && !s->shutdown;
    r.error = s->shutdown;
    snprintf(r.error_text, sizeof r.error_text, "%s", s->shutdown ? "shutdown" : "");
    fs_report_in(fs, ctx, &r, stamp);
}

/* a field that must be empty or a number in [lo, hi]; 0 empty, 1 set, -1 refused */
static int ranged(const nmea_sentence *m, int i, double lo, double hi, double *out)
{
    double v;
    int r = nmea_field_double(m, i, &v);
    if (r == 1 && (v < lo || v > hi))
        return -1;
    if (r == 1)
        *out = v;
    return r;
}

/* A time field as the vehicle writes it: hhmmss(.ss) (into seconds of the
 * day) or seconds since 1970 with decimals (9 to 11 digits before the point:
 * 1973 to 5138), telling which in *epoch. 0 empty, 1 read, -1 neither. */
static int vehicle_time(const nmea_sentence *m, int i, double *out, int *epoch)
{
    const char *v = i < m->nfields ? m->field[i] : "";
    size_t int_digits = strspn(v, "0123456789");
    if (*v && int_digits >= 9 && int_digits <= 11) {
        double t;
        if (nmea_field_double(m, i, &t) != 1)
            return -1;
        *out = t;
        *epoch = 1;
        return 1;
    }
    int r = nmea_field_time_of_day(m, i, out);
    if (r == 1)
        *epoch = 0;
    return r;
}

/* $BFNVG,TIME,LAT,N|S,LON,E|W,QUALITY,ALTITUDE,DEPTH,HEADING,ROLL,PITCH,COMPUTED_TIME */
static void nvg(bluefin_state *s, fs_state *fs, drv_ctx *ctx, const nmea_sentence *m, int64_t stamp)
{
    if (m->nfields < 11) {
        drv_drop(ctx, "NVG too short", "%d fields, at least 11", m->nfields);
        return;
    }
    double tod, lat = NAN, lon = NAN;
    long quality = 0; /* empty: not known (not used beyond this check) */
    int epoch = s->epoch_times;
    if (vehicle_time(m, 0, &tod, &epoch) < 0) {
        drv_drop(ctx, "bad time", "NVG time '%.20s'", m->field[0]);
        return;
    }
    /* no fix: the numbers empty, their hemispheres perhaps still written */
    int no_lat = !*m->field[1], no_lon = !*m->field[3];
    if ((!no_lat && nmea_field_latitude(m, 1, &lat) < 0) || (!no_lon && nmea_field_longitude(m, 3, &lon) < 0) ||
        no_lat != no_lon) {
        drv_drop(ctx, "bad position", "NVG '%.16s' '%.2s' '%.16s' '%.2s'", m->field[1], m->field[2], m->field[3],
                 m->field[4]);
        return;
    }
    if (nmea_field_int(m, 5, &quality) < 0 || quality < 0 || quality > 9) {
        drv_drop(ctx, "bad position quality", "NVG quality '%.10s'", m->field[5]);
        return;
    }
    fs_nav nav = {lat, lon, NAN, NAN, NAN, NAN, NAN, NAN};
    double alt = -1.0, v;
    /* the altitude over the seabed: empty or negative when it has none */
    int a = nmea_field_double(m, 6, &alt);
    if (a < 0 || (a == 1 && alt > MAX_ALTITUDE_M)) {
        drv_drop(ctx, "altitude out of range", "NVG altitude '%.20s' m (up to %g)", m->field[6], MAX_ALTITUDE_M);
        return;
    }
    nav.altitude_m = a == 1 && alt >= 0.0 ? alt : -1.0;
    if (ranged(m, 7, -10.0, MAX_DEPTH_M, &nav.depth_m) < 0) {
        drv_drop(ctx, "depth out of range", "NVG depth '%.20s' m", m->field[7]);
        return;
    }
    double hdg = NAN, roll = NAN, pitch = NAN;
    /* a heading of -180 .. 360: some write it signed (wrapped below) */
    if (ranged(m, 8, -180.0, 360.0, &hdg) < 0 || ranged(m, 9, -180.0, 180.0, &roll) < 0 ||
        ranged(m, 10, -90.0, 90.0, &pitch) < 0) {
        drv_drop(ctx, "attitude out of range", "NVG heading '%.12s' roll '%.12s' pitch '%.12s' deg", m->field[8],
                 m->field[9], m->field[10]);
        return;
    }
    int computed_epoch = epoch;
    if (m->nfields > 11 && vehicle_time(m, 11, &v, &computed_epoch) < 0) {
        drv_drop(ctx, "bad time", "NVG computed time '%.20s'", m->field[11]);
        return;
    }
    s->epoch_times = epoch;
    nav.heading_rad = isnan(hdg) ? NAN : fmod(hdg + 360.0, 360.0) * M_PI / 180.0;
    nav.roll_rad = roll * M_PI / 180.0;
    nav.pitch_rad = pitch * M_PI / 180.0;
    fs_heard(fs, ctx, stamp);
    /* published with a position of its own: one without (no fix) only updates
     * the rest, never republishes the last position as new */
    fs_nav_in(fs, ctx, &nav, !isnan(lat), stamp);
}

/* $BFNVR,TIME,EAST,NORTH,DOWN [m/s],PITCH_RATE,ROLL_RATE,YAW_RATE: the speed
 * over ground from the first two; the rates are checked, not used */
static void nvr(fs_state *fs, drv_ctx *ctx, const nmea_sentence *m, int64_t stamp)
{
    if (m->nfields < 7) {
        drv_drop(ctx, "NVR too short", "%d fields, at least 7", m->nfields);
        return;
    }
    double ve = NAN, vn = NAN, vd = NAN, rate;
    if (ranged(m, 1, -MAX_SPEED_MPS, MAX_SPEED_MPS, &ve) < 0 || ranged(m, 2, -MAX_SPEED_MPS, MAX_SPEED_MPS, &vn) < 0 ||
        ranged(m, 3, -MAX_SPEED_MPS, MAX_SPEED_MPS, &vd) < 0) {
        drv_drop(ctx, "velocity out of range", "NVR '%.12s' '%.12s' '%.12s' m/s", m->field[1], m->field[2],
                 m->field[3]);
        return;
    }
    for (int i = 4; i < 7; i++)
        if (ranged(m, i, -1000.0, 1000.0, &rate) < 0) {
            drv_drop(ctx, "rate out of range", "NVR '%.12s' deg/s", m->field[i]);
            return;
        }
    double speed = hypot(ve, vn);
    if (speed > MAX_SPEED_MPS) {
        drv_drop(ctx, "velocity out of range", "NVR %g m/s over ground", speed);
        return;
    }
    fs_nav nav = {NAN, NAN, NAN, NAN, NAN, NAN, NAN, speed};
    fs_heard(fs, ctx, stamp);
    fs_nav_in(fs, ctx, &nav, 0, stamp);
}

/* printable words of the vehicle's, kept short: letters, digits, a few marks */
static int word_ok(const char *w, size_t max)
{
    if (strlen(w) > max)
        return 0;
    for (const char *c = w; *c; c++)
        if (*c < 0x20 || *c > 0x7e)
            return 0;
    return 1;
}

/* The command an acknowledgement names: RMB, or written whole (BPRMB), in
 * either case (Goby3 compares it case-blind). */
static int acks_rmb(const char *what)
{
    if (strlen(what) == 5 && (what[0] == 'B' || what[0] == 'b') && (what[1] == 'P' || what[1] == 'p'))
        what += 2;
    return strlen(what) == 3 && (what[0] | 0x20) == 'r' && (what[1] | 0x20) == 'm' && (what[2] | 0x20) == 'b';
}

/* $BFACK,TIME,SENTENCE,ITS_TIME,INSERT_ID,STATUS,FUTURE,DESCRIPTION: status 0
 * an invalid request, 1 not processed, 2 processed, 3 pending */
static void ack(bluefin_state *s, fs_state *fs, drv_ctx *ctx, const nmea_sentence *m, int64_t stamp)
{
    (void)s;
    long status;
    if (m->nfields < 5 || nmea_field_int(m, 4, &status) != 1 || status < 0 || status > 3) {
        drv_drop(ctx, "bad ack", "'%.60s'", m->text);
        return;
    }
    fs_heard(fs, ctx, stamp);
    if (status <= 1 && acks_rmb(m->field[1])) {
        /* the vehicle refused our request: counted as the core counts its own */
        /* the description is the seventh field, after one for future use; a
         * vehicle that leaves that one out writes it sixth */
        const char *why = m->nfields > 6 && *m->field[6]   ? m->field[6]
                          : m->nfields > 5 && *m->field[5] ? m->field[5]
                          : status                         ? "not processed"
                                                           : "invalid request";
        fs->setpoints_refused++;
        snprintf(fs->last_refusal, sizeof fs->last_refusal, "refused by the frontseat: %.100s", why);
        drv_drop(ctx, "setpoint: refused by the frontseat", "BFACK status %ld: %.60s", status, why);
    }
}

static void on_sentence(bluefin_state *s, fs_state *fs, drv_ctx *ctx, const nmea_sentence *m, int64_t stamp)
{
    const char *t = m->type;
    if (strcmp(m->talker, "BF") != 0) {
        fs_heard(fs, ctx, stamp); /* another talker on the line: alive, not used */
        return;
    }
    if (!strcmp(t, "NVG")) {
        nvg(s, fs, ctx, m, stamp);
    } else if (!strcmp(t, "NVR")) {
        nvr(fs, ctx, m, stamp);
    } else if (!strcmp(t, "ACK")) {
        ack(s, fs, ctx, m, stamp);
    } else if (!strcmp(t, "MIS")) {
        /* $BFMIS,TIME,MISSION,STATUS: "Running" its mission; anything else idle */
        const char *status = m->nfields > 2 ? m->field[2] : "";
        if (!word_ok(status, 64) || !*status) {
            drv_drop(ctx, "bad mission status", "'%.60s'", m->text);
            return;
        }
        snprintf(s->mission, sizeof s->mission, "%.15s", status);
        if (!strstr(status, "Running"))
            s->control = 0; /* no mission: nothing of ours flies */
        fs_heard(fs, ctx, stamp);
        report(s, fs, ctx, stamp);
    } else if (!strcmp(t, "MSC")) {
        /* a payload mission command: the vehicle hands over (Goby3's default
         * trigger), unless it speaks $BFCTL */
        if (!s->heard_ctl)
            s->control = 1;
        fs_heard(fs, ctx, stamp);
        report(s, fs, ctx, stamp);
    } else if (!strcmp(t, "CTL")) {
        /* $BFCTL,TIME,0|1: the backseat has control or not (SPI 1.10 on) */
        const char *c = m->nfields > 1 ? m->field[1] : "";
        if (strcmp(c, "0") != 0 && strcmp(c, "1") != 0) {
            drv_drop(ctx, "bad control field", "CTL '%.10s'", c);
            return;
        }
        s->heard_ctl = 1;
        s->control = c[0] == '1';
        fs_heard(fs, ctx, stamp);
        report(s, fs, ctx, stamp);
    } else if (!strcmp(t, "SHT")) {
        s->shutdown = 1;
        s->control = 0;
        fs_heard(fs, ctx, stamp);
        report(s, fs, ctx, stamp);
    } else {
        fs_heard(fs, ctx, stamp); /* $BFSVS, $BFRVL, $BFDVL, $BFCTD, $BFMBS, ...: alive, not used */
    }
}

static void bluefin_feed(void *ps, fs_state *fs, drv_ctx *ctx, const uint8_t *b, size_t n, int64_t stamp)
{
    bluefin_state *s = ps;
    if (stamp > s->stamp)
        s->stamp = stamp;
    nmea_sentence m;
    for (size_t i = 0; i < n; i++) {
        int r = nmea_framer_push(&s->framer, b[i], &m);
        if (r == NMEA_OK) {
            drv_frame_ok(ctx, stamp);
            on_sentence(s, fs, ctx, &m, stamp);
        } else if (r > 0) {
            drv_drop(ctx, nmea_result_name((nmea_result)r), "%.*s", (int)(s->framer.len < 60 ? s->framer.len : 60),
                     s->framer.buf);
        }
        if (s->framer.garbage_bytes != s->garbage_seen) {
            s->garbage_seen = s->framer.garbage_bytes;
            if (!s->in_garbage)
                drv_drop(ctx, "garbage", "bytes outside any sentence, from 0x%02x", b[i]);
            s->in_garbage = 1;
        } else if (s->framer.in_sentence) {
            s->in_garbage = 0;
        }
    }
}

static int bluefin_request(void *ps, const fs_limits *lim, const fs_request *rq, char *out, size_t n)
{
    (void)lim; /* the BPI has no pitch limit nor timeout in its request */
    bluefin_state *s = ps;
    char t[32], body[128];
    time_of(s, s->stamp, t, sizeof t);
    if (rq->speed_mps < 0.01) /* stop: no rudder, no pitch, no rpm (Goby3's form) */
        snprintf(body, sizeof body, "BPRMB,%s,0,0,2,0,0,1", t);
    else
        snprintf(body, sizeof body, "BPRMB,%s,%.1f,%.1f,0,%.2f,1,0", t, rq->heading_deg, rq->depth_m, rq->speed_mps);
    return nmea_format(out, n, body);
}

static int bluefin_poll(void *ps, char *out, size_t n)
{
    bluefin_state *s = ps;
    char body[96];
    if (s->log_next < N_LOG) {
        snprintf(body, sizeof body, "BPLOG,%s,ON", log_ids[s->log_next++]);
        return nmea_format(out, n, body);
    }
    if (++s->polls >= RELOG_EVERY) {
        s->polls = 0;
        s->log_next = 0;
    }
    if (s->polls % HEARTBEAT_EVERY)
        return 0;
    char t[32];
    time_of(s, s->stamp, t, sizeof t);
    snprintf(body, sizeof body, "BPSTS,%s,1,auv-frontseat", t);
    return nmea_format(out, n, body);
}

static void bluefin_reset(void *ps)
{
    bluefin_state *s = ps;
    nmea_framer_init(&s->framer, 1); /* the checksum is optional: checked when present */
    s->garbage_seen = 0;
    s->in_garbage = 0;
    s->log_next = 0; /* a new stream: ask for the logging again */
    s->polls = 0;
}

const fs_proto bluefin_proto = {
    .name = "bluefin",
    .summary = "Bluefin standard payload interface, Huxley ($BPRMB requests; $BFNVG, $BFNVR, $BFMIS, $BFCTL reports)",
    .default_baud = 19200, /* Huxley is mostly reached over TCP (--tcp HOST:29500, Goby3) */
    .state_size = sizeof(bluefin_state),
    .feed = bluefin_feed,
    .encode_request = bluefin_request,
    .encode_poll = bluefin_poll,
    .reset = bluefin_reset,
};
