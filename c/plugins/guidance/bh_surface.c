/* surface, surface_fix, timer.
 *
 * surface and surface_fix stop the prop (or run it at `rpm`) and ask the pilot
 * for a bow-up pitch: the positively buoyant vehicle floats up, and with the
 * prop turning the pitch drives it up. surface with a `speed` asks instead for
 * a depth of 0 m at that speed: a commercial vehicle's frontseat, flown from
 * its backseat (docs/frontseat.md), holds depths and speeds, never a pitch or
 * an rpm. surface is done above `depth`;
 * surface_fix stays at the surface until a GPS fix newer than the state's
 * entry arrives (done) or `timeout` passes (failed, for `when failed`). */
#include <math.h>

#include "gd_behaviors.h"
#include "gd_slots.h"

#define RPM_TO_RADPS (2.0 * M_PI / 60.0)
#define PITCH_PARAM \
    CHASM_PARAM_DOUBLE_RANGE("pitch", "rad", 10 * M_PI / 180, 0, 45 * M_PI / 180, "bow-up pitch asked of the pilot")
#define RPM_PARAM \
    CHASM_PARAM_DOUBLE_RANGE("rpm", "rad/s", 0, 0, 3000 * RPM_TO_RADPS, "prop speed on the way up (0: float up)")
#define FIX_TYPE_2D 2 /* auv.gps_fix_t.FIX_2D */

const chasm_param_spec gd_surface_params[SURF_NPARAMS] = {
    [SURF_PITCH] = PITCH_PARAM,
    [SURF_RPM] = RPM_PARAM,
    [SURF_DEPTH] = CHASM_PARAM_DOUBLE_RANGE("depth", "m", 0.5, 0.1, 10, "done when shallower than this"),
    [SURF_SPEED] = CHASM_PARAM_DOUBLE_RANGE("speed", "m/s", 0, 0, 5.0,
                                            "> 0: ask a depth of 0 m at this speed (a frontseat), not pitch and rpm"),
    [SURF_IN_DEPTH] = GD_IN_DEPTH,
    [SURF_OUT_VERTICAL_MODE] = GD_OUT_VERTICAL_MODE,
    [SURF_OUT_PITCH] = GD_OUT_PITCH,
    [SURF_OUT_SPEED_MODE] = GD_OUT_SPEED_MODE,
    [SURF_OUT_RPM] = GD_OUT_RPM,
    [SURF_OUT_DEPTH] = GD_OUT_DEPTH,
    [SURF_OUT_SPEED] = GD_OUT_SPEED,
};

const chasm_param_spec gd_surface_fix_params[FIX_NPARAMS] = {
    [FIX_TIMEOUT] = CHASM_PARAM_DOUBLE_RANGE("timeout", "s", 180, 1, 86400, "failed without a fix for this long"),
    [FIX_PITCH] = PITCH_PARAM,
    [FIX_RPM] = RPM_PARAM,
    [FIX_IN_GPS] = CHASM_READ("in_gps", CHASM_INT, "", "gps.fix_type", "GPS fix type (2: 2D, 3: 3D)"),
    [FIX_OUT_VERTICAL_MODE] = GD_OUT_VERTICAL_MODE,
    [FIX_OUT_PITCH] = GD_OUT_PITCH,
    [FIX_OUT_SPEED_MODE] = GD_OUT_SPEED_MODE,
    [FIX_OUT_RPM] = GD_OUT_RPM,
};

const chasm_param_spec gd_timer_params[TIMER_NPARAMS] = {
    [TIMER_DURATION] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("duration", "s", 0, 1e7, "done after this long in the state"),
};

/* Both schemas list the four outputs in this order, from out_vertical_mode on. */
_Static_assert(SURF_OUT_RPM - SURF_OUT_VERTICAL_MODE == 3 && SURF_OUT_PITCH == SURF_OUT_VERTICAL_MODE + 1 &&
                   SURF_OUT_SPEED_MODE == SURF_OUT_VERTICAL_MODE + 2,
               "surface outputs out of order");
_Static_assert(FIX_OUT_RPM - FIX_OUT_VERTICAL_MODE == 3 && FIX_OUT_PITCH == FIX_OUT_VERTICAL_MODE + 1 &&
                   FIX_OUT_SPEED_MODE == FIX_OUT_VERTICAL_MODE + 2,
               "surface_fix outputs out of order");
static void float_up(chasm_ctx *c, int pitch, int rpm, int out_vertical_mode)
{
    chasm_write_int(c, out_vertical_mode, GD_VERTICAL_PITCH);
    chasm_write_double(c, out_vertical_mode + 1, chasm_param_double(c, pitch));
    chasm_write_int(c, out_vertical_mode + 2, GD_SPEED_RPM);
    chasm_write_double(c, out_vertical_mode + 3, chasm_param_double(c, rpm) / RPM_TO_RADPS);
}

/* surface: floated up (pitch, rpm), or driven up to a depth of 0 m at `speed` */
static void surface_out(chasm_ctx *c)
{
    double speed = chasm_param_double(c, SURF_SPEED);
    if (speed <= 0.0) {
        float_up(c, SURF_PITCH, SURF_RPM, SURF_OUT_VERTICAL_MODE);
        return;
    }
    chasm_write_int(c, SURF_OUT_VERTICAL_MODE, GD_VERTICAL_DEPTH);
    chasm_write_double(c, SURF_OUT_DEPTH, 0.0);
    chasm_write_int(c, SURF_OUT_SPEED_MODE, GD_SPEED_MPS);
    chasm_write_double(c, SURF_OUT_SPEED, speed);
}

int gd_surface_start(chasm_ctx *c, void *state)
{
    (void)state;
    surface_out(c);
    return 0;
}

chasm_status_code gd_surface_step(chasm_ctx *c, void *state)
{
    (void)state;
    surface_out(c);
    return chasm_read_double(c, SURF_IN_DEPTH) < chasm_param_double(c, SURF_DEPTH) ? CHASM_DONE : CHASM_RUNNING;
}

int gd_surface_fix_start(chasm_ctx *c, void *state)
{
    (void)state;
    float_up(c, FIX_PITCH, FIX_RPM, FIX_OUT_VERTICAL_MODE);
    return 0;
}

chasm_status_code gd_surface_fix_step(chasm_ctx *c, void *state)
{
    (void)state;
    float_up(c, FIX_PITCH, FIX_RPM, FIX_OUT_VERTICAL_MODE);
    /* A fix is new if its time of validity (the variable's age comes from the
     * message's utime) is after the state was entered. */
    if (chasm_age_s(c, FIX_IN_GPS) < c->time_in_state_s && chasm_read_int(c, FIX_IN_GPS) >= FIX_TYPE_2D)
        return CHASM_DONE;
    if (c->time_in_state_s >= chasm_param_double(c, FIX_TIMEOUT)) {
        chasm_log(c, "surface_fix: no GPS fix before the timeout");
        return CHASM_FAILED;
    }
    return CHASM_RUNNING;
}

int gd_timer_start(chasm_ctx *c, void *state)
{
    (void)c;
    (void)state;
    return 0;
}

chasm_status_code gd_timer_step(chasm_ctx *c, void *state)
{
    (void)state;
    return c->time_in_state_s >= chasm_param_double(c, TIMER_DURATION) ? CHASM_DONE : CHASM_RUNNING;
}
