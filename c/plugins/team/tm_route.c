#include "tm_route.h"

#include <math.h>
#include <string.h>

static double dist(gd_point a, gd_point b) { return hypot(a.n - b.n, a.e - b.e); }

/* The point at route position k (k = -1 is the start). */
static gd_point at(gd_point start, const gd_point *pts, const int *r, int k) { return k < 0 ? start : pts[r[k]]; }

static void cheapest_insertion(gd_point start, const gd_point *pts, int n, int *r)
{
    unsigned char used[TM_ROUTE_MAX] = {0};
    for (int len = 0; len < n; len++) {
        int best_p = -1, best_pos = 0;
        double best = INFINITY;
        for (int p = 0; p < n; p++) {
            if (used[p])
                continue;
            for (int pos = 0; pos <= len; pos++) {
                gd_point prev = at(start, pts, r, pos - 1);
                double add = dist(prev, pts[p]);
                if (pos < len)
                    add += dist(pts[p], pts[r[pos]]) - dist(prev, pts[r[pos]]);
                if (add < best - 1e-9) {
                    best = add;
                    best_p = p;
                    best_pos = pos;
                }
            }
        }
        memmove(r + best_pos + 1, r + best_pos, (size_t)(len - best_pos) * sizeof *r);
        r[best_pos] = best_p;
        used[best_p] = 1;
    }
}

/* 2-opt on an open path with a fixed start: reversing r[i..j] replaces the
 * edges (i-1, i) and (j, j+1) by (i-1, j) and (i, j+1); at the open end
 * there is no edge (j, j+1). */
static void two_opt(gd_point start, const gd_point *pts, int n, int *r)
{
    for (int improved = 1, rounds = 0; improved && rounds < 100; rounds++) {
        improved = 0;
        for (int i = 0; i < n - 1; i++) {
            for (int j = i + 1; j < n; j++) {
                gd_point a = at(start, pts, r, i - 1), b = pts[r[i]], c = pts[r[j]];
                double before = dist(a, b), after = dist(a, c);
                if (j + 1 < n) {
                    gd_point d = pts[r[j + 1]];
                    before += dist(c, d);
                    after += dist(b, d);
                }
                if (after < before - 1e-9) {
                    for (int x = i, y = j; x < y; x++, y--) {
                        int t = r[x];
                        r[x] = r[y];
                        r[y] = t;
                    }
                    improved = 1;
                }
            }
        }
    }
}

/* Or-opt: move a stretch of 1 to 3 targets (either way round) to the place
 * where it adds the least, when that shortens the path. 2-opt alone cannot
 * move one target to another part of the route without reversing all that
 * lies between. Returns 1 if it moved something. */
static int or_opt(gd_point start, const gd_point *pts, int n, int *r)
{
    int moved = 0;
    for (int len = 1; len <= 3; len++) {
        for (int i = 0; i + len <= n; i++) {
            gd_point prev = at(start, pts, r, i - 1), first = pts[r[i]], last = pts[r[i + len - 1]];
            double gain = dist(prev, first);
            if (i + len < n)
                gain += dist(last, pts[r[i + len]]) - dist(prev, pts[r[i + len]]);
            int best_k = -2, best_rev = 0;
            double best = gain - 1e-9;
            for (int k = -1; k < n; k++) {   /* insert after route position k (-1: after the start) */
                if (k >= i - 1 && k < i + len)
                    continue;
                int kn = k + 1 == i ? i + len : k + 1;   /* the successor once the stretch is out */
                gd_point a = at(start, pts, r, k);
                double fwd = dist(a, first), rev = dist(a, last);
                if (kn < n) {
                    gd_point b = pts[r[kn]];
                    fwd += dist(last, b) - dist(a, b);
                    rev += dist(first, b) - dist(a, b);
                }
                if (fwd < best) {
                    best = fwd;
                    best_k = k;
                    best_rev = 0;
                }
                if (rev < best) {
                    best = rev;
                    best_k = k;
                    best_rev = 1;
                }
            }
            if (best_k == -2)
                continue;
            int seg[3], out[TM_ROUTE_MAX], m = 0;
            for (int j = 0; j < len; j++)
                seg[j] = r[best_rev ? i + len - 1 - j : i + j];
            if (best_k == -1)
                for (int j = 0; j < len; j++)
                    out[m++] = seg[j];
            for (int k = 0; k < n; k++) {
                if (k >= i && k < i + len)
                    continue;
                out[m++] = r[k];
                if (k == best_k)
                    for (int j = 0; j < len; j++)
                        out[m++] = seg[j];
            }
            memcpy(r, out, (size_t)n * sizeof *r);
            moved = 1;
        }
    }
    return moved;
}

void tm_route_plan(gd_point start, const gd_point *pts, int n, int *order)
{
    if (n > TM_ROUTE_MAX)
        n = TM_ROUTE_MAX;
    cheapest_insertion(start, pts, n, order);
    for (int rounds = 0; rounds < 20; rounds++) {
        two_opt(start, pts, n, order);
        if (!or_opt(start, pts, n, order))
            break;
    }
}

void tm_route_nearest(gd_point start, const gd_point *pts, int n, int *order)
{
    unsigned char used[TM_ROUTE_MAX] = {0};
    gd_point here = start;
    for (int k = 0; k < n && k < TM_ROUTE_MAX; k++) {
        int best = -1;
        double bd = INFINITY;
        for (int p = 0; p < n; p++)
            if (!used[p] && dist(here, pts[p]) < bd - 1e-9) {
                bd = dist(here, pts[p]);
                best = p;
            }
        used[best] = 1;
        order[k] = best;
        here = pts[best];
    }
}

double tm_route_length(gd_point start, const gd_point *pts, const int *order, int n)
{
    double s = 0.0;
    gd_point here = start;
    for (int k = 0; k < n; k++) {
        s += dist(here, pts[order[k]]);
        here = pts[order[k]];
    }
    return s;
}
