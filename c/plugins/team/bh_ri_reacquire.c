/* ri_reacquire: the reacquire-identify vehicle's mission. Targets come from
 * the contact reports team_link stores (merged across reporters by position,
 * tm_targets.h); the route from the vehicle through the pending targets is
 * planned by cheapest insertion and 2-opt (tm_route.h) and replanned when a
 * report adds a target or a target is decided. The vehicle steers (guidance's
 * ILOS, gd_geometry.c) to the first target of the route and through it, in
 * straight passes until it is decided (pass_heading). Looks (reacquire_look_t, a messages
 * input) weigh in on the nearest pending target within `merge` of the look
 * until a sequential test decides it to `ident_error` (tm_targets_look);
 * a target not identified after look_timeout spent on it as the current
 * target (from first coming within ident_range) is NOT_FOUND. Every result is queued for the link (ident) and
 * posted as an event. DONE when no target is pending and every teammate is
 * done, aborted or lost. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "auv/auv_reacquire_look_t.h"
#include "tm_behaviors.h"
#include "tm_route.h"
#include "tm_store.h"

const chasm_param_spec tm_ri_params[RI_NPARAMS] = {
    [RI_LOOKS] = CHASM_READ("looks", CHASM_MESSAGES, "", "looks",
                            "the short-range sensor's looks (a `messages` variable bound to <V>.LOOKS)"),
    [RI_MERGE] = CHASM_PARAM_DOUBLE_RANGE(
        "merge", "m", 5, 0, 100, "reports, and looks after a target's first, within this distance are one object"),
    [RI_LOOK_GATE] = CHASM_PARAM_DOUBLE_RANGE(
        "look_gate", "m", 10, 0, 100,
        "a target's first look counts within this of the reports (both vehicles' navigation errors)"),
    [RI_IDENT_RANGE] = CHASM_PARAM_DOUBLE_RANGE("ident_range", "m", 6, 0.5, 200,
                                                "the sensor's useful range: the target is reached within it"),
    [RI_LOOK_TIMEOUT] = CHASM_PARAM_DOUBLE_RANGE("look_timeout", "s", 180, 1, 3600,
                                                 "not found if no look decides it this long after reaching it"),
    [RI_IDENT_ERROR] = CHASM_PARAM_DOUBLE_RANGE(
        "ident_error", "", 0.001, 1e-9, 0.5,
        "a target is decided once its looks leave at most this probability that the call is wrong"),
    [RI_RUNOUT] = CHASM_PARAM_DOUBLE_RANGE(
        "runout", "m", 30, 1, 1000,
        "straight run past a target before turning back for the next pass (wider than the turning circle)"),
    [RI_SPEED] = CHASM_PARAM_DOUBLE_RANGE("speed", "m/s", 1.5, 0.1, 5, "speed through the water"),
    TM_VERTICAL_PARAMS(RI_DEPTH, RI_ALTITUDE),
    [RI_LOOKAHEAD] = CHASM_PARAM_DOUBLE_RANGE("lookahead", "m", 10, 1, 500, "LOS lookahead distance"),
    TM_POSITION_INPUTS(RI_IN_NORTH, RI_IN_EAST),
    TM_STEER_OUTPUTS(RI_OUT_HEADING),
};
_Static_assert(CHASM_COUNT(tm_ri_params) == RI_NPARAMS, "ri_reacquire schema and slots disagree");
_Static_assert(RI_OUT_ALTITUDE - RI_OUT_HEADING == TM_OUT_ALTITUDE, "setpoint slots out of tm_steer's order");

static gd_point here(chasm_ctx *c) { return (gd_point){chasm_read_double(c, RI_IN_NORTH), chasm_read_double(c, RI_IN_EAST)}; }

/* Records a result: event, ident for the link. */
static void decided(chasm_ctx *c, tm_store *s, int i)
{
    tm_target *t = &s->targets.t[i];
    int not_found = t->state == TM_T_NOT_FOUND;
    char why[48];
    if (!not_found)
        snprintf(why, sizeof why, "%s after %d looks", t->result == TM_RESULT_MINE ? "mine" : "not mine", t->looks);
    else if (t->looks)   /* looks that disagreed too much to decide in time */
        snprintf(why, sizeof why, "undecided after %d looks", t->looks);
    else
        snprintf(why, sizeof why, "no look in time");
    tm_post(s, c->now_us, not_found ? TM_EV_TARGET_NOT_FOUND : TM_EV_TARGET_IDENTIFIED, t->key.origin,
             t->key.number, t->n, t->e, t->result, why);
    int k = tm_outbox_ident(&s->out);
    if (k >= 0)
        s->idents[k] = (tm_ident){t->key, t->result, not_found ? t->n : t->look_n, not_found ? t->e : t->look_e,
                                  (double)c->now_us * 1e-6};
    s->targets_changed = 1;
}

static gd_point aim_point(const tm_target *t)
{
    gd_point g;
    tm_target_where(t, &g.n, &g.e);
    return g;
}

/* Reacquire passes. A vehicle turns wider than its identification sensor
 * sees (a REMUS 100 loops some 28 m across), so it cannot orbit an object
 * within a few metres: asked to, it flies a wide loop with the object out of
 * range most of the time. Once the target is reached it flies passes
 * instead: straight at the aim point (pure pursuit ends on the point), on
 * through it on the same course for `runout` metres, then turns and comes
 * back from wherever the turn left it. The pass ends when the point goes
 * behind: its bearing jumps more than 90 degrees off the course (a pass
 * over the point), or, when pursuit cannot close in because the point lies
 * inside the turning circle, its bearing has swung half way round since the
 * pass began (`swept`): judged on the last commanded course alone, pursuit
 * of such a point turns the bearing a little each cycle, never 90 degrees at
 * once, and the vehicle circled it for ever some 10 m off (the demo lost a
 * target so). A runout wider than the turning circle keeps the point
 * outside it when the vehicle comes about. */
static double pass_heading(chasm_ctx *c, tm_ri_state *st, gd_point g, gd_point p)
{
    double d = hypot(g.n - p.n, g.e - p.e), bearing = atan2(g.e - p.e, g.n - p.n);
    double runout = chasm_param_double(c, RI_RUNOUT);
    if (st->passing && d > runout) {
        st->passing = 0;   /* ran out: come about */
        st->swept = 0.0;
    }
    if (!st->passing) {
        double turn = remainder(bearing - st->pass_course, 2 * M_PI);
        st->swept += turn;
        if ((fabs(turn) > M_PI / 2 || fabs(st->swept) > M_PI) && d <= runout) {
            st->passing = 1;   /* went by, or cannot close in: hold the course */
            st->swept = 0.0;
        } else {
            st->pass_course = bearing;
        }
    }
    double h = fmod(st->pass_course, 2 * M_PI);
    return h < 0 ? h + 2 * M_PI : h;
}

static void replan(chasm_ctx *c, tm_store *s, tm_ri_state *st)
{
    int idx[TM_MAX_TARGETS], order[TM_MAX_TARGETS];
    gd_point pts[TM_MAX_TARGETS];
    int n = tm_targets_pending(&s->targets, idx, TM_MAX_TARGETS);
    for (int i = 0; i < n; i++)
        pts[i] = (gd_point){s->targets.t[idx[i]].n, s->targets.t[idx[i]].e};
    gd_point p = here(c);
    tm_route_plan(p, pts, n, order);
    char text[200] = "";
    size_t used = 0;
    for (int i = 0; i < n && used < sizeof text; i++) {
        const tm_target *t = &s->targets.t[idx[order[i]]];
        used += (size_t)snprintf(text + used, sizeof text - used, "%s%s:%d", i ? " " : "", tm_name(s, t->key.origin),
                                 t->key.number);
    }
    int next = n ? idx[order[0]] : -1;
    if (n)
        tm_post(s, c->now_us, TM_EV_ROUTE, -1, -1, p.n, p.e, 0, text);
    if (next != st->current) {
        st->current = next;
        st->passing = st->close = 0;
        st->swept = 0.0;
        if (next >= 0) {
            gd_line_make(&st->leg, p, aim_point(&s->targets.t[next]));
            st->los = (gd_los){chasm_param_double(c, RI_LOOKAHEAD), 0.0, 0.0};
        }
    }
    s->targets_changed = 0;
}

/* Are all teammates done, aborted or lost? */
static int team_finished(const tm_store *s)
{
    for (int v = 0; v < s->roster.n; v++) {
        const tm_peer *p = &s->peer[v];
        if (v != s->me && !p->lost && !(p->has_status && p->state == TM_ST_DONE))
            return 0;
    }
    return 1;
}

int tm_ri_start(chasm_ctx *c, void *state)
{
    tm_ri_state *st = state;
    tm_store *s = tm_store_for(c, "ri_reacquire");
    if (!s)
        return -1;
    st->current = -1;
    s->merge_m = chasm_param_double(c, RI_MERGE);
    if (!s->is_ri) {
        s->is_ri = 1;
        /* reports heard before this behavior ran get their ack now */
        for (int i = 0; i < s->targets.n; i++) {
            const tm_target *t = &s->targets.t[i];
            tm_outbox_ack(&s->out, t->key.origin, t->key.number);
            for (int j = 0; j < t->n_alias; j++)
                tm_outbox_ack(&s->out, t->alias[j].origin, t->alias[j].number);
        }
    }
    s->targets_changed = 1;
    return 0;
}

chasm_status_code tm_ri_step(chasm_ctx *c, void *state)
{
    tm_ri_state *st = state;
    tm_store *s = tm_store_get();
    const void *msg;
    size_t len;
    while ((msg = chasm_next_message(c, RI_LOOKS, &len))) {
        auv_reacquire_look_t k;
        if (len > 1u << 20 || auv_reacquire_look_t_decode(msg, 0, (int)len, &k) < 0) {
            s->undecodable++;
            continue;
        }
        int i = tm_targets_look(&s->targets, k.north_m, k.east_m, k.result, k.confidence,
                                chasm_param_double(c, RI_LOOK_GATE), chasm_param_double(c, RI_MERGE),
                                chasm_param_double(c, RI_IDENT_ERROR));
        auv_reacquire_look_t_decode_cleanup(&k);
        if (i >= 0)
            decided(c, s, i);
    }
    gd_point p = here(c);
    /* the current target: reached? timed out? */
    if (st->current >= 0) {
        tm_target *t = &s->targets.t[st->current];
        if (t->state == TM_T_PENDING) {
            gd_point g = aim_point(t);
            double d = hypot(p.n - g.n, p.e - g.e);
            if (d <= chasm_param_double(c, RI_IDENT_RANGE))
                t->engaged = 1;
            /* only while it is the current target: one that a replan set aside
             * (a nearer report came in) is not timed out while the vehicle
             * works elsewhere (the demo lost a target so: 140 of its 180 s ran
             * while the vehicle identified two others) */
            if (t->engaged)
                t->look_s += c->dt_s;
            if (t->look_s > chasm_param_double(c, RI_LOOK_TIMEOUT)) {
                t->state = TM_T_NOT_FOUND;
                t->result = TM_RESULT_NOT_FOUND;
                decided(c, s, st->current);
            }
        } else {
            s->targets_changed = 1;
        }
    }
    if (s->targets_changed)
        replan(c, s, st);
    double heading;
    if (st->current >= 0) {
        tm_target *t = &s->targets.t[st->current];
        gd_point g = aim_point(t);
        if (!st->close && hypot(g.n - p.n, g.e - p.e) <= chasm_param_double(c, RI_RUNOUT))
            st->close = 1;
        if (st->close) {
            /* passes from here on; a pass that went by reaches the target
             * even if it missed by more than ident_range (the clock starts) */
            heading = pass_heading(c, st, g, p);
            if (st->passing)
                t->engaged = 1;
        } else {
            double along;
            heading = gd_los_heading(&st->los, &st->leg, p, c->dt_s, &along, NULL);
            st->pass_course = heading;   /* the first pass is this approach */
            if (along >= st->leg.length) {   /* abeam and far: aim again from here */
                gd_line_make(&st->leg, p, g);
                heading = gd_los_heading(&st->los, &st->leg, p, 0.0, NULL, NULL);
            }
        }
        s->state = TM_ST_REACQUIRE;
        st->idle_set = 0;
    } else {
        if (team_finished(s)) {
            s->state = TM_ST_DONE;
            return CHASM_DONE;
        }
        if (!st->idle_set) {
            st->idle = p;
            st->idle_set = 1;
        }
        heading = gd_circle_heading(st->idle, 20.0, 1, chasm_param_double(c, RI_LOOKAHEAD), p);
        s->state = TM_ST_REACQUIRE;
    }
    tm_steer(c, heading, RI_SPEED, RI_DEPTH, RI_ALTITUDE, RI_OUT_HEADING, s->depth_offset);
    return CHASM_RUNNING;
}
