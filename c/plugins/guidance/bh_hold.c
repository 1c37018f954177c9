/* hold_depth, hold_altitude, hold_heading, set_speed: constant setpoints for
 * the pilot, written at entry and every cycle (never done). They combine in
 * one state with a behavior for the other axes, e.g. track + hold_altitude. */
#include <math.h>

#include "gd_behaviors.h"
#include "gd_slots.h"
#include "plugins/lib/pu_angle.h"

#define RPM_TO_RADPS (2.0 * M_PI / 60.0)

const chasm_param_spec gd_hold_depth_params[HDEPTH_NPARAMS] = {
    [HDEPTH_DEPTH] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("depth", "m", 0, 6000, "depth to hold"),
    [HDEPTH_OUT_VERTICAL_MODE] = GD_OUT_VERTICAL_MODE,
    [HDEPTH_OUT_DEPTH] = GD_OUT_DEPTH,
};

const chasm_param_spec gd_hold_altitude_params[HALT_NPARAMS] = {
    [HALT_ALTITUDE] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("altitude", "m", 0.5, 1000, "height above the seabed to hold"),
    [HALT_OUT_VERTICAL_MODE] = GD_OUT_VERTICAL_MODE,
    [HALT_OUT_ALTITUDE] = GD_OUT_ALTITUDE,
};

const chasm_param_spec gd_hold_heading_params[HHEAD_NPARAMS] = {
    [HHEAD_HEADING] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("heading", "rad", -2 * M_PI, 2 * M_PI, "heading to hold"),
    [HHEAD_OUT_HEADING] = GD_OUT_HEADING,
};

/* speed or rpm: exactly one is given (set_speed's start says so otherwise). */
const chasm_param_spec gd_set_speed_params[SPEED_NPARAMS] = {
    [SPEED_SPEED] = CHASM_PARAM_OPTIONAL_RANGE("speed", CHASM_DOUBLE, "m/s", 0, 5, "speed through the water (or rpm)"),
    [SPEED_RPM] = CHASM_PARAM_OPTIONAL_RANGE("rpm", CHASM_DOUBLE, "rad/s", 0, 3000 * RPM_TO_RADPS,
                                             "open-loop propeller speed, e.g. 1200 rpm (or speed)"),
    [SPEED_OUT_SPEED_MODE] = GD_OUT_SPEED_MODE,
    [SPEED_OUT_SPEED] = GD_OUT_SPEED,
    [SPEED_OUT_RPM] = GD_OUT_RPM,
};

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
    if (chasm_param_given(c, SPEED_SPEED)) {
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
    if (chasm_param_given(c, SPEED_SPEED) == chasm_param_given(c, SPEED_RPM))
        return gd_refuse(c, "set_speed", "give either speed (m/s) or rpm, not %s",
                         chasm_param_given(c, SPEED_SPEED) ? "both" : "neither");
    write_speed(c);
    return 0;
}
chasm_status_code gd_set_speed_step(chasm_ctx *c, void *state)
{
    (void)state;
    write_speed(c);
    return CHASM_RUNNING;
}
