#include "tm_keepclear.h"

#include <math.h>

tm_track tm_track_advance(tm_track a, double dt)
{
    a.n += a.speed * cos(a.heading) * dt;
    a.e += a.speed * sin(a.heading) * dt;
    return a;
}

double tm_cpa(tm_track a, tm_track b, double horizon, double *t_cpa)
{
    double dn = b.n - a.n, de = b.e - a.e;
    double vn = b.speed * cos(b.heading) - a.speed * cos(a.heading);
    double ve = b.speed * sin(b.heading) - a.speed * sin(a.heading);
    double vv = vn * vn + ve * ve;
    double t = vv > 1e-12 ? -(dn * vn + de * ve) / vv : 0.0;
    if (t < 0.0)
        t = 0.0;
    if (t > horizon)
        t = horizon;
    if (t_cpa)
        *t_cpa = t;
    return hypot(dn + vn * t, de + ve * t);
}
