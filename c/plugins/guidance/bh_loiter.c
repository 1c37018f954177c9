/* loiter: station keeping on a circle around a point (gd_circle_heading):
 * from far away the vehicle heads for the centre, then it runs along the
 * circle, clockwise unless told otherwise. Never done. */
#include "gd_behaviors.h"
#include "gd_slots.h"

const chasm_param_spec gd_loiter_params[LOITER_NPARAMS] = {
    [LOITER_NORTH] = GD_COORD("north", "centre, north"),
    [LOITER_EAST] = GD_COORD("east", "centre, east"),
    [LOITER_RADIUS] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("radius", "m", 5, 10000,
                                                        "circle radius (above the turning radius)"),
    [LOITER_SPEED] = GD_SPEED_PARAM,
    [LOITER_CLOCKWISE] = CHASM_PARAM_BOOL("clockwise", 1, "direction seen from above"),
    [LOITER_LOOKAHEAD] = GD_LOOKAHEAD_PARAM,
    GD_HORIZONTAL_SLOTS(LOITER),
};

static const gd_horizontal slots = {LOITER_IN_NORTH, LOITER_IN_EAST, LOITER_SPEED, LOITER_OUT_HEADING,
                                    LOITER_OUT_SPEED, LOITER_OUT_SPEED_MODE};

chasm_status_code gd_loiter_step(chasm_ctx *c, void *state)
{
    (void)state;
    gd_point centre = {chasm_param_double(c, LOITER_NORTH), chasm_param_double(c, LOITER_EAST)};
    gd_command(c, &slots, gd_circle_heading(centre, chasm_param_double(c, LOITER_RADIUS),
                                            chasm_param_bool(c, LOITER_CLOCKWISE),
                                            chasm_param_double(c, LOITER_LOOKAHEAD), gd_position(c, &slots)));
    return CHASM_RUNNING;
}

int gd_loiter_start(chasm_ctx *c, void *state)
{
    gd_loiter_step(c, state);
    return 0;
}
