/* loiter: station keeping on a circle around a point (gd_circle_heading):
 * from far away the vehicle heads for the centre, then it runs along the
 * circle, clockwise unless told otherwise. Never done. */
#include "gd_behaviors.h"
#include "gd_slots.h"

const chasm_param_spec gd_loiter_params[] = {
    GD_COORD("north", "centre, north"),
    GD_COORD("east", "centre, east"),
    {"radius", CHASM_PARAM, CHASM_DOUBLE, "m", 1, 0, NULL, 1, 5, 10000, "circle radius (above the turning radius)"},
    GD_SPEED_PARAM,
    {"clockwise", CHASM_PARAM, CHASM_BOOL, "", 0, 1, NULL, 0, 0, 0, "direction seen from above"},
    GD_LOOKAHEAD_PARAM,
    GD_IN_NORTH, GD_IN_EAST, GD_OUT_HEADING, GD_OUT_SPEED, GD_OUT_SPEED_MODE,
};
_Static_assert(CHASM_COUNT(gd_loiter_params) == LOITER_NPARAMS, "loiter schema and slots disagree");

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
