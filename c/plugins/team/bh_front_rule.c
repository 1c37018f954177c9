/* front_rule: the course along the front that takes this vehicle to where the
 * team's front estimate is least certain (tm_front_rule.h), for a
 * front_zigzag that reads it (`in_course`): the zig-zag keeps crossing the
 * front, the rule decides which way along it.
 *
 *   do front_rule(from = -50 m, to = 800 m, course = 0.3 rad, front = front_team, out_course = zz_course)
 *   do front_zigzag(course = 0.3 rad, in_course = zz_course, ...)
 *
 * `front` is the vehicle's team estimate (<V>.FRONT_TEAM, front_estimate_t:
 * its own samples with the teammates' summaries as priors). With no OK
 * estimate, or one older than max_age, it writes the planned `course` (the
 * fallback: the vehicles fly their planned lines) and says so once in the
 * log; when an estimate comes, it says where it sends the vehicle. The
 * looks: its own position every `record` seconds and each teammate's
 * position at each status heard (team_link's store), kept in the store so
 * that re-entering the state keeps them. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "auv/auv_front_estimate_t.h"
#include "tm_behaviors.h"
#include "tm_store.h"

const chasm_param_spec tm_front_rule_params[FR_NPARAMS] = {
    [FR_FROM] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("from", "m", -100000, 100000,
                                                  "start of the stretch of front to map, along the estimated front"),
    [FR_TO] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("to", "m", -100000, 100000, "its end (> from)"),
    [FR_CELL] = CHASM_PARAM_DOUBLE_RANGE("cell", "m", 50, 1, 10000, "the stretch is cut into cells this long"),
    [FR_NEAR] = CHASM_PARAM_DOUBLE_RANGE("near", "m", 60, 1, 10000,
                                         "a position this close to the estimated front is a look at it"),
    [FR_RECORD] = CHASM_PARAM_DOUBLE_RANGE("record", "s", 10, 0.1, 3600, "own position recorded this often"),
    [FR_REPLAN] = CHASM_PARAM_DOUBLE_RANGE("replan", "s", 60, 1, 36000,
                                           "a target not reached is given again after this long"),
    [FR_COURSE] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("course", "rad", -2 * M_PI, 2 * M_PI,
                                                    "the planned course: flown while there is no team estimate"),
    [FR_MAX_AGE] = CHASM_PARAM_DOUBLE_RANGE("max_age", "s", 120, 1, 36000, "an estimate older than this is not used"),
    [FR_FRONT] = CHASM_READ_REQUIRED("front", CHASM_MESSAGES, "",
                                     "the team's front estimate (messages bound to <V>.FRONT_TEAM front_estimate_t)"),
    TM_POSITION_INPUTS(FR_IN_NORTH, FR_IN_EAST),
    [FR_OUT_COURSE] = CHASM_WRITE("out_course", CHASM_DOUBLE, "rad", NULL, "the course to advance along (rad)"),
    [FR_OUT_TARGET] = CHASM_WRITE("out_target", CHASM_DOUBLE, "m", NULL,
                                  "the target's place along the front (NaN without an estimate)"),
    [FR_OUT_ADAPTIVE] = CHASM_WRITE("out_adaptive", CHASM_BOOL, "", NULL,
                                    "steering by the team's estimate (false: the planned course)"),
};
_Static_assert(CHASM_COUNT(tm_front_rule_params) == FR_NPARAMS, "front_rule schema and slots disagree");

static double now_s(const chasm_ctx *c) { return (double)c->now_us * 1e-6; }

int tm_front_rule_start(chasm_ctx *c, void *state)
{
    tm_front_rule_state *st = state;
    if (!tm_store_for(c, "front_rule"))
        return -1;
    if (chasm_param_double(c, FR_TO) <= chasm_param_double(c, FR_FROM)) {
        chasm_log(c, "front_rule: `to` must be beyond `from`");
        return -1;
    }
    st->t_record = -1e300;
    for (int i = 0; i < 16; i++)
        st->t_status[i] = -1e300;
    return 0;
}

static void take_estimates(chasm_ctx *c, tm_store *s, tm_front_rule_state *st)
{
    const void *msg;
    size_t len;
    while ((msg = chasm_next_message(c, FR_FRONT, &len))) {
        auv_front_estimate_t f;
        if (len > 1u << 16 || auv_front_estimate_t_decode(msg, 0, (int)len, &f) < 0) {
            s->undecodable++;
            continue;
        }
        if (f.status == AUV_FRONT_ESTIMATE_T_STATUS_OK && isfinite(f.angle_rad) && isfinite(f.offset_m)) {
            st->angle = f.angle_rad;
            st->offset = f.offset_m;
            st->t_est = now_s(c);
            st->have_est = 1;
        }
        auv_front_estimate_t_decode_cleanup(&f);
    }
}

/* Own position every `record` s, each teammate's at each new status. */
static void record_looks(chasm_ctx *c, tm_store *s, tm_front_rule_state *st)
{
    double t = now_s(c);
    if (t - st->t_record >= chasm_param_double(c, FR_RECORD)) {
        tm_fr_add(&s->looks, chasm_read_double(c, FR_IN_NORTH), chasm_read_double(c, FR_IN_EAST));
        st->t_record = t;
    }
    for (int v = 0; v < s->roster.n && v < 16; v++) {
        const tm_peer *p = &s->peer[v];
        if (v == s->me || !p->has_status || p->t_status <= st->t_status[v])
            continue;
        tm_fr_add(&s->looks, p->track.n, p->track.e);
        st->t_status[v] = p->t_status;
    }
}

static void fallback(chasm_ctx *c, tm_front_rule_state *st, const char *why)
{
    if (!st->said_fallback) {   /* once, each time it falls back */
        char msg[200];
        snprintf(msg, sizeof msg, "front_rule: %s: the planned course %.3f rad", why, chasm_param_double(c, FR_COURSE));
        chasm_log(c, msg);
        st->said_fallback = 1;
    }
    st->adaptive = 0;
    st->have_target = 0;
    chasm_write_double(c, FR_OUT_COURSE, chasm_param_double(c, FR_COURSE));
    chasm_write_double(c, FR_OUT_TARGET, NAN);
    chasm_write_bool(c, FR_OUT_ADAPTIVE, 0);
}

chasm_status_code tm_front_rule_step(chasm_ctx *c, void *state)
{
    tm_front_rule_state *st = state;
    tm_store *s = tm_store_get();
    take_estimates(c, s, st);
    record_looks(c, s, st);
    if (!st->have_est) {
        fallback(c, st, "no team estimate yet");
        return CHASM_RUNNING;
    }
    if (now_s(c) - st->t_est > chasm_param_double(c, FR_MAX_AGE)) {
        fallback(c, st, "the team estimate is too old");
        return CHASM_RUNNING;
    }
    tm_fr_front f = {st->angle, st->offset};
    double cell = chasm_param_double(c, FR_CELL), t = now_s(c);
    double own_s = tm_fr_along(&f, chasm_read_double(c, FR_IN_NORTH), chasm_read_double(c, FR_IN_EAST));
    if (!st->have_target || fabs(own_s - st->target) < cell / 2 || t - st->t_pick > chasm_param_double(c, FR_REPLAN)) {
        /* the team now, in roster order: itself and every teammate heard, not lost, not done */
        double pos_s[16], targets[16];
        int n = 0, mine = 0;
        for (int v = 0; v < s->roster.n && v < 16; v++) {
            const tm_peer *p = &s->peer[v];
            if (v == s->me) {
                mine = n;
                pos_s[n++] = own_s;
            } else if (p->has_status && !p->lost && p->state != TM_ST_DONE) {
                tm_track at = tm_track_advance(p->track, t - p->t_status);
                pos_s[n++] = tm_fr_along(&f, at.n, at.e);
            }
        }
        tm_fr_assign(&s->looks, &f, chasm_param_double(c, FR_NEAR), pos_s, n, chasm_param_double(c, FR_FROM),
                     chasm_param_double(c, FR_TO), cell, targets);
        double moved = st->have_target ? fabs(targets[mine] - st->target) : INFINITY;
        st->target = targets[mine];
        st->have_target = 1;
        st->t_pick = t;
        if (moved >= cell / 2) {
            char msg[200];
            snprintf(msg, sizeof msg,
                     "front_rule: to %.0f m along the front (now at %.0f), %.0f m from the team's nearest look; "
                     "%d vehicles share the front", st->target, own_s,
                     tm_fr_uncertainty(&s->looks, &f, chasm_param_double(c, FR_NEAR), pos_s, n, st->target), n);
            chasm_log(c, msg);
        }
    }
    st->adaptive = 1;
    st->said_fallback = 0;
    double course = st->target >= own_s ? st->angle : st->angle + M_PI;
    chasm_write_double(c, FR_OUT_COURSE, remainder(course, 2 * M_PI));
    chasm_write_double(c, FR_OUT_TARGET, st->target);
    chasm_write_bool(c, FR_OUT_ADAPTIVE, 1);
    return CHASM_RUNNING;
}
