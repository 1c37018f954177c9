/* depth_within, altitude_within, heading_within, pitch_within and near:
 * |measured - value| <= tolerance (angles the short way round), and the
 * distance to a point. A measurement that is not a number (or an unknown
 * altitude, which the navigation reports as negative) never satisfies them. */
#include <math.h>

#include "plugins/checks/checks.h"
#include "plugins/lib/pu_angle.h"

/* The one schema of the four, for a quantity `what` read from var. */
#define WITHIN_SPECS(var, unit, what, maxval, maxtol)                                                         \
    {                                                                                                          \
        [WITHIN_MEASURED] = CHASM_READ("measured", CHASM_DOUBLE, unit, var, "the " what " compared"),          \
        [WITHIN_VALUE] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("value", unit, -(maxval), maxval,                   \
                                                           "the " what " wanted"),                             \
        [WITHIN_TOLERANCE] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("tolerance", unit, 0, maxtol,                   \
                                                               "largest difference"),                          \
    }

const chasm_param_spec checks_depth_within_params[WITHIN_NPARAMS] =
    WITHIN_SPECS("nav.depth_m", "m", "depth", 11000, 11000);
const chasm_param_spec checks_altitude_within_params[WITHIN_NPARAMS] =
    WITHIN_SPECS("nav.altitude_m", "m", "altitude", 11000, 11000);
const chasm_param_spec checks_heading_within_params[WITHIN_NPARAMS] =
    WITHIN_SPECS("nav.heading_rad", "rad", "heading", 2 * PU_PI, PU_PI);
const chasm_param_spec checks_pitch_within_params[WITHIN_NPARAMS] =
    WITHIN_SPECS("nav.pitch_rad", "rad", "pitch", PU_PI / 2, PU_PI);

static int within(const chasm_ctx *c, double diff) { return fabs(diff) <= chasm_param_double(c, WITHIN_TOLERANCE); }

static int plain(chasm_ctx *c)
{
    return within(c, chasm_read_double(c, WITHIN_MEASURED) - chasm_param_double(c, WITHIN_VALUE));
}
int checks_depth_within_evaluate(chasm_ctx *c) { return plain(c); }
int checks_pitch_within_evaluate(chasm_ctx *c) { return plain(c); }

int checks_altitude_within_evaluate(chasm_ctx *c)
{
    double a = chasm_read_double(c, WITHIN_MEASURED);
    return a >= 0.0 && within(c, a - chasm_param_double(c, WITHIN_VALUE));
}

int checks_heading_within_evaluate(chasm_ctx *c)
{
    return within(c, pu_angle_diff(chasm_read_double(c, WITHIN_MEASURED), chasm_param_double(c, WITHIN_VALUE)));
}

/* ------------------------------------------------------------------ near */

const chasm_param_spec checks_near_params[N_NPARAMS] = {
    [N_NORTH] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("north", "m", -1e7, 1e7, "the point, north of the origin"),
    [N_EAST] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("east", "m", -1e7, 1e7, "the point, east of the origin"),
    [N_AT_NORTH] = CHASM_READ("at_north", CHASM_DOUBLE, "m", "nav.north_m", "vehicle position, north"),
    [N_AT_EAST] = CHASM_READ("at_east", CHASM_DOUBLE, "m", "nav.east_m", "vehicle position, east"),
    [N_RADIUS] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("radius", "m", 0, 1e7, "largest horizontal distance"),
};

int checks_near_evaluate(chasm_ctx *c)
{
    double dn = chasm_read_double(c, N_AT_NORTH) - chasm_param_double(c, N_NORTH);
    double de = chasm_read_double(c, N_AT_EAST) - chasm_param_double(c, N_EAST);
    return hypot(dn, de) <= chasm_param_double(c, N_RADIUS);
}
