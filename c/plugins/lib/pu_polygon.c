#include "plugins/lib/pu_polygon.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static const char *skip_space(const char *s)
{
    while (isspace((unsigned char)*s))
        s++;
    return s;
}

/* One number; returns the end or NULL (err filled). */
static const char *number(const char *text, const char *s, double *out, const char *what, int vertex, char *err,
                          size_t el)
{
    s = skip_space(s);
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s) {
        snprintf(err, el, "vertex %d: expected the %s coordinate (a number in metres) at character %d", vertex, what,
                 (int)(s - text) + 1);
        return NULL;
    }
    if (!isfinite(v) || errno == ERANGE) {
        snprintf(err, el, "vertex %d: the %s coordinate is not a finite number", vertex, what);
        return NULL;
    }
    *out = v;
    return end;
}

/* Orientation of (a, b, c): > 0 counter-clockwise (east, north axes). */
static double cross(double an, double ae, double bn, double be, double cn, double ce)
{
    return (be - ae) * (cn - an) - (bn - an) * (ce - ae);
}

/* c lies on segment a-b (given that a, b, c are collinear). */
static int on_segment(double an, double ae, double bn, double be, double cn, double ce)
{
    return fmin(an, bn) <= cn && cn <= fmax(an, bn) && fmin(ae, be) <= ce && ce <= fmax(ae, be);
}

/* Edges i and j (not neighbours) cross or touch: either way the outline has
 * no clear inside. */
static int edges_meet(const pu_polygon *p, int i, int j)
{
    int i2 = (i + 1) % p->n, j2 = (j + 1) % p->n;
    const double *N = p->north, *E = p->east;
    double d1 = cross(N[i], E[i], N[i2], E[i2], N[j], E[j]);
    double d2 = cross(N[i], E[i], N[i2], E[i2], N[j2], E[j2]);
    double d3 = cross(N[j], E[j], N[j2], E[j2], N[i], E[i]);
    double d4 = cross(N[j], E[j], N[j2], E[j2], N[i2], E[i2]);
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
        return 1;
    return (d1 == 0 && on_segment(N[i], E[i], N[i2], E[i2], N[j], E[j])) ||
           (d2 == 0 && on_segment(N[i], E[i], N[i2], E[i2], N[j2], E[j2])) ||
           (d3 == 0 && on_segment(N[j], E[j], N[j2], E[j2], N[i], E[i])) ||
           (d4 == 0 && on_segment(N[j], E[j], N[j2], E[j2], N[i2], E[i2]));
}

/* Edge i and the next one turn back onto each other (a spike). */
static int folds_back(const pu_polygon *p, int i)
{
    int b = (i + 1) % p->n, c = (i + 2) % p->n;
    const double *N = p->north, *E = p->east;
    double dot = (N[b] - N[i]) * (N[c] - N[b]) + (E[b] - E[i]) * (E[c] - E[b]);
    return cross(N[i], E[i], N[b], E[b], N[c], E[c]) == 0 && dot < 0;
}

int pu_polygon_parse(const char *text, pu_polygon *out, char *err, size_t el)
{
    out->n = 0;
    if (!text) {
        snprintf(err, el, "no polygon given");
        return -1;
    }
    const char *s = skip_space(text);
    if (!*s) {
        snprintf(err, el, "the polygon is empty: write vertices as \"north,east; north,east; ...\" in metres");
        return -1;
    }
    for (;;) {
        int k = out->n + 1;
        if (out->n == PU_POLYGON_MAX) {
            snprintf(err, el, "more than %d vertices", PU_POLYGON_MAX);
            return -1;
        }
        double n, e;
        if (!(s = number(text, s, &n, "north", k, err, el)))
            return -1;
        s = skip_space(s);
        if (*s != ',') {
            snprintf(err, el, "vertex %d: expected ',' between north and east at character %d", k, (int)(s - text) + 1);
            return -1;
        }
        if (!(s = number(text, s + 1, &e, "east", k, err, el)))
            return -1;
        out->north[out->n] = n;
        out->east[out->n] = e;
        out->n++;
        s = skip_space(s);
        if (*s == ';') {
            s = skip_space(s + 1);
            if (!*s) /* a trailing ';' is harmless */
                break;
            continue;
        }
        if (!*s)
            break;
        snprintf(err, el, "vertex %d: expected ';' before the next vertex at character %d", k, (int)(s - text) + 1);
        return -1;
    }
    if (out->n < 3) {
        snprintf(err, el, "a polygon needs at least 3 vertices, %d given", out->n);
        return -1;
    }
    for (int i = 0; i < out->n; i++) {
        int j = (i + 1) % out->n;
        if (out->north[i] == out->north[j] && out->east[i] == out->east[j]) {
            snprintf(err, el, "vertices %d and %d are the same point (do not repeat the first vertex at the end)",
                     i + 1, j + 1);
            return -1;
        }
    }
    int collinear = 1;
    for (int i = 2; i < out->n && collinear; i++)
        collinear = cross(out->north[0], out->east[0], out->north[1], out->east[1], out->north[i], out->east[i]) == 0;
    if (collinear) {
        snprintf(err, el, "the polygon has no area (its vertices are on one line)");
        return -1;
    }
    for (int i = 0; i < out->n; i++) {
        if (folds_back(out, i)) {
            snprintf(err, el, "edges %d-%d and %d-%d fold back onto each other", i + 1, (i + 1) % out->n + 1,
                     (i + 1) % out->n + 1, (i + 2) % out->n + 1);
            return -1;
        }
        for (int j = i + 2; j < out->n; j++) {
            if (i == 0 && j == out->n - 1)
                continue; /* neighbours share a vertex */
            if (edges_meet(out, i, j)) {
                snprintf(err, el, "edges %d-%d and %d-%d cross: the outline must not touch or cross itself", i + 1,
                         (i + 1) % out->n + 1, j + 1, (j + 1) % out->n + 1);
                return -1;
            }
        }
    }
    if (fabs(pu_polygon_signed_area(out)) < 1e-9) {
        snprintf(err, el, "the polygon has no area (its vertices are on one line)");
        return -1;
    }
    return 0;
}

void pu_polygon_box(pu_polygon *out, double north, double east, double length, double width)
{
    out->n = 4;
    const double n[4] = {north, north + length, north + length, north};
    const double e[4] = {east, east, east + width, east + width};
    for (int i = 0; i < 4; i++) {
        out->north[i] = n[i];
        out->east[i] = e[i];
    }
}

double pu_polygon_signed_area(const pu_polygon *p)
{
    double a = 0.0;
    for (int i = 0; i < p->n; i++) {
        int j = (i + 1) % p->n;
        a += p->east[i] * p->north[j] - p->east[j] * p->north[i];
    }
    return 0.5 * a;
}

static double segment_distance(double pn, double pe, double an, double ae, double bn, double be)
{
    double dn = bn - an, de = be - ae;
    double len2 = dn * dn + de * de;
    double t = len2 > 0.0 ? ((pn - an) * dn + (pe - ae) * de) / len2 : 0.0;
    t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
    return hypot(pn - (an + t * dn), pe - (ae + t * de));
}

double pu_polygon_edge_distance(const pu_polygon *p, double north, double east)
{
    double best = INFINITY;
    for (int i = 0; i < p->n; i++) {
        int j = (i + 1) % p->n;
        best = fmin(best, segment_distance(north, east, p->north[i], p->east[i], p->north[j], p->east[j]));
    }
    return best;
}

int pu_polygon_contains(const pu_polygon *p, double north, double east)
{
    if (!isfinite(north) || !isfinite(east))
        return 0;
    if (pu_polygon_edge_distance(p, north, east) <= 1e-9)
        return 1;
    /* even-odd ray cast towards +east */
    int inside = 0;
    for (int i = 0, j = p->n - 1; i < p->n; j = i++) {
        if ((p->north[i] > north) != (p->north[j] > north)) {
            double e_at = p->east[j] + (north - p->north[j]) * (p->east[i] - p->east[j]) / (p->north[i] - p->north[j]);
            if (east < e_at)
                inside = !inside;
        }
    }
    return inside;
}
