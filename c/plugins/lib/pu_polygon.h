/* pu_polygon.h: polygons in the local north/east frame, written in plans as
 * strings (c/plugins/lib, linked into every plugin).
 *
 * Text form: vertices "north,east" in metres separated by ';', e.g.
 *   "0,0; 0,500; 300,500; 300,0"
 * At least 3 and at most PU_POLYGON_MAX vertices, in either winding order;
 * the last vertex joins the first (do not repeat it). Whitespace is free.
 * Rejected: anything not a number, missing commas, non-finite values, fewer
 * than 3 vertices, repeated consecutive vertices, zero area, edges that
 * cross or touch each other, and spikes (an edge folding back onto the one
 * before): such an outline has no clear inside. */
#ifndef PU_POLYGON_H
#define PU_POLYGON_H

#include <stddef.h>

#include "plugins/lib/pu_visibility.h"

#define PU_POLYGON_MAX 64

typedef struct {
    int n;
    double north[PU_POLYGON_MAX];
    double east[PU_POLYGON_MAX];
} pu_polygon;

/* Parses text into out. Returns 0, or -1 with a one-line reason in err that
 * names the vertex (1-based) or the character position where it went wrong. */
PU_HIDDEN int pu_polygon_parse(const char *text, pu_polygon *out, char *err, size_t errlen);
/* An axis-aligned box from a corner and its extents (length north, width
 * east, both > 0) as a 4-vertex polygon. */
PU_HIDDEN void pu_polygon_box(pu_polygon *out, double north, double east, double length, double width);
/* 1 if (north, east) is inside or on the boundary (within 1e-9 m). */
PU_HIDDEN int pu_polygon_contains(const pu_polygon *p, double north, double east);
/* Distance [m] from (north, east) to the nearest edge (>= 0, inside or out). */
PU_HIDDEN double pu_polygon_edge_distance(const pu_polygon *p, double north, double east);
/* Signed area [m^2]: positive when the outline runs counter-clockwise on a
 * map (north up, east right), e.g. east, then north, then west. */
PU_HIDDEN double pu_polygon_signed_area(const pu_polygon *p);

#endif
