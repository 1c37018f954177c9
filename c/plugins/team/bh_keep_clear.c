/* keep_clear: deconfliction from peer statuses. Each teammate's last status
 * is dead-reckoned (course and speed since its time) and so is this vehicle;
 * if a teammate with a LOWER team index is predicted within `radius` within
 * `horizon` seconds, this vehicle (the higher index gives way) sets a depth
 * offset of `band` that team_survey and ri_reacquire add to their depth (or
 * take from their altitude). The offset is cleared when every such teammate
 * is predicted beyond radius + hysteresis. Teammates lost or not heard for
 * `silent` are ignored. */
#include <stdio.h>

#include "tm_behaviors.h"
#include "tm_store.h"

#include "plugins/lib/pu_angle.h"

const chasm_param_spec tm_keepclear_params[KC_NPARAMS] = {
    [KC_RADIUS] = CHASM_PARAM_DOUBLE_RANGE("radius", "m", 30, 1, 1000, "keep at least this far apart horizontally"),
    [KC_BAND] = CHASM_PARAM_DOUBLE_RANGE("band", "m", 3, 0.5, 50, "depth offset while giving way"),
    [KC_HORIZON] = CHASM_PARAM_DOUBLE_RANGE("horizon", "s", 30, 1, 600, "how far ahead paths are predicted"),
    [KC_HYSTERESIS] = CHASM_PARAM_DOUBLE_RANGE("hysteresis", "m", 10, 0, 1000, "clear only beyond radius + hysteresis"),
    [KC_SILENT] = CHASM_PARAM_DOUBLE_RANGE("silent", "s", 120, 1, 3600, "ignore a teammate not heard for this long"),
    [KC_IN_NORTH] = CHASM_READ("north", CHASM_DOUBLE, "m", "nav.north_m", "own position north"),
    [KC_IN_EAST] = CHASM_READ("east", CHASM_DOUBLE, "m", "nav.east_m", "own position east"),
    [KC_IN_HEADING] = CHASM_READ("heading", CHASM_DOUBLE, "rad", "nav.heading_rad", "own heading"),
    [KC_IN_SPEED] = CHASM_READ("speed", CHASM_DOUBLE, "m/s", "nav.speed_over_ground_mps", "own speed over ground"),
    [KC_OUT_OFFSET] = CHASM_WRITE("out_offset", CHASM_DOUBLE, "m", NULL,
                                  "also write the offset to this variable (optional)"),
};
_Static_assert(CHASM_COUNT(tm_keepclear_params) == KC_NPARAMS, "keep_clear schema and slots disagree");

int tm_keepclear_start(chasm_ctx *c, void *state)
{
    tm_keepclear_state *k = state;
    k->peer = -1;
    return tm_store_for(c, "keep_clear") ? 0 : -1;
}

chasm_status_code tm_keepclear_step(chasm_ctx *c, void *state)
{
    tm_keepclear_state *k = state;
    tm_store *s = tm_store_get();
    double now = (double)c->now_us * 1e-6;
    tm_track me = {chasm_read_double(c, KC_IN_NORTH), chasm_read_double(c, KC_IN_EAST),
                   pu_wrap_2pi(chasm_read_double(c, KC_IN_HEADING)), chasm_read_double(c, KC_IN_SPEED)};
    double radius = chasm_param_double(c, KC_RADIUS), horizon = chasm_param_double(c, KC_HORIZON);
    double closest = 1e30;
    int closest_peer = -1;
    for (int j = 0; j < s->me && j < s->roster.n; j++) {
        tm_peer *p = &s->peer[j];
        if (!p->has_status || p->lost || now - p->t_heard > chasm_param_double(c, KC_SILENT))
            continue;
        tm_track them = tm_track_advance(p->track, now - p->t_status);
        double d = tm_cpa(me, them, horizon, NULL);
        if (d < closest) {
            closest = d;
            closest_peer = j;
        }
    }
    if (!k->active && closest < radius) {
        k->active = 1;
        k->peer = closest_peer;
        char text[96];
        snprintf(text, sizeof text, "predicted %.0f m apart within %.0f s: offset %.1f m", closest, horizon,
                 chasm_param_double(c, KC_BAND));
        tm_post(s, c->now_us, TM_EV_KEEP_CLEAR, closest_peer, -1, me.n, me.e, 0, text);
    } else if (k->active && closest > radius + chasm_param_double(c, KC_HYSTERESIS)) {
        k->active = 0;
        k->peer = -1;
    }
    s->depth_offset = k->active ? chasm_param_double(c, KC_BAND) : 0.0;
    chasm_write_double(c, KC_OUT_OFFSET, s->depth_offset);
    return CHASM_RUNNING;
}

void tm_keepclear_stop(chasm_ctx *c, void *state)
{
    (void)c;
    (void)state;
    tm_store_get()->depth_offset = 0.0;   /* the offset lives only while keep_clear runs */
}
