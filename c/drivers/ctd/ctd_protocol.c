/* auv-ctd's protocol: an SBE 49 FastCAT samples continuously (16 Hz) once
 * started, a line a scan (sbe49.h). Each scan is published as a ctd_t stamped
 * with the receive time of its line's end (the instrument's scans carry no
 * time): conductivity, temperature and pressure as measured; salinity the
 * instrument's if it sends one (OutputSal=Y), else PSS-78 from the three
 * (pss78.h); depth from the pressure at --latitude (UNESCO 1983); sound speed
 * the instrument's if it sends one (OutputSV=Y), else NaN: no TEOS-10 in C.
 *
 * With --configure FORMAT the driver sets the instrument up when the port
 * opens: Stop, OutputFormat=FORMAT (and OutputSal=Y, OutputSV=Y for format 3),
 * Start; without it the instrument is left as it is (AutoRun, or started by
 * its operator). Prompts, command echoes and the instrument's text are not
 * scans and are passed over; a scan that fails its format or ranges is
 * dropped by reason (sbe49.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "auv/auv_ctd_t.h"
#include "drivers/ctd/ctd.h"
#include "drivers/ctd/pss78.h"

#define DEFAULT_LATITUDE 45.0

int ctd_set_latitude(void *state, const char *v, char *err, size_t n)
{
    ctd_state *s = state;
    char *end;
    double d = strtod(v, &end);
    if (end == v || *end || !(d >= -90.0 && d <= 90.0)) {
        snprintf(err, n, "--latitude wants degrees in -90..90, not '%s'", v);
        return -1;
    }
    s->latitude_deg = d;
    s->settings_done |= 1;
    return 0;
}

int ctd_set_configure(void *state, const char *v, char *err, size_t n)
{
    ctd_state *s = state;
    if (strcmp(v, "1") && strcmp(v, "3")) {
        snprintf(err, n, "--configure wants an OutputFormat the driver reads, 1 (hex) or 3 (decimal), not '%s'", v);
        return -1;
    }
    s->configure = atoi(v);
    return 0;
}

static int ctd_init(void *state, drv_ctx *ctx)
{
    ctd_state *s = state;
    if (!(s->settings_done & 1))
        s->latitude_deg = DEFAULT_LATITUDE;
    s->ctd_type = auv_type_find("ctd_t");
    if (!s->ctd_type) {
        drv_log(ctx, "ctd_t is not in the type table");
        return -1;
    }
    return 0;
}

static void say(drv_ctx *ctx, const char *command)
{
    char line[64];
    int n = snprintf(line, sizeof line, "%s\r\n", command);
    drv_write(ctx, (const uint8_t *)line, (size_t)n);
}

static void ctd_opened(void *state, drv_ctx *ctx)
{
    ctd_state *s = state;
    if (!s->configure)
        return;
    say(ctx, ""); /* wakes the command interpreter: the S> prompt */
    say(ctx, "Stop");
    say(ctx, s->configure == 1 ? "OutputFormat=1" : "OutputFormat=3");
    if (s->configure == 3) {
        say(ctx, "OutputSal=Y");
        say(ctx, "OutputSV=Y");
    }
    say(ctx, "Start");
}

void ctd_line(ctd_state *s, drv_ctx *ctx, const char *line, size_t n, int64_t stamp)
{
    sbe49_sample x;
    const char *why;
    sbe49_kind k = sbe49_parse_line(line, n, &x, &why);
    if (k == SBE49_NOT_DATA)
        return;
    if (k == SBE49_BAD) {
        drv_drop(ctx, why, "'%.*s'%s", (int)(n > 40 ? 40 : n), line,
                 strcmp(why, "raw counts") ? "" : ": set the instrument's OutputFormat=1 or 3");
        return;
    }
    auv_ctd_t m = {0};
    m.utime = stamp;
    m.vehicle = (char *)ctx->vehicle;
    m.conductivity_s_per_m = x.conductivity_s_per_m;
    m.temperature_c = x.temperature_c;
    m.pressure_dbar = x.pressure_dbar;
    m.salinity_psu = isnan(x.salinity_psu) ? pss78_salinity(x.conductivity_s_per_m, x.temperature_c, x.pressure_dbar)
                                           : x.salinity_psu;
    m.depth_m = pss78_depth(x.pressure_dbar, s->latitude_deg);
    m.sound_speed_mps = x.sound_speed_mps;
    m.valid = 1;
    drv_frame_ok(ctx, stamp);
    drv_publish(ctx, "CTD", s->ctd_type, &m);
}

static void ctd_feed(void *state, drv_ctx *ctx, const uint8_t *bytes, size_t n, int64_t stamp)
{
    ctd_state *s = state;
    for (size_t i = 0; i < n; i++) {
        char c = (char)bytes[i];
        /* a scan ends with CR LF; a line that ends with CR alone or LF alone
         * (a terminal server's, a converter's) ends as well; the empty line
         * between the CR and the LF of CR LF is nothing */
        if (c == '\n' || c == '\r') {
            if (s->n == 0 && !s->overflow)
                continue;
            if (s->overflow)
                drv_drop(ctx, "line too long", "over %d characters", SBE49_MAX_LINE);
            else
                ctd_line(s, ctx, s->line, s->n, stamp);
            s->n = 0;
            s->overflow = 0;
        } else if (s->n < SBE49_MAX_LINE) {
            s->line[s->n++] = c;
        } else {
            s->overflow = 1;
        }
    }
}

static void ctd_reset(void *state, drv_ctx *ctx)
{
    (void)ctx;
    ctd_state *s = state;
    s->n = 0;   /* a half line never ends */
    s->overflow = 0;
}

static const drv_flag ctd_flags[] = {
    {"--latitude", "DEG", "the vehicle's latitude, for depth from pressure (default 45)", ctd_set_latitude},
    {"--configure", "FORMAT", "at open: Stop, OutputFormat=FORMAT (1 hex or 3 decimal; 3 with OutputSal=Y and "
                              "OutputSV=Y), Start (default: leave the instrument as it is)", ctd_set_configure},
    {0},
};

const drv_protocol ctd_protocol = {
    .device = "CTD",
    .program = "auv-ctd",
    .summary = "A Sea-Bird SBE 49 FastCAT CTD (OutputFormat=1 engineering hex or 3 engineering decimal) into "
               "ctd_t on <VEHICLE>.CTD: salinity the instrument's or PSS-78, depth by UNESCO 1983 at --latitude, "
               "each scan stamped with its line's receive time.",
    .default_baud = 9600,
    .state_size = sizeof(ctd_state),
    .flags = ctd_flags,
    .init = ctd_init,
    .feed = ctd_feed,
    .opened = ctd_opened,
    .reset = ctd_reset,
};
DRV_REGISTER(ctd_protocol)
