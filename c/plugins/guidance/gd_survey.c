#include "gd_survey.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

int gd_polygon_parse(const char *text, gd_polygon *out, char *err, size_t errlen)
{
    out->n = 0;
    const char *p = text;
    for (int k = 1;; k++) {
        char *end;
        double n = strtod(p, &end);
        const char *q = end;
        while (isspace((unsigned char)*q))
            q++;
        if (end == p || *q != ',') {
            snprintf(err, errlen, "polygon vertex %d: expected 'north,east' in metres at \"%.20s\"", k, p);
            return -1;
        }
        p = q + 1;
        double e = strtod(p, &end);
        if (end == p) {
            snprintf(err, errlen, "polygon vertex %d: expected a number after ',' at \"%.20s\"", k, p);
            return -1;
        }
        if (!isfinite(n) || !isfinite(e)) {
            snprintf(err, errlen, "polygon vertex %d is not finite", k);
            return -1;
        }
        if (out->n == GD_MAX_VERTICES) {
            snprintf(err, errlen, "polygon has more than %d vertices", GD_MAX_VERTICES);
            return -1;
        }
        out->v[out->n++] = (gd_point){n, e};
        p = end;
        while (isspace((unsigned char)*p))
            p++;
        if (*p == '\0')
            break;
        if (*p != ';') {
            snprintf(err, errlen, "polygon vertex %d: expected ';' before the next vertex at \"%.20s\"", k, p);
            return -1;
        }
        p++;
        while (isspace((unsigned char)*p))
            p++;
        if (*p == '\0')
            break; /* a trailing ';' */
    }
    if (out->n > 1 && out->v[0].n == out->v[out->n - 1].n && out->v[0].e == out->v[out->n - 1].e)
        out->n--;
    if (out->n < 3) {
        snprintf(err, errlen, "a polygon needs at least 3 vertices, got %d", out->n);
        return -1;
    }
    return 0;
}

void gd_polygon_box(gd_polygon *out, gd_point c, double heading, double length, double width)
{
    double tn = cos(heading), te = sin(heading); /* along the heading */
    double rn = -te, re = tn;                    /* to its right */
    out->n = 4;
    out->v[0] = c;
    out->v[1] = (gd_point){c.n + length * tn, c.e + length * te};
    out->v[2] = (gd_point){c.n + length * tn + width * rn, c.e + length * te + width * re};
    out->v[3] = (gd_point){c.n + width * rn, c.e + width * re};
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

int gd_survey_lines(const gd_polygon *area, double heading, double spacing, gd_track *lines, int max, char *err,
                    size_t errlen)
{
    double x[GD_MAX_VERTICES], y[GD_MAX_VERTICES];
    double ymin = INFINITY, ymax = -INFINITY, xmin = INFINITY, xmax = -INFINITY;
    for (int i = 0; i < area->n; i++) {
        to_frame(area->v[i], heading, &x[i], &y[i]);
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
