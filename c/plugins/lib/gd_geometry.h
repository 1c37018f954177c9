/* Horizontal guidance geometry in the local NED plane (metres, radians,
 * headings clockwise from north), shared by the plugins that steer (guidance,
 * team): a path line's frame, the
 * integral line-of-sight (ILOS) law and circle following (angles wrap with
 * plugins/lib/pu_angle.h). Pure functions and
 * small state structs, so the unit tests can drive them without an engine. */
#ifndef GD_GEOMETRY_H
#define GD_GEOMETRY_H

#include "plugins/lib/pu_visibility.h"

typedef struct {
    double n, e;
} gd_point;

/* A directed straight path from a to b. */
typedef struct {
    gd_point a, b;
    double length;   /* |b - a| */
    double course;   /* direction a -> b, [0, 2pi) */
    double tn, te;   /* unit vector a -> b (north if a == b) */
} gd_line;

PU_HIDDEN void gd_line_make(gd_line *l, gd_point a, gd_point b);
/* Position of p in the line's frame: along-track from a (positive towards b)
 * and cross-track (positive to the right of the direction of travel). */
PU_HIDDEN void gd_line_frame(const gd_line *l, gd_point p, double *along, double *cross);

/* Integral line-of-sight guidance (after Borhaug, Pavlov and Pettersen 2008):
 *
 *   heading_d = course - atan((e + b) / L)
 *   db/dt     = ki * e * L^2 / (L^2 + (e + b)^2),   |b| <= L
 *
 * e is the cross-track error, L the lookahead distance and b an integral
 * offset that learns the crab angle a steady cross current needs (plain LOS,
 * ki = 0, leaves e = L tan(crab) in a current). The offset integrates only
 * within L/2 of the line (a turn or a re-acquisition does not wind it up) and
 * slows down further out; |b| <= L bounds the crab it can learn to 45 degrees. */
typedef struct {
    double lookahead;   /* L [m], > 0 */
    double ki;          /* integral rate [1/s], >= 0 */
    double b;           /* integral offset [m] */
} gd_los;

/* Desired heading [0, 2pi) for position p on line l; advances the integral by
 * dt seconds. along/cross (may be NULL) receive p's position in the frame. */
PU_HIDDEN double gd_los_heading(gd_los *g, const gd_line *l, gd_point p, double dt, double *along, double *cross);

/* Circle following: the heading that converges onto the circle of radius r
 * around c and runs along it (clockwise seen from above when cw != 0):
 *
 *   heading_d = bearing(c -> p) +- (pi/2 + atan((d - r) / L))
 *
 * d is p's distance from c; far outside it points at the centre, on the circle
 * along the tangent, at the centre across it. */
PU_HIDDEN double gd_circle_heading(gd_point c, double r, int cw, double lookahead, gd_point p);

#endif
