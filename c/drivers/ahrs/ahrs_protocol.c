/* auv-ahrs's protocol: NMEA framing (c/drivers/common/nmea.c) and the heading
 * and attitude sentences (ahrs_nmea.c) behind the driver framework.
 *
 * What is published: one ahrs_t per accepted PASHR, PRDID or VNYMR, stamped with its
 * receive time, with its roll, pitch and heading and valid = true. ahrs_t has a
 * single `valid` flag for all six values; VNYMR carries the body rates, PASHR
 * and PRDID do not: its p, q and r are NaN. A NaN in a "valid" message is what auv-nav
 * refuses as implausible (c/nav/nav_lcm.cpp), so auv-nav runs on this driver
 * only with a device sending VNYMR (docs/drivers.md, "auv-ahrs"). An HDT carries
 * no attitude: publishing it would put NaN roll and pitch under valid = true,
 * or a true heading under valid = false, so HDT is checked (its refusals
 * counted like any other) and counted as a frame, and not published. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "auv/auv_ahrs_t.h"
#include "drivers/ahrs/ahrs.h"

static int parse_sign(const char *v, int *out)
{
    if (!strcmp(v, "1") || !strcmp(v, "+1"))
        *out = 1;
    else if (!strcmp(v, "-1"))
        *out = -1;
    else
        return -1;
    return 0;
}

int ahrs_set_roll_sign(void *state, const char *v, char *err, size_t n)
{
    ahrs_state *a = state;
    if (parse_sign(v, &a->cfg.roll_sign) < 0) {
        snprintf(err, n, "--roll-sign wants 1 or -1, not '%s'", v);
        return -1;
    }
    a->settings_done |= 1;
    return 0;
}

int ahrs_set_pitch_sign(void *state, const char *v, char *err, size_t n)
{
    ahrs_state *a = state;
    if (parse_sign(v, &a->cfg.pitch_sign) < 0) {
        snprintf(err, n, "--pitch-sign wants 1 or -1, not '%s'", v);
        return -1;
    }
    a->settings_done |= 2;
    return 0;
}

int ahrs_set_heading_offset(void *state, const char *v, char *err, size_t n)
{
    ahrs_state *a = state;
    char *end;
    double d = strtod(v, &end);
    /* a mounting misalignment is a fraction of a turn; beyond one turn it is a typo */
    if (end == v || *end || !isfinite(d) || fabs(d) > 360.0) {
        snprintf(err, n, "--heading-offset wants degrees in [-360, 360], not '%s'", v);
        return -1;
    }
    a->cfg.heading_offset_deg = d;
    a->settings_done |= 4;
    return 0;
}

static int ahrs_init(void *state, drv_ctx *ctx)
{
    ahrs_state *a = state;
    const ahrs_nmea_config def = AHRS_NMEA_DEFAULTS;
    if (!(a->settings_done & 1))
        a->cfg.roll_sign = def.roll_sign;
    if (!(a->settings_done & 2))
        a->cfg.pitch_sign = def.pitch_sign;
    if (!(a->settings_done & 4))
        a->cfg.heading_offset_deg = def.heading_offset_deg;
    nmea_framer_init(&a->framer, 0);
    a->ahrs_type = auv_type_find("ahrs_t");
    if (!a->ahrs_type) {
        drv_log(ctx, "ahrs_t is not in the type table");
        return -1;
    }
    return 0;
}

static void publish(ahrs_state *a, drv_ctx *ctx, const ahrs_nmea_reading *r, int64_t stamp)
{
    auv_ahrs_t m;
    memset(&m, 0, sizeof m);
    m.utime = stamp;
    m.vehicle = (char *)ctx->vehicle;
    m.roll_rad = r->roll_rad;
    m.pitch_rad = r->pitch_rad;
    m.heading_rad = r->heading_rad;
    if (r->has_rates) {
        m.p_radps = r->p_radps;
        m.q_radps = r->q_radps;
        m.r_radps = r->r_radps;
    } else {
        m.p_radps = m.q_radps = m.r_radps = NAN; /* PASHR: no gyro rates */
    }
    m.valid = 1;
    drv_publish(ctx, "AHRS", a->ahrs_type, &m);
}

static void on_sentence(ahrs_state *a, drv_ctx *ctx, int64_t stamp)
{
    ahrs_nmea_reading r;
    ahrs_nmea_result res = ahrs_nmea_decode(&a->sentence, &a->cfg, &r);
    if (res == AHRS_NMEA_NOT_MINE)
        return; /* another sentence on the line (a GPS's, a $GPZDA): not an error */
    if (res != AHRS_NMEA_OK) {
        drv_drop(ctx, ahrs_nmea_result_name(res), "%.80s", a->sentence.text);
        return;
    }
    drv_frame_ok(ctx, stamp);
    if (r.has_attitude)
        publish(a, ctx, &r, stamp); /* an HDT: checked and counted above, no message (see the top) */
}

static void ahrs_feed(void *state, drv_ctx *ctx, const uint8_t *bytes, size_t n, int64_t stamp)
{
    ahrs_state *a = state;
    for (size_t i = 0; i < n; i++) {
        int r = nmea_framer_push(&a->framer, bytes[i], &a->sentence);
        if (r == NMEA_OK)
            on_sentence(a, ctx, stamp);
        else if (r > 0)
            drv_drop(ctx, nmea_result_name((nmea_result)r), "%.*s", (int)(a->framer.len < 60 ? a->framer.len : 60),
                     a->framer.buf);
        /* garbage between sentences: one count per run of it, not per byte */
        if (a->framer.garbage_bytes != a->garbage_seen) {
            a->garbage_seen = a->framer.garbage_bytes;
            if (!a->in_garbage)
                drv_drop(ctx, "garbage", "bytes outside any sentence, from 0x%02x", bytes[i]);
            a->in_garbage = 1;
        } else if (r >= 0) { /* a line ended: the run of garbage before it is over */
            a->in_garbage = 0;
        }
    }
}

static void ahrs_reset(void *state, drv_ctx *ctx)
{
    ahrs_state *a = state;
    (void)ctx;
    /* a half sentence of a lost stream never ends */
    nmea_framer_init(&a->framer, 0);
    a->garbage_seen = 0;
    a->in_garbage = 0;
}

static const drv_flag ahrs_flags[] = {
    {"--roll-sign", "S", "1 or -1: the device's roll times S is the project's (starboard down positive)",
     ahrs_set_roll_sign},
    {"--pitch-sign", "S", "1 or -1: the device's pitch times S is the project's (bow up positive)",
     ahrs_set_pitch_sign},
    {"--heading-offset", "DEG", "added to every heading: the mounting's yaw misalignment (default 0)",
     ahrs_set_heading_offset},
    {0},
};

const drv_protocol ahrs_protocol = {
    .device = "AHRS",
    .program = "auv-ahrs",
    .summary = "NMEA 0183 compass/AHRS: $PASHR or RDI's $PRDID (heading, roll, pitch) or VectorNav's\n"
               "$VNYMR (yaw, pitch, roll and the body rates) into one ahrs_t per sentence on <ID>.AHRS,\n"
               "stamped with its receive time; PASHR's and PRDID's body rates are NaN (they have none).\n"
               "$--HDT and $--THS are checked and counted, not published (no attitude).",
    .default_baud = 9600,
    .state_size = sizeof(ahrs_state),
    .flags = ahrs_flags,
    .init = ahrs_init,
    .feed = ahrs_feed,
    .reset = ahrs_reset,
};

DRV_REGISTER(ahrs_protocol)
