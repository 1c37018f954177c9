/* Schema entries shared by the guidance behaviors: the navigation variables
 * they read and the setpoint variables they write, each defaulting to the
 * field the navigator binding gives it (missions/bindings/navigator.bind), so
 * a plan normally passes only parameters. A plan may bind another variable:
 * `hold_depth(depth = 10 m, out_depth = my.depth)`. */
#ifndef GD_SLOTS_H
#define GD_SLOTS_H

#include <math.h>

#include "chasm/chasm_plugin.h"
#include "plugins/lib/gd_geometry.h"

/* auv.setpoint_t modes (lcmtypes/setpoint_t.lcm) */
enum { GD_VERTICAL_DEPTH = 0, GD_VERTICAL_ALTITUDE = 1, GD_VERTICAL_PITCH = 2 };
enum { GD_SPEED_MPS = 0, GD_SPEED_RPM = 1 };

#define GD_READS(name, unit, var, doc) {name, CHASM_READS, CHASM_DOUBLE, unit, 0, 0, var, 0, 0, 0, doc}
#define GD_WRITES(name, type, unit, var, doc) {name, CHASM_WRITES, type, unit, 0, 0, var, 0, 0, 0, doc}

#define GD_IN_NORTH GD_READS("in_north", "m", "nav.north_m", "vehicle north position")
#define GD_IN_EAST GD_READS("in_east", "m", "nav.east_m", "vehicle east position")
#define GD_IN_DEPTH GD_READS("in_depth", "m", "nav.depth_m", "vehicle depth")
#define GD_IN_ALTITUDE GD_READS("in_altitude", "m", "nav.altitude_m", "height above the seabed (< 0: unknown)")
#define GD_IN_SPEED GD_READS("in_speed", "m/s", "nav.u_mps", "surge speed")

#define GD_OUT_HEADING GD_WRITES("out_heading", CHASM_DOUBLE, "rad", "setpoint.heading_rad", "heading setpoint")
#define GD_OUT_SPEED GD_WRITES("out_speed", CHASM_DOUBLE, "m/s", "setpoint.speed_mps", "speed setpoint")
#define GD_OUT_SPEED_MODE GD_WRITES("out_speed_mode", CHASM_INT, "", "setpoint.speed_mode", "0 m/s, 1 rpm")
#define GD_OUT_RPM GD_WRITES("out_rpm", CHASM_DOUBLE, "", "setpoint.prop_rpm", "prop rpm setpoint")
#define GD_OUT_VERTICAL_MODE \
    GD_WRITES("out_vertical_mode", CHASM_INT, "", "setpoint.vertical_mode", "0 depth, 1 altitude, 2 pitch")
#define GD_OUT_DEPTH GD_WRITES("out_depth", CHASM_DOUBLE, "m", "setpoint.depth_m", "depth setpoint")
#define GD_OUT_ALTITUDE GD_WRITES("out_altitude", CHASM_DOUBLE, "m", "setpoint.altitude_m", "altitude setpoint")
#define GD_OUT_PITCH GD_WRITES("out_pitch", CHASM_DOUBLE, "rad", "setpoint.pitch_rad", "pitch setpoint")

/* A speed parameter common to the horizontal behaviors. */
#define GD_SPEED_PARAM {"speed", CHASM_PARAM, CHASM_DOUBLE, "m/s", 0, 1.5, NULL, 1, 0.1, 5.0, "speed through the water"}
/* A required north or east coordinate. */
#define GD_COORD(name, doc) {name, CHASM_PARAM, CHASM_DOUBLE, "m", 1, 0, NULL, 1, -1e6, 1e6, doc}
/* Line-of-sight tuning (gd_geometry.h), common to the behaviors that steer. */
#define GD_LOOKAHEAD_PARAM {"lookahead", CHASM_PARAM, CHASM_DOUBLE, "m", 0, 10, NULL, 1, 1, 500, \
                         "LOS lookahead distance: larger is smoother, slower to converge"}
#define GD_INTEGRAL_PARAM {"integral", CHASM_PARAM, CHASM_DOUBLE, "Hz", 0, 0.04, NULL, 1, 0, 1, \
                        "ILOS integral rate: removes the cross-track offset of a cross current (0: plain LOS)"}
/* Parameters that belong to one of two forms (a box or a polygon, depths or
 * altitudes) have no default: this value, outside every range, marks them
 * absent. (Not NaN: the engine also stores every default as an integer.) */
#define GD_ABSENT (-1e15)
#define GD_GIVEN(c, slot) (chasm_param_double(c, slot) != GD_ABSENT)

/* The slots of a behavior that steers: where it reads the position, its
 * speed parameter and where it writes heading, speed and speed mode. */
typedef struct {
    int in_north, in_east, speed, out_heading, out_speed, out_speed_mode;
} gd_horizontal;

PU_HIDDEN gd_point gd_position(const chasm_ctx *c, const gd_horizontal *h);
/* Writes the heading setpoint (wrapped to [0, 2pi)) and the speed in m/s. */
PU_HIDDEN void gd_command(chasm_ctx *c, const gd_horizontal *h, double heading);

/* Reports a parameter problem found at state entry (the loader checked each
 * value; this is for combinations) and makes start() fail. */
PU_HIDDEN int gd_refuse(chasm_ctx *c, const char *behavior, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

#endif
