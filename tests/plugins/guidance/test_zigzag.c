/* front_zigzag against synthetic temperature series: a kinematic vehicle
 * (gd_kinematic.c) in a front T(x) = Ta + (Tb - Ta) (1 + tanh(x / w)) / 2
 * across a straight line, with noise; the rule's turns, the crossings it
 * reports, the max_leg fallback and the readings it must not use. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "gd_tests.h"
#include "plugins/guidance/gd_behaviors.h"
#include "plugins/lib/gd_geometry.h"

#define DEG (M_PI / 180.0)
#define DT 0.1

/* The front runs north along east = FRONT_E: 16 degC west of it, 12 east. */
#define FRONT_E 100.0
#define TA 16.0
#define TB 12.0
#define WIDTH 20.0

static const char *const CTD_DECL = "input ctd.temperature_c : double\ninput ctd.valid : bool\n"
                                    "var crossings : int = 0\nvar leg : int = 0\nvar cross_n : double m = 0 m\n"
                                    "var cross_e : double m = 0 m\nvar cross_t : double s = 0 s\n";

/* A reproducible noise in [-1, 1] (an LCG: the same series on every machine). */
static double noise(uint32_t *seed)
{
    *seed = *seed * 1664525u + 1013904223u;
    return (double)(*seed >> 8) / (double)(1u << 23) - 1.0;
}

static double water(double east) { return TA + (TB - TA) * 0.5 * (1.0 + tanh((east - FRONT_E) / WIDTH)); }

static chasm_machine *load_zigzag(const char *args)
{
    char plan[2048];
    snprintf(plan, sizeof plan,
             "%sstate zz {\n    do front_zigzag(%s, out_crossings = crossings, out_leg = leg, "
             "out_crossing_north = cross_n, out_crossing_east = cross_e, out_crossing_time = cross_t)\n"
             "    do hold_depth(depth = 5 m)\n    when done -> over\n}\nstate over {\n}\n",
             CTD_DECL, args);
    return gd_load(plan);
}

typedef struct {
    int crossings, legs;
    double cross_e[16], cross_t[16]; /* reported */
    double turn_e[16];               /* where the vehicle was when each leg began */
    double worst_report;             /* |reported east - front| */
} zz_run;

/* The vehicle's navigation and the water where it is, at t = 0, then the plan starts. */
static void start_in_water(chasm_machine *m, const kin_vehicle *v)
{
    pt_set(m, "nav.north_m", v->n, 0);
    pt_set(m, "nav.east_m", v->e, 0);
    pt_set(m, "nav.depth_m", v->depth, 0);
    pt_set(m, "nav.u_mps", v->u, 0);
    pt_set(m, "ctd.temperature_c", water(v->e), 0);
    pt_set_bool(m, "ctd.valid", 1, 0);
    chasm_start(m, 0);
}

/* Flies m for `seconds` with the temperature of water(east) + noise_c * noise, a
 * reading every cycle (`bad`: every third reading is NaN, 99 degC or not valid). */
static zz_run fly_front(chasm_machine *m, kin_vehicle *v, double seconds, double noise_c, int bad)
{
    zz_run r = {0};
    uint32_t seed = 12345;
    start_in_water(m, v);
    int legs = 1, k = 0;
    for (double t = DT; t < seconds && !strcmp(pt_leaf(m), "zz"); t += DT, k++) {
        double temp = water(v->e) + noise_c * noise(&seed);
        int valid = 1;
        if (bad && k % 9 == 0)
            temp = NAN;
        else if (bad && k % 9 == 3)
            temp = 99.0;
        else if (bad && k % 9 == 6)
            valid = 0;
        pt_set(m, "ctd.temperature_c", temp, t);
        pt_set_bool(m, "ctd.valid", valid, t);
        fly(m, v, t, DT);
        int leg = (int)pt_get_int(m, "leg");
        if (leg != legs && legs < 16) {
            r.turn_e[legs - 1] = v->e;
            legs = leg;
        }
        int n = (int)pt_get_int(m, "crossings");
        if (n > r.crossings && n <= 16) {
            r.cross_e[n - 1] = pt_get(m, "cross_e");
            r.cross_t[n - 1] = pt_get(m, "cross_t");
            r.worst_report = fmax(r.worst_report, fabs(r.cross_e[n - 1] - FRONT_E));
            r.crossings = n;
        }
    }
    r.legs = legs;
    return r;
}

void zigzag_turns_after_each_crossing(void)
{
    chasm_machine *m = load_zigzag("course = 0 deg, angle = 60 deg, delta = 4, crossings = 5");
    if (!m)
        return;
    kin_vehicle v = {0, 40, 60 * DEG, 5.0, 1.5, 0, 0, 10 * DEG};
    zz_run r = fly_front(m, &v, 1200, 0.01, 0);
    CHECK(!strcmp(pt_leaf(m), "over")); /* done after 5 */
    CHECK(r.crossings == 5);
    CHECK(r.legs == 5);
    /* each crossing is reported where the gradient peaked: the front, to a
     * few metres (the window's bins and the thermistor-free series) */
    CHECK(r.worst_report < 4.0);
    for (int i = 0; i < r.crossings - 1; i++) {
        /* the turn comes after the crossing, on the far side, within 40 m across the front:
         * the gradient is down to 0.3 of its peak 24 m across (sech^2), plus half the window */
        double past = (i % 2 == 0 ? 1 : -1) * (r.turn_e[i] - FRONT_E);
        CHECK(past > 20.0 && past < 40.0);
        CHECK(r.cross_t[i + 1] > r.cross_t[i]);
        printf("# leg %d: crossing reported at east %.2f m (front %.0f m), turned %.1f m past it\n", i + 1,
               r.cross_e[i], FRONT_E, past);
    }
    CHECK_HAS(pt_log, "front_zigzag: crossing 1 at");
    chasm_free(m);
}

void zigzag_falls_back_to_max_leg(void)
{
    /* a front weaker than fraction * delta (the 4 degC front where 12 are
     * expected) is never taken for a crossing: the legs end at max_leg */
    chasm_machine *m = load_zigzag("course = 0 deg, angle = 45 deg, delta = 12, max_leg = 120 m, first_right = false");
    if (!m)
        return;
    kin_vehicle v = {0, 160, 315 * DEG, 5.0, 1.5, 0, 0, 10 * DEG};
    zz_run r = fly_front(m, &v, 400, 0.01, 0);
    CHECK(r.crossings == 0);
    CHECK(r.legs >= 4); /* 120 m at 1.5 m/s is 80 s a leg */
    CHECK_HAS(pt_log, "front_zigzag: leg 1 ended at max_leg 120 m without a crossing");
    /* the first leg went left of the course (north-west), through the front: 85 m west */
    CHECK(r.turn_e[0] < 85 && r.turn_e[0] > 65);
    chasm_free(m);
}

void zigzag_skips_bad_readings(void)
{
    /* a third of the readings not a number, 99 degC or marked not valid: the
     * rule sees the front all the same, from the others */
    chasm_machine *m = load_zigzag("course = 0 deg, angle = 60 deg, delta = 4, crossings = 3");
    if (!m)
        return;
    kin_vehicle v = {0, 40, 60 * DEG, 5.0, 1.5, 0, 0, 10 * DEG};
    zz_run r = fly_front(m, &v, 1000, 0.01, 1);
    CHECK(r.crossings == 3);
    CHECK(r.worst_report < 4.0);
    chasm_free(m);
    /* with no CTD at all (never a reading) every leg is a max_leg leg */
    m = load_zigzag("course = 0 deg, angle = 60 deg, delta = 4, max_leg = 50 m");
    if (!m)
        return;
    kin_vehicle w = {0, 40, 60 * DEG, 5.0, 1.5, 0, 0, 10 * DEG};
    chasm_start(m, 0);
    for (double t = DT; t < 200; t += DT)
        fly(m, &w, t, DT);
    CHECK(pt_get_int(m, "crossings") == 0 && pt_get_int(m, "leg") >= 4);
    CHECK_HAS(pt_log, "without a crossing (no usable temperature)");
    chasm_free(m);
}

void zigzag_window_fit(void)
{
    /* the along-track fit: a straight temperature ramp gives its slope and its
     * value at the newest bin; too few bins, or too short a span, no fit */
    gd_zz_state s;
    memset(&s, 0, sizeof s);
    for (int k = 0; k < 30; k++) {
        s.buf[k] = (gd_zz_sample){k * 0.5, 10.0 + 0.02 * k * 0.5, k, 0, k};
        s.count = k + 1;
    }
    gd_zz_fit_t f = gd_zz_fit(&s, 10.0);
    CHECK(f.ok);
    CHECK_NEAR(f.gradient, 0.02, 1e-12);
    CHECK_NEAR(f.level, 10.0 + 0.02 * 29 * 0.5, 1e-12);
    CHECK_NEAR(f.centre.s, 9.5, 1e-9); /* the window's 21 bins: s 4.5 .. 14.5 */
    s.count = 5;
    CHECK(!gd_zz_fit(&s, 10.0).ok);
    s.count = 30;
    CHECK(!gd_zz_fit(&s, 100.0).ok); /* 14.5 m of a 100 m window */
}

/* in_course (a sampling team's front_rule) turns the zig-zag round along the
 * front: from the next leg on it advances the other way, still crossing. */
void zigzag_follows_in_course(void)
{
    char plan[2048];
    snprintf(plan, sizeof plan,
             "%sinput zz_course : double rad\nstate zz {\n    do front_zigzag(course = 0 deg, in_course = zz_course, "
             "angle = 60 deg, delta = 4, out_crossings = crossings, out_leg = leg)\n"
             "    do hold_depth(depth = 5 m)\n}\n",
             CTD_DECL);
    chasm_machine *m = gd_load(plan);
    if (!m)
        return;
    kin_vehicle v = {0, 40, 60 * DEG, 5.0, 1.5, 0, 0, 10 * DEG};
    start_in_water(m, &v);
    double north_at_turn = 0, t = DT;
    int turned_at = -1;
    for (; t < 1200 && pt_get_int(m, "crossings") < 8; t += DT) {
        pt_set(m, "ctd.temperature_c", water(v.e), t);
        pt_set_bool(m, "ctd.valid", 1, t);
        if (turned_at < 0 && pt_get_int(m, "crossings") >= 3) {
            pt_set(m, "zz_course", M_PI, t);   /* back south along the front */
            turned_at = (int)pt_get_int(m, "crossings");
            north_at_turn = v.n;
        }
        fly(m, &v, t, DT);
    }
    CHECK(turned_at == 3);
    CHECK(pt_get_int(m, "crossings") == 8);   /* it kept crossing after the reversal */
    printf("# reversed at %.0f m north after 3 crossings; after 5 more at %.0f m north, %.0f m from the front\n",
           north_at_turn, v.n, v.e - FRONT_E);
    CHECK(v.n < north_at_turn - 60);         /* and went back south */
    CHECK(fabs(v.e - FRONT_E) < 60);         /* along the front, not away from it */
    chasm_free(m);
}
