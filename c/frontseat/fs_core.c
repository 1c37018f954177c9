/* auv-frontseat's core (frontseat.h): the setpoints in, the requests out at the
 * protocol's pace, the frontseat's navigation and state published. What a
 * frontseat's sentences look like is its protocol's (fs_protocols.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "auv/auv_frontseat_status_t.h"
#include "auv/auv_nav_solution_t.h"
#include "frontseat/frontseat.h"

/* WGS-84, as python/sim/geo.py and auv-gps (c/drivers/gps) */
#define WGS84_A 6378137.0
#define WGS84_E2 6.69437999014e-3
#define STATUS_PERIOD_US 1000000

enum { SET_MAX_DEPTH = 1, SET_MIN_SPEED = 2, SET_MAX_SPEED = 4, SET_MAX_PITCH = 8, SET_TIMEOUT = 16,
       SET_HELM = 32, SET_POLL = 64, SET_RESEND = 128, SET_SP_TIMEOUT = 256, SET_SILENT = 512 };

static int number_in(const char *v, double lo, double hi, double *out)
{
    char *end;
    double d = strtod(v, &end);
    if (end == v || *end || !isfinite(d) || d < lo || d > hi)
        return -1;
    *out = d;
    return 0;
}

/* one setter per numeric flag: the name, its range and where it goes */
#define NUMERIC_FLAG(fn, flag, field, bit, lo, hi, unit)                                           \
    static int fn(void *state, const char *v, char *err, size_t n)                                \
    {                                                                                              \
        fs_state *fs = state;                                                                      \
        if (number_in(v, lo, hi, &fs->field) < 0) {                                                \
            snprintf(err, n, "%s wants %s in [%g, %g], not '%s'", flag, unit, lo, hi, v);          \
            return -1;                                                                             \
        }                                                                                          \
        fs->settings_done |= bit;                                                                  \
        return 0;                                                                                  \
    }
NUMERIC_FLAG(set_max_depth, "--max-depth", lim.max_depth_m, SET_MAX_DEPTH, 0.0, 6000.0, "metres")
NUMERIC_FLAG(set_min_speed, "--min-speed", lim.min_speed_mps, SET_MIN_SPEED, 0.0, 20.0, "m/s")
NUMERIC_FLAG(set_max_speed, "--max-speed", lim.max_speed_mps, SET_MAX_SPEED, 0.01, 20.0, "m/s")
NUMERIC_FLAG(set_max_pitch, "--max-pitch", lim.max_pitch_deg, SET_MAX_PITCH, 1.0, 60.0, "degrees")
NUMERIC_FLAG(set_request_timeout, "--request-timeout", lim.request_timeout_s, SET_TIMEOUT, 1.0, 120.0, "seconds")
NUMERIC_FLAG(set_poll_period, "--poll-period", poll_period_s, SET_POLL, 0.05, 10.0, "seconds")
NUMERIC_FLAG(set_resend_period, "--resend-period", resend_period_s, SET_RESEND, 0.1, 60.0, "seconds")
NUMERIC_FLAG(set_setpoint_timeout, "--setpoint-timeout", setpoint_timeout_s, SET_SP_TIMEOUT, 0.1, 60.0, "seconds")
NUMERIC_FLAG(set_silent_after, "--silent-after", silent_after_s, SET_SILENT, 0.2, 600.0, "seconds")

static int set_helm_version(void *state, const char *v, char *err, size_t n)
{
    fs_state *fs = state;
    double d;
    if (number_in(v, 1.0, 99.0, &d) < 0 || d != floor(d)) {
        snprintf(err, n, "--helm-version wants the frontseat software's major version 1 .. 99, not '%s'", v);
        return -1;
    }
    fs->lim.helm_version = (int)d;
    fs->settings_done |= SET_HELM;
    return 0;
}

static int set_protocol(void *state, const char *v, char *err, size_t n)
{
    fs_state *fs = state;
    fs->proto = fs_proto_find(v);
    if (!fs->proto) {
        snprintf(err, n, "--protocol wants one of: %s, not '%s'", fs_proto_names(), v);
        return -1;
    }
    return 0;
}

static int set_origin(void *state, const char *v, char *err, size_t n)
{
    fs_state *fs = state;
    char buf[128];
    snprintf(buf, sizeof buf, "%s", v);
    char *comma = strchr(buf, ',');
    double lat, lon;
    if (!comma || (*comma = '\0', number_in(buf, -89.999, 89.999, &lat) < 0) ||
        number_in(comma + 1, -180.0, 180.0, &lon) < 0) {
        snprintf(err, n, "--origin wants LAT,LON in degrees (|LAT| < 90, |LON| <= 180), not '%s'", v);
        return -1;
    }
    double s = sin(lat * M_PI / 180.0), d = 1.0 - WGS84_E2 * s * s;
    double rm = WGS84_A * (1.0 - WGS84_E2) / pow(d, 1.5), rn = WGS84_A / sqrt(d);
    fs->have_origin = 1;
    fs->lat0 = lat;
    fs->lon0 = lon;
    fs->dlat = (1.0 / rm) * 180.0 / M_PI;
    fs->dlon = (1.0 / (rn * cos(lat * M_PI / 180.0))) * 180.0 / M_PI;
    return 0;
}

static void *proto_state(fs_state *fs) { return fs->proto_state; }

static int8_t state_of(const fs_state *fs)
{
    if (fs->last_heard < 0)
        return AUV_FRONTSEAT_STATUS_T_STATE_NOT_CONNECTED;
    if (fs->silent)
        return AUV_FRONTSEAT_STATUS_T_STATE_SILENT;
    if (!fs->have_report)
        return AUV_FRONTSEAT_STATUS_T_STATE_FRONTSEAT;
    if (fs->report.error)
        return AUV_FRONTSEAT_STATUS_T_STATE_ERROR;
    if (fs->report.manual)
        return AUV_FRONTSEAT_STATUS_T_STATE_MANUAL;
    return fs->report.has_control ? AUV_FRONTSEAT_STATUS_T_STATE_PAYLOAD : AUV_FRONTSEAT_STATUS_T_STATE_FRONTSEAT;
}

/* the payload has control: the frontseat says so and is not silent */
static int has_control(const fs_state *fs) { return state_of(fs) == AUV_FRONTSEAT_STATUS_T_STATE_PAYLOAD; }

static int fresh_setpoint(const fs_state *fs, int64_t now)
{
    return fs->sp_arrived >= 0 && now - fs->sp_arrived <= (int64_t)(fs->setpoint_timeout_s * 1e6);
}

static void publish_status(fs_state *fs, drv_ctx *ctx, int64_t now)
{
    auv_frontseat_status_t m;
    memset(&m, 0, sizeof m);
    m.utime = now;
    m.vehicle = (char *)ctx->vehicle;
    m.protocol = (char *)fs->proto->name;
    m.state = state_of(fs);
    m.mode = fs->have_report ? fs->report.mode : "";
    m.has_control = has_control(fs);
    m.requesting = fs->have_request && fresh_setpoint(fs, now) && fs->last_heard >= 0 && !fs->silent;
    m.error = fs->have_report && fs->report.error && !fs->silent;
    m.error_text = m.error ? fs->report.error_text : "";
    m.last_message_utime = fs->last_heard;
    m.last_message_age_s = fs->last_heard < 0 ? -1.0 : (double)(now - fs->last_heard) / 1e6;
    if (m.last_message_age_s < -1.0)
        m.last_message_age_s = 0.0; /* a stamp after now (a replay's order): no negative age */
    m.setpoints_received = fs->setpoints_received;
    m.requests_sent = fs->requests_sent;
    m.setpoints_clamped = fs->setpoints_clamped;
    m.setpoints_refused = fs->setpoints_refused;
    m.last_refusal = fs->last_refusal;
    m.control_granted = fs->control_granted;
    m.control_lost = fs->control_lost;
    drv_publish(ctx, "FRONTSEAT", auv_type_find("frontseat_status_t"), &m);
    fs->last_status = now;
    fs->published_state = m.state;
}

/* publish at once when the state changes, and count control coming and going */
static void state_maybe_changed(fs_state *fs, drv_ctx *ctx, int64_t now)
{
    int ctl = has_control(fs);
    if (ctl != fs->published_control) {
        if (ctl)
            fs->control_granted++;
        else
            fs->control_lost++;
        fs->published_control = ctl;
        drv_log(ctx, "control %s (frontseat mode '%s'%s%s)", ctl ? "granted to the payload" : "with the frontseat",
                fs->have_report ? fs->report.mode : "", fs->silent ? ", silent" : "",
                fs->report.error ? ", error" : "");
    }
    if (state_of(fs) != fs->published_state)
        publish_status(fs, ctx, now);
}

static void refuse(fs_state *fs, drv_ctx *ctx, const char *reason)
{
    fs->setpoints_refused++;
    snprintf(fs->last_refusal, sizeof fs->last_refusal, "refused: %s", reason);
    char r[DRV_REASON_LEN];
    snprintf(r, sizeof r, "setpoint: %s", reason);
    drv_drop(ctx, r, "not sent to the frontseat");
}

/* the newest setpoint, as a request, to the frontseat; 0 sent */
static int send_request(fs_state *fs, drv_ctx *ctx, int64_t now, int counting)
{
    char clamped[120];
    fs_request rq;
    const char *why =
        fs_setpoint_request(&fs->sp, &fs->lim, fs->nav.depth_m, fs->nav.altitude_m, &rq, clamped, sizeof clamped);
    if (why) {
        if (counting)
            refuse(fs, ctx, why);
        fs->have_request = 0;
        return -1;
    }
    if (clamped[0] && counting) {
        fs->setpoints_clamped++;
        snprintf(fs->last_refusal, sizeof fs->last_refusal, "clamped: %s", clamped);
    }
    fs->rq = rq;
    fs->have_request = 1;
    char out[256];
    int len = fs->proto->encode_request(proto_state(fs), &fs->lim, &rq, out, sizeof out);
    if (len <= 0)
        return -1;
    fs->last_request_sent = now;
    if (drv_write(ctx, (const uint8_t *)out, (size_t)len) == 0)
        fs->requests_sent++;
    return 0;
}

static void on_setpoint(void *state, drv_ctx *ctx, const void *msg, int64_t now)
{
    fs_state *fs = state;
    const auv_setpoint_t *sp = msg;
    fs->setpoints_received++;
    if (sp->utime > 0 && now - sp->utime > (int64_t)(fs->setpoint_timeout_s * 1e6)) {
        refuse(fs, ctx, "stale setpoint");
        return;
    }
    fs->sp = *sp;
    fs->sp.vehicle = NULL; /* freed by the framework after this call */
    fs->sp_arrived = now;
    if (fs->last_heard < 0 || fs->silent) {
        /* nothing to ask a frontseat that does not answer: the plan hears it (FRONTSEAT) */
        refuse(fs, ctx, fs->silent ? "frontseat silent" : "frontseat not connected");
        fs->have_request = 0;
        return;
    }
    send_request(fs, ctx, now, 1);
}

void fs_heard(fs_state *fs, drv_ctx *ctx, int64_t stamp)
{
    int was_silent = fs->silent;
    if (stamp > fs->last_heard)
        fs->last_heard = stamp;
    fs->silent = 0;
    if (was_silent)
        drv_log(ctx, "the frontseat answers again");
}

void fs_report_in(fs_state *fs, drv_ctx *ctx, const fs_report *r, int64_t stamp)
{
    fs->report = *r;
    fs->have_report = 1;
    state_maybe_changed(fs, ctx, stamp);
}

void fs_nav_in(fs_state *fs, drv_ctx *ctx, const fs_nav *nav, int publish, int64_t stamp)
{
    const double *in = &nav->lat_deg;
    double *held = &fs->nav.lat_deg;
    for (size_t i = 0; i < sizeof(fs_nav) / sizeof(double); i++)
        if (!isnan(in[i]))
            held[i] = in[i];
    if (!publish)
        return;
    fs->nav_stamp = stamp;
    const fs_nav *n = &fs->nav;
    if (isnan(n->lat_deg) || isnan(n->depth_m) || isnan(n->heading_rad))
        return; /* not a whole solution yet: a depth and a heading come with the first $C */
    auv_nav_solution_t m;
    memset(&m, 0, sizeof m);
    m.utime = stamp;
    m.vehicle = (char *)ctx->vehicle;
    m.source = AUV_NAV_SOLUTION_T_SOURCE_EKF; /* the frontseat's own filter: not the simulator's */
    m.status = AUV_NAV_SOLUTION_T_STATUS_ALIGNED;
    m.latitude_deg = n->lat_deg;
    m.longitude_deg = n->lon_deg;
    m.north_m = fs->have_origin ? (n->lat_deg - fs->lat0) / fs->dlat : NAN;
    m.east_m = fs->have_origin ? (n->lon_deg - fs->lon0) / fs->dlon : NAN;
    m.depth_m = n->depth_m;
    m.altitude_m = isnan(n->altitude_m) ? -1.0 : n->altitude_m;
    m.roll_rad = isnan(n->roll_rad) ? 0.0 : n->roll_rad;
    m.pitch_rad = isnan(n->pitch_rad) ? 0.0 : n->pitch_rad;
    m.heading_rad = n->heading_rad;
    /* the frontseat says a speed over ground and no velocity: taken as the surge;
     * the rest is not known (NaN) */
    m.u_mps = n->speed_mps;
    m.v_mps = m.w_mps = m.p_radps = m.q_radps = m.r_radps = NAN;
    m.speed_over_ground_mps = n->speed_mps;
    m.course_over_ground_rad = NAN;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            m.position_cov_m2[i][j] = m.velocity_cov_m2ps2[i][j] = m.attitude_cov_rad2[i][j] = NAN;
    drv_publish(ctx, "NAV", auv_type_find("nav_solution_t"), &m);
}

static int fs_init(void *state, drv_ctx *ctx)
{
    fs_state *fs = state;
    if (!fs->proto)
        fs->proto = &iver3_proto;
    if (fs->proto->state_size > FS_PROTO_STATE_MAX) {
        drv_log(ctx, "protocol %s: state of %zu bytes over %d", fs->proto->name, fs->proto->state_size,
                FS_PROTO_STATE_MAX);
        return -1;
    }
    const struct {
        int bit;
        double *field;
        double value;
    } defaults[] = {
        {SET_MAX_DEPTH, &fs->lim.max_depth_m, 100.0},   {SET_MIN_SPEED, &fs->lim.min_speed_mps, 0.5},
        {SET_MAX_SPEED, &fs->lim.max_speed_mps, 2.5},   {SET_MAX_PITCH, &fs->lim.max_pitch_deg, 30.0},
        {SET_TIMEOUT, &fs->lim.request_timeout_s, 5.0}, {SET_POLL, &fs->poll_period_s, 0.2},
        {SET_RESEND, &fs->resend_period_s, 1.0},        {SET_SP_TIMEOUT, &fs->setpoint_timeout_s, 2.0},
        {SET_SILENT, &fs->silent_after_s, 3.0},
    };
    for (size_t i = 0; i < sizeof defaults / sizeof *defaults; i++)
        if (!(fs->settings_done & defaults[i].bit))
            *defaults[i].field = defaults[i].value;
    if (!(fs->settings_done & SET_HELM))
        fs->lim.helm_version = 5;
    if (fs->lim.min_speed_mps >= fs->lim.max_speed_mps) {
        drv_log(ctx, "--min-speed %g is not below --max-speed %g", fs->lim.min_speed_mps, fs->lim.max_speed_mps);
        return -1;
    }
    fs->last_heard = fs->nav_stamp = fs->sp_arrived = -1;
    fs->last_request_sent = fs->last_poll_sent = fs->last_status = INT64_MIN / 2;
    fs->nav = (fs_nav){NAN, NAN, NAN, NAN, NAN, NAN, NAN, NAN};
    fs->published_state = -1;
    fs->proto->reset(proto_state(fs)); /* its framer's rules set before the first byte, not at the port's opening */
    return 0;
}

static void fs_feed(void *state, drv_ctx *ctx, const uint8_t *bytes, size_t n, int64_t stamp)
{
    fs_state *fs = state;
    fs->proto->feed(proto_state(fs), fs, ctx, bytes, n, stamp);
}

static void fs_tick(void *state, drv_ctx *ctx, int64_t now)
{
    fs_state *fs = state;
    if (now - fs->last_poll_sent >= (int64_t)(fs->poll_period_s * 1e6)) {
        char out[128];
        int len = fs->proto->encode_poll(proto_state(fs), out, sizeof out);
        fs->last_poll_sent = now;
        if (len > 0)
            drv_write(ctx, (const uint8_t *)out, (size_t)len);
    }
    if (fs->last_heard >= 0 && !fs->silent && now - fs->last_heard > (int64_t)(fs->silent_after_s * 1e6)) {
        fs->silent = 1;
        fs->have_request = 0; /* stop asking: the plan hears it on FRONTSEAT */
        drv_log(ctx, "the frontseat is silent: nothing for %.1f s", (double)(now - fs->last_heard) / 1e6);
    }
    if (!fresh_setpoint(fs, now))
        fs->have_request = 0; /* the navigator stopped: the frontseat takes back after its timeout */
    if (fs->have_request && !fs->silent && now - fs->last_request_sent >= (int64_t)(fs->resend_period_s * 1e6))
        send_request(fs, ctx, now, 0);
    state_maybe_changed(fs, ctx, now);
    if (now - fs->last_status >= STATUS_PERIOD_US)
        publish_status(fs, ctx, now);
}

static void fs_reset(void *state, drv_ctx *ctx)
{
    (void)ctx;
    fs_state *fs = state;
    fs->proto->reset(proto_state(fs));
}

/* the port opened (the first time too): a new stream. What was written before,
 * into a port not yet open (Bluefin's $BPLOG at the first polls), the vehicle
 * never heard: the protocol starts over and asks again. */
static void fs_opened(void *state, drv_ctx *ctx)
{
    (void)ctx;
    fs_state *fs = state;
    fs->proto->reset(proto_state(fs));
}

static const drv_flag fs_flags[] = {
    {"--protocol", "NAME", "the frontseat's protocol: iver3 (default) or bluefin", set_protocol},
    {"--origin", "LAT,LON", "the world's origin: NAV's north_m and east_m (NaN without)", set_origin},
    {"--max-depth", "M", "deeper setpoints are clamped to this (default 100)", set_max_depth},
    {"--min-speed", "M/S", "slower setpoints are refused (default 0.5)", set_min_speed},
    {"--max-speed", "M/S", "faster setpoints are clamped to this (default 2.5)", set_max_speed},
    {"--max-pitch", "DEG", "the pitch the frontseat may use to reach a depth (default 30)", set_max_pitch},
    {"--request-timeout", "S", "the frontseat takes back control after this without a request (default 5)",
     set_request_timeout},
    {"--helm-version", "N", "the frontseat software's major version (iver3: depth in feet before 5; default 5)",
     set_helm_version},
    {"--poll-period", "S", "how often the frontseat is asked for its data (default 0.2)", set_poll_period},
    {"--resend-period", "S", "how often a held setpoint is asked again (default 1)", set_resend_period},
    {"--setpoint-timeout", "S", "a setpoint older than this is not sent (default 2)", set_setpoint_timeout},
    {"--silent-after", "S", "the frontseat is silent after this without a sentence (default 3)", set_silent_after},
    {0},
};

static const drv_subscription fs_subs[] = {
    {"SETPOINT", "setpoint_t", on_setpoint},
    {0},
};

const drv_protocol frontseat_protocol = {
    .device = "FRONTSEAT",
    .program = "auv-frontseat",
    .summary = "A commercial vehicle's frontseat from its backseat: the navigator's setpoints (<V>.SETPOINT) as "
               "the frontseat's requests, its navigation on <V>.NAV, its state on <V>.FRONTSEAT "
               "(docs/frontseat.md). Protocols (--protocol): iver3, the Iver3 Remote Helm; bluefin, Bluefin's "
               "standard payload interface (Huxley, usually --tcp HOST:29500).",
    .default_baud = 19200,
    .state_size = sizeof(fs_state),
    .flags = fs_flags,
    .subscriptions = fs_subs,
    .init = fs_init,
    .feed = fs_feed,
    .tick = fs_tick,
    .opened = fs_opened,
    .reset = fs_reset,
};
DRV_REGISTER(frontseat_protocol)
