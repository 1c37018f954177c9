/* The sampling team's rule: where along the front the team's estimate is least
 * certain, computed the same way on every vehicle from what the team shares
 * (the team's front estimate, the teammates' statuses) and its own track.
 *
 * The front's position is known where the team has crossed it and grows
 * uncertain with the distance from there: the estimator's straight fit is only
 * as good as its extrapolation, and a meander or a bend shows only where
 * someone looked. So the uncertainty of a place s along the front (s measured
 * along the estimated front from the point of it nearest the origin) is its
 * distance to the nearest "look": a recorded position within `near` of the
 * estimated front (own, every `record` seconds; a teammate's, at each status
 * heard), or where a vehicle is now (it is looking there). The extent
 * [s_from, s_to] is cut into cells, and the team's vehicles are given
 * targets in turn: the least certain cell to the vehicle nearest it, which
 * then counts as a look, the next least certain to the nearest of the rest,
 * and so on; every vehicle computes the whole assignment from the same
 * shared data and takes its own share. A target is kept until the vehicle
 * reaches it or `replan` seconds have passed, so the assignment does not
 * dither as the vehicles move. */
#ifndef TM_FRONT_RULE_H
#define TM_FRONT_RULE_H

#include "plugins/lib/pu_visibility.h"

#define TM_FR_MAX_POINTS 2048
#define TM_FR_MAX_CELLS 400

typedef struct {
    double n, e;
} tm_fr_point;

typedef struct {
    double angle, offset;   /* the estimated front: direction (rad from north) and offset to its right */
} tm_fr_front;

typedef struct {
    tm_fr_point pts[TM_FR_MAX_POINTS];   /* ring: the oldest is overwritten */
    int n, head;
    long dropped;                        /* points overwritten (a very long mission) */
} tm_fr_looks;

PU_HIDDEN void tm_fr_add(tm_fr_looks *l, double n, double e);
/* Along-front coordinate s and across-front distance x of a point. */
PU_HIDDEN double tm_fr_along(const tm_fr_front *f, double n, double e);
PU_HIDDEN double tm_fr_across(const tm_fr_front *f, double n, double e);
/* Distance along the front from s to the nearest look: the recorded points
 * within `near` of the front, and the places `extra_s` (along the front:
 * where the vehicles are now, the targets already given). Infinity with none. */
PU_HIDDEN double tm_fr_uncertainty(const tm_fr_looks *l, const tm_fr_front *f, double near, const double *extra_s,
                                   int n_extra, double s);
/* The least certain cell's centre in [s_from, s_to] (cells of `cell` metres),
 * ties to the one nearest near_s (the first, if near_s is NaN). */
PU_HIDDEN double tm_fr_pick(const tm_fr_looks *l, const tm_fr_front *f, double near, const double *extra_s,
                            int n_extra, double s_from, double s_to, double cell, double near_s);
/* The team's targets: n vehicles at along-front places pos_s (the roster's
 * order, the same on every vehicle); the least certain cell goes to the
 * vehicle nearest it, then counts as looked at, and so on until each has
 * one (ties: the lower index). targets[k] is vehicle k's. n <= 16. */
PU_HIDDEN void tm_fr_assign(const tm_fr_looks *l, const tm_fr_front *f, double near, const double *pos_s, int n,
                            double s_from, double s_to, double cell, double *targets);

#endif
