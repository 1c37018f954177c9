/* Geometry of plugin `guidance`: line frames, the ILOS law
 * (cross-track error decays, with and without a cross current), circle
 * following and survey line generation for boxes and polygons. */
#include <math.h>

#include "gd_tests.h"
#include "plugins/lib/gd_geometry.h"
#include "plugins/guidance/gd_survey.h"
#include "plugins/lib/pu_angle.h"

#define DEG (M_PI / 180.0)

void line_frame(void)
{
    gd_line l;
    gd_line_make(&l, (gd_point){0, 0}, (gd_point){0, 100}); /* due east */
    CHECK_NEAR(l.course, M_PI / 2, 1e-12);
    CHECK_NEAR(l.length, 100, 1e-12);
    double s, e;
    gd_line_frame(&l, (gd_point){10, 50}, &s, &e);
    CHECK_NEAR(s, 50, 1e-12);
    CHECK_NEAR(e, -10, 1e-12); /* north of an eastward line is to its left */
    gd_line_frame(&l, (gd_point){-3, -20}, &s, &e);
    CHECK_NEAR(s, -20, 1e-12);
    CHECK_NEAR(e, 3, 1e-12);
}

void los_heading_wraps(void)
{
    gd_line l;
    gd_line_make(&l, (gd_point){0, 0}, (gd_point){100, 0}); /* due north: course 0 */
    gd_los g = {10, 0, 0};
    double right = gd_los_heading(&g, &l, (gd_point){50, 10}, 0.1, NULL, NULL);
    double left = gd_los_heading(&g, &l, (gd_point){50, -10}, 0.1, NULL, NULL);
    CHECK_NEAR(right, 2 * M_PI - M_PI / 4, 1e-12); /* 10 m right at L = 10 m: 45 deg to port, as 315 deg */
    CHECK_NEAR(left, M_PI / 4, 1e-12);
    CHECK_NEAR(gd_los_heading(&g, &l, (gd_point){50, 0}, 0.1, NULL, NULL), 0.0, 1e-12);
    /* far from the line the law points almost straight at it, never beyond */
    double far = gd_los_heading(&g, &l, (gd_point){50, 1e5}, 0.1, NULL, NULL);
    CHECK(far > 1.5 * M_PI && far < 1.5 * M_PI + 1 * DEG);
}

/* Flies a kinematic vehicle along l for T seconds; returns |e| at the end
 * and the largest |e| after `settle` seconds. */
static double fly_line(gd_los *g, const gd_line *l, gd_point p, double psi, double cur_e, double T, double *worst_after,
                       double settle)
{
    double e = 0;
    *worst_after = 0;
    for (double t = 0; t < T; t += 0.1) {
        double psi_d = gd_los_heading(g, l, p, 0.1, NULL, &e);
        double rate = fmax(-0.2, fmin(0.2, 0.8 * pu_wrap_pi(psi_d - psi)));
        psi += rate * 0.1;
        p.n += 1.5 * cos(psi) * 0.1;
        p.e += (1.5 * sin(psi) + cur_e) * 0.1;
        if (t >= settle)
            *worst_after = fmax(*worst_after, fabs(e));
    }
    return fabs(e);
}

void los_cross_track_decays(void)
{
    gd_line l;
    gd_line_make(&l, (gd_point){0, 0}, (gd_point){5000, 0});
    double worst;
    gd_los g = {10, 0, 0};
    double e60 = fly_line(&g, &l, (gd_point){0, 30}, 0, 0, 60, &worst, 0);
    CHECK(e60 < 0.5);
    gd_los g2 = {10, 0, 0};
    fly_line(&g2, &l, (gd_point){0, 30}, 0, 0, 200, &worst, 60);
    CHECK(worst < 0.5); /* and it stays there: no oscillation */
    /* starting off the line heading the wrong way (a U-turn) also converges */
    gd_los g3 = {10, 0, 0};
    CHECK(fly_line(&g3, &l, (gd_point){100, -40}, M_PI, 0, 150, &worst, 0) < 0.5);
}

void ilos_removes_the_current_offset(void)
{
    gd_line l;
    gd_line_make(&l, (gd_point){0, 0}, (gd_point){20000, 0});
    double worst;
    /* 0.3 m/s across a line flown at 1.5 m/s: plain LOS settles where
     * atan(e / L) equals the crab angle asin(0.2), e = L tan(asin 0.2) = 2.04 m */
    gd_los plain = {10, 0, 0};
    double e_plain = fly_line(&plain, &l, (gd_point){0, 0}, 0, 0.3, 300, &worst, 200);
    CHECK_NEAR(e_plain, 10 * tan(asin(0.2)), 0.1);
    gd_los ilos = {10, 0.04, 0};
    fly_line(&ilos, &l, (gd_point){0, 0}, 0, 0.3, 400, &worst, 200);
    CHECK(worst < 0.1);
    CHECK_NEAR(ilos.b, 10 * tan(asin(0.2)), 0.1); /* the learnt offset is the crab */
    /* far from the line (a turn, an approach) the offset does not integrate */
    gd_los g = {10, 0.04, 0};
    gd_los_heading(&g, &l, (gd_point){0, 8}, 1.0, NULL, NULL);
    CHECK(g.b == 0.0);
    gd_los_heading(&g, &l, (gd_point){0, 2}, 1.0, NULL, NULL);
    CHECK(g.b > 0.0);
}

void circle_following(void)
{
    gd_point c = {100, 100};
    /* far outside: towards the centre; on the circle: along the tangent */
    CHECK_NEAR(gd_circle_heading(c, 20, 1, 10, (gd_point){100, 1e6}), 1.5 * M_PI, 1e-3);
    CHECK_NEAR(gd_circle_heading(c, 20, 1, 10, (gd_point){120, 100}), M_PI / 2, 1e-12); /* north point, cw: east */
    CHECK_NEAR(gd_circle_heading(c, 20, 0, 10, (gd_point){120, 100}), 1.5 * M_PI, 1e-12);
    /* a vehicle converges onto the circle and stays on it */
    gd_point p = {0, 0};
    double psi = 0, worst = 0;
    for (double t = 0; t < 600; t += 0.1) {
        double psi_d = gd_circle_heading(c, 50, 1, 10, p);
        psi += fmax(-0.2, fmin(0.2, 0.8 * pu_wrap_pi(psi_d - psi))) * 0.1;
        p.n += 1.5 * cos(psi) * 0.1;
        p.e += 1.5 * sin(psi) * 0.1;
        if (t > 300)
            worst = fmax(worst, fabs(hypot(p.n - c.n, p.e - c.e) - 50));
    }
    CHECK(worst < 1.0);
}

static int lines_of(const char *poly, double heading, double spacing, gd_track *lines)
{
    pu_polygon a;
    char err[160];
    if (pu_polygon_parse(poly, &a, err, sizeof err) != 0) {
        fprintf(stderr, "%s\n", err);
        return -1;
    }
    return gd_survey_lines(&a, heading, spacing, lines, GD_MAX_LINES, err, sizeof err);
}

#define CHECK_POINT(p, N, E)              \
    do {                                  \
        CHECK_NEAR((p).n, N, 1e-9);       \
        CHECK_NEAR((p).e, E, 1e-9);       \
    } while (0)

void survey_lines_box(void)
{
    pu_polygon box;
    gd_track l[GD_MAX_LINES];
    char err[160];
    /* 100 m north by 50 m east at 20 m: 3 strips of 16.67 m, lines down their middles */
    gd_box_polygon(&box, (gd_point){0, 0}, 0, 100, 50);
    CHECK(gd_survey_lines(&box, 0, 20, l, GD_MAX_LINES, err, sizeof err) == 3);
    CHECK_POINT(l[0].start, 0, 50.0 / 6);
    CHECK_POINT(l[0].end, 100, 50.0 / 6);
    CHECK_POINT(l[1].start, 100, 25); /* alternating */
    CHECK_POINT(l[1].end, 0, 25);
    CHECK_POINT(l[2].start, 0, 250.0 / 6);
    /* heading east: the width lies to the south; 40 m at 20 m is 2 lines, not 3 */
    gd_box_polygon(&box, (gd_point){0, 0}, M_PI / 2, 100, 40);
    CHECK(gd_survey_lines(&box, M_PI / 2, 20, l, GD_MAX_LINES, err, sizeof err) == 2);
    CHECK_POINT(l[0].start, -10, 0);
    CHECK_POINT(l[0].end, -10, 100);
    CHECK_POINT(l[1].start, -30, 100);
    /* a box of no width is one line along it */
    gd_box_polygon(&box, (gd_point){5, 5}, M_PI / 4, 100, 0);
    CHECK(gd_survey_lines(&box, M_PI / 4, 20, l, GD_MAX_LINES, err, sizeof err) == 1);
    CHECK_POINT(l[0].start, 5, 5);
    CHECK_POINT(l[0].end, 5 + 100 / sqrt(2), 5 + 100 / sqrt(2));
    /* too many lines is an error, not a truncated survey */
    gd_box_polygon(&box, (gd_point){0, 0}, 0, 100, 1e5);
    CHECK(gd_survey_lines(&box, 0, 1, l, GD_MAX_LINES, err, sizeof err) == -1);
    CHECK_HAS(err, "more than the 500 allowed");
}

void survey_lines_polygon(void)
{
    gd_track l[GD_MAX_LINES];
    /* a right triangle, lines north-south: each runs from the south edge to the hypotenuse */
    CHECK(lines_of("0,0; 100,0; 0,100", 0, 25, l) == 4);
    CHECK_POINT(l[0].start, 0, 12.5);
    CHECK_POINT(l[0].end, 87.5, 12.5);
    CHECK_POINT(l[1].start, 62.5, 37.5);
    CHECK_POINT(l[1].end, 0, 37.5);
    CHECK_POINT(l[3].start, 12.5, 87.5);
    /* lines east-west (heading 90 deg) over the same triangle, wound the other way */
    CHECK(lines_of(" 0,0 ; 0,100; 100,0;", M_PI / 2, 50, l) == 2);
    CHECK_POINT(l[0].start, 75, 0); /* left of an eastward heading is north */
    CHECK_POINT(l[0].end, 75, 25);
    CHECK_POINT(l[1].start, 25, 75);
    CHECK_POINT(l[1].end, 25, 0);
    /* a U opening north (arms east 0-10 and 20-30 m, joined south of 10 m north),
     * lines east-west: a line through both arms spans the notch */
    CHECK(lines_of("0,0; 0,30; 100,30; 100,20; 10,20; 10,10; 100,10; 100,0", M_PI / 2, 10, l) == 10);
    CHECK_POINT(l[0].start, 95, 0);
    CHECK_POINT(l[0].end, 95, 30);
    CHECK_POINT(l[1].start, 85, 30);
    CHECK_POINT(l[9].end, 5, 0);
}
