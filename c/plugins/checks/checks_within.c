/* depth_within, altitude_within, heading_within, pitch_within and near:
 * |measured - value| <= tolerance (angles the short way round), and the
 * distance to a point. A measurement that is not a number (or an unknown
 * altitude, which the navigation reports as negative) never satisfies them. */
#include <math.h>

#include "plugins/checks/checks.h"
#include "plugins/lib/pu_angle.h"

enum { MEASURED, VALUE, TOLERANCE, WITHIN_NPARAMS };

/* The one schema of the four, for a quantity `what` read from var. */
#define WITHIN_SPECS(var, unit, what, maxval, maxtol)                                                         \
    {                                                                                                          \
        [MEASURED] = CHASM_READ("measured", CHASM_DOUBLE, unit, var, "the " what " compared"),                 \
        [VALUE] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("value", unit, -(maxval), maxval, "the " what " wanted"),  \
        [TOLERANCE] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("tolerance", unit, 0, maxtol, "largest difference"),   \
    }

static const chasm_param_spec depth_params[] = WITHIN_SPECS("nav.depth_m", "m", "depth", 11000, 11000);
static const chasm_param_spec altitude_params[] = WITHIN_SPECS("nav.altitude_m", "m", "altitude", 11000, 11000);
static const chasm_param_spec heading_params[] = WITHIN_SPECS("nav.heading_rad", "rad", "heading", 2 * PU_PI, PU_PI);
static const chasm_param_spec pitch_params[] = WITHIN_SPECS("nav.pitch_rad", "rad", "pitch", PU_PI / 2, PU_PI);

static int within(const chasm_ctx *c, double diff) { return fabs(diff) <= chasm_param_double(c, TOLERANCE); }

static int depth_eval(chasm_ctx *c) { return within(c, chasm_read_double(c, MEASURED) - chasm_param_double(c, VALUE)); }
static int pitch_eval(chasm_ctx *c) { return within(c, chasm_read_double(c, MEASURED) - chasm_param_double(c, VALUE)); }

static int altitude_eval(chasm_ctx *c)
{
    double a = chasm_read_double(c, MEASURED);
    return a >= 0.0 && within(c, a - chasm_param_double(c, VALUE));
}

static int heading_eval(chasm_ctx *c)
{
    return within(c, pu_angle_diff(chasm_read_double(c, MEASURED), chasm_param_double(c, VALUE)));
}

const chasm_test_spec checks_depth_within = {"depth_within", "depth within tolerance of value", depth_params,
                                             CHASM_COUNT(depth_params), depth_eval};
const chasm_test_spec checks_altitude_within = {"altitude_within",
                                                "altitude within tolerance of value (false while unknown)",
                                                altitude_params, CHASM_COUNT(altitude_params), altitude_eval};
const chasm_test_spec checks_heading_within = {"heading_within",
                                               "heading within tolerance of value, the short way round",
                                               heading_params, CHASM_COUNT(heading_params), heading_eval};
const chasm_test_spec checks_pitch_within = {"pitch_within", "pitch within tolerance of value", pitch_params,
                                             CHASM_COUNT(pitch_params), pitch_eval};

/* ------------------------------------------------------------------ near */

enum { N_NORTH, N_EAST, N_AT_NORTH, N_AT_EAST, N_RADIUS, N_NPARAMS };

static const chasm_param_spec near_params[N_NPARAMS] = {
    [N_NORTH] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("north", "m", -1e7, 1e7, "the point, north of the origin"),
    [N_EAST] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("east", "m", -1e7, 1e7, "the point, east of the origin"),
    [N_AT_NORTH] = CHASM_READ("at_north", CHASM_DOUBLE, "m", "nav.north_m", "vehicle position, north"),
    [N_AT_EAST] = CHASM_READ("at_east", CHASM_DOUBLE, "m", "nav.east_m", "vehicle position, east"),
    [N_RADIUS] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("radius", "m", 0, 1e7, "largest horizontal distance"),
};

static int near_eval(chasm_ctx *c)
{
    double dn = chasm_read_double(c, N_AT_NORTH) - chasm_param_double(c, N_NORTH);
    double de = chasm_read_double(c, N_AT_EAST) - chasm_param_double(c, N_EAST);
    return hypot(dn, de) <= chasm_param_double(c, N_RADIUS);
}

const chasm_test_spec checks_near = {"near", "within radius of a point (horizontal distance)", near_params,
                                     CHASM_COUNT(near_params), near_eval};
