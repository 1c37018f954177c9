/* The OceanServer / L3Harris Iver3 "Remote Helm" serial protocol, the
 * backseat's side (docs/frontseat.md, "Iver3": the sentences, their fields and
 * where each is published). NMEA-style lines "$BODY*hh" CR LF, the checksum the
 * XOR of BODY, at 19200 baud:
 *
 *   backseat -> frontseat  $OSD,G,C,S,P,,,,          ask for its data
 *                          $OMS,HDG,DEPTH,PITCH,KN,T  fly this heading [deg], depth
 *                                                     (m from helm version 5, ft
 *                                                     before), max pitch [deg],
 *                                                     speed [kn] for T s
 *   frontseat -> backseat  $OSI,...                   state and navigation
 *                          $C<h>P<p>R<r>T<t>D<ft>     its compass: attitude, depth
 *                          $ACK,...  $GPRMC,...       heard, not used
 *
 * The $C sentence has no commas and an address of numbers: not an NMEA
 * address, so this file frames its lines itself (the same rules as
 * c/drivers/common/nmea.c: printable ASCII, a length cap, a checksum checked
 * when present: optional, as in NMEA 0183). */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "drivers/common/nmea.h"
#include "frontseat/frontseat.h"

#define LINE_MAX_CHARS 250
#define MAX_FIELDS 40
#define FT_TO_M 0.3048
#define KN_TO_MPS (1852.0 / 3600.0)
#define OSI_MIN_FIELDS 14 /* OSI and 13 fields: through the mission time remaining */

typedef struct {
    char line[LINE_MAX_CHARS + 1];
    size_t len;
    int in_line, skipping, in_garbage;
} iver3_state;

/* A number filling the whole field; 0 empty, 1 ok, -1 malformed. */
static int number(const char *s, double *out)
{
    if (!*s)
        return 0;
    char *end;
    double d = strtod(s, &end);
    if (*end || !isfinite(d))
        return -1;
    /* no hex, no "inf", no "nan": strtod takes them, the protocol never sends them */
    for (const char *c = s; *c; c++)
        if (!(isdigit((unsigned char)*c) || *c == '.' || *c == '-' || *c == '+'))
            return -1;
    *out = d;
    return 1;
}

static int in_range(const char *s, double lo, double hi, double *out)
{
    int r = number(s, out);
    return r == 1 && *out >= lo && *out <= hi;
}

/* The mode word: its first character decides, as Goby3's Iver driver reads
 * it (a firmware may write more after it): N normal (its mission), S stopped,
 * P parking, M manual override, m manual parking ("mP"; ACFR writes "Mp",
 * an M), A servo mode (the backseat's $OMS requests steer it), W mission mode. */
static int mode_known(const char *m) { return *m && strchr("NSPMmAW", *m) != NULL; }

static void osi(fs_state *fs, drv_ctx *ctx, char **f, int nf, int64_t stamp)
{
    if (nf < OSI_MIN_FIELDS) {
        drv_drop(ctx, "OSI too short", "%d fields, at least %d", nf - 1, OSI_MIN_FIELDS - 1);
        return;
    }
    if (!mode_known(f[2])) {
        drv_drop(ctx, "unknown mode", "OSI mode '%.16s'", f[2]);
        return;
    }
    fs_nav nav = {NAN, NAN, NAN, NAN, NAN, NAN, NAN, NAN};
    double v = NAN;
    /* an empty field is not known (no fix yet, no altimeter, ...): the others
     * stand; both coordinates or neither */
    int no_lat = !*f[4], no_lon = !*f[5];
    if ((!no_lat && !in_range(f[4], -90.0, 90.0, &nav.lat_deg)) ||
        (!no_lon && !in_range(f[5], -180.0, 180.0, &nav.lon_deg)) || no_lat != no_lon) {
        drv_drop(ctx, "bad position", "OSI latitude '%.20s', longitude '%.20s'", f[4], f[5]);
        return;
    }
    if (*f[6] && !in_range(f[6], 0.0, 20.0, &v)) {
        drv_drop(ctx, "speed out of range", "OSI speed '%.20s' kn (0 .. 20)", f[6]);
        return;
    }
    nav.speed_mps = *f[6] ? v * KN_TO_MPS : NAN;
    /* the altimeter: empty or negative when it has no bottom */
    int a = number(f[9], &v);
    if (a < 0 || (a == 1 && v > 1000.0)) {
        drv_drop(ctx, "altitude out of range", "OSI altimeter '%.20s' ft (up to 1000)", f[9]);
        return;
    }
    nav.altitude_m = a == 1 && v >= 0.0 ? v * FT_TO_M : -1.0;
    /* the error word: N none, else one or more codes run together ("SopStl") */
    const char *err = f[8];
    if (strlen(err) >= sizeof ((fs_report *)0)->error_text) {
        drv_drop(ctx, "bad error field", "OSI error '%.20s'", err);
        return;
    }
    for (const char *c = err; *c; c++)
        if (!isalnum((unsigned char)*c)) {
            drv_drop(ctx, "bad error field", "OSI error '%.20s'", err);
            return;
        }
    /* Remote Helm 4 added the true heading and the corrected depth (Goby3);
     * older ones leave them to the $C sentence */
    if (nf > 14 && *f[14]) {
        if (!in_range(f[14], 0.0, 360.0, &v)) {
            drv_drop(ctx, "heading out of range", "OSI heading '%.20s' deg", f[14]);
            return;
        }
        nav.heading_rad = fmod(v, 360.0) * M_PI / 180.0;
    }
    if (nf > 15 && *f[15]) {
        if (!in_range(f[15], -30.0, 3300.0, &v)) {
            drv_drop(ctx, "depth out of range", "OSI depth '%.20s' ft", f[15]);
            return;
        }
        nav.depth_m = v * FT_TO_M;
    }
    fs_report r = {0};
    snprintf(r.mode, sizeof r.mode, "%s", f[2]);
    r.has_control = f[2][0] == 'A';
    r.manual = f[2][0] == 'M' || f[2][0] == 'm';
    r.error = *err && strcmp(err, "N") != 0;
    snprintf(r.error_text, sizeof r.error_text, "%s", r.error ? err : "");
    fs_heard(fs, ctx, stamp);
    fs_report_in(fs, ctx, &r, stamp);
    /* published with a position of its own: one without (no fix) updates the
     * rest and never republishes the last position as new */
    fs_nav_in(fs, ctx, &nav, !no_lat, stamp);
}

/* "C<h>P<p>R<r>T<t>D<ft>": a letter, then its number. The OceanServer
 * compass behind it writes what it is set to write: a field may be left
 * out, and others follow (M magnetic field, Mx My Mz, A, Ax Ay Az, ...):
 * those are skipped, the five known ones read where they stand (C first). */
static void compass(fs_state *fs, drv_ctx *ctx, const char *body, int64_t stamp)
{
    static const char keys[] = "CPRTD";
    double val[5] = {NAN, NAN, NAN, NAN, NAN};
    const char *p = body; /* line_done saw "C" and a number first */
    while (*p) {
        char tag[4], num[32];
        size_t t = 0, k = 0;
        while (isalpha((unsigned char)*p) && t < sizeof tag - 1)
            tag[t++] = *p++;
        tag[t] = '\0';
        while (*p && (isdigit((unsigned char)*p) || *p == '.' || *p == '-' || *p == '+') && k < sizeof num - 1)
            num[k++] = *p++;
        num[k] = '\0';
        double v;
        if (!t || number(num, &v) != 1) {
            drv_drop(ctx, "bad compass sentence", "'%.40s': '%.10s' is not a letter and its number", body,
                     p - k - t);
            return;
        }
        const char *known = t == 1 ? strchr(keys, tag[0]) : NULL;
        if (!known)
            continue; /* another of the compass's outputs: not used */
        if (!isnan(val[known - keys])) {
            drv_drop(ctx, "bad compass sentence", "'%.40s': %s twice", body, tag);
            return;
        }
        val[known - keys] = v;
    }
    if (val[0] < 0.0 || val[0] > 360.0 || fabs(val[1]) > 90.0 || fabs(val[2]) > 180.0 ||
        val[4] < -30.0 || val[4] > 3300.0) {
        drv_drop(ctx, "compass out of range", "heading %g, pitch %g, roll %g, depth %g ft", val[0], val[1], val[2],
                 val[4]);
        return;
    }
    fs_nav nav = {NAN, NAN, NAN, NAN, NAN, NAN, NAN, NAN};
    nav.heading_rad = fmod(val[0], 360.0) * M_PI / 180.0;
    nav.pitch_rad = val[1] * M_PI / 180.0;
    nav.roll_rad = val[2] * M_PI / 180.0;
    nav.depth_m = val[4] * FT_TO_M;
    fs_heard(fs, ctx, stamp);
    fs_nav_in(fs, ctx, &nav, 0, stamp);
}

static void line_done(iver3_state *s, fs_state *fs, drv_ctx *ctx, int64_t stamp)
{
    s->line[s->len] = '\0';
    /* the checksum is optional (NMEA 0183; Goby3's Iver driver checks it when
     * present): a '*' must be followed by two hex digits and match */
    char *star = strrchr(s->line, '*');
    if (star && (strlen(star) != 3 || !isxdigit((unsigned char)star[1]) || !isxdigit((unsigned char)star[2]))) {
        drv_drop(ctx, "bad checksum", "'%.40s': '*' without two hex digits", s->line);
        return;
    }
    char *body = s->line + 1;
    if (star) {
        unsigned want = (unsigned)strtoul(star + 1, NULL, 16);
        *star = '\0';
        if (nmea_checksum(body, strlen(body)) != want) {
            drv_drop(ctx, "bad checksum", "'%.40s'", body);
            return;
        }
    }
    drv_frame_ok(ctx, stamp);
    if (body[0] == 'C' && (isdigit((unsigned char)body[1]) || body[1] == '.' || body[1] == '-')) {
        compass(fs, ctx, body, stamp);
        return;
    }
    char *f[MAX_FIELDS];
    int nf = 0;
    for (char *p = body;; p++) {
        if (nf == MAX_FIELDS) {
            drv_drop(ctx, "too many fields", "'%.40s'", body);
            return;
        }
        f[nf++] = p;
        p = strchr(p, ',');
        if (!p)
            break;
        *p = '\0';
    }
    if (!strcmp(f[0], "OSI"))
        osi(fs, ctx, f, nf, stamp);
    else
        fs_heard(fs, ctx, stamp); /* $ACK, $GPRMC, ...: alive, not used */
}

static int ends_with_checksum(const iver3_state *s)
{
    return s->len >= 4 && s->line[s->len - 3] == '*' && isxdigit((unsigned char)s->line[s->len - 2]) &&
           isxdigit((unsigned char)s->line[s->len - 1]);
}

static void iver3_feed(void *ps, fs_state *fs, drv_ctx *ctx, const uint8_t *b, size_t n, int64_t stamp)
{
    iver3_state *s = ps;
    for (size_t i = 0; i < n; i++) {
        uint8_t c = b[i];
        if (c == '$') {
            /* a whole sentence (its *hh there) run into the next '$' without a
             * line end (a full output buffer drops the CR LF): two sentences,
             * as c/drivers/common/nmea.c reads them; a cut one is truncated */
            if (s->in_line && !s->skipping && ends_with_checksum(s))
                line_done(s, fs, ctx, stamp);
            else if (s->in_line)
                drv_drop(ctx, "truncated", "a new '$' after '%.30s'", s->line);
            s->in_line = 1;
            s->skipping = 0;
            s->in_garbage = 0;
            s->len = 0;
            s->line[s->len++] = '$';
            continue;
        }
        if (c == '\r' || c == '\n') {
            if (s->in_line && !s->skipping)
                line_done(s, fs, ctx, stamp);
            s->in_line = s->skipping = 0;
            s->in_garbage = 0;
            continue;
        }
        if (!s->in_line) {
            if (!s->in_garbage) /* one count per run of bytes between lines */
                drv_drop(ctx, "garbage", "byte 0x%02x outside a sentence", c);
            s->in_garbage = 1;
            continue;
        }
        if (s->skipping)
            continue;
        if ((c < 0x20 || c > 0x7e) && s->len <= 6 && !memchr(s->line, ',', s->len)) {
            /* a '$' in binary between the lines began no sentence: garbage, not
             * a broken line (as c/drivers/common/nmea.c reads it) */
            if (!s->in_garbage)
                drv_drop(ctx, "garbage", "byte 0x%02x after '%.6s'", c, s->line);
            s->in_line = 0;
            s->in_garbage = 1;
        } else if (c < 0x20 || c > 0x7e) {
            drv_drop(ctx, "bad character", "byte 0x%02x in '%.30s'", c, s->line);
            s->skipping = 1;
        } else if (s->len >= LINE_MAX_CHARS) {
            drv_drop(ctx, "too long", "over %d characters", LINE_MAX_CHARS);
            s->skipping = 1;
        } else {
            s->line[s->len++] = (char)c;
        }
    }
}

static int finish(const char *body, char *out, size_t n) { return nmea_format(out, n, body); }

static int iver3_request(void *ps, const fs_limits *lim, const fs_request *rq, char *out, size_t n)
{
    (void)ps;
    /* Remote Helm 5 takes the depth in metres, earlier ones in feet (Goby3's
     * iver_driver_config.proto) */
    double depth = lim->helm_version >= 5 ? rq->depth_m : rq->depth_m / FT_TO_M;
    char body[128];
    snprintf(body, sizeof body, "OMS,%.1f,%.1f,%.1f,%.1f,%d", rq->heading_deg, depth, lim->max_pitch_deg,
             rq->speed_mps / KN_TO_MPS, (int)lround(lim->request_timeout_s));
    return finish(body, out, n);
}

static int iver3_poll(void *ps, char *out, size_t n)
{
    (void)ps;
    return finish("OSD,G,C,S,P,,,,", out, n);
}

static void iver3_reset(void *ps)
{
    iver3_state *s = ps;
    s->in_line = s->skipping = s->in_garbage = 0;
    s->len = 0;
}

const fs_proto iver3_proto = {
    .name = "iver3",
    .summary = "OceanServer/L3Harris Iver3 Remote Helm ($OMS requests; $OSI and $C reports)",
    .default_baud = 19200,
    .state_size = sizeof(iver3_state),
    .feed = iver3_feed,
    .encode_request = iver3_request,
    .encode_poll = iver3_poll,
    .reset = iver3_reset,
};
