/* team_status: queue this vehicle's status for the link (`do team_status()
 * every 20 s`). The frame carries the newest status only; the state code is
 * the one the team behaviors set (survey, takeover, reacquire, done) unless
 * the plan gives one: `team_status(code = 5)` in an abort state tells the
 * team this vehicle gave up, so they take its lines over at once. */
#include "tm_behaviors.h"
#include "tm_store.h"

#include "plugins/lib/pu_angle.h"

const chasm_param_spec tm_status_params[STATUS_NPARAMS] = {
    [STATUS_CODE] = CHASM_PARAM_INT_RANGE("code", -1, -1, 7,
                                          "state code to send (-1: as the team behaviors set it; 5 = abort)"),
    [STATUS_NORTH] = CHASM_READ("north", CHASM_DOUBLE, "m", "nav.north_m", "own position north"),
    [STATUS_EAST] = CHASM_READ("east", CHASM_DOUBLE, "m", "nav.east_m", "own position east"),
    [STATUS_DEPTH] = CHASM_READ("depth", CHASM_DOUBLE, "m", "nav.depth_m", "own depth"),
    [STATUS_HEADING] = CHASM_READ("heading", CHASM_DOUBLE, "rad", "nav.heading_rad", "own heading"),
    [STATUS_SPEED] = CHASM_READ("speed", CHASM_DOUBLE, "m/s", "nav.speed_over_ground_mps", "own speed over ground"),
};
_Static_assert(CHASM_COUNT(tm_status_params) == STATUS_NPARAMS, "team_status schema and slots disagree");

int tm_status_start(chasm_ctx *c, void *state)
{
    (void)state;
    return tm_store_for(c, "team_status") ? 0 : -1;
}

chasm_status_code tm_status_step(chasm_ctx *c, void *state)
{
    (void)state;
    tm_store *s = tm_store_get();
    s->own = (tm_track){chasm_read_double(c, STATUS_NORTH), chasm_read_double(c, STATUS_EAST),
                        pu_wrap_2pi(chasm_read_double(c, STATUS_HEADING)), chasm_read_double(c, STATUS_SPEED)};
    s->own_depth = chasm_read_double(c, STATUS_DEPTH);
    s->t_own = (double)c->now_us * 1e-6;
    int64_t code = chasm_param_int(c, STATUS_CODE);
    s->status_state = code >= 0 ? (int)code : s->state;
    tm_outbox_status(&s->out);
    return CHASM_RUNNING;
}
