/* Behaviors of plugin `guidance` in plans: the loader's parameter checks
 * (file:line:col), and each behavior stepped by libchasm against a
 * kinematic vehicle (gd_test_main.c). */
#include <math.h>
#include <stdlib.h>

#include "gd_tests.h"
#include "plugins/lib/gd_geometry.h"
#include "plugins/lib/pu_angle.h"

#define DEG (M_PI / 180.0)
#define DT 0.1

static kin_vehicle vehicle_at(double n, double e, double psi)
{
    return (kin_vehicle){n, e, psi, 5.0, 1.5, 0, 0, 10 * DEG};
}

/* Sets the navigation at t = 0 and starts m there. */
static void begin(chasm_machine *m, const kin_vehicle *v)
{
    pt_set(m, "nav.north_m", v->n, 0);
    pt_set(m, "nav.east_m", v->e, 0);
    pt_set(m, "nav.depth_m", v->depth, 0);
    pt_set(m, "nav.u_mps", v->u, 0);
    chasm_start(m, 0);
}

/* The error loading `state s {\n <body> \n}` must contain `expect`, which may
 * use %d for the body's line number. */
static void expect_error(const char *body, const char *expect)
{
    char plan[1024], want[512];
    snprintf(plan, sizeof plan, "state s {\n%s\n}\n", body);
    snprintf(want, sizeof want, expect, first_line() + 1);
    CHECK_HAS(gd_errors(plan, 1), want);
}

void parameter_errors(void)
{
    expect_error("    do goto(north = 10 m)", "t.chasm:%d:8: error: 'goto' needs parameter 'east': waypoint east");
    expect_error("    do goto(north = 0 m, east = 0 m, radius = 0.1 m)",
                 "t.chasm:%d:47: error: parameter 'radius' of 'goto' is 0.1 m, outside its range [0.5, 1000] m");
    expect_error("    do track(from_north = 0 m, from_east = 0 m, to_north = 1 km, to_east = 0 m, speed = 3 m)",
                 "t.chasm:%d:89: error: parameter 'speed' of 'track' is a speed (m/s), but 'm' is a length");
    expect_error("    do lawnmower(polygon = \"0,0; 9,0; 0,9\", heading = 0 deg, spacing = 0.5 m)",
                 "t.chasm:%d:72: error: parameter 'spacing' of 'lawnmower' is 0.5 m, outside its range [1, 10000] m");
    expect_error("    do yoyo(min_depth = 2 m, max_depth = 10 m, pitch = 60 deg)",
                 "t.chasm:%d:56: error: parameter 'pitch' of 'yoyo' is 1.0472 rad, outside its range");
    expect_error("    do loiter(north = 0 m, east = 0 m, radus = 50 m)",
                 "t.chasm:%d:40: error: unknown parameter 'radus' for 'loiter' (did you mean 'radius'?)");
    expect_error("    do surface_fix(timeout = 10 m)", "t.chasm:%d:30: error:");
    expect_error("    do timer()", "t.chasm:%d:8: error: 'timer' needs parameter 'duration'");
    /* two behaviors of one state may not write the same setpoint */
    expect_error("    do hold_heading(heading = 90 deg)\n    do goto(north = 1 m, east = 1 m)", "setpoint.heading_rad");
    /* the default variables must be declared (navigator_io.chasm does it) */
    CHECK_HAS(gd_errors("state s {\n    do hold_depth(depth = 5 m)\n}\n", 0),
                   "t.chasm:3:8: error: 'hold_depth' writes variable 'setpoint.vertical_mode' (its default for "
                   "'out_vertical_mode'), which the plan does not declare");
    /* ... or bound by the plan to its own variables of the right unit */
    CHECK_HAS(gd_errors("var d : double s\nvar mode : int\nstate s {\n"
                               "    do hold_depth(depth = 5 m, out_depth = d, out_vertical_mode = mode)\n}\n", 0),
                   "t.chasm:5:44: error: parameter 'out_depth' of 'hold_depth' expects a variable in 'm', but 'd' "
                   "is declared in 's'");
    CHECK(!strcmp(gd_errors("var d : double m\nvar mode : int\nstate s {\n"
                              "    do hold_depth(depth = 5 m, out_depth = d, out_vertical_mode = mode)\n}\n", 0),
                  ""));
}

void goto_reaches_the_waypoint_on_the_line(void)
{
    chasm_machine *m = gd_load("state go {\n    do goto(north = 300 m, east = 100 m, radius = 3 m)\n"
                            "    when done -> there\n}\nstate there {\n}\n");
    if (!m)
        return;
    kin_vehicle v = vehicle_at(0, 0, 0);
    v.cur_e = -0.2; /* pushes it off the line */
    begin(m, &v);
    gd_line l;
    gd_line_make(&l, (gd_point){0, 0}, (gd_point){300, 100});
    double worst = 0, t = 0;
    for (; t < 400 && !strcmp(pt_leaf(m), "go"); t += DT) {
        fly(m, &v, t, DT);
        double s, e;
        gd_line_frame(&l, (gd_point){v.n, v.e}, &s, &e);
        if (s > 60) /* once the initial turn onto the line is over */
            worst = fmax(worst, fabs(e));
    }
    CHECK(!strcmp(pt_leaf(m), "there"));
    CHECK(hypot(v.n - 300, v.e - 100) < 3.5);
    CHECK(worst < 1.5);
    CHECK(t > 200 && t < 260); /* 316 m at 1.5 m/s */
    CHECK(pt_get(m, "setpoint.speed_mps") == 1.5 && pt_get(m, "setpoint.speed_mode") == 0);
    chasm_free(m);
}

void track_is_done_past_its_end(void)
{
    chasm_machine *m = gd_load("state leg {\n    do track(from_north = 0 m, from_east = 40 m, to_north = 200 m, "
                            "to_east = 40 m, speed = 2 m/s)\n    when done -> next_leg\n}\nstate next_leg {\n}\n");
    if (!m)
        return;
    kin_vehicle v = vehicle_at(-20, 0, 0);
    v.u = 2.0;
    begin(m, &v);
    double t = 0;
    for (; t < 300 && !strcmp(pt_leaf(m), "leg"); t += DT)
        fly(m, &v, t, DT);
    CHECK(!strcmp(pt_leaf(m), "next_leg"));
    CHECK_NEAR(v.n, 200, 0.5);   /* done as it passes the end ... */
    CHECK_NEAR(v.e, 40, 0.5);    /* ... on the line */
    CHECK(pt_get(m, "setpoint.speed_mps") == 2.0);
    chasm_free(m);
}

#define BOX_SURVEY                                                                                      \
    "var survey_line : int = 0\n"                                                                       \
    "input sim.fix_due : bool\n"                                                                        \
    "test fix_due : sim.fix_due\n"                                                                      \
    "state survey {\n"                                                                                  \
    "    when fix_due -> gps\n"                                                                         \
    "    when done -> finished\n"                                                                       \
    "    state lines {\n"                                                                               \
    "        do lawnmower(north = 0 m, east = 0 m, length = 200 m, width = 90 m, heading = 0 deg,\n"   \
    "                     spacing = 30 m, turn_radius = 10 m)\n"                                        \
    "        do hold_depth(depth = 10 m)\n"                                                             \
    "    }\n"                                                                                           \
    "}\n"                                                                                               \
    "state gps {\n"                                                                                     \
    "    when elapsed > 30 s -> resume survey\n"                                                         \
    "}\n"                                                                                               \
    "state finished {\n"                                                                                \
    "}\n"

/* Largest |cross-track| from line k (east = 15 + 30 k, north 0..200) while the vehicle is
 * inside the box's along-track span, per line; lines the vehicle never flew stay -1. */
static void track_box(const kin_vehicle *v, int line, double *worst)
{
    if (line < 0 || line > 2 || v->n < 0 || v->n > 200)
        return;
    worst[line] = fmax(worst[line], fabs(v->e - (15 + 30 * line)));
}

void lawnmower_flies_every_line(void)
{
    chasm_machine *m = gd_load(BOX_SURVEY);
    if (!m)
        return;
    chasm_var_set_bool(m, chasm_var_find(m, "sim.fix_due"), false, 0);
    kin_vehicle v = vehicle_at(-40, 15, 0);
    begin(m, &v);
    double worst[3] = {-1, -1, -1}, t = 0;
    int seen = 0; /* progress values in order, as digits */
    for (; t < 2000 && strcmp(pt_leaf(m), "finished"); t += DT) {
        fly(m, &v, t, DT);
        int line = (int)pt_get(m, "survey_line");
        if (line != seen % 10)
            seen = seen * 10 + line;
        track_box(&v, line, worst);
    }
    CHECK(!strcmp(pt_leaf(m), "finished"));
    CHECK(seen == 123); /* 0, 1, 2, then 3 = all done */
    for (int k = 0; k < 3; k++) {
        CHECK(worst[k] >= 0 && worst[k] < 1.0);
        if (!(worst[k] < 1.0))
            fprintf(stderr, "line %d: worst cross-track %.2f m\n", k, worst[k]);
    }
    CHECK(pt_get(m, "setpoint.depth_m") == 10 && pt_get(m, "setpoint.vertical_mode") == 0);
    chasm_free(m);
}

void lawnmower_resume_continues_the_line(void)
{
    chasm_machine *m = gd_load(BOX_SURVEY);
    if (!m)
        return;
    int fix = chasm_var_find(m, "sim.fix_due");
    chasm_var_set_bool(m, fix, false, 0);
    kin_vehicle v = vehicle_at(-40, 15, 0);
    begin(m, &v);
    double t = 0;
    /* fly until halfway down line 1 (east 45 m, flown southwards) */
    for (; t < 2000 && !(pt_get(m, "survey_line") == 1 && fabs(v.e - 45) < 1 && v.n < 100); t += DT)
        fly(m, &v, t, DT);
    CHECK(pt_get(m, "survey_line") == 1);
    chasm_var_set_bool(m, fix, true, (int64_t)(t * 1e6));
    fly(m, &v, t, DT);
    t += DT;
    CHECK(!strcmp(pt_leaf(m), "gps"));
    CHECK(pt_get(m, "survey_line") == 1);
    chasm_var_set_bool(m, fix, false, (int64_t)(t * 1e6));
    /* at the surface the vehicle drifts off: heading setpoint no longer updated */
    for (double t0 = t; t < t0 + 31; t += DT) {
        v.e += 0.5 * DT; /* 15 m east */
        fly(m, &v, t, DT);
    }
    CHECK(!strcmp(pt_leaf(m), "survey/lines"));
    CHECK(pt_get(m, "survey_line") == 1); /* not back to line 0 */
    /* LOS on line 1 (southwards): 15 m to the east of it is to its left, so the
     * setpoint points south-west, between 180 and 270 deg */
    double hdg = pt_get(m, "setpoint.heading_rad");
    CHECK(hdg > M_PI && hdg < 1.5 * M_PI);
    double north_at_resume = v.n, worst = 0;
    for (; t < 4000 && pt_get(m, "survey_line") == 1; t += DT) {
        fly(m, &v, t, DT);
        if (v.n < north_at_resume - 60 && v.n > 0)
            worst = fmax(worst, fabs(v.e - 45));
    }
    CHECK(worst < 1.0);         /* back on line 1 ... */
    CHECK(v.n < 0);             /* ... which it finished southwards */
    CHECK(pt_get(m, "survey_line") == 2);
    chasm_free(m);
}

void lawnmower_polygon_and_progress_at_entry(void)
{
    /* a plan can start (or restart) a survey at any line by its progress variable */
    chasm_machine *m = gd_load("var survey_line : int = 3\nstate s {\n"
                            "    do lawnmower(polygon = \"0,0; 100,0; 0,100\", heading = 0 deg, spacing = 25 m)\n"
                            "    when done -> d\n}\nstate d {\n}\n");
    if (!m)
        return;
    kin_vehicle v = vehicle_at(-30, 87.5, 0);
    begin(m, &v);
    double t = 0;
    for (; t < 500 && strcmp(pt_leaf(m), "d"); t += DT)
        fly(m, &v, t, DT);
    CHECK(!strcmp(pt_leaf(m), "d"));
    CHECK(pt_get(m, "survey_line") == 4);
    CHECK(t < 60); /* only the last line (12.5 m + run-in/out) was flown */
    chasm_free(m);
}

void bad_combinations_fail_at_entry(void)
{
    static const struct {
        const char *action, *message;
    } cases[] = {
        {"lawnmower(north = 0 m, east = 0 m, length = 100 m, polygon = \"0,0; 1,0; 0,1\", heading = 0 deg, "
         "spacing = 10 m)",
         "lawnmower: give a polygon or a box (north, east, length, width), not both"},
        {"lawnmower(north = 0 m, length = 100 m, heading = 0 deg, spacing = 10 m)",
         "lawnmower: the box needs east, width (or give a polygon)"},
        {"lawnmower(polygon = \"0,0; 1,0\", heading = 0 deg, spacing = 10 m)",
         "lawnmower: polygon: a polygon needs at least 3 vertices, 2 given"},
        {"yoyo(min_depth = 2 m, max_altitude = 10 m, pitch = 10 deg)",
         "yoyo: give min_depth and max_depth, or min_altitude and max_altitude"},
        {"yoyo(min_depth = 12 m, max_depth = 10 m, pitch = 10 deg)", "yoyo: the band is empty"},
        {"yoyo(min_depth = 2 m, max_depth = 10 m)", "yoyo: give either pitch (a flight-path angle) or rate (a vertical speed), not neither"},
        {"yoyo(min_depth = 2 m, max_depth = 10 m, pitch = 10 deg, rate = 0.2 m/s)", "not both"},
        {"yoyo(min_altitude = 2 m, max_altitude = 10 m, rate = 0.2 m/s, floor = 3 m)", "yoyo: floor is for the depth form"},
        {"set_speed()", "set_speed: give either speed (m/s) or rpm, not neither"},
        {"set_speed(speed = 1 m/s, rpm = 1000 rpm)", "set_speed: give either speed (m/s) or rpm, not both"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char plan[512];
        snprintf(plan, sizeof plan, "var survey_line : int = 0\nstate s {\n    do %s\n    when failed -> f\n}\nstate f {\n}\n",
                 cases[i].action);
        chasm_machine *m = gd_load(plan);
        if (!m)
            continue;
        pt_log[0] = 0;
        kin_vehicle v = vehicle_at(0, 0, 0);
        begin(m, &v);
        fly(m, &v, DT, DT);
        CHECK(!strcmp(pt_leaf(m), "f"));
        CHECK_HAS(pt_log, cases[i].message);
        chasm_free(m);
    }
}

void timer_is_done_after_its_duration(void)
{
    chasm_machine *m = gd_load("state wait {\n    do timer(duration = 2 min)\n    when done -> go\n}\nstate go {\n}\n");
    if (!m)
        return;
    chasm_start(m, 0);
    for (int64_t t = 100000; t < 119950000; t += 100000)
        chasm_step(m, t);
    CHECK(!strcmp(pt_leaf(m), "wait"));
    chasm_step(m, 120000000);
    CHECK(!strcmp(pt_leaf(m), "go"));
    chasm_free(m);
}

#define FIX_PLAN                                                                     \
    "state up {\n    do surface_fix(timeout = 60 s)\n    when failed -> lost\n" \
    "    when done -> fixed\n}\nstate lost {\n}\nstate fixed {\n}\n"

void surface_fix_times_out_as_failed(void)
{
    chasm_machine *m = gd_load(FIX_PLAN);
    if (!m)
        return;
    chasm_start(m, 0);
    for (int64_t t = 100000; t < 59950000; t += 100000)
        chasm_step(m, t);
    CHECK(!strcmp(pt_leaf(m), "up"));
    CHECK(pt_get(m, "setpoint.vertical_mode") == 2 && pt_get(m, "setpoint.speed_mode") == 1);
    CHECK(pt_get(m, "setpoint.prop_rpm") == 0 && fabs(pt_get(m, "setpoint.pitch_rad") - 10 * DEG) < 1e-12);
    chasm_step(m, 60000000);
    CHECK(!strcmp(pt_leaf(m), "lost"));
    CHECK_HAS(pt_log, "surface_fix: no GPS fix before the timeout");
    chasm_free(m);
    /* uncaught, the failure ends the mission */
    m = gd_load("state up {\n    do surface_fix(timeout = 5 s)\n}\n");
    if (!m)
        return;
    chasm_start(m, 0);
    chasm_run_state rs = CHASM_RUN_RUNNING;
    for (int64_t t = 100000; t <= 6000000 && rs == CHASM_RUN_RUNNING; t += 100000)
        rs = chasm_step(m, t);
    CHECK(rs == CHASM_RUN_FAILED);
    chasm_free(m);
}

void surface_fix_needs_a_new_fix(void)
{
    chasm_machine *m = gd_load(FIX_PLAN);
    if (!m)
        return;
    pt_set_int(m, "gps.fix_type", 3, -10); /* a fix from before the state was entered */
    chasm_start(m, 0);
    for (int64_t t = 100000; t <= 20000000; t += 100000)
        chasm_step(m, t);
    CHECK(!strcmp(pt_leaf(m), "up"));
    pt_set_int(m, "gps.fix_type", 0, 20.0); /* a message without a fix */
    chasm_step(m, 20100000);
    chasm_step(m, 20200000);
    CHECK(!strcmp(pt_leaf(m), "up"));
    pt_set_int(m, "gps.fix_type", 3, 20.25);
    chasm_step(m, 20300000);
    CHECK(!strcmp(pt_leaf(m), "fixed"));
    chasm_free(m);
}

void surface_floats_up(void)
{
    chasm_machine *m = gd_load("state up {\n    do surface(rpm = 300 rpm, pitch = 20 deg)\n    when done -> top\n}\n"
                            "state top {\n}\n");
    if (!m)
        return;
    kin_vehicle v = vehicle_at(0, 0, 0);
    v.depth = 10;
    begin(m, &v);
    CHECK(pt_get(m, "setpoint.vertical_mode") == 2 && pt_get(m, "setpoint.speed_mode") == 1);
    CHECK_NEAR(pt_get(m, "setpoint.prop_rpm"), 300, 1e-9);
    CHECK_NEAR(pt_get(m, "setpoint.pitch_rad"), 20 * DEG, 1e-12);
    double t = 0;
    for (; t < 100 && !strcmp(pt_leaf(m), "up"); t += DT) {
        v.depth -= 0.25 * DT;
        fly(m, &v, t, DT);
    }
    CHECK(!strcmp(pt_leaf(m), "top"));
    CHECK(v.depth < 0.5 && v.depth > 0.4);
    chasm_free(m);
}

/* surface(speed = ...): a frontseat holds depths and speeds only (docs/frontseat.md):
 * the way up is a depth of 0 m at that speed, and it is done above `depth` as the other */
void surface_at_a_speed_asks_for_depth_zero(void)
{
    chasm_machine *m = gd_load("state up {\n    do surface(speed = 1.2 m/s)\n    when done -> top\n}\n"
                               "state top {\n}\n");
    if (!m)
        return;
    kin_vehicle v = vehicle_at(0, 0, 0);
    v.depth = 10;
    begin(m, &v);
    CHECK(pt_get(m, "setpoint.vertical_mode") == 0 && pt_get(m, "setpoint.speed_mode") == 0);
    CHECK(pt_get(m, "setpoint.depth_m") == 0.0);
    CHECK_NEAR(pt_get(m, "setpoint.speed_mps"), 1.2, 1e-12);
    double t = 0;
    for (; t < 100 && !strcmp(pt_leaf(m), "up"); t += DT) {
        v.depth -= 0.25 * DT;
        fly(m, &v, t, DT);
        CHECK(pt_get(m, "setpoint.vertical_mode") == 0 || strcmp(pt_leaf(m), "up"));
    }
    CHECK(!strcmp(pt_leaf(m), "top"));
    CHECK(v.depth < 0.5 && v.depth > 0.4);
    chasm_free(m);
}

void yoyo_stays_in_its_band(void)
{
    chasm_machine *m = gd_load("state profile {\n    do yoyo(min_depth = 4 m, max_depth = 12 m, pitch = 15 deg)\n}\n");
    if (!m)
        return;
    kin_vehicle v = vehicle_at(0, 0, 0);
    v.depth = 0;
    begin(m, &v);
    double lo = 1e9, hi = -1e9, sp_lo = 1e9, sp_hi = -1e9;
    int reversals = 0, last_dir = 0;
    for (double t = 0; t < 600; t += DT) {
        fly(m, &v, t, DT);
        double sp = pt_get(m, "setpoint.depth_m");
        /* the vehicle follows the setpoint at up to 0.5 m/s, with a lag */
        v.depth += fmax(-0.5, fmin(0.5, 0.5 * (sp - v.depth))) * DT;
        sp_lo = fmin(sp_lo, sp);
        sp_hi = fmax(sp_hi, sp);
        if (t > 60) {
            lo = fmin(lo, v.depth);
            hi = fmax(hi, v.depth);
        }
        int dir = sp > 8 ? 1 : -1;
        if (dir != last_dir)
            reversals++, last_dir = dir;
    }
    CHECK(sp_lo >= 4 && sp_hi <= 12);
    CHECK(lo < 4.6 && hi > 11.4);  /* full profiles */
    CHECK(reversals >= 8);        /* 8 m at 1.5 sin 15 deg = 0.39 m/s: about 21 s per leg */
    CHECK(pt_get(m, "setpoint.vertical_mode") == 0);
    chasm_free(m);
    /* the altitude form commands altitude */
    m = gd_load("state profile {\n    do yoyo(min_altitude = 3 m, max_altitude = 9 m, pitch = 10 deg)\n}\n");
    if (!m)
        return;
    pt_set(m, "nav.altitude_m", -1, 0); /* unknown: starts from the top of the band */
    begin(m, &v);
    CHECK(pt_get(m, "setpoint.vertical_mode") == 1 && pt_get(m, "setpoint.altitude_m") == 9);
    chasm_free(m);
}

void yoyo_rate_floor_and_profiles(void)
{
    /* the rate form ramps at the given vertical speed; a floor of 3 m over a
     * seabed at 12 m turns every dive back up at 9 m, short of the 20 m limit;
     * each reversal is counted in the variable the plan binds */
    chasm_machine *m = gd_load("var n : int = 0\n"
                               "state profile {\n    do yoyo(min_depth = 2 m, max_depth = 20 m, rate = 0.25 m/s, "
                               "floor = 3 m, out_profiles = n)\n}\n");
    if (!m)
        return;
    kin_vehicle v = vehicle_at(0, 0, 0);
    v.depth = 2;
    const double seabed = 12;
    pt_set(m, "nav.altitude_m", seabed - v.depth, 0);
    begin(m, &v);
    double deepest = 0, sp_deepest = 0, ramp = 0;
    int64_t profiles = 0;
    for (double t = 0; t < 400; t += DT) {
        pt_set(m, "nav.altitude_m", seabed - v.depth, t);
        double before = pt_get(m, "setpoint.depth_m");
        fly(m, &v, t, DT);
        double sp = pt_get(m, "setpoint.depth_m");
        if (t > 1 && t < 10) /* the first dive, far from both limits */
            ramp = fmax(ramp, (sp - before) / DT);
        v.depth += fmax(-0.5, fmin(0.5, 0.5 * (sp - v.depth))) * DT;
        deepest = fmax(deepest, v.depth);
        sp_deepest = fmax(sp_deepest, sp);
        profiles = (int64_t)pt_get(m, "n");
    }
    CHECK_NEAR(ramp, 0.25, 1e-9);
    /* the floor: 12 m - 3 m; the setpoint leads the vehicle by its lag (0.5 m) */
    CHECK(sp_deepest < 9.6 && deepest < 9.2);
    CHECK(deepest > 8.9);
    /* 7 m down and up at 0.25 m/s (eased at the top): about 60 s a round trip */
    CHECK(profiles >= 10 && profiles <= 14);
    chasm_free(m);
}

void holds_and_speed(void)
{
    chasm_machine *m = gd_load("state s {\n    do hold_heading(heading = -90 deg)\n    do hold_altitude(altitude = 8 m)\n"
                            "    do set_speed(rpm = 1200 rpm)\n}\nstate t {\n    do hold_depth(depth = 30 ft)\n"
                            "    do set_speed(speed = 3 kn)\n}\n");
    if (!m)
        return;
    chasm_start(m, 0);
    CHECK_NEAR(pt_get(m, "setpoint.heading_rad"), 1.5 * M_PI, 1e-12);
    CHECK(pt_get(m, "setpoint.altitude_m") == 8 && pt_get(m, "setpoint.vertical_mode") == 1);
    CHECK_NEAR(pt_get(m, "setpoint.prop_rpm"), 1200, 1e-9);
    CHECK(pt_get(m, "setpoint.speed_mode") == 1);
    chasm_free(m);
    m = gd_load("state t {\n    do hold_depth(depth = 30 ft)\n    do set_speed(speed = 3 kn)\n}\n");
    if (!m)
        return;
    chasm_start(m, 0);
    chasm_step(m, 100000);
    CHECK_NEAR(pt_get(m, "setpoint.depth_m"), 9.144, 1e-9);
    CHECK(pt_get(m, "setpoint.vertical_mode") == 0 && pt_get(m, "setpoint.speed_mode") == 0);
    CHECK_NEAR(pt_get(m, "setpoint.speed_mps"), 3 * 1852.0 / 3600, 1e-9);
    chasm_free(m);
}

void loiter_circles_the_point(void)
{
    chasm_machine *m = gd_load("state s {\n    do loiter(north = 200 m, east = 0 m, radius = 40 m, speed = 1 m/s, "
                            "clockwise = false)\n}\n");
    if (!m)
        return;
    kin_vehicle v = vehicle_at(0, 0, 0);
    v.u = 1.0;
    begin(m, &v);
    double worst = 0, turned = 0, last = atan2(v.e, v.n - 200);
    for (double t = 0; t < 1200; t += DT) {
        fly(m, &v, t, DT);
        double b = atan2(v.e, v.n - 200);
        if (t > 600) {
            worst = fmax(worst, fabs(hypot(v.n - 200, v.e) - 40));
            turned += pu_wrap_pi(b - last);
        }
        last = b;
    }
    CHECK(worst < 1.0);
    CHECK(turned < -2 * M_PI); /* counter-clockwise: bearings from the centre decrease */
    CHECK(pt_get(m, "setpoint.speed_mps") == 1.0);
    chasm_free(m);
}
