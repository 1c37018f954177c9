/* auv-dvl's protocol: PD0 framing, decoding, continuity and the dvl_t
 * (pd0.h) behind the driver framework's callbacks (drv_protocol.h).
 * docs/drivers.md, "auv-dvl". */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "auv/auv_dvl_t.h"
#include "drivers/dvl/dvl.h"
#include "drivers/dvl/pd0.h"

/* A cut ensemble is flushed after this much silence. The bytes of one
 * ensemble arrive back to back (at 9600 baud a 1 kB ensemble is a steady
 * trickle of reads ms apart), so half a second without a byte while one is
 * half held means the device stopped mid-ensemble. */
#define DEFAULT_TIMEOUT_S 0.5

typedef struct {
    pd0_framer framer;
    pd0_ensemble ens;
    pd0_continuity cont;
    pd0_mounting mount;
    const auv_type_entry_t *dvl_type;
    double timeout_s;
    int settings_done;    /* bits: 1 mounting, 2 sigma, 4 timeout */
    double mount_deg[3];  /* yaw, pitch, roll as given */
    double sigma_mps;
    int64_t last_rx;      /* stamp of the newest bytes, -1 before any */
    uint64_t bytes_in;    /* bytes fed since the start, for the log lines */
    uint64_t garbage_seen;
    int in_garbage;       /* this run of garbage was counted already */
    int after_refusal;    /* bytes skipped now are the rest of a refused ensemble */
} dvl_state;

static int parse_double(const char *v, double *out)
{
    char *end;
    double d = strtod(v, &end);
    if (end == v || *end || !isfinite(d))
        return -1;
    *out = d;
    return 0;
}

static int set_mounting(void *state, const char *v, char *err, size_t n)
{
    dvl_state *s = state;
    char buf[128];
    snprintf(buf, sizeof buf, "%s", v);
    double a[3];
    char *p = buf;
    for (int i = 0; i < 3; i++) {
        char *comma = strchr(p, ',');
        if ((i < 2) != (comma != NULL))
            goto bad;
        if (comma)
            *comma = '\0';
        if (parse_double(p, &a[i]) < 0)
            goto bad;
        p = comma + 1;
    }
    if (fabs(a[0]) > 180.0 || fabs(a[1]) > 90.0 || fabs(a[2]) > 180.0)
        goto bad;
    memcpy(s->mount_deg, a, sizeof a);
    s->settings_done |= 1;
    return 0;
bad:
    snprintf(err, n,
             "--mounting wants YAW,PITCH,ROLL in degrees (|YAW| <= 180, |PITCH| <= 90, |ROLL| <= 180), not '%s'", v);
    return -1;
}

static int set_sigma(void *state, const char *v, char *err, size_t n)
{
    dvl_state *s = state;
    double d;
    if (parse_double(v, &d) < 0 || d <= 0.0 || d > 10.0) {
        snprintf(err, n, "--sigma wants m/s in (0, 10], not '%s'", v);
        return -1;
    }
    s->sigma_mps = d;
    s->settings_done |= 2;
    return 0;
}

static int set_timeout(void *state, const char *v, char *err, size_t n)
{
    dvl_state *s = state;
    double d;
    if (parse_double(v, &d) < 0 || d < 0.05 || d > 10.0) {
        snprintf(err, n, "--ensemble-timeout wants seconds in [0.05, 10], not '%s'", v);
        return -1;
    }
    s->timeout_s = d;
    s->settings_done |= 4;
    return 0;
}

static int dvl_init(void *state, drv_ctx *ctx)
{
    dvl_state *s = state;
    /* the flags set their own values; the rest are defaults (the state starts zeroed) */
    pd0_mounting_default(&s->mount);
    if (s->settings_done & 1) {
        s->mount.yaw_rad = s->mount_deg[0] * M_PI / 180.0;
        s->mount.pitch_rad = s->mount_deg[1] * M_PI / 180.0;
        s->mount.roll_rad = s->mount_deg[2] * M_PI / 180.0;
    }
    if (s->settings_done & 2)
        s->mount.velocity_sigma_mps = s->sigma_mps;
    if (!(s->settings_done & 4))
        s->timeout_s = DEFAULT_TIMEOUT_S;
    pd0_framer_init(&s->framer);
    s->last_rx = -1;
    s->dvl_type = auv_type_find("dvl_t");
    if (!s->dvl_type) {
        drv_log(ctx, "dvl_t is not in the type table");
        return -1;
    }
    return 0;
}

/* Garbage is counted once per run of skipped bytes, not per byte (a baud
 * mismatch is one event, not thousands). Bytes skipped right after a refused
 * header are the rest of that ensemble: its refusal counted them already. */
static void count_garbage(dvl_state *s, drv_ctx *ctx)
{
    if (s->framer.garbage_bytes == s->garbage_seen)
        return;
    uint64_t n = s->framer.garbage_bytes - s->garbage_seen;
    s->garbage_seen = s->framer.garbage_bytes;
    if (!s->in_garbage && !s->after_refusal)
        drv_drop(ctx, "garbage", "%llu bytes outside any ensemble", (unsigned long long)n);
    s->in_garbage = 1;
}

/* A header is in view (held, or just handed out or refused): a run of
 * garbage before it has ended. */
static void header_seen(dvl_state *s)
{
    s->in_garbage = 0;
    s->after_refusal = 0;
}

static int holds_header(const pd0_framer *f)
{
    return f->len - f->start >= 2 && f->buf[f->start] == 0x7F && f->buf[f->start + 1] == 0x7F;
}

/* The ensemble number's continuity; returns 0 when the ensemble is not to be
 * published (a repeat: the same ping twice would count twice in a filter). */
static int check_continuity(dvl_state *s, drv_ctx *ctx, uint32_t number, int64_t device_utime)
{
    uint32_t last = s->cont.last;
    long k = pd0_continuity_update(&s->cont, number, device_utime);
    if (k > 0)
        drv_drop(ctx, "ensemble gap", "ensemble %u after %u: %ld missed", number, last, k);
    else if (k == -1)
        drv_drop(ctx, "repeated ensemble", "ensemble %u again", number);
    else if (k == -2)
        drv_drop(ctx, "ensemble number restarted", "ensemble %u after %u: the device restarted", number, last);
    return k != -1;
}

static void on_ensemble(dvl_state *s, drv_ctx *ctx, const uint8_t *p, size_t n, int64_t stamp)
{
    pd0_result r = pd0_decode(p, n, &s->ens);
    if (r != PD0_OK) {
        drv_drop(ctx, pd0_result_name(r), "an ensemble of %zu bytes", n);
        return;
    }
    drv_frame_ok(ctx, stamp);
    if (!check_continuity(s, ctx, s->ens.ensemble_number, pd0_rtc_utime(&s->ens.rtc)))
        return;
    auv_dvl_t m;
    memset(&m, 0, sizeof m);
    pd0_to_dvl(&s->ens, &s->mount, &m);
    /* the receive time of the ensemble's last byte, on the vehicle's clock;
     * the DVL's own RTC is in device_utime (docs/drivers.md, "auv-dvl") */
    m.utime = stamp;
    m.vehicle = (char *)ctx->vehicle;
    drv_publish(ctx, "DVL", s->dvl_type, &m);
}

static void dvl_feed(void *state, drv_ctx *ctx, const uint8_t *bytes, size_t n, int64_t stamp)
{
    dvl_state *s = state;
    const uint8_t *ens;
    size_t used, len;
    int r;
    s->last_rx = stamp;
    s->bytes_in += n;
    while ((r = pd0_framer_push(&s->framer, bytes, n, &used, &ens, &len)) != -1) {
        bytes += used;
        n -= used;
        count_garbage(s, ctx);
        header_seen(s);
        if (r == PD0_OK) {
            on_ensemble(s, ctx, ens, len, stamp);
        } else {
            drv_drop(ctx, pd0_result_name((pd0_result)r), "a header in the read ending at stream byte %llu",
                     (unsigned long long)s->bytes_in);
            /* the search resumes one byte on, through the rest of the refused ensemble */
            s->after_refusal = 1;
        }
    }
    count_garbage(s, ctx);
    if (holds_header(&s->framer))
        header_seen(s);
}

static void dvl_tick(void *state, drv_ctx *ctx, int64_t now)
{
    dvl_state *s = state;
    if (s->last_rx < 0 || s->framer.len == s->framer.start)
        return;
    if ((double)(now - s->last_rx) < s->timeout_s * 1e6)
        return;
    if (pd0_framer_flush(&s->framer) == PD0_TRUNCATED)
        drv_drop(ctx, pd0_result_name(PD0_TRUNCATED), "the device went quiet mid-ensemble for %.2f s",
                 (double)(now - s->last_rx) / 1e6);
    count_garbage(s, ctx);
    s->in_garbage = 0;
    s->after_refusal = 0;
}

static void dvl_reset(void *state, drv_ctx *ctx)
{
    dvl_state *s = state;
    (void)ctx;
    /* a half ensemble of a lost stream never ends; the ensemble numbers go on
     * (ensembles missed while the port was away show as a gap) */
    pd0_framer_init(&s->framer);
    s->garbage_seen = 0;
    s->in_garbage = 0;
    s->after_refusal = 0;
}

static const drv_flag dvl_flags[] = {
    {"--mounting", "YAW,PITCH,ROLL",
     "the DVL's rotation from the body [degrees, ZYX] (default 0,0,0: beam 3 forward, looking down)", set_mounting},
    {"--sigma", "M/S", "velocity_sigma_mps published with a good velocity (default 0.01)", set_sigma},
    {"--ensemble-timeout", "S", "a half ensemble is dropped after S seconds of silence (default 0.5)", set_timeout},
    {0},
};

const drv_protocol dvl_protocol = {
    .device = "DVL",
    .program = "auv-dvl",
    .summary = "Teledyne RDI DVL, PD0 binary ensembles (Workhorse, Pathfinder, Tasman, Navigator), in any\n"
               "frame, into one dvl_t per ensemble on <ID>.DVL in body axes, stamped with the receive time\n"
               "of the ensemble's last byte; the DVL's RTC is in device_utime.",
    .default_baud = 9600,
    .state_size = sizeof(dvl_state),
    .flags = dvl_flags,
    .init = dvl_init,
    .feed = dvl_feed,
    .tick = dvl_tick,
    .reset = dvl_reset,
};

DRV_REGISTER(dvl_protocol)
