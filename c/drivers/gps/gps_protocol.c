/* auv-gps's protocol: NMEA framing (c/drivers/common/nmea.c), the sentences
 * (gps_sentence.c) and the epochs (gps_epoch.c), behind the driver framework's
 * callbacks (drv_protocol.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "drivers/gps/gps.h"

/* 1990: the GPS epoch's 1980 (a receiver that lost its almanac says it) is
 * refused, NMEA's own 1994 examples are not; a week rollover's 1999 is a
 * date, wrong but decoded (raise --min-year where that matters) */
#define DEFAULT_MIN_YEAR 1990
#define DEFAULT_UERE_M 2.0
#define DEFAULT_EPOCH_TIMEOUT_S 0.5
/* WGS-84, as python/sim/geo.py: the two frames must agree to the millimetre */
#define WGS84_A 6378137.0
#define WGS84_E2 6.69437999014e-3

static int parse_double(const char *v, double *out)
{
    char *end;
    double d = strtod(v, &end);
    if (end == v || *end || !isfinite(d))
        return -1;
    *out = d;
    return 0;
}

int gps_set_origin(void *state, const char *v, char *err, size_t n)
{
    gps_state *g = state;
    char buf[128];
    snprintf(buf, sizeof buf, "%s", v);
    char *comma = strchr(buf, ',');
    double lat, lon;
    if (!comma || (*comma = '\0', parse_double(buf, &lat) < 0) || parse_double(comma + 1, &lon) < 0 ||
        fabs(lat) >= 90.0 || fabs(lon) > 180.0) {
        snprintf(err, n, "--origin wants LAT,LON in degrees (|LAT| < 90, |LON| <= 180), not '%s'", v);
        return -1;
    }
    /* python/sim/geo.py LocalFrame.re_origin: the radii of curvature at the origin */
    double s = sin(lat * M_PI / 180.0), d = 1.0 - WGS84_E2 * s * s;
    double rm = WGS84_A * (1.0 - WGS84_E2) / pow(d, 1.5), rn = WGS84_A / sqrt(d);
    g->have_origin = 1;
    g->lat0 = lat;
    g->lon0 = lon;
    g->dlat = (1.0 / rm) * 180.0 / M_PI;
    g->dlon = (1.0 / (rn * cos(lat * M_PI / 180.0))) * 180.0 / M_PI;
    return 0;
}

int gps_set_min_year(void *state, const char *v, char *err, size_t n)
{
    gps_state *g = state;
    char *end;
    long y = strtol(v, &end, 10);
    if (*end || y < 1980 || y > 2099) {
        snprintf(err, n, "--min-year wants a year 1980 .. 2099, not '%s'", v);
        return -1;
    }
    g->min_year = (int)y;
    g->settings_done |= 1;
    return 0;
}

int gps_set_uere(void *state, const char *v, char *err, size_t n)
{
    gps_state *g = state;
    double d;
    if (parse_double(v, &d) < 0 || d <= 0.0 || d > 1000.0) {
        snprintf(err, n, "--uere wants metres in (0, 1000], not '%s'", v);
        return -1;
    }
    g->uere_m = d;
    g->settings_done |= 2;
    return 0;
}

int gps_set_epoch_timeout(void *state, const char *v, char *err, size_t n)
{
    gps_state *g = state;
    double d;
    if (parse_double(v, &d) < 0 || d < 0.05 || d > 10.0) {
        snprintf(err, n, "--epoch-timeout wants seconds in [0.05, 10], not '%s'", v);
        return -1;
    }
    g->epoch_timeout_s = d;
    g->settings_done |= 4;
    return 0;
}

static int gps_init(void *state, drv_ctx *ctx)
{
    gps_state *g = state;
    /* defaults for what the flags did not set (the state starts zeroed) */
    if (!(g->settings_done & 1))
        g->min_year = DEFAULT_MIN_YEAR;
    if (!(g->settings_done & 2))
        g->uere_m = DEFAULT_UERE_M;
    if (!(g->settings_done & 4))
        g->epoch_timeout_s = DEFAULT_EPOCH_TIMEOUT_S;
    nmea_framer_init(&g->framer, 1); /* the checksum is optional but in RMC (gps_sentence.c) */
    g->gsa_stamp = g->vtg_stamp = -1;
    g->fix_type = auv_type_find("gps_fix_t");
    if (!g->fix_type) {
        drv_log(ctx, "gps_fix_t is not in the type table");
        return -1;
    }
    if (!g->have_origin)
        drv_log(ctx, "no --origin: gps_fix_t.north_m and east_m are NaN (auv-nav will not use the fixes)");
    return 0;
}

static void on_sentence(gps_state *g, drv_ctx *ctx, int64_t stamp)
{
    gps_values v;
    char why[200];
    /* A receiver that never checksums (an HP 58534A) is taken as it is; one
     * that does and sends a standard sentence without is a line that lost its
     * *hh. (Its maker's proprietary lines are the maker's: MTK's $POLYN come
     * without, among checksummed sentences; none is used.) */
    if (g->sentence.checksummed)
        g->seen_checksum = 1;
    else if (g->seen_checksum && g->sentence.talker[0]) {
        drv_drop(ctx, "no checksum", "%.80s: this receiver checksums its sentences", g->sentence.text);
        return;
    }
    const char *reason = gps_decode(&g->sentence, g->min_year, &v, why, sizeof why);
    if (reason) {
        drv_drop(ctx, reason, "%s", why);
        return;
    }
    drv_frame_ok(ctx, stamp);
    gps_epoch_sentence(g, ctx, &v, stamp);
}

static void gps_feed(void *state, drv_ctx *ctx, const uint8_t *bytes, size_t n, int64_t stamp)
{
    gps_state *g = state;
    g->last_rx = stamp;
    for (size_t i = 0; i < n; i++) {
        int r = nmea_framer_push(&g->framer, bytes[i], &g->sentence);
        if (r == NMEA_OK)
            on_sentence(g, ctx, stamp);
        else if (r > 0)
            drv_drop(ctx, nmea_result_name((nmea_result)r), "%.*s", (int)(g->framer.len < 60 ? g->framer.len : 60), g->framer.buf);
        /* garbage between sentences: one count per run of it, not per byte */
        if (g->framer.garbage_bytes != g->garbage_seen) {
            g->garbage_seen = g->framer.garbage_bytes;
            if (!g->in_garbage)
                drv_drop(ctx, "garbage", "bytes outside any sentence, from 0x%02x", bytes[i]);
            g->in_garbage = 1;
        } else if (r >= 0) { /* a line ended: the run of garbage before it is over */
            g->in_garbage = 0;
        }
    }
}

static void gps_tick(void *state, drv_ctx *ctx, int64_t now) { gps_epoch_tick(state, ctx, now); }

static void gps_reset(void *state, drv_ctx *ctx)
{
    gps_state *g = state;
    (void)ctx;
    /* a half sentence of a lost stream never ends; the epoch may still
     * complete from the bytes that follow the reopening */
    nmea_framer_init(&g->framer, 1); /* the checksum is optional but in RMC (gps_sentence.c) */
    g->garbage_seen = 0;
    g->in_garbage = 0;
}

static void gps_finish(void *state, drv_ctx *ctx, int64_t now)
{
    (void)now;
    gps_epoch_close(state, ctx);
}

static const drv_flag gps_flags[] = {
    {"--origin", "LAT,LON", "the world's local frame origin, for north_m/east_m (flat earth, as the simulator)",
     gps_set_origin},
    {"--min-year", "YEAR", "refuse dates before YEAR (default 1990: a lost almanac says 1980)",
     gps_set_min_year},
    {"--uere", "M", "user range error: horizontal_sigma_m = M x HDOP (default 2)", gps_set_uere},
    {"--epoch-timeout", "S", "publish an incomplete epoch after S seconds of quiet (default 0.5)", gps_set_epoch_timeout},
    {0},
};

const drv_protocol gps_protocol = {
    .device = "GPS",
    .program = "auv-gps",
    .summary = "NMEA 0183 GNSS receiver: GGA, RMC, VTG, GSA, ZDA (talkers GP, GN, GL, GA, GB, BD, GQ, GI)\n"
               "into one gps_fix_t per epoch on <ID>.GPS, stamped with the receive time of the epoch's\n"
               "first sentence; the receiver's UTC is in utc_utime.",
    .default_baud = 9600,
    .state_size = sizeof(gps_state),
    .flags = gps_flags,
    .init = gps_init,
    .feed = gps_feed,
    .tick = gps_tick,
    .reset = gps_reset,
    .finish = gps_finish,
};

DRV_REGISTER(gps_protocol)
