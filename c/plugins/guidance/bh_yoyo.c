/* yoyo: a vertical saw-tooth between two depths (or two altitudes) for
 * profiling sensors, while a horizontal behavior of the same state steers. The
 * depth (altitude) setpoint ramps between the limits at U sin(pitch), U the
 * measured surge speed, or at a given vertical `rate`, so the vehicle climbs
 * and dives at that flight-path angle (vertical speed) while the pilot's own
 * depth (altitude) loop keeps it on the ramp; the setpoint never leaves the
 * band. Over the last min(2 m, band / 4) before a limit the ramp slows down
 * (to a tenth), so the vehicle arrives with little vertical speed instead of
 * overshooting; at the limit the setpoint waits until the vehicle is within
 * min(0.5 m, band / 5) of it, then ramps back: every profile spans the whole
 * band. In the depth form an altitude `floor` turns a dive back up where the
 * seabed comes within it (the profile is cut short, never the seabed hit).
 * Each reversal is a profile completed, counted in `out_profiles` if the plan
 * binds it. Never done. */
#include <math.h>

#include "gd_behaviors.h"
#include "gd_slots.h"

/* A limit of the band: depths or altitudes are given, a pair of one form. */
#define BAND(name, lo, hi, doc) CHASM_PARAM_OPTIONAL_RANGE(name, CHASM_DOUBLE, "m", lo, hi, doc)
#define MIN_RAMP_SPEED 0.3 /* m/s: keeps the ramp moving while the vehicle is slow or stopped */
#define EASE_M 2.0          /* the ramp slows down over this distance before a limit ... */
#define MIN_EASE 0.1        /* ... to this fraction of its rate */

const chasm_param_spec gd_yoyo_params[YOYO_NPARAMS] = {
    [YOYO_MIN_DEPTH] = BAND("min_depth", 0, 6000, "shallow limit (depth form)"),
    [YOYO_MAX_DEPTH] = BAND("max_depth", 0, 6000, "deep limit (depth form)"),
    [YOYO_MIN_ALTITUDE] = BAND("min_altitude", 0.5, 1000, "low limit above the seabed (altitude form)"),
    [YOYO_MAX_ALTITUDE] = BAND("max_altitude", 0.5, 1000, "high limit above the seabed (altitude form)"),
    [YOYO_PITCH] = CHASM_PARAM_OPTIONAL_RANGE("pitch", CHASM_DOUBLE, "rad", 2 * M_PI / 180, 45 * M_PI / 180,
                                              "flight-path angle of the climbs and dives (or give rate)"),
    [YOYO_RATE] = CHASM_PARAM_OPTIONAL_RANGE("rate", CHASM_DOUBLE, "m/s", 0.02, 2.0,
                                             "vertical speed of the climbs and dives (or give pitch)"),
    [YOYO_FLOOR] = BAND("floor", 0.5, 1000,
                        "depth form: a dive turns back up where the altitude falls below this (unknown: no floor)"),
    [YOYO_IN_DEPTH] = GD_IN_DEPTH,
    [YOYO_IN_ALTITUDE] = GD_IN_ALTITUDE,
    [YOYO_IN_SPEED] = GD_IN_SPEED,
    [YOYO_OUT_VERTICAL_MODE] = GD_OUT_VERTICAL_MODE,
    [YOYO_OUT_DEPTH] = GD_OUT_DEPTH,
    [YOYO_OUT_ALTITUDE] = GD_OUT_ALTITUDE,
    [YOYO_OUT_PROFILES] = CHASM_WRITE("out_profiles", CHASM_INT, "", NULL,
                                      "dives and climbs completed (each reversal), if the plan binds a variable"),
};

/* The band coordinate of the vehicle: depth, or altitude (< 0: unknown). */
static double measured(const chasm_ctx *c, const gd_yoyo_state *s)
{
    return chasm_read_double(c, s->altitude_mode ? YOYO_IN_ALTITUDE : YOYO_IN_DEPTH);
}

static void write(chasm_ctx *c, const gd_yoyo_state *s)
{
    chasm_write_int(c, YOYO_OUT_VERTICAL_MODE, s->altitude_mode ? GD_VERTICAL_ALTITUDE : GD_VERTICAL_DEPTH);
    chasm_write_double(c, s->altitude_mode ? YOYO_OUT_ALTITUDE : YOYO_OUT_DEPTH, s->target);
    chasm_write_int(c, YOYO_OUT_PROFILES, s->profiles);
}

int gd_yoyo_start(chasm_ctx *c, void *state)
{
    gd_yoyo_state *s = state;
    int depths = chasm_param_given(c, YOYO_MIN_DEPTH) + chasm_param_given(c, YOYO_MAX_DEPTH);
    int alts = chasm_param_given(c, YOYO_MIN_ALTITUDE) + chasm_param_given(c, YOYO_MAX_ALTITUDE);
    if (!((depths == 2 && alts == 0) || (depths == 0 && alts == 2)))
        return gd_refuse(c, "yoyo", "give min_depth and max_depth, or min_altitude and max_altitude");
    if (chasm_param_given(c, YOYO_PITCH) == chasm_param_given(c, YOYO_RATE))
        return gd_refuse(c, "yoyo", "give either pitch (a flight-path angle) or rate (a vertical speed), not %s",
                         chasm_param_given(c, YOYO_PITCH) ? "both" : "neither");
    s->altitude_mode = alts == 2;
    if (s->altitude_mode && chasm_param_given(c, YOYO_FLOOR))
        return gd_refuse(c, "yoyo", "floor is for the depth form: the altitude form's min_altitude is its floor");
    int lo = s->altitude_mode ? YOYO_MIN_ALTITUDE : YOYO_MIN_DEPTH;
    s->lo = chasm_param_double(c, lo);
    s->hi = chasm_param_double(c, lo + 1);
    if (!(s->lo < s->hi))
        return gd_refuse(c, "yoyo", "the band is empty: the minimum %g m is not below the maximum %g m", s->lo,
                         s->hi);
    double z = measured(c, s);
    if (s->altitude_mode && z < 0.0)
        z = s->hi; /* altitude unknown (too high for the altimeter): start from the top */
    s->target = fmin(s->hi, fmax(s->lo, z));
    /* head for the farther limit first */
    int to_hi = z < 0.5 * (s->lo + s->hi);
    s->down = s->altitude_mode ? !to_hi : to_hi;
    s->profiles = 0;
    write(c, s);
    return 0;
}

/* The speed of the ramp [m/s]: the given rate, or the surge speed's share at the flight-path angle. */
static double ramp_rate(const chasm_ctx *c)
{
    if (chasm_param_given(c, YOYO_RATE))
        return chasm_param_double(c, YOYO_RATE);
    return fmax(MIN_RAMP_SPEED, chasm_read_double(c, YOYO_IN_SPEED)) * sin(chasm_param_double(c, YOYO_PITCH));
}

/* Depth form with a floor: diving, and the seabed is within the floor (a
 * known altitude below it). */
static int on_the_floor(const chasm_ctx *c, const gd_yoyo_state *s)
{
    if (s->altitude_mode || !s->down || !chasm_param_given(c, YOYO_FLOOR))
        return 0;
    double alt = chasm_read_double(c, YOYO_IN_ALTITUDE);
    return alt >= 0.0 && alt < chasm_param_double(c, YOYO_FLOOR);
}

chasm_status_code gd_yoyo_step(chasm_ctx *c, void *state)
{
    gd_yoyo_state *s = state;
    double z = measured(c, s);
    if (on_the_floor(c, s)) {
        /* the dive ends here: the setpoint comes back to the vehicle's depth (never
         * deeper), and the climb starts from it */
        s->target = fmax(s->lo, fmin(s->target, z));
        s->down = 0;
        s->profiles++;
        write(c, s);
        return CHASM_RUNNING;
    }
    /* in band coordinates, "up the band" is deeper in depth form, higher in altitude form */
    int up_band = s->altitude_mode ? !s->down : s->down;
    double limit = up_band ? s->hi : s->lo;
    /* slow down over the last `ease` metres: the vehicle arrives at the limit
     * with little vertical speed instead of overshooting it */
    double ease = fmin(EASE_M, 0.25 * (s->hi - s->lo));
    double step = ramp_rate(c) * fmax(MIN_EASE, fmin(1.0, fabs(limit - s->target) / ease)) * c->dt_s;
    s->target = up_band ? fmin(limit, s->target + step) : fmax(limit, s->target - step);
    double tol = fmin(0.5, 0.2 * (s->hi - s->lo));
    if (s->target == limit && fabs(z - limit) <= tol && !(s->altitude_mode && z < 0.0)) {
        s->down = !s->down;
        s->profiles++;
    }
    write(c, s);
    return CHASM_RUNNING;
}
