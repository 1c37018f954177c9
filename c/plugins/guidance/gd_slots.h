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

/* Entries of the schemas, indexed by each behavior's slots (gd_behaviors.h):
 * `[GOTO_IN_NORTH] = GD_IN_NORTH`. */
#define GD_IN_NORTH CHASM_READ("in_north", CHASM_DOUBLE, "m", "nav.north_m", "vehicle north position")
#define GD_IN_EAST CHASM_READ("in_east", CHASM_DOUBLE, "m", "nav.east_m", "vehicle east position")
#define GD_IN_DEPTH CHASM_READ("in_depth", CHASM_DOUBLE, "m", "nav.depth_m", "vehicle depth")
#define GD_IN_ALTITUDE \
    CHASM_READ("in_altitude", CHASM_DOUBLE, "m", "nav.altitude_m", "height above the seabed (< 0: unknown)")
#define GD_IN_SPEED CHASM_READ("in_speed", CHASM_DOUBLE, "m/s", "nav.u_mps", "surge speed")

#define GD_OUT_HEADING CHASM_WRITE("out_heading", CHASM_DOUBLE, "rad", "setpoint.heading_rad", "heading setpoint")
#define GD_OUT_SPEED CHASM_WRITE("out_speed", CHASM_DOUBLE, "m/s", "setpoint.speed_mps", "speed setpoint")
#define GD_OUT_SPEED_MODE CHASM_WRITE("out_speed_mode", CHASM_INT, "", "setpoint.speed_mode", "0 m/s, 1 rpm")
#define GD_OUT_RPM CHASM_WRITE("out_rpm", CHASM_DOUBLE, "", "setpoint.prop_rpm", "prop rpm setpoint")
#define GD_OUT_VERTICAL_MODE \
    CHASM_WRITE("out_vertical_mode", CHASM_INT, "", "setpoint.vertical_mode", "0 depth, 1 altitude, 2 pitch")
#define GD_OUT_DEPTH CHASM_WRITE("out_depth", CHASM_DOUBLE, "m", "setpoint.depth_m", "depth setpoint")
#define GD_OUT_ALTITUDE CHASM_WRITE("out_altitude", CHASM_DOUBLE, "m", "setpoint.altitude_m", "altitude setpoint")
#define GD_OUT_PITCH CHASM_WRITE("out_pitch", CHASM_DOUBLE, "rad", "setpoint.pitch_rad", "pitch setpoint")

/* The position inputs and steering outputs of a behavior whose slots are
 * named PREFIX_IN_NORTH ... PREFIX_OUT_SPEED_MODE (gd_horizontal below). */
#define GD_HORIZONTAL_SLOTS(P)                                                                                  \
    [P##_IN_NORTH] = GD_IN_NORTH, [P##_IN_EAST] = GD_IN_EAST, [P##_OUT_HEADING] = GD_OUT_HEADING,               \
    [P##_OUT_SPEED] = GD_OUT_SPEED, [P##_OUT_SPEED_MODE] = GD_OUT_SPEED_MODE

/* A speed parameter common to the horizontal behaviors. */
#define GD_SPEED_PARAM CHASM_PARAM_DOUBLE_RANGE("speed", "m/s", 1.5, 0.1, 5.0, "speed through the water")
/* A required north or east coordinate. */
#define GD_COORD(name, doc) CHASM_PARAM_REQUIRED_DOUBLE_RANGE(name, "m", -1e6, 1e6, doc)
/* Line-of-sight tuning (gd_geometry.h), common to the behaviors that steer. */
#define GD_LOOKAHEAD_PARAM                                                    \
    CHASM_PARAM_DOUBLE_RANGE("lookahead", "m", 10, 1, 500,                     \
                             "LOS lookahead distance: larger is smoother, slower to converge")
#define GD_INTEGRAL_PARAM                                                     \
    CHASM_PARAM_DOUBLE_RANGE("integral", "Hz", 0.04, 0, 1,                     \
                             "ILOS integral rate: removes the cross-track offset of a cross current (0: plain LOS)")
/* Parameters that belong to one of two forms (a box or a polygon, depths or
 * altitudes) are CHASM_PARAM_OPTIONAL_RANGE: no default, and
 * chasm_param_given() tells which form the plan chose. */

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
