/* front_zigzag: a zig-zag across a front between two water masses, each leg
 * ended by what the CTD measured rather than by a planned length.
 *
 * The legs run at course + angle and course - angle in turn (the first to the
 * right of the course unless first_right is false), each a straight line from
 * where the vehicle was when the leg began, flown with ILOS. On each leg the
 * temperature readings (in_temperature, default ctd.temperature_c) are
 * averaged in bins of window / 20 metres along the leg, and a straight line
 * through the bins of the last `window` metres gives the smoothed temperature
 * (its value at the newest bin) and the along-track gradient (its slope).
 *
 * The rule. Once the vehicle is `settle` metres along the leg (the turn is
 * behind it) the smoothed temperature is the leg's reference T_ref. The
 * front has been crossed, and the vehicle turns onto the next leg, when both
 *
 *   moved:    |T - T_ref| >= fraction * delta    (delta: the two waters' difference)
 *   steadied: |dT/ds| <= steady * peak |dT/ds| of the leg since T_ref
 *
 * hold: the water has changed by most of the difference between the masses,
 * and the gradient has peaked and fallen, so the vehicle is through the
 * front, not in it. The crossing is reported where the gradient peaked: the
 * mean position and time of the window's bins at the peak (out_crossings,
 * out_crossing_north, _east, _time; the plan binds them if it wants them). A
 * leg that reaches `max_leg` metres without a crossing ends all the same (the
 * fallback: a front weaker than fraction * delta, or no CTD). Readings that
 * are stale (over 1 s old), marked not valid, not a number or outside the
 * range of sea water (-3 to 45 degC) are skipped. Done after `crossings`
 * crossings (0: never).
 *
 * in_course, when bound and written (a sampling team's front_rule), replaces
 * `course` from the next leg on. A course reversed (more than 90 degrees from
 * the last leg's) keeps the leg heading back across the front: the side
 * flips with it, since the front's near side is then to the other hand. */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gd_behaviors.h"
#include "gd_slots.h"

#define BINS_PER_WINDOW 20
#define MIN_FIT_BINS 6          /* a fit needs this many bins ... */
#define MIN_FIT_SPAN 0.5        /* ... spanning this fraction of the window */
#define MAX_READING_AGE_S 1.0   /* a reading older than this is not the water here */
#define SEA_MIN_C (-3.0)        /* in-situ temperatures a sea holds */
#define SEA_MAX_C 45.0

const chasm_param_spec gd_front_zigzag_params[ZZ_NPARAMS] = {
    [ZZ_COURSE] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("course", "rad", -2 * M_PI, 2 * M_PI,
                                                    "base course the zig-zag advances along (usually along the front)"),
    [ZZ_ANGLE] = CHASM_PARAM_DOUBLE_RANGE("angle", "rad", 45 * M_PI / 180, 10 * M_PI / 180, 85 * M_PI / 180,
                                          "legs at course +- angle"),
    [ZZ_DELTA] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("delta", "", 0.01, 40,
                                                   "temperature difference between the two water masses [degC]"),
    [ZZ_FRACTION] = CHASM_PARAM_DOUBLE_RANGE("fraction", "", 0.6, 0.1, 1.0,
                                             "crossed once the temperature has moved by this fraction of delta ..."),
    [ZZ_STEADY] = CHASM_PARAM_DOUBLE_RANGE("steady", "", 0.3, 0.01, 1.0,
                                           "... and the gradient has fallen to this fraction of its peak"),
    [ZZ_WINDOW] = CHASM_PARAM_DOUBLE_RANGE("window", "m", 10, 1, 200,
                                           "along-track window of the temperature's smoothing and gradient"),
    [ZZ_SETTLE] = CHASM_PARAM_DOUBLE_RANGE("settle", "m", 15, 0, 1000,
                                           "distance along a leg (the turn) before its reference temperature"),
    [ZZ_MAX_LEG] = CHASM_PARAM_DOUBLE_RANGE("max_leg", "m", 300, 10, 100000,
                                            "a leg with no crossing ends after this distance"),
    [ZZ_CROSSINGS] = CHASM_PARAM_INT_RANGE("crossings", 0, 0, 100000, "done after this many crossings (0: never)"),
    [ZZ_FIRST_RIGHT] = CHASM_PARAM_BOOL("first_right", 1, "the first leg is course + angle (else course - angle)"),
    [ZZ_SPEED] = GD_SPEED_PARAM,
    [ZZ_LOOKAHEAD] = GD_LOOKAHEAD_PARAM,
    [ZZ_INTEGRAL] = GD_INTEGRAL_PARAM,
    [ZZ_IN_TEMPERATURE] = CHASM_READ("in_temperature", CHASM_DOUBLE, "", "ctd.temperature_c",
                                     "measured water temperature [degC]"),
    [ZZ_IN_VALID] = CHASM_READ("in_valid", CHASM_BOOL, "", "ctd.valid", "the temperature is a measurement"),
    [ZZ_OUT_CROSSINGS] = CHASM_WRITE("out_crossings", CHASM_INT, "", NULL, "crossings so far"),
    [ZZ_OUT_CROSSING_NORTH] = CHASM_WRITE("out_crossing_north", CHASM_DOUBLE, "m", NULL,
                                          "where the last crossing's gradient peaked, north"),
    [ZZ_OUT_CROSSING_EAST] = CHASM_WRITE("out_crossing_east", CHASM_DOUBLE, "m", NULL, "... east"),
    [ZZ_OUT_CROSSING_TIME] = CHASM_WRITE("out_crossing_time", CHASM_DOUBLE, "s", NULL,
                                         "... and when (mission time)"),
    [ZZ_IN_COURSE] = CHASM_READ("in_course", CHASM_DOUBLE, "rad", NULL,
                                "optional: the course from the next leg on, when written (front_rule)"),
    [ZZ_OUT_LEG] = CHASM_WRITE("out_leg", CHASM_INT, "", NULL, "the leg being flown, from 1"),
    GD_HORIZONTAL_SLOTS(ZZ),
};

static const gd_horizontal zz_slots = {ZZ_IN_NORTH, ZZ_IN_EAST, ZZ_SPEED, ZZ_OUT_HEADING, ZZ_OUT_SPEED,
                                       ZZ_OUT_SPEED_MODE};

static double now_s(const chasm_ctx *c) { return (double)c->now_us * 1e-6; }

/* Starts a leg from where the vehicle is, on the side s->side. */
static void begin_leg(chasm_ctx *c, gd_zz_state *s)
{
    gd_point p = gd_position(c, &zz_slots);
    double course = chasm_param_double(c, ZZ_COURSE), given = chasm_read_double(c, ZZ_IN_COURSE);
    if (chasm_age_s(c, ZZ_IN_COURSE) < 1e299 && isfinite(given))
        course = given;
    if (s->leg > 0 && fabs(remainder(course - s->course, 2 * M_PI)) > M_PI / 2)
        s->side = -s->side;   /* reversed along the front: back across it is the other hand now */
    s->course = course;
    double chi = course + s->side * chasm_param_double(c, ZZ_ANGLE);
    /* the line runs on past max_leg: the leg ends by the rule or by max_leg, never at the line's end */
    double len = chasm_param_double(c, ZZ_MAX_LEG) + 10 * chasm_param_double(c, ZZ_LOOKAHEAD);
    gd_line_make(&s->line, p, (gd_point){p.n + len * cos(chi), p.e + len * sin(chi)});
    s->los.b = 0.0;
    s->leg++;
    s->head = s->count = 0;
    s->bin = LONG_MIN;
    s->acc_k = 0;
    s->have_ref = 0;
    s->g_peak = 0.0;
    chasm_write_int(c, ZZ_OUT_LEG, s->leg);
}

gd_zz_fit_t gd_zz_fit(const gd_zz_state *s, double window)
{
    gd_zz_fit_t f = {0};
    if (s->count == 0)
        return f;
    const gd_zz_sample *newest = &s->buf[(s->head + s->count - 1) % GD_ZZ_CAP];
    double n = 0, ms = 0, mt = 0, mn = 0, me = 0, mtime = 0, first = newest->s;
    for (int k = 0; k < s->count; k++) {
        const gd_zz_sample *x = &s->buf[(s->head + k) % GD_ZZ_CAP];
        if (x->s < newest->s - window)
            continue;
        n++;
        ms += x->s, mt += x->t_c, mn += x->n, me += x->e, mtime += x->time;
        first = fmin(first, x->s);
    }
    if (n < MIN_FIT_BINS || newest->s - first < MIN_FIT_SPAN * window)
        return f;
    ms /= n, mt /= n;
    double sxx = 0, sxy = 0;
    for (int k = 0; k < s->count; k++) {
        const gd_zz_sample *x = &s->buf[(s->head + k) % GD_ZZ_CAP];
        if (x->s < newest->s - window)
            continue;
        sxx += (x->s - ms) * (x->s - ms);
        sxy += (x->s - ms) * (x->t_c - mt);
    }
    f.ok = sxx > 0;
    f.gradient = f.ok ? sxy / sxx : 0.0;
    f.level = mt + f.gradient * (newest->s - ms);
    f.centre = (gd_zz_sample){ms, mt, mn / n, me / n, mtime / n};
    return f;
}

/* Closes the bin being filled: its means become a sample. */
static void push_bin(gd_zz_state *s)
{
    if (s->acc_k == 0)
        return;
    double k = s->acc_k;
    gd_zz_sample x = {s->acc_s / k, s->acc_t / k, s->acc_n / k, s->acc_e / k, s->acc_time / k};
    if (s->count == GD_ZZ_CAP) {
        s->head = (s->head + 1) % GD_ZZ_CAP;
        s->count--;
    }
    s->buf[(s->head + s->count) % GD_ZZ_CAP] = x;
    s->count++;
    s->acc_s = s->acc_t = s->acc_n = s->acc_e = s->acc_time = 0.0;
    s->acc_k = 0;
}

/* The reading of this cycle, if it is one of sea water now. */
static int reading(const chasm_ctx *c, double *t_c)
{
    *t_c = chasm_read_double(c, ZZ_IN_TEMPERATURE);
    return chasm_read_bool(c, ZZ_IN_VALID) && chasm_age_s(c, ZZ_IN_TEMPERATURE) <= MAX_READING_AGE_S &&
           isfinite(*t_c) && *t_c >= SEA_MIN_C && *t_c <= SEA_MAX_C;
}

/* The rule, on each new bin; 1 when the front has been crossed. */
static int crossed(chasm_ctx *c, gd_zz_state *s, double along)
{
    gd_zz_fit_t f = gd_zz_fit(s, chasm_param_double(c, ZZ_WINDOW));
    if (!f.ok)
        return 0;
    if (!s->have_ref) {
        if (along >= chasm_param_double(c, ZZ_SETTLE)) {
            s->have_ref = 1;
            s->t_ref = f.level;
        }
        return 0;
    }
    double g = fabs(f.gradient);
    if (g > s->g_peak) {
        s->g_peak = g;
        s->at_peak = f.centre;
    }
    int moved = fabs(f.level - s->t_ref) >= chasm_param_double(c, ZZ_FRACTION) * chasm_param_double(c, ZZ_DELTA);
    return moved && g <= chasm_param_double(c, ZZ_STEADY) * s->g_peak;
}

int gd_front_zigzag_start(chasm_ctx *c, void *state)
{
    gd_zz_state *s = state;
    s->los = (gd_los){chasm_param_double(c, ZZ_LOOKAHEAD), chasm_param_double(c, ZZ_INTEGRAL), 0.0};
    s->side = chasm_param_bool(c, ZZ_FIRST_RIGHT) ? 1 : -1;
    s->crossings = 0;
    chasm_write_int(c, ZZ_OUT_CROSSINGS, 0);
    begin_leg(c, s);
    gd_command(c, &zz_slots, gd_los_heading(&s->los, &s->line, gd_position(c, &zz_slots), 0.0, NULL, NULL));
    return 0;
}

chasm_status_code gd_front_zigzag_step(chasm_ctx *c, void *state)
{
    gd_zz_state *s = state;
    gd_point p = gd_position(c, &zz_slots);
    double along;
    gd_command(c, &zz_slots, gd_los_heading(&s->los, &s->line, p, c->dt_s, &along, NULL));
    double t_c;
    if (along >= 0.0 && reading(c, &t_c)) {
        long bin = (long)floor(along * BINS_PER_WINDOW / chasm_param_double(c, ZZ_WINDOW));
        if (bin > s->bin || s->bin == LONG_MIN) { /* a new bin: the last one is complete */
            int had = s->acc_k > 0;
            push_bin(s);
            s->bin = bin;
            if (had && crossed(c, s, along)) {
                s->crossings++;
                chasm_write_int(c, ZZ_OUT_CROSSINGS, s->crossings);
                chasm_write_double(c, ZZ_OUT_CROSSING_NORTH, s->at_peak.n);
                chasm_write_double(c, ZZ_OUT_CROSSING_EAST, s->at_peak.e);
                chasm_write_double(c, ZZ_OUT_CROSSING_TIME, s->at_peak.time);
                char msg[200];
                snprintf(msg, sizeof msg,
                         "front_zigzag: crossing %lld at %.1f N %.1f E (t %.1f s), leg %d turned %.0f m on; "
                         "%.3f -> %.3f degC, peak gradient %.4f degC/m",
                         (long long)s->crossings, s->at_peak.n, s->at_peak.e, s->at_peak.time, s->leg, along,
                         s->t_ref, gd_zz_fit(s, chasm_param_double(c, ZZ_WINDOW)).level, s->g_peak);
                chasm_log(c, msg);
                int64_t want = chasm_param_int(c, ZZ_CROSSINGS);
                if (want > 0 && s->crossings >= want)
                    return CHASM_DONE;
                s->side = -s->side;
                begin_leg(c, s);
                return CHASM_RUNNING;
            }
        }
        if (bin == s->bin) { /* a bin already closed (the vehicle went back) takes nothing */
            s->acc_s += along, s->acc_t += t_c, s->acc_n += p.n, s->acc_e += p.e, s->acc_time += now_s(c);
            s->acc_k++;
        }
    }
    if (along >= chasm_param_double(c, ZZ_MAX_LEG)) {
        char msg[160];
        snprintf(msg, sizeof msg, "front_zigzag: leg %d ended at max_leg %.0f m without a crossing%s", s->leg,
                 chasm_param_double(c, ZZ_MAX_LEG), s->have_ref ? "" : " (no usable temperature)");
        chasm_log(c, msg);
        s->side = -s->side;
        begin_leg(c, s);
    }
    return CHASM_RUNNING;
}
