/* Route through the RI vehicle's target queue: an open path from the
 * vehicle's position through every target (it does not return). Built by
 * cheapest insertion (each step inserts the target, at the place, that adds
 * the least length), then improved by 2-opt (reversing a stretch while that
 * shortens the path) and Or-opt (moving a stretch of up to 3 targets
 * elsewhere) until neither helps. Deterministic: ties go to the lower index, so the same
 * queue gives the same route on every run. Nearest-neighbour is here only as
 * the yardstick the tests compare against. */
#ifndef TM_ROUTE_H
#define TM_ROUTE_H

#include "plugins/lib/gd_geometry.h"

#define TM_ROUTE_MAX 256

/* order receives a permutation of 0..n-1 (n <= TM_ROUTE_MAX). */
PU_HIDDEN void tm_route_plan(gd_point start, const gd_point *pts, int n, int *order);
PU_HIDDEN void tm_route_nearest(gd_point start, const gd_point *pts, int n, int *order);
PU_HIDDEN double tm_route_length(gd_point start, const gd_point *pts, const int *order, int n);

#endif
