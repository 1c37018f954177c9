/* setpoint_t -> the request a frontseat takes (frontseat.h). The rule: what
 * would make the vehicle go deeper or faster than the limits is brought
 * inside them (clamped, with the reason); what the frontseat cannot do, or a
 * value that is no number, is refused and never sent. Refusing is safe: a
 * frontseat that hears no request for its timeout takes the vehicle back and
 * flies its own mission (docs/frontseat.md). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "frontseat/frontseat.h"

static void note(char *clamped, size_t clen, const char *what)
{
    if (!clen)
        return;
    size_t used = strlen(clamped);
    snprintf(clamped + used, clen - used, "%s%s", used ? ", " : "", what);
}

const char *fs_setpoint_request(const auv_setpoint_t *sp, const fs_limits *lim, double nav_depth_m,
                                double nav_altitude_m, fs_request *rq, char *clamped, size_t clen)
{
    if (clen)
        clamped[0] = '\0';
    if (sp->utime <= 0)
        return "setpoint without a time";
    if (!isfinite(sp->heading_rad))
        return "heading not a number";

    double depth;
    switch (sp->vertical_mode) {
    case AUV_SETPOINT_T_VERTICAL_DEPTH:
        if (!isfinite(sp->depth_m))
            return "depth not a number";
        depth = sp->depth_m;
        break;
    case AUV_SETPOINT_T_VERTICAL_ALTITUDE:
        /* the frontseat holds a depth: the depth that puts the vehicle at the
         * altitude asked for over the seabed under it now */
        if (!isfinite(sp->altitude_m))
            return "altitude not a number";
        if (!isfinite(nav_depth_m) || !isfinite(nav_altitude_m) || nav_altitude_m < 0.0)
            return "altitude setpoint without an altitude";
        depth = nav_depth_m + nav_altitude_m - sp->altitude_m;
        break;
    case AUV_SETPOINT_T_VERTICAL_PITCH:
        return "pitch setpoint (the frontseat holds a depth)";
    default:
        return "unknown vertical mode";
    }

    double speed;
    switch (sp->speed_mode) {
    case AUV_SETPOINT_T_SPEED_MPS:
        if (!isfinite(sp->speed_mps))
            return "speed not a number";
        speed = sp->speed_mps;
        break;
    case AUV_SETPOINT_T_SPEED_RPM:
        return "rpm setpoint (the frontseat holds a speed)";
    default:
        return "unknown speed mode";
    }
    /* slower than the frontseat can fly is not made faster: refused */
    if (speed < lim->min_speed_mps)
        return "speed under the minimum";
    if (speed > lim->max_speed_mps) {
        speed = lim->max_speed_mps;
        note(clamped, clen, "speed over the maximum");
    }
    if (depth > lim->max_depth_m) {
        depth = lim->max_depth_m;
        note(clamped, clen, "depth over the maximum");
    }
    if (depth < 0.0) {
        depth = 0.0;
        note(clamped, clen, "depth above the surface");
    }
    double h = fmod(sp->heading_rad * 180.0 / M_PI, 360.0);
    if (h < 0.0)
        h += 360.0;
    /* the wire carries tenths of a degree in 0 .. 359.9: 359.96 is written 0.0,
     * never 360.0, which is no heading of the range */
    h = round(h * 10.0) / 10.0;
    if (h >= 360.0) /* also fmod of -tiny + 360 */
        h = 0.0;
    rq->heading_deg = h;
    rq->depth_m = depth;
    rq->speed_mps = speed;
    return NULL;
}
