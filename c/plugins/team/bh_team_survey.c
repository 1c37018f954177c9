/* team_survey: fly this vehicle's own lines, then the lines it takes over
 * from lost teammates (the takeover rule, tm_lines.h).
 *
 *   team_survey(lines = "0: 0,0 0,400; 1: 20,0 20,400; ...", depth = 10 m)
 *
 * Each line: a goto to its start (ILOS from where the vehicle is), then ILOS
 * along it to its end (guidance's geometry, plugins/lib/gd_geometry.c).
 * Progress lives in the store (next_line, an index into this vehicle's work
 * list: own lines, then taken ones), so the status tells the team where this
 * vehicle is in its list and a re-entered state continues where it was. When
 * a teammate is lost (team_link decides), the rest of its list is dealt once;
 * a LINES_TAKEN event lists this vehicle's share. DONE when every line it has
 * is flown. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "tm_behaviors.h"
#include "tm_store.h"

const chasm_param_spec tm_survey_params[SV_NPARAMS] = {
    [SV_LINES] = CHASM_PARAM_REQUIRED_STRING("lines",
        "the team's lines: \"owner: n,e n,e; ...\" (the same string in every plan)"),
    [SV_SPEED] = CHASM_PARAM_DOUBLE_RANGE("speed", "m/s", 1.5, 0.1, 5, "speed through the water"),
    TM_VERTICAL_PARAMS(SV_DEPTH, SV_ALTITUDE),
    [SV_RADIUS] = CHASM_PARAM_DOUBLE_RANGE("radius", "m", 5, 0.5, 1000,
                                           "a line's start is reached within this distance"),
    [SV_LOOKAHEAD] = CHASM_PARAM_DOUBLE_RANGE("lookahead", "m", 10, 1, 500, "LOS lookahead distance"),
    [SV_INTEGRAL] = CHASM_PARAM_DOUBLE_RANGE("integral", "Hz", 0.04, 0, 1, "ILOS integral rate (0: plain LOS)"),
    TM_POSITION_INPUTS(SV_IN_NORTH, SV_IN_EAST),
    TM_STEER_OUTPUTS(SV_OUT_HEADING),
};
_Static_assert(CHASM_COUNT(tm_survey_params) == SV_NPARAMS, "team_survey schema and slots disagree");
_Static_assert(SV_OUT_ALTITUDE - SV_OUT_HEADING == TM_OUT_ALTITUDE, "setpoint slots out of tm_steer's order");

/* Deals the lines of every teammate lost since the last call (once each). */
static void take_over(chasm_ctx *c, tm_store *s, const tm_lines *l)
{
    int alive[TM_MAX_TEAM];
    /* a teammate whose status says done has ended its survey and would
     * never fly a line dealt to it: it is not a survivor for the deal */
    for (int v = 0; v < s->roster.n; v++)
        alive[v] = !s->peer[v].lost && !(s->peer[v].has_status && s->peer[v].state == TM_ST_DONE);
    alive[s->me] = 1;
    for (int v = 0; v < s->roster.n; v++) {
        tm_peer *p = &s->peer[v];
        if (v == s->me || !p->lost || p->dealt)
            continue;
        p->dealt = 1;
        int to[TM_MAX_LINES];
        int from = p->has_status ? p->next_line : 0;
        if (!tm_takeover_deal(&s->work, l, v, from, alive, s->roster.n, to))
            continue;
        char text[200] = "";
        size_t used = 0;
        for (int k = from; k < s->work.n[v]; k++) {   /* in the order dealt */
            int i = s->work.line[v][k];
            if (to[i] == s->me)
                used += (size_t)snprintf(text + used, used < sizeof text ? sizeof text - used : 0, "%s%d",
                                         used ? " " : "", i);
        }
        if (used)
            tm_post(s, c->now_us, TM_EV_LINES_TAKEN, v, -1, 0, 0, 0, text);
    }
}

/* The next line to fly from the work list (own first, then taken), or -1
 * when all are flown; *taken says which. */
static int next_line(const tm_store *s, const tm_survey_state *st, int *taken)
{
    int own[TM_MAX_LINES];
    *taken = s->next_line >= tm_own_lines(&st->lines, s->me, own, TM_MAX_LINES);
    return s->next_line < s->work.n[s->me] ? s->work.line[s->me][s->next_line] : -1;
}

static void begin(chasm_ctx *c, tm_survey_state *st, int line)
{
    st->line = line;
    gd_point here = {chasm_read_double(c, SV_IN_NORTH), chasm_read_double(c, SV_IN_EAST)};
    const tm_line *ln = &st->lines.l[line];
    st->phase = hypot(here.n - ln->a.n, here.e - ln->a.e) <= chasm_param_double(c, SV_RADIUS);
    gd_line_make(&st->path, st->phase ? ln->a : here, st->phase ? ln->b : ln->a);
    st->los = (gd_los){chasm_param_double(c, SV_LOOKAHEAD), chasm_param_double(c, SV_INTEGRAL), 0.0};
}

int tm_survey_start(chasm_ctx *c, void *state)
{
    tm_survey_state *st = state;
    tm_store *s = tm_store_for(c, "team_survey");
    if (!s)
        return -1;
    char why[160];
    if (tm_lines_parse(&st->lines, chasm_param_string(c, SV_LINES), s->roster.n, why, sizeof why)) {
        char msg[240];
        snprintf(msg, sizeof msg, "team_survey: lines: %s", why);
        chasm_log(c, msg);
        return -1;
    }
    st->line = -1;
    if (!s->work_ready) {   /* progress lives in the store: a re-entered state goes on */
        tm_work_init(&s->work, &st->lines, s->roster.n);
        s->work_ready = 1;
    }
    return 0;
}

chasm_status_code tm_survey_step(chasm_ctx *c, void *state)
{
    tm_survey_state *st = state;
    tm_store *s = tm_store_get();
    take_over(c, s, &st->lines);
    int taken;
    if (st->line < 0) {
        int l = next_line(s, st, &taken);
        if (l < 0) {
            s->state = TM_ST_DONE;
            return CHASM_DONE;
        }
        begin(c, st, l);
    }
    next_line(s, st, &taken);
    gd_point p = {chasm_read_double(c, SV_IN_NORTH), chasm_read_double(c, SV_IN_EAST)};
    double along;
    double heading = gd_los_heading(&st->los, &st->path, p, c->dt_s, &along, NULL);
    /* the transit ends within radius of the line's start, or once past it:
     * a start the turn cannot reach within radius (the next line 30 m
     * over, a 20 m turning circle) is never met, and the vehicle would fly
     * on along the transit for ever */
    if (st->phase == 0 && (hypot(p.n - st->path.b.n, p.e - st->path.b.e) <= chasm_param_double(c, SV_RADIUS) ||
                           along >= st->path.length)) {
        const tm_line *ln = &st->lines.l[st->line];
        st->phase = 1;
        gd_line_make(&st->path, ln->a, ln->b);
        heading = gd_los_heading(&st->los, &st->path, p, 0.0, &along, NULL);
    } else if (st->phase == 1 && along >= st->path.length) {
        s->next_line++;
        st->line = -1;
    }
    s->state = st->phase == 0 ? TM_ST_TRANSIT : taken ? TM_ST_TAKEOVER : TM_ST_SURVEY;
    tm_steer(c, heading, SV_SPEED, SV_DEPTH, SV_ALTITUDE, SV_OUT_HEADING, s->depth_offset);
    return CHASM_RUNNING;
}
