/* The checks plugin's test handlers in plans loaded by the real libchasm,
 * the polygon parser of the shared lib, and the loader's parameter checks. */
#include "../common/plugin_test.h"
#include "plugins/lib/pu_polygon.h"

#define DEG (3.14159265358979323846 / 180.0)

static const char *IO =
    "use checks\n"
    "input nav.depth_m : double m\n"
    "input nav.altitude_m : double m\n"
    "input nav.heading_rad : double rad\n"
    "input nav.pitch_rad : double rad\n"
    "input nav.north_m : double m\n"
    "input nav.east_m : double m\n"; /* 7 lines */

/* IO, then `test t : <handler>` on line 8, and a plan that goes to `hit`
 * when it holds. */
static const char *plan_with(const char *handler)
{
    static char buf[4096];
    snprintf(buf, sizeof buf, "%stest t : %s\nstate idle {\n    when t -> hit\n}\nstate hit {\n}\n", IO, handler);
    return buf;
}

/* Does the handler hold for these inputs? */
static int holds(const char *handler, double depth, double altitude, double heading_deg, double pitch_deg,
                 double north, double east)
{
    chasm_machine *m = pt_load(plan_with(handler));
    if (!m)
        return -1;
    pt_set(m, "nav.depth_m", depth, 0);
    pt_set(m, "nav.altitude_m", altitude, 0);
    pt_set(m, "nav.heading_rad", heading_deg * DEG, 0);
    pt_set(m, "nav.pitch_rad", pitch_deg * DEG, 0);
    pt_set(m, "nav.north_m", north, 0);
    pt_set(m, "nav.east_m", east, 0);
    pt_start(m, 0);
    pt_step(m, 0.1);
    int hit = !strcmp(pt_leaf(m), "hit");
    chasm_free(m);
    return hit;
}

static int at_depth(const char *h, double d) { return holds(h, d, 10, 0, 0, 0, 0); }
static int at_heading(const char *h, double deg) { return holds(h, 0, 10, deg, 0, 0, 0); }
static int at_position(const char *h, double n, double e) { return holds(h, 0, 10, 0, 0, n, e); }

static void checks_within(void)
{
    const char *d = "depth_within(value = 10 m, tolerance = 0.5 m)";
    CHECK(at_depth(d, 10.0) == 1 && at_depth(d, 10.5) == 1 && at_depth(d, 9.5) == 1);
    CHECK(at_depth(d, 10.51) == 0 && at_depth(d, 9.4) == 0 && at_depth(d, NAN) == 0);
    CHECK(at_depth("depth_within(value = 30 ft, tolerance = 1 ft)", 9.0) == 1);  /* units convert */
    const char *a = "altitude_within(value = 8 m, tolerance = 1 m)";
    CHECK(holds(a, 0, 8.5, 0, 0, 0, 0) == 1 && holds(a, 0, 9.5, 0, 0, 0, 0) == 0);
    /* unknown altitude (negative) never satisfies it, even if the value is negative */
    CHECK(holds("altitude_within(value = -1 m, tolerance = 1 m)", 0, -1, 0, 0, 0, 0) == 0);
    const char *p = "pitch_within(value = -10 deg, tolerance = 2 deg)";
    CHECK(holds(p, 0, 10, 0, -11.5, 0, 0) == 1 && holds(p, 0, 10, 0, -7, 0, 0) == 0);
}

static void checks_heading_wraps(void)
{
    const char *h = "heading_within(value = 359 deg, tolerance = 5 deg)";
    CHECK(at_heading(h, 2.0) == 1);       /* 3 degrees across north */
    CHECK(at_heading(h, 355.0) == 1);
    CHECK(at_heading(h, 5.0) == 0);       /* 6 degrees */
    CHECK(at_heading(h, 179.0) == 0);
    const char *z = "heading_within(value = 0 deg, tolerance = 1 deg)";
    CHECK(at_heading(z, 359.5) == 1 && at_heading(z, 360.0) == 1 && at_heading(z, 0.5) == 1);
}

static void checks_near(void)
{
    const char *n = "near(north = 100 m, east = -50 m, radius = 10 m)";
    CHECK(at_position(n, 106, -42) == 1);   /* 10 m exactly */
    CHECK(at_position(n, 107, -42) == 0);
    CHECK(at_position(n, NAN, -50) == 0);
}

static void checks_outside_polygon(void)
{
    /* an L-shaped area: concave, so a box test would be wrong */
    const char *l = "outside_area(polygon = \"0,0; 0,100; 50,100; 50,50; 100,50; 100,0\")";
    CHECK(at_position(l, 25, 25) == 0);
    CHECK(at_position(l, 75, 25) == 0);
    CHECK(at_position(l, 75, 75) == 1);     /* in the notch */
    CHECK(at_position(l, -1, 50) == 1);
    CHECK(at_position(l, 0, 50) == 0);      /* on the edge is inside */
    CHECK(at_position(l, NAN, 0) == 1);     /* unknown position: outside */
    const char *margin = "outside_area(polygon = \"0,0; 0,100; 100,100; 100,0\", margin = 10 m)";
    CHECK(at_position(margin, 50, 50) == 0);
    CHECK(at_position(margin, 50, 95) == 1); /* inside, but within 10 m of the edge */
}

static void checks_outside_box(void)
{
    const char *b = "outside_area(north = 10 m, east = 20 m, length = 100 m, width = 50 m)";
    CHECK(at_position(b, 50, 40) == 0);
    CHECK(at_position(b, 50, 71) == 1);     /* east of 20 + 50 */
    CHECK(at_position(b, 111, 40) == 1);    /* north of 10 + 100 */
    /* length along heading 90 (east), width to its right (south) */
    const char *r = "outside_area(north = 0 m, east = 0 m, length = 100 m, width = 50 m, heading = 90 deg)";
    CHECK(at_position(r, -25, 50) == 0);
    CHECK(at_position(r, 25, 50) == 1);
    CHECK(at_position(r, -25, 101) == 1);
}

/* A malformed area loads (the loader cannot see inside a string), then the
 * test is TRUE from the first cycle: the plan aborts to safety, and the
 * reason is logged once. */
static void fails_safe(const char *handler, const char *reason)
{
    CHECK(strcmp(pt_errors(plan_with(handler)), "") == 0);
    chasm_machine *m = pt_load(plan_with(handler));
    if (!m)
        return;
    pt_set(m, "nav.north_m", 1, 0);
    pt_set(m, "nav.east_m", 1, 0);
    pt_start(m, 0);
    for (int i = 1; i <= 10; i++)
        pt_step(m, 0.1 * i);
    CHECK(strcmp(pt_leaf(m), "hit") == 0);
    CHECK_HAS(pt_log, reason);
    const char *first = strstr(pt_log, "outside_area: ");
    CHECK(first && !strstr(first + 1, "outside_area: "));   /* once, not every cycle */
    chasm_free(m);
    pt_log_clear();
}

static void checks_malformed_area_fails_safe(void)
{
    fails_safe("outside_area(polygon = \"0,0; 0,100; 100\")",
               "outside_area: vertex 3: expected ',' between north and east at character 16: the test is true");
    fails_safe("outside_area(polygon = \"0,0; 100,100; 0,100; 100,0\")", "edges 1-2 and 3-4 cross");
    fails_safe("outside_area(polygon = \"0,0; 0,100\")", "a polygon needs at least 3 vertices, 2 given");
    fails_safe("outside_area(margin = 5 m)", "no area: give polygon");
    fails_safe("outside_area(polygon = \"0,0; 0,1; 1,1\", length = 5 m, width = 5 m)", "give either polygon or a box");
}

static void checks_param_errors(void)
{
    const char *e = pt_errors(plan_with("depth_within(value = 10 m, tolerance = -1 m)"));
    CHECK_HAS(e, "t.chasm:8:49: error: parameter 'tolerance' of 'depth_within' is -1 m, outside its range [0, 11000] m");
    e = pt_errors(plan_with("depth_within(value = 10, tolerance = 1 m)"));
    CHECK_HAS(e, "t.chasm:8:31: error: parameter 'value' of 'depth_within' needs a unit: it is a length");
    e = pt_errors(plan_with("depth_within(tolerance = 1 m)"));
    CHECK_HAS(e, "t.chasm:8:10: error: 'depth_within' needs parameter 'value'");
    e = pt_errors(plan_with("outside_area(polygon = 5)"));
    CHECK_HAS(e, "t.chasm:8:33: error: parameter 'polygon' of 'outside_area' must be a string in quotes, not 5");
    e = pt_errors(plan_with("near(north = 1 m, east = 1 m, radius = 5 s)"));
    CHECK_HAS(e, "t.chasm:8:49: error: parameter 'radius' of 'near' is a length (m), but 's' is a duration");
    e = pt_errors(plan_with("heading_within(value = 90 deg, tolerance = 200 deg)"));
    CHECK_HAS(e, "outside its range [0, 3.14159] rad");
}

static void polygon_parser(void)
{
    pu_polygon p;
    char err[160];
    CHECK(pu_polygon_parse(" 0,0 ;0, 10;10 ,10; 10,0; ", &p, err, sizeof err) == 0 && p.n == 4);
    CHECK_NEAR(pu_polygon_signed_area(&p), 100.0, 1e-9);    /* east, north, west: counter-clockwise */
    CHECK(pu_polygon_parse("-1.5e2,2; 3,4; 5,-6", &p, err, sizeof err) == 0 && p.north[0] == -150.0);
    static const struct { const char *text, *error; } bad[] = {
        {"", "the polygon is empty"},
        {"0,0; 1,1", "at least 3 vertices, 2 given"},
        {"0,0; 1,1; 2,2", "no area"},
        {"0,0; 0,0; 1,1; 1,0", "vertices 1 and 2 are the same point"},
        {"0,0; 0,1; 1,1; 0,0", "vertices 4 and 1 are the same point (do not repeat the first vertex"},
        {"0,0; 0,x; 1,1", "vertex 2: expected the east coordinate (a number in metres) at character 8"},
        {"0,0; 0 1; 1,1", "vertex 2: expected ',' between north and east at character 8"},
        {"0,0; 0,1 1,1", "vertex 2: expected ';' before the next vertex at character 10"},
        {"0,0; 0,1e999; 1,1", "vertex 2: the east coordinate is not a finite number"},
        {"0,0; 10,10; 0,10; 10,0", "edges 1-2 and 3-4 cross"},
        {"0,0; 0,10; 0,5; 5,5", "edges 1-2 and 2-3 fold back onto each other"},
        {"0,0; 0,10; 10,10; 10,5; 0,5; -5,5; -5,0", "cross"},  /* a vertex on another edge */
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        err[0] = '\0';
        CHECK(pu_polygon_parse(bad[i].text, &p, err, sizeof err) == -1);
        CHECK_HAS(err, bad[i].error);
    }
    char many[4096] = "";
    for (int i = 0; i <= PU_POLYGON_MAX; i++) /* 65 vertices on a circle */
        snprintf(many + strlen(many), sizeof many - strlen(many), "%.3f,%.3f;", 100 * cos(i * 0.0966),
                 100 * sin(i * 0.0966));
    CHECK(pu_polygon_parse(many, &p, err, sizeof err) == -1);
    CHECK_HAS(err, "more than 64 vertices");
}

static void polygon_geometry(void)
{
    pu_polygon p;
    char err[160];
    CHECK(pu_polygon_parse("0,0; 0,10; 10,10; 10,0", &p, err, sizeof err) == 0);
    CHECK(pu_polygon_contains(&p, 5, 5) && !pu_polygon_contains(&p, 11, 5) && pu_polygon_contains(&p, 10, 5));
    CHECK_NEAR(pu_polygon_edge_distance(&p, 5, 5), 5.0, 1e-12);
    CHECK_NEAR(pu_polygon_edge_distance(&p, 13, 14), 5.0, 1e-12);   /* to the corner (10, 10) */
    pu_polygon_box(&p, 1, 2, 3, 4);
    CHECK(p.n == 4 && pu_polygon_contains(&p, 3.9, 5.9) && !pu_polygon_contains(&p, 4.1, 5));
}

const unit_test plugin_tests[] = {
    {"checks_within", checks_within},
    {"checks_heading_wraps", checks_heading_wraps},
    {"checks_near", checks_near},
    {"checks_outside_polygon", checks_outside_polygon},
    {"checks_outside_box", checks_outside_box},
    {"checks_malformed_area_fails_safe", checks_malformed_area_fails_safe},
    {"checks_param_errors", checks_param_errors},
    {"polygon_parser", polygon_parser},
    {"polygon_geometry", polygon_geometry},
    {NULL, NULL},
};
