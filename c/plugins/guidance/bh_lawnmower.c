/* lawnmower: fly every track line of an area (gd_survey.h), line after line,
 * with integral LOS on each line and a circular turn between lines.
 *
 * Each line is flown on a path extended by `lead` beyond the area at both
 * ends (and beyond its neighbours' ends, for a slanted polygon edge), so the
 * vehicle turns outside the area and has `lead` metres to settle on the next
 * line before the area starts. The turn follows a half circle of radius
 * max(turn_radius, spacing / 2) from the end of one path towards the next
 * line; with a radius larger than half the spacing it ends beyond the next
 * line and the LOS run-in brings the vehicle back onto it.
 *
 * Progress: the index of the line being flown (or turned to) is written to an
 * int variable (default `survey_line`) whenever it changes, and read at entry:
 * leaving the state for a GPS fix and coming back continues that line from
 * where the vehicle is. When every line is flown it holds the number of lines
 * and the behavior reports done. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gd_behaviors.h"
#include "gd_slots.h"

/* A box parameter: the box or the polygon is given, so none has a default. */
#define FORM(name, lo, doc) CHASM_PARAM_OPTIONAL_RANGE(name, CHASM_DOUBLE, "m", lo, 1e6, doc)

const chasm_param_spec gd_lawnmower_params[MOW_NPARAMS] = {
    [MOW_NORTH] = FORM("north", -1e6, "box corner, north (box form)"),
    [MOW_EAST] = FORM("east", -1e6, "box corner, east (box form)"),
    [MOW_LENGTH] = FORM("length", 1, "box length along the heading (box form)"),
    [MOW_WIDTH] = FORM("width", 0, "box width, to the right of the heading (box form)"),
    [MOW_POLYGON] = CHASM_PARAM_STRING("polygon", "", "area as \"n,e; n,e; ...\" in metres (polygon form)"),
    [MOW_HEADING] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("heading", "rad", -2 * M_PI, 2 * M_PI, "direction of the lines"),
    [MOW_SPACING] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("spacing", "m", 1, 10000, "largest distance between lines"),
    [MOW_TURN_RADIUS] = CHASM_PARAM_DOUBLE_RANGE("turn_radius", "m", 20, 1, 1000, "radius of the turns between lines"),
    /* no default: the default is computed from two other parameters */
    [MOW_LEAD] = CHASM_PARAM_OPTIONAL_RANGE("lead", CHASM_DOUBLE, "m", 0, 1000,
                                            "run-in/run-out beyond the area (default max(lookahead, 2 turn_radius))"),
    [MOW_SPEED] = GD_SPEED_PARAM,
    [MOW_LOOKAHEAD] = GD_LOOKAHEAD_PARAM,
    [MOW_INTEGRAL] = GD_INTEGRAL_PARAM,
    GD_HORIZONTAL_SLOTS(MOW),
    [MOW_PROGRESS] = CHASM_WRITE("progress", CHASM_INT, "", "survey_line",
                                 "index of the line being flown (resume continues it)"),
};

static const gd_horizontal slots = {MOW_IN_NORTH, MOW_IN_EAST, MOW_SPEED, MOW_OUT_HEADING, MOW_OUT_SPEED,
                                    MOW_OUT_SPEED_MODE};

static double along_of(gd_point p, const gd_line *dir) { return p.n * dir->tn + p.e * dir->te; }

gd_line gd_mow_path(const gd_mow_state *s, int k)
{
    const gd_track *t = &s->lines[k];
    gd_line dir;
    gd_line_make(&dir, t->start, t->end);
    double x0 = along_of(t->start, &dir);
    double in = x0, out = along_of(t->end, &dir);
    if (k > 0)
        in = fmin(in, along_of(s->lines[k - 1].end, &dir));
    if (k + 1 < s->n_lines)
        out = fmax(out, along_of(s->lines[k + 1].start, &dir));
    in -= s->lead;
    out += s->lead;
    gd_line path;
    gd_line_make(&path, (gd_point){t->start.n + (in - x0) * dir.tn, t->start.e + (in - x0) * dir.te},
                 (gd_point){t->start.n + (out - x0) * dir.tn, t->start.e + (out - x0) * dir.te});
    return path;
}

/* The area from the parameters: a polygon, or a box; not both. */
static int area_of(chasm_ctx *c, pu_polygon *area)
{
    const char *poly = chasm_param_string(c, MOW_POLYGON);
    static const char *const box_names[] = {"north", "east", "length", "width"};
    int given = 0;
    char missing[64] = "";
    for (int i = 0; i < 4; i++) {
        if (chasm_param_given(c, MOW_NORTH + i))
            given++;
        else
            snprintf(missing + strlen(missing), sizeof missing - strlen(missing), "%s%s", *missing ? ", " : "",
                     box_names[i]);
    }
    if (poly[0]) {
        if (given)
            return gd_refuse(c, "lawnmower", "give a polygon or a box (north, east, length, width), not both");
        char err[160];
        if (pu_polygon_parse(poly, area, err, sizeof err) != 0)
            return gd_refuse(c, "lawnmower", "polygon: %s", err);
        return 0;
    }
    if (given < 4)
        return gd_refuse(c, "lawnmower", "the box needs %s (or give a polygon)", missing);
    gd_box_polygon(area, (gd_point){chasm_param_double(c, MOW_NORTH), chasm_param_double(c, MOW_EAST)},
                   chasm_param_double(c, MOW_HEADING), chasm_param_double(c, MOW_LENGTH),
                   chasm_param_double(c, MOW_WIDTH));
    return 0;
}

static void begin_line(chasm_ctx *c, gd_mow_state *s)
{
    s->turning = 0;
    s->path = gd_mow_path(s, s->line);
    chasm_write_int(c, MOW_PROGRESS, s->line);
}

int gd_lawnmower_start(chasm_ctx *c, void *state)
{
    gd_mow_state *s = state;
    pu_polygon area;
    if (area_of(c, &area) != 0)
        return -1;
    char err[160];
    s->n_lines = gd_survey_lines(&area, chasm_param_double(c, MOW_HEADING), chasm_param_double(c, MOW_SPACING),
                                 s->lines, GD_MAX_LINES, err, sizeof err);
    if (s->n_lines < 0)
        return gd_refuse(c, "lawnmower", "%s", err);
    double lookahead = chasm_param_double(c, MOW_LOOKAHEAD);
    s->lead = chasm_param_given(c, MOW_LEAD) ? chasm_param_double(c, MOW_LEAD)
                                    : fmax(lookahead, 2.0 * chasm_param_double(c, MOW_TURN_RADIUS));
    s->los = (gd_los){lookahead, chasm_param_double(c, MOW_INTEGRAL), 0.0};
    int64_t done = chasm_read_int(c, MOW_PROGRESS);
    s->line = done < 0 ? 0 : done > s->n_lines ? s->n_lines : (int)done;
    if (s->line < s->n_lines) {
        begin_line(c, s);
        gd_command(c, &slots, gd_los_heading(&s->los, &s->path, gd_position(c, &slots), 0.0, NULL, NULL));
    }
    return 0;
}

/* From the end of the current path, a half circle towards the next line. */
static void begin_turn(chasm_ctx *c, gd_mow_state *s)
{
    double cross;
    gd_line_frame(&s->path, s->lines[s->line].start, NULL, &cross);
    s->turn_cw = cross > 0.0; /* the next line is to the right: turn right */
    s->turn_r = fmax(chasm_param_double(c, MOW_TURN_RADIUS), fabs(cross) / 2.0);
    double side = s->turn_cw ? 1.0 : -1.0;
    s->centre = (gd_point){s->path.b.n - side * s->turn_r * s->path.te, s->path.b.e + side * s->turn_r * s->path.tn};
    s->turning = 1;
    s->turn_since_s = c->time_in_state_s;
    chasm_write_int(c, MOW_PROGRESS, s->line);
}

chasm_status_code gd_lawnmower_step(chasm_ctx *c, void *state)
{
    gd_mow_state *s = state;
    if (s->line >= s->n_lines)
        return CHASM_DONE;
    gd_point p = gd_position(c, &slots);
    if (s->turning) {
        double along;
        gd_line_frame(&s->path, p, &along, NULL);
        /* The turn ends when the vehicle is back abeam the end of the path it
         * left (where the next path starts); a turn that takes more than two
         * circles' time (a current stronger than the vehicle) gives up to LOS. */
        double circle_s = 2.0 * M_PI * s->turn_r / chasm_param_double(c, MOW_SPEED);
        if (along < s->path.length || c->time_in_state_s - s->turn_since_s > 2.0 * circle_s) {
            begin_line(c, s);
            s->los.b = -s->los.b; /* the next line runs the other way: the learnt crab flips sign */
        } else {
            gd_command(c, &slots, gd_circle_heading(s->centre, s->turn_r, s->turn_cw, s->los.lookahead, p));
            return CHASM_RUNNING;
        }
    }
    double along;
    gd_command(c, &slots, gd_los_heading(&s->los, &s->path, p, c->dt_s, &along, NULL));
    if (along < s->path.length)
        return CHASM_RUNNING;
    s->line++;
    if (s->line == s->n_lines) {
        chasm_write_int(c, MOW_PROGRESS, s->line);
        return CHASM_DONE;
    }
    begin_turn(c, s);
    return CHASM_RUNNING;
}
