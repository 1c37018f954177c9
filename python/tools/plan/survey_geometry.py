"""Plane geometry for survey planning, in local metres (north, east).

Polygons are lists of (north, east) vertices, either orientation, convex or
concave, not self-intersecting. A survey works in a frame turned to the
line heading: `u` along the lines, `v` across them (to starboard).
"""

from __future__ import annotations

import math
import re

Point = tuple[float, float]


class GeometryError(ValueError):
    pass


def parse_polygon(text: str) -> list[Point]:
    """'n,e; n,e; ...' (metres) -> vertices; the closing vertex may be repeated."""
    pts = []
    for i, part in enumerate(p for p in re.split(r"[;\n]", text) if p.strip()):
        xy = part.replace(",", " ").split()
        if len(xy) != 2:
            raise GeometryError(f"polygon vertex {i + 1} '{part.strip()}': expected 'north,east'")
        try:
            n, e = float(xy[0]), float(xy[1])
        except ValueError:
            raise GeometryError(f"polygon vertex {i + 1} '{part.strip()}': not a number") from None
        if not (math.isfinite(n) and math.isfinite(e)):
            raise GeometryError(f"polygon vertex {i + 1}: not finite")
        pts.append((n, e))
    if len(pts) > 1 and pts[0] == pts[-1]:
        pts.pop()
    check_polygon(pts)
    return pts


def format_polygon(pts: list[Point]) -> str:
    return "; ".join(f"{n:.1f},{e:.1f}" for n, e in pts)


def area(pts: list[Point]) -> float:
    """Unsigned area (shoelace)."""
    s = 0.0
    for (x1, y1), (x2, y2) in zip(pts, pts[1:] + pts[:1]):
        s += x1 * y2 - x2 * y1
    return abs(s) / 2.0


def _segments_cross(a: Point, b: Point, c: Point, d: Point) -> bool:
    def orient(p, q, r):
        v = (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
        return (v > 1e-9) - (v < -1e-9)

    return orient(a, b, c) * orient(a, b, d) < 0 and orient(c, d, a) * orient(c, d, b) < 0


def check_polygon(pts: list[Point]) -> None:
    if len(pts) < 3:
        raise GeometryError(f"a polygon needs at least 3 vertices, got {len(pts)}")
    n = len(pts)
    edges = [(pts[i], pts[(i + 1) % n]) for i in range(n)]
    for i in range(n):
        for j in range(i + 2, n):
            if i == 0 and j == n - 1:
                continue
            if _segments_cross(*edges[i], *edges[j]):
                raise GeometryError(f"the polygon crosses itself (edges {i + 1} and {j + 1})")
    if area(pts) < 1.0:
        raise GeometryError("the polygon has (almost) no area")


class Frame:
    """Survey frame: u along the line heading, v across (starboard positive)."""

    def __init__(self, heading_rad: float) -> None:
        self.h = heading_rad
        self.ca, self.sa = math.cos(heading_rad), math.sin(heading_rad)

    def to_uv(self, p: Point) -> Point:
        n, e = p
        return (n * self.ca + e * self.sa, -n * self.sa + e * self.ca)

    def to_ne(self, q: Point) -> Point:
        u, v = q
        return (u * self.ca - v * self.sa, u * self.sa + v * self.ca)


def clip_v(poly: list[Point], lo: float, hi: float) -> list[Point]:
    """Sutherland-Hodgman clip of a (u, v) polygon to lo <= v <= hi. The area of
    the result is exact for concave polygons too (any extra edges lie on the
    clip lines and enclose nothing)."""

    def clip(pts, inside, cross):
        out = []
        for i, cur in enumerate(pts):
            prev = pts[i - 1]
            if inside(cur):
                if not inside(prev):
                    out.append(cross(prev, cur))
                out.append(cur)
            elif inside(prev):
                out.append(cross(prev, cur))
        return out

    def at(v0):
        return lambda p, q: (p[0] + (q[0] - p[0]) * (v0 - p[1]) / (q[1] - p[1]), v0)

    pts = clip(poly, lambda p: p[1] >= lo, at(lo))
    return clip(pts, lambda p: p[1] <= hi, at(hi)) if pts else []


def chord(poly: list[Point], v: float) -> list[tuple[float, float]]:
    """Intervals of u where the line v = const lies inside the (u, v) polygon."""
    us = []
    for (u1, v1), (u2, v2) in zip(poly, poly[1:] + poly[:1]):
        if (v1 <= v < v2) or (v2 <= v < v1):
            us.append(u1 + (u2 - u1) * (v - v1) / (v2 - v1))
    us.sort()
    return [(us[i], us[i + 1]) for i in range(0, len(us) - 1, 2) if us[i + 1] > us[i]]


def band_extent(poly: list[Point], lo: float, hi: float) -> list[tuple[float, float]]:
    """Intervals of u that the polygon occupies anywhere in lo <= v <= hi.

    Chords are taken at every vertex offset in the band, at its edges and just
    inside them; between two such offsets every chord end moves linearly, so
    the union of these chords is the band's extent, and a gap that is open at
    every sample stays open across the band."""
    eps = 1e-6 * max(1.0, hi - lo)
    vs = sorted(
        {lo + eps, hi - eps, (lo + hi) / 2}
        | {v for _, v in poly if lo < v < hi}
        | {v + eps for _, v in poly if lo < v + eps < hi}
        | {v - eps for _, v in poly if lo < v - eps < hi}
    )
    ivs = sorted(iv for v in vs for iv in chord(poly, v))
    merged: list[list[float]] = []
    for a, b in ivs:
        if merged and a <= merged[-1][1] + 1e-9:
            merged[-1][1] = max(merged[-1][1], b)
        else:
            merged.append([a, b])
    return [(a, b) for a, b in merged]


def split_by_area(poly_uv: list[Point], parts: int, tol: float = 1e-9) -> list[float]:
    """Across-track cuts v_0 < ... < v_parts so each strip holds area/parts."""
    vmin, vmax = min(v for _, v in poly_uv), max(v for _, v in poly_uv)
    total = area(poly_uv)
    cuts = [vmin]
    for k in range(1, parts):
        target = total * k / parts
        lo, hi = cuts[-1], vmax
        while hi - lo > tol * max(1.0, vmax - vmin):
            mid = (lo + hi) / 2
            if area(clip_v(poly_uv, vmin, mid)) < target:
                lo = mid
            else:
                hi = mid
        cuts.append((lo + hi) / 2)
    return cuts + [vmax]


def convex_hull(pts: list[Point]) -> list[Point]:
    """Andrew's monotone chain, counter-clockwise in (north, east)."""
    p = sorted(set(pts))
    if len(p) < 3:
        return p

    def half(seq):
        out: list[Point] = []
        for q in seq:
            while (
                len(out) >= 2
                and ((out[-1][0] - out[-2][0]) * (q[1] - out[-2][1]) - (out[-1][1] - out[-2][1]) * (q[0] - out[-2][0]))
                <= 0
            ):
                out.pop()
            out.append(q)
        return out

    lower, upper = half(p), half(reversed(p))
    return lower[:-1] + upper[:-1]


def buffer_convex(hull: list[Point], margin: float, segments: int = 3) -> list[Point]:
    """A convex polygon grown by `margin` (corners rounded with a few vertices)."""
    out: list[Point] = []
    n = len(hull)
    sign = (
        1.0
        if sum(hull[i][0] * hull[(i + 1) % n][1] - hull[(i + 1) % n][0] * hull[i][1] for i in range(n)) > 0
        else -1.0
    )
    for i in range(n):
        prev, cur, nxt = hull[i - 1], hull[i], hull[(i + 1) % n]
        a0 = math.atan2(cur[1] - prev[1], cur[0] - prev[0]) - sign * math.pi / 2
        a1 = math.atan2(nxt[1] - cur[1], nxt[0] - cur[0]) - sign * math.pi / 2
        d = (a1 - a0 + math.pi) % (2 * math.pi) - math.pi
        for k in range(segments + 1):
            a = a0 + d * k / segments
            q = (cur[0] + margin * math.cos(a), cur[1] + margin * math.sin(a))
            if not out or math.dist(out[-1], q) > 0.5:  # a straight corner adds one point, not several
                out.append(q)
    return out if math.dist(out[0], out[-1]) > 0.5 else out[:-1]


def simplify_convex_outer(poly: list[Point], max_vertices: int) -> list[Point]:
    """A convex polygon with at most max_vertices vertices that contains poly
    (itself convex): repeatedly drop the edge whose two neighbours, extended
    until they meet, add the least area. Growing, never cutting, keeps every
    margin the caller built into poly. GeometryError if it cannot get there."""
    if max_vertices < 3:
        raise GeometryError(f"a polygon limit of {max_vertices} vertices is below 3")
    pts = list(poly)
    if sum(a[0] * b[1] - b[0] * a[1] for a, b in zip(pts, pts[1:] + pts[:1])) < 0:
        pts.reverse()  # counter-clockwise in (north, east)
    while len(pts) > max_vertices:
        n, best = len(pts), None
        for i in range(n):
            p0, p1, p2, p3 = pts[i - 1], pts[i], pts[(i + 1) % n], pts[(i + 2) % n]
            d1 = (p1[0] - p0[0], p1[1] - p0[1])
            d2 = (p2[0] - p3[0], p2[1] - p3[1])
            den = d1[0] * d2[1] - d1[1] * d2[0]
            if abs(den) < 1e-12:
                continue
            # p1 + s d1 = p2 + t d2, with s, t >= 0: the extensions meet beyond the edge
            s = ((p2[0] - p1[0]) * d2[1] - (p2[1] - p1[1]) * d2[0]) / den
            t = ((p2[0] - p1[0]) * d1[1] - (p2[1] - p1[1]) * d1[0]) / den
            if s < 0 or t < 0:
                continue
            x = (p1[0] + s * d1[0], p1[1] + s * d1[1])
            added = area([p1, x, p2])
            if best is None or added < best[0]:
                best = (added, i, x)
        if best is None:
            raise GeometryError(f"cannot bound the operating area by {max_vertices} vertices")
        _, i, x = best
        if i + 1 < n:
            pts[i : i + 2] = [x]
        else:  # the edge from the last vertex to the first
            pts = [x] + pts[1:-1]
    return pts
