#include "plugins/lib/pu_angle.h"

#include <math.h>

double pu_wrap_2pi(double a)
{
    double w = fmod(a, 2.0 * PU_PI);
    if (w < 0.0)
        w += 2.0 * PU_PI;
    /* fmod of a tiny negative number plus 2pi rounds to exactly 2pi */
    return w >= 2.0 * PU_PI ? 0.0 : w;
}

double pu_wrap_pi(double a)
{
    double w = pu_wrap_2pi(a);
    return w > PU_PI ? w - 2.0 * PU_PI : w;
}

double pu_angle_diff(double a, double b) { return pu_wrap_pi(a - b); }
