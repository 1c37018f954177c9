/* hold_depth, hold_altitude, hold_heading, set_speed: constant setpoints for
 * the pilot, written at entry and every cycle (never done). They combine in
 * one state with a behavior for the other axes, e.g. track + hold_altitude. */
#include <math.h>

#include "gd_behaviors.h"
#include "gd_slots.h"
#include "plugins/lib/pu_angle.h"

#define RPM_TO_RADPS (2.0 * M_PI / 60.0)

const chasm_param_spec gd_hold_depth_params[] = {
    {"depth", CHASM_PARAM, CHASM_DOUBLE, "m", 1, 0, NULL, 1, 0, 6000, "depth to hold"},
    GD_OUT_VERTICAL_MODE, GD_OUT_DEPTH,
};
_Static_assert(CHASM_COUNT(gd_hold_depth_params) == HDEPTH_NPARAMS, "hold_depth schema and slots disagree");

const chasm_param_spec gd_hold_altitude_params[] = {
    {"altitude", CHASM_PARAM, CHASM_DOUBLE, "m", 1, 0, NULL, 1, 0.5, 1000, "height above the seabed to hold"},
    GD_OUT_VERTICAL_MODE, GD_OUT_ALTITUDE,
};
_Static_assert(CHASM_COUNT(gd_hold_altitude_params) == HALT_NPARAMS, "hold_altitude schema and slots disagree");

const chasm_param_spec gd_hold_heading_params[] = {
    {"heading", CHASM_PARAM, CHASM_DOUBLE, "rad", 1, 0, NULL, 1, -2 * M_PI, 2 * M_PI, "heading to hold"},
    GD_OUT_HEADING,
};
_Static_assert(CHASM_COUNT(gd_hold_heading_params) == HHEAD_NPARAMS, "hold_heading schema and slots disagree");

const chasm_param_spec gd_set_speed_params[] = {
    {"speed", CHASM_PARAM, CHASM_DOUBLE, "m/s", 0, GD_ABSENT, NULL, 1, 0, 5, "speed through the water (or rpm)"},
    {"rpm", CHASM_PARAM, CHASM_DOUBLE, "rad/s", 0, GD_ABSENT, NULL, 1, 0, 3000 * RPM_TO_RADPS,
     "open-loop propeller speed, e.g. 1200 rpm (or speed)"},
    GD_OUT_SPEED_MODE, GD_OUT_SPEED, GD_OUT_RPM,
};
_Static_assert(CHASM_COUNT(gd_set_speed_params) == SPEED_NPARAMS, "set_speed schema and slots disagree");

/* A behavior that writes its setpoints at entry and every cycle, never done. */
#define CONSTANT_SETPOINT(id, write)                              \
    int gd_##id##_start(chasm_ctx *c, void *state)                \
    {                                                             \
        (void)state;                                              \
        write(c);                                                 \
        return 0;                                                 \
    }                                                             \
    chasm_status_code gd_##id##_step(chasm_ctx *c, void *state)   \
    {                                                             \
        (void)state;                                              \
        write(c);                                                 \
        return CHASM_RUNNING;                                     \
    }

static void write_depth(chasm_ctx *c)
{
    chasm_write_int(c, HDEPTH_OUT_VERTICAL_MODE, GD_VERTICAL_DEPTH);
    chasm_write_double(c, HDEPTH_OUT_DEPTH, chasm_param_double(c, HDEPTH_DEPTH));
}
CONSTANT_SETPOINT(hold_depth, write_depth)

static void write_altitude(chasm_ctx *c)
{
    chasm_write_int(c, HALT_OUT_VERTICAL_MODE, GD_VERTICAL_ALTITUDE);
    chasm_write_double(c, HALT_OUT_ALTITUDE, chasm_param_double(c, HALT_ALTITUDE));
}
CONSTANT_SETPOINT(hold_altitude, write_altitude)

static void write_heading(chasm_ctx *c)
{
    chasm_write_double(c, HHEAD_OUT_HEADING, pu_wrap_2pi(chasm_param_double(c, HHEAD_HEADING)));
}
CONSTANT_SETPOINT(hold_heading, write_heading)

static void write_speed(chasm_ctx *c)
{
    if (GD_GIVEN(c, SPEED_SPEED)) {
        chasm_write_int(c, SPEED_OUT_SPEED_MODE, GD_SPEED_MPS);
        chasm_write_double(c, SPEED_OUT_SPEED, chasm_param_double(c, SPEED_SPEED));
    } else {
        chasm_write_int(c, SPEED_OUT_SPEED_MODE, GD_SPEED_RPM);
        chasm_write_double(c, SPEED_OUT_RPM, chasm_param_double(c, SPEED_RPM) / RPM_TO_RADPS);
    }
}
int gd_set_speed_start(chasm_ctx *c, void *state)
{
    (void)state;
    if (GD_GIVEN(c, SPEED_SPEED) == GD_GIVEN(c, SPEED_RPM))
        return gd_refuse(c, "set_speed", "give either speed (m/s) or rpm, not %s",
                         GD_GIVEN(c, SPEED_SPEED) ? "both" : "neither");
    write_speed(c);
    return 0;
}
chasm_status_code gd_set_speed_step(chasm_ctx *c, void *state)
{
    (void)state;
    write_speed(c);
    return CHASM_RUNNING;
}
