/* goto and track: integral line-of-sight guidance along a straight line
 * (gd_geometry.h). goto flies the line from where the vehicle is at entry to
 * the waypoint, so a current or a disturbance is corrected back onto that line
 * instead of curving the approach; track flies a given line. */
#include <math.h>

#include "gd_behaviors.h"
#include "gd_slots.h"

const chasm_param_spec gd_goto_params[GOTO_NPARAMS] = {
    [GOTO_NORTH] = GD_COORD("north", "waypoint north"),
    [GOTO_EAST] = GD_COORD("east", "waypoint east"),
    [GOTO_SPEED] = GD_SPEED_PARAM,
    [GOTO_RADIUS] = CHASM_PARAM_DOUBLE_RANGE("radius", "m", 5, 0.5, 1000, "done within this distance"),
    [GOTO_LOOKAHEAD] = GD_LOOKAHEAD_PARAM,
    [GOTO_INTEGRAL] = GD_INTEGRAL_PARAM,
    GD_HORIZONTAL_SLOTS(GOTO),
};

const chasm_param_spec gd_track_params[TRACK_NPARAMS] = {
    [TRACK_FROM_NORTH] = GD_COORD("from_north", "start of the line, north"),
    [TRACK_FROM_EAST] = GD_COORD("from_east", "start of the line, east"),
    [TRACK_TO_NORTH] = GD_COORD("to_north", "end of the line, north"),
    [TRACK_TO_EAST] = GD_COORD("to_east", "end of the line, east"),
    [TRACK_SPEED] = GD_SPEED_PARAM,
    [TRACK_LOOKAHEAD] = GD_LOOKAHEAD_PARAM,
    [TRACK_INTEGRAL] = GD_INTEGRAL_PARAM,
    GD_HORIZONTAL_SLOTS(TRACK),
};

static const gd_horizontal goto_slots = {GOTO_IN_NORTH, GOTO_IN_EAST, GOTO_SPEED,
                                         GOTO_OUT_HEADING, GOTO_OUT_SPEED, GOTO_OUT_SPEED_MODE};
static const gd_horizontal track_slots = {TRACK_IN_NORTH, TRACK_IN_EAST, TRACK_SPEED,
                                          TRACK_OUT_HEADING, TRACK_OUT_SPEED, TRACK_OUT_SPEED_MODE};

/* One guidance cycle on s->line; returns the along-track position. */
static double steer(chasm_ctx *c, gd_los_state *s, const gd_horizontal *h)
{
    double along;
    gd_command(c, h, gd_los_heading(&s->los, &s->line, gd_position(c, h), c->dt_s, &along, NULL));
    return along;
}

int gd_goto_start(chasm_ctx *c, void *state)
{
    gd_los_state *s = state;
    gd_point target = {chasm_param_double(c, GOTO_NORTH), chasm_param_double(c, GOTO_EAST)};
    gd_line_make(&s->line, gd_position(c, &goto_slots), target);
    s->los = (gd_los){chasm_param_double(c, GOTO_LOOKAHEAD), chasm_param_double(c, GOTO_INTEGRAL), 0.0};
    steer(c, s, &goto_slots);
    return 0;
}

chasm_status_code gd_goto_step(chasm_ctx *c, void *state)
{
    gd_los_state *s = state;
    gd_point p = gd_position(c, &goto_slots);
    if (hypot(p.n - s->line.b.n, p.e - s->line.b.e) <= chasm_param_double(c, GOTO_RADIUS))
        return CHASM_DONE;
    if (s->line.length < 1e-6) /* started on the waypoint but outside the radius: aim at it */
        gd_line_make(&s->line, p, s->line.b);
    steer(c, s, &goto_slots);
    return CHASM_RUNNING;
}

int gd_track_start(chasm_ctx *c, void *state)
{
    gd_los_state *s = state;
    gd_line_make(&s->line, (gd_point){chasm_param_double(c, TRACK_FROM_NORTH), chasm_param_double(c, TRACK_FROM_EAST)},
                 (gd_point){chasm_param_double(c, TRACK_TO_NORTH), chasm_param_double(c, TRACK_TO_EAST)});
    s->los = (gd_los){chasm_param_double(c, TRACK_LOOKAHEAD), chasm_param_double(c, TRACK_INTEGRAL), 0.0};
    steer(c, s, &track_slots);
    return 0;
}

chasm_status_code gd_track_step(chasm_ctx *c, void *state)
{
    gd_los_state *s = state;
    double along = steer(c, s, &track_slots);
    return along >= s->line.length ? CHASM_DONE : CHASM_RUNNING;
}
