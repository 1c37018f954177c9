#include "gd_geometry.h"

#include <math.h>

#include "plugins/lib/pu_angle.h"

void gd_line_make(gd_line *l, gd_point a, gd_point b)
{
    l->a = a;
    l->b = b;
    double dn = b.n - a.n, de = b.e - a.e;
    l->length = hypot(dn, de);
    if (l->length > 1e-9) {
        l->tn = dn / l->length;
        l->te = de / l->length;
    } else {
        l->tn = 1.0;
        l->te = 0.0;
    }
    l->course = pu_wrap_2pi(atan2(l->te, l->tn));
}

void gd_line_frame(const gd_line *l, gd_point p, double *along, double *cross)
{
    double dn = p.n - l->a.n, de = p.e - l->a.e;
    if (along)
        *along = dn * l->tn + de * l->te;
    /* right of the direction of travel: t rotated 90 degrees clockwise = (-te, tn) */
    if (cross)
        *cross = -dn * l->te + de * l->tn;
}

double gd_los_heading(gd_los *g, const gd_line *l, gd_point p, double dt, double *along, double *cross)
{
    double s, e;
    gd_line_frame(l, p, &s, &e);
    double L = g->lookahead;
    /* conditional integration: only near the line, so the transient of a
     * turn or a re-acquisition does not wind the offset up */
    if (g->ki > 0.0 && dt > 0.0 && fabs(e) < 0.5 * L) {
        double q = e + g->b;
        g->b += dt * g->ki * e * L * L / (L * L + q * q);
        g->b = fmax(-L, fmin(L, g->b));
    }
    if (along)
        *along = s;
    if (cross)
        *cross = e;
    return pu_wrap_2pi(l->course - atan((e + g->b) / L));
}

double gd_circle_heading(gd_point c, double r, int cw, double lookahead, gd_point p)
{
    double dn = p.n - c.n, de = p.e - c.e;
    double d = hypot(dn, de);
    double bearing = atan2(de, dn); /* from the centre out to p */
    double turn = M_PI / 2.0 + atan((d - r) / lookahead);
    return pu_wrap_2pi(cw ? bearing + turn : bearing - turn);
}
