#include "tm_front_rule.h"

#include <math.h>

void tm_fr_add(tm_fr_looks *l, double n, double e)
{
    if (!isfinite(n) || !isfinite(e))
        return;
    if (l->n < TM_FR_MAX_POINTS) {
        l->pts[(l->head + l->n++) % TM_FR_MAX_POINTS] = (tm_fr_point){n, e};
        return;
    }
    l->pts[l->head] = (tm_fr_point){n, e};
    l->head = (l->head + 1) % TM_FR_MAX_POINTS;
    l->dropped++;
}

double tm_fr_along(const tm_fr_front *f, double n, double e) { return n * cos(f->angle) + e * sin(f->angle); }

double tm_fr_across(const tm_fr_front *f, double n, double e)
{
    return -n * sin(f->angle) + e * cos(f->angle) - f->offset;
}

double tm_fr_uncertainty(const tm_fr_looks *l, const tm_fr_front *f, double near, const double *extra_s,
                         int n_extra, double s)
{
    double best = INFINITY;
    for (int i = 0; i < l->n; i++) {
        const tm_fr_point *p = &l->pts[(l->head + i) % TM_FR_MAX_POINTS];
        if (fabs(tm_fr_across(f, p->n, p->e)) > near)
            continue;   /* not a look at the front (transit, or the front was elsewhere) */
        best = fmin(best, fabs(tm_fr_along(f, p->n, p->e) - s));
    }
    for (int i = 0; i < n_extra; i++)
        if (isfinite(extra_s[i]))
            best = fmin(best, fabs(extra_s[i] - s));
    return best;
}

double tm_fr_pick(const tm_fr_looks *l, const tm_fr_front *f, double near, const double *extra_s, int n_extra,
                  double s_from, double s_to, double cell, double near_s)
{
    int cells = (int)ceil((s_to - s_from) / cell);
    if (cells < 1)
        cells = 1;
    if (cells > TM_FR_MAX_CELLS)
        cells = TM_FR_MAX_CELLS;
    double width = (s_to - s_from) / cells;
    double best_s = s_from + width / 2, best_u = -1, best_d = INFINITY;
    for (int k = 0; k < cells; k++) {
        double s = s_from + (k + 0.5) * width;
        double u = fmin(tm_fr_uncertainty(l, f, near, extra_s, n_extra, s), 1e9);   /* no look at all: all tie */
        double d = isnan(near_s) ? 0.0 : fabs(s - near_s);
        /* a tie within a tenth of a cell goes to the nearer cell: no long trip for nothing */
        if (u > best_u + 0.1 * width || (fabs(u - best_u) <= 0.1 * width && d < best_d))
            best_s = s, best_u = u, best_d = d;
    }
    return best_s;
}

void tm_fr_assign(const tm_fr_looks *l, const tm_fr_front *f, double near, const double *pos_s, int n, double s_from,
                  double s_to, double cell, double *targets)
{
    double extra[32];
    int n_extra = 0, given[16] = {0};
    if (n > 16)
        n = 16;
    for (int k = 0; k < n; k++)
        extra[n_extra++] = pos_s[k];   /* every vehicle looks where it is */
    for (int round = 0; round < n; round++) {
        double c = tm_fr_pick(l, f, near, extra, n_extra, s_from, s_to, cell, NAN);
        int who = -1;
        for (int k = 0; k < n; k++)
            if (!given[k] && (who < 0 || fabs(pos_s[k] - c) < fabs(pos_s[who] - c)))
                who = k;
        targets[who] = c;
        given[who] = 1;
        extra[n_extra++] = c;
    }
}
