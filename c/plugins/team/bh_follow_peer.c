/* follow_peer: keep station on a teammate from what the link says of it (a
 * leader-follower pair; docs/missions.md, "Writing your own team").
 *
 *   follow_peer(peer = "AUV1", behind = 30 m, side = 20 m, speed = 1.5 m/s)
 *
 * The station is `behind` metres astern of the peer and `side` metres to its
 * right (negative: left), on the peer's last status dead-reckoned to now
 * (course and speed since its time, like keep_clear). The follower steers at
 * a point `lookahead` metres ahead of the station along the peer's course (so
 * it settles on the peer's track instead of chasing a point), and sets its
 * speed to the peer's plus `gain` times how far it is behind the station
 * along that course, between `min_speed` and `max_speed`. Until the peer's
 * first status it circles where it is. DONE when the peer's status says
 * done; FAILED when the peer is lost (team_link decides), so the plan says
 * what a follower does alone. */
#include <math.h>

#include "tm_behaviors.h"
#include "tm_keepclear.h"
#include "tm_store.h"

#include "plugins/lib/pu_angle.h"

const chasm_param_spec tm_follow_params[FP_NPARAMS] = {
    [FP_PEER] = CHASM_PARAM_REQUIRED_STRING("peer", "the teammate followed (a roster name)"),
    [FP_BEHIND] = CHASM_PARAM_DOUBLE_RANGE("behind", "m", 30, -1000, 1000,
                                           "station distance astern of the peer (negative: ahead)"),
    [FP_SIDE] = CHASM_PARAM_DOUBLE_RANGE("side", "m", 0, -1000, 1000,
                                         "station distance to the peer's right (negative: left)"),
    [FP_SPEED] = CHASM_PARAM_DOUBLE_RANGE("speed", "m/s", 1.5, 0.1, 5,
                                          "speed when on station (the peer's, if it reports one)"),
    [FP_MIN_SPEED] = CHASM_PARAM_DOUBLE_RANGE("min_speed", "m/s", 0.5, 0.1, 5, "slowest speed while dropping back"),
    [FP_MAX_SPEED] = CHASM_PARAM_DOUBLE_RANGE("max_speed", "m/s", 2.2, 0.1, 5, "fastest speed while catching up"),
    [FP_GAIN] = CHASM_PARAM_DOUBLE_RANGE("gain", "Hz", 0.05, 0, 10, "speed added per metre behind the station"),
    TM_VERTICAL_PARAMS(FP_DEPTH, FP_ALTITUDE),
    [FP_LOOKAHEAD] = CHASM_PARAM_DOUBLE_RANGE("lookahead", "m", 20, 1, 500,
                                              "steer at this point ahead of the station along the peer's course"),
    TM_POSITION_INPUTS(FP_IN_NORTH, FP_IN_EAST),
    TM_STEER_OUTPUTS(FP_OUT_HEADING),
};
_Static_assert(CHASM_COUNT(tm_follow_params) == FP_NPARAMS, "follow_peer schema and slots disagree");
_Static_assert(FP_OUT_ALTITUDE - FP_OUT_HEADING == TM_OUT_ALTITUDE, "setpoint slots out of tm_steer's order");

int tm_follow_start(chasm_ctx *c, void *state)
{
    tm_follow_state *f = state;
    tm_store *s = tm_store_for(c, "follow_peer");
    if (!s)
        return -1;
    f->peer = tm_roster_index(&s->roster, chasm_param_string(c, FP_PEER));
    f->idle_set = 0;
    if (f->peer < 0 || f->peer == s->me) {
        chasm_log(c, f->peer < 0 ? "follow_peer: peer is not in the team roster (team_link's `team`)"
                                 : "follow_peer: a vehicle cannot follow itself");
        return -1;
    }
    return 0;
}

chasm_status_code tm_follow_step(chasm_ctx *c, void *state)
{
    tm_follow_state *f = state;
    tm_store *s = tm_store_get();
    const tm_peer *p = &s->peer[f->peer];
    if (p->lost)
        return CHASM_FAILED;
    if (p->has_status && p->state == TM_ST_DONE)
        return CHASM_DONE;
    gd_point here = {chasm_read_double(c, FP_IN_NORTH), chasm_read_double(c, FP_IN_EAST)};
    double heading, speed = chasm_param_double(c, FP_SPEED);
    if (!p->has_status) {   /* nothing heard yet: wait on a circle */
        if (!f->idle_set) {
            f->idle = here;
            f->idle_set = 1;
        }
        heading = gd_circle_heading(f->idle, 20.0, 1, chasm_param_double(c, FP_LOOKAHEAD), here);
    } else {
        double now = (double)c->now_us * 1e-6;
        tm_track leader = tm_track_advance(p->track, now - p->t_status);
        double cn = cos(leader.heading), ce = sin(leader.heading);   /* along the course; right = (-ce, cn) */
        double behind = chasm_param_double(c, FP_BEHIND), side = chasm_param_double(c, FP_SIDE);
        gd_point station = {leader.n - behind * cn - side * ce, leader.e - behind * ce + side * cn};
        double ahead = chasm_param_double(c, FP_LOOKAHEAD);
        gd_point aim = {station.n + ahead * cn, station.e + ahead * ce};
        heading = pu_wrap_2pi(atan2(aim.e - here.e, aim.n - here.n));
        /* metres behind the station along the peer's course (negative: ahead of it) */
        double lag = (station.n - here.n) * cn + (station.e - here.e) * ce;
        double base = leader.speed > 0.1 ? leader.speed : speed;
        speed = fmin(chasm_param_double(c, FP_MAX_SPEED),
                     fmax(chasm_param_double(c, FP_MIN_SPEED), base + chasm_param_double(c, FP_GAIN) * lag));
    }
    tm_steer(c, heading, FP_SPEED, FP_DEPTH, FP_ALTITUDE, FP_OUT_HEADING, s->depth_offset);
    chasm_write_double(c, FP_OUT_HEADING + TM_OUT_SPEED, speed);
    return CHASM_RUNNING;
}
