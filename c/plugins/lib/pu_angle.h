/* pu_angle.h: angle wrapping for plugins (c/plugins/lib, linked into every plugin).
 *
 * Angles are radians. Headings on the blackboard are [0, 2pi) clockwise from
 * north (nav_solution_t, setpoint_t); errors between two angles must be taken
 * the short way round, which is what pu_angle_diff does. */
#ifndef PU_ANGLE_H
#define PU_ANGLE_H

#include "plugins/lib/pu_visibility.h"

#define PU_PI 3.14159265358979323846

/* a wrapped into (-pi, pi]. Finite input gives finite output; NaN stays NaN. */
PU_HIDDEN double pu_wrap_pi(double a);
/* a wrapped into [0, 2pi): a heading. */
PU_HIDDEN double pu_wrap_2pi(double a);
/* The signed smallest rotation from b to a, in (-pi, pi]: a - b the short way
 * (pu_angle_diff(0.1, 2pi - 0.1) = 0.2). */
PU_HIDDEN double pu_angle_diff(double a, double b);

#endif
