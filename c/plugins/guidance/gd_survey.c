#include "gd_survey.h"

#include <math.h>
#include <stdio.h>

void gd_box_polygon(pu_polygon *out, gd_point c, double heading, double length, double width)
{
    double tn = cos(heading), te = sin(heading); /* along the heading */
    double rn = -te, re = tn;                    /* to its right */
    const double n[4] = {c.n, c.n + length * tn, c.n + length * tn + width * rn, c.n + width * rn};
    const double e[4] = {c.e, c.e + length * te, c.e + length * te + width * re, c.e + width * re};
    out->n = 4;
    for (int i = 0; i < 4; i++) {
        out->north[i] = n[i];
        out->east[i] = e[i];
    }
}

/* The survey frame: x along the heading, y to its right. */
static void to_frame(gd_point p, double heading, double *x, double *y)
{
    *x = p.n * cos(heading) + p.e * sin(heading);
    *y = -p.n * sin(heading) + p.e * cos(heading);
}

static gd_point from_frame(double x, double y, double heading)
{
    return (gd_point){x * cos(heading) - y * sin(heading), x * sin(heading) + y * cos(heading)};
}

int gd_survey_lines(const pu_polygon *area, double heading, double spacing, gd_track *lines, int max, char *err,
                    size_t errlen)
{
    double x[PU_POLYGON_MAX], y[PU_POLYGON_MAX];
    double ymin = INFINITY, ymax = -INFINITY, xmin = INFINITY, xmax = -INFINITY;
    for (int i = 0; i < area->n; i++) {
        to_frame((gd_point){area->north[i], area->east[i]}, heading, &x[i], &y[i]);
        ymin = fmin(ymin, y[i]);
        ymax = fmax(ymax, y[i]);
        xmin = fmin(xmin, x[i]);
        xmax = fmax(xmax, x[i]);
    }
    double extent = ymax - ymin;
    /* the fewest equal strips no wider than spacing (a hair of slack so that
     * width = k * spacing gives k strips, not k + 1) */
    double strips = fmax(1.0, ceil(extent / spacing - 1e-9));
    if (strips > max) {
        snprintf(err, errlen, "the area is %.0f m across: %.0f lines at %g m spacing, more than the %d allowed",
                 extent, strips, spacing, max);
        return -1;
    }
    int n = (int)strips;
    for (int k = 0; k < n; k++) {
        double yk = ymin + (k + 0.5) * extent / n;
        double lo = INFINITY, hi = -INFINITY;
        if (extent < 1e-9) { /* a degenerate area: one line along it */
            lo = xmin;
            hi = xmax;
        }
        for (int i = 0; i < area->n; i++) {
            int j = (i + 1) % area->n;
            /* half-open test, so a vertex on the line is counted once */
            if ((y[i] <= yk && yk < y[j]) || (y[j] <= yk && yk < y[i])) {
                double xc = x[i] + (yk - y[i]) * (x[j] - x[i]) / (y[j] - y[i]);
                lo = fmin(lo, xc);
                hi = fmax(hi, xc);
            }
        }
        gd_point a = from_frame(lo, yk, heading), b = from_frame(hi, yk, heading);
        lines[k] = k % 2 == 0 ? (gd_track){a, b} : (gd_track){b, a};
    }
    return n;
}
