/* setpoint_watch: says what the pilot is doing and counts the setpoints it
 * ignores (pilot_status_t on <VEHICLE>.PILOT_STATUS).
 *
 * The manager stamps every setpoint variable with the message's utime, so a
 * setpoint stamped 0, or older than the timeout when it arrives, is stale
 * from the start and the pilot idles. Without this behavior that happens
 * with no word anywhere. A new setpoint is told from the previous one by its
 * utime and values (identical repeats count once); it is ignored if its
 * utime is 0 or older than `timeout` at the cycle it is first seen. The count
 * lives in its output variable, so the instances in `idle` and `fly` carry
 * it on across state changes. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "plugins/pilot/pilot.h"

/* A field of the setpoint watched: read as is, its doc says which. */
#define IN(name, type, unit, var) CHASM_READ(name, type, unit, var, "the setpoint's " name)

const chasm_param_spec pilot_setpoint_watch_params[W_NPARAMS] = {
    [W_UTIME] = IN("utime", CHASM_INT, "", "setpoint.utime"),
    [W_HEADING] = IN("heading", CHASM_DOUBLE, "rad", "setpoint.heading_rad"),
    [W_DEPTH] = IN("depth", CHASM_DOUBLE, "m", "setpoint.depth_m"),
    [W_ALTITUDE] = IN("altitude", CHASM_DOUBLE, "m", "setpoint.altitude_m"),
    [W_PITCH] = IN("pitch", CHASM_DOUBLE, "rad", "setpoint.pitch_rad"),
    [W_SPEED] = IN("speed", CHASM_DOUBLE, "m/s", "setpoint.speed_mps"),
    [W_RPM] = IN("rpm", CHASM_DOUBLE, "", "setpoint.prop_rpm"),
    [W_VMODE] = IN("vertical_mode", CHASM_INT, "", "setpoint.vertical_mode"),
    [W_SMODE] = IN("speed_mode", CHASM_INT, "", "setpoint.speed_mode"),
    [W_REF] = IN("speed_reference", CHASM_INT, "", "setpoint.speed_reference"),
    [W_COUNT] = CHASM_WRITE("ignored", CHASM_INT, "", "pilot.setpoints_ignored", "setpoints ignored so far"),
    [W_IGNORING] = CHASM_WRITE("ignoring", CHASM_BOOL, "", "pilot.ignoring", "the newest setpoint is ignored"),
    [W_REASON] = CHASM_WRITE("reason", CHASM_INT, "", "pilot.last_ignored_reason",
                             "1: utime 0, 2: utime older than timeout"),
    [W_LAST] = CHASM_WRITE("last", CHASM_INT, "", "pilot.last_ignored_utime",
                           "utime of the last setpoint ignored [us]"),
    [W_STATE] = CHASM_WRITE("state", CHASM_INT, "", "pilot.state", "0 idle, 1 flying"),
    [W_REF_OUT] = CHASM_WRITE("reference", CHASM_INT, "", "pilot.speed_reference", "what speed is held against"),
    [W_TIMEOUT] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE(
        "timeout", "s", 0, 3600, "a setpoint older than this on arrival is ignored (the plan's setpoint_timeout)"),
    [W_FLYING] = CHASM_PARAM_REQUIRED_BOOL("flying", "true in the state that flies"),
};

static void snapshot(const chasm_ctx *c, double *out)
{
    out[0] = (double)chasm_read_int(c, W_UTIME);
    for (int i = W_HEADING; i <= W_RPM; i++)
        out[i] = chasm_read_double(c, i);
    out[W_VMODE] = (double)chasm_read_int(c, W_VMODE);
    out[W_SMODE] = (double)chasm_read_int(c, W_SMODE);
    out[W_SMODE + 1] = (double)chasm_read_int(c, W_REF);
}

static int same(const double *a, const double *b, int n)
{
    for (int i = 0; i < n; i++)
        if (!(a[i] == b[i] || (isnan(a[i]) && isnan(b[i]))))
            return 0;
    return 1;
}

/* No start(): each instance judges the setpoint in hand at its first step.
 * Transitions run before actions, so the state entered because a setpoint
 * went stale is the one that sees (and counts) it, once. */

chasm_status_code pilot_setpoint_watch_step(chasm_ctx *c, void *st)
{
    pilot_watch_state *s = st;
    double now[W_SMODE + 2];
    snapshot(c, now);
    int64_t utime = chasm_read_int(c, W_UTIME);
    int fresh = !s->seen || !same(now, s->last, W_SMODE + 2);
    /* Before any setpoint arrives the variables were never set (age 1e300): nothing to judge. */
    int arrived = chasm_age_s(c, W_UTIME) < 1e299;
    if (fresh && arrived) {
        int reason = utime == 0 ? 1 : (double)(c->now_us - utime) * 1e-6 > chasm_param_double(c, W_TIMEOUT) ? 2 : 0;
        chasm_write_bool(c, W_IGNORING, reason != 0);
        if (reason) {
            int64_t n = chasm_read_int(c, W_COUNT) + 1;
            chasm_write_int(c, W_COUNT, n);
            chasm_write_int(c, W_REASON, reason);
            chasm_write_int(c, W_LAST, utime);
            if (n == 1 || (n & (n - 1)) == 0) { /* 1, 2, 4, 8...: a word in the log, not a flood */
                char msg[160];
                snprintf(msg, sizeof msg, "setpoint ignored (%s, utime %lld); %lld so far",
                         reason == 1 ? "utime 0" : "older than setpoint_timeout", (long long)utime, (long long)n);
                chasm_log(c, msg);
            }
        }
    }
    memcpy(s->last, now, sizeof now);
    s->seen = 1;
    chasm_write_int(c, W_STATE, chasm_param_bool(c, W_FLYING) ? 1 : 0);
    chasm_write_int(c, W_REF_OUT, chasm_read_int(c, W_REF));
    return CHASM_RUNNING;
}
