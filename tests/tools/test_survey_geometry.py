"""Survey planner geometry, checked by rasterising: every point of the polygon
seen by a sidescan swath (also with lines pushed off track by the overlap
margin), equal areas per vehicle, convex and concave polygons, bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tools.plan.survey_geometry import GeometryError, area, parse_polygon
from tools.plan.survey_plan import Sonar, plan_survey

CONVEX = [(0, 0), (400, -60), (520, 250), (200, 420), (-30, 300)]
L_SHAPE = [(0, 0), (600, 0), (600, 150), (200, 150), (200, 450), (0, 450)]
U_SHAPE = [(0, 0), (500, 0), (500, 400), (0, 400), (0, 280), (350, 280), (350, 120), (0, 120)]


def inside(poly, pts):
    """Even-odd rule, written here independently of the planner."""
    x, y = pts[:, 0], pts[:, 1]
    res = np.zeros(len(pts), bool)
    for (x1, y1), (x2, y2) in zip(poly, poly[1:] + poly[:1]):
        crosses = (y1 > y) != (y2 > y)
        with np.errstate(divide="ignore", invalid="ignore"):
            xc = x1 + (y - y1) * (x2 - x1) / (y2 - y1)
        res ^= crosses & (x < xc)
    return res


def raster(poly, cell=2.0):
    p = np.array(poly, float)
    n = np.arange(p[:, 0].min() + cell / 2, p[:, 0].max(), cell)
    e = np.arange(p[:, 1].min() + cell / 2, p[:, 1].max(), cell)
    g = np.array([(a, b) for a in n for b in e])
    return g[inside(poly, g)]


def looks(points, segments, sonar):
    """How many line segments image each point: along-track within the segment,
    across-track distance in [nadir gap, range]."""
    count = np.zeros(len(points), int)
    for (n0, e0), (n1, e1) in segments:
        d = np.array([n1 - n0, e1 - e0])
        length = np.hypot(*d)
        d /= length
        rel = points - np.array([n0, e0])
        along = rel @ d
        across = np.abs(rel @ np.array([-d[1], d[0]]))
        count += (along >= 0) & (along <= length) & (across >= sonar.nadir_gap_m) & (across <= sonar.range_m)
    return count


def shifted(survey, sign):
    """Each line moved across track by +-margin, alternating (neighbours apart, then together)."""
    out = []
    for v in survey.vehicles:
        for leg in v.lines:
            d = np.subtract(leg.end, leg.start)
            d /= np.hypot(*d)
            off = np.array([-d[1], d[0]]) * survey.margin_m * 0.99 * sign * (-1) ** leg.line
            out.append((tuple(leg.start + off), tuple(leg.end + off)))
    return out


CASES = [
    (CONVEX, 3, 20.0, Sonar(50, 5), 0.2),
    (CONVEX, 1, 0.0, Sonar(40, 0), 0.0),
    (L_SHAPE, 2, 90.0, Sonar(45, 4), 0.1),
    (U_SHAPE, 3, 0.0, Sonar(30, 3), 0.25),
    (U_SHAPE, 2, 37.0, Sonar(35, 0), 0.15),
]


@pytest.mark.parametrize("poly,n,heading,sonar,overlap", CASES)
def test_every_point_is_covered_also_with_the_overlap_margin_used_up(poly, n, heading, sonar, overlap):
    s = plan_survey(poly, n, math.radians(heading), sonar, overlap)
    pts = raster(poly)
    nominal = [(leg.start, leg.end) for v in s.vehicles for leg in v.lines]
    assert looks(pts, nominal, sonar).min() >= 1
    for sign in (1, -1):
        assert looks(pts, shifted(s, sign), sonar).min() >= 1, f"margin {s.margin_m} not tolerated"
    assert s.spacing_m == pytest.approx(sonar.full_spacing() * (1 - overlap))
    for v in s.vehicles:
        assert all(b - a <= s.spacing_m + 1e-9 for a, b in zip(v.offsets, v.offsets[1:]))


@pytest.mark.parametrize("poly,n,heading,sonar,overlap", CASES)
def test_areas_are_balanced_within_half_a_percent(poly, n, heading, sonar, overlap):
    s = plan_survey(poly, n, math.radians(heading), sonar, overlap)
    total = area(poly)
    assert sum(v.area_m2 for v in s.vehicles) == pytest.approx(total, rel=1e-9)
    for v in s.vehicles:
        assert v.area_m2 == pytest.approx(total / n, rel=1e-6)
    # independently: raster cells by across-track position against the strips
    pts = raster(poly, 1.0)
    h = math.radians(heading)
    across = -pts[:, 0] * math.sin(h) + pts[:, 1] * math.cos(h)
    for v in s.vehicles:
        frac = np.mean((across >= v.strip[0]) & (across < v.strip[1]))
        assert abs(frac - 1 / n) < 0.005


@pytest.mark.parametrize("gap", [0.0, 5.0])
def test_full_spacing_is_tight(gap):
    """At the full spacing a lattice of lines covers everything; 5 % wider leaves holes."""
    sonar = Sonar(40, gap)
    full = sonar.full_spacing()
    pts = np.array([(0.0, e) for e in np.linspace(0, 3 * full, 2000)])
    for spacing, want_full in ((full, True), (full * 1.05, False)):
        segs = [((-10.0, k * spacing), (10.0, k * spacing)) for k in range(-3, 8)]
        assert (looks(pts, segs, sonar).min() >= 1) == want_full


def test_concave_lines_skip_the_notch_only_when_the_swath_cannot_see_across_it():
    s = plan_survey(U_SHAPE, 1, 0.0, Sonar(30, 3), 0.0, run_in_m=10)
    # lines along north at east offsets; the U's notch spans north 0..350 between east 120 and 280
    for v in s.vehicles:
        by_line = {}
        for leg in v.lines:
            by_line.setdefault(leg.line, []).append(leg)
        for legs in by_line.values():
            e = legs[0].start[1]
            if 120 + 30 < e < 280 - 30:  # the swath sees only the notch's open side
                assert len(legs) == 1 and min(legs[0].start[0], legs[0].end[0]) > 340 - 10
            else:
                assert len(legs) == 1 and min(legs[0].start[0], legs[0].end[0]) < 0


def test_operating_area_holds_all_legs_with_room():
    s = plan_survey(CONVEX, 3, 0.3, Sonar(50, 5), 0.2)
    ends = np.array([p for v in s.vehicles for leg in v.legs for p in (leg.start, leg.end)] + CONVEX, float)
    assert inside(s.operating_area, ends).all()
    hull_far = np.array([(p[0] + 20, p[1]) for p in ends])
    assert inside(s.operating_area, hull_far).all()  # margin > 20 m everywhere


def test_vehicles_start_near_their_first_line():
    starts = [(-50, 0), (-50, 200), (600, 400)]
    s = plan_survey(CONVEX, 3, 0.0, Sonar(50, 5), 0.2, starts=starts)
    for v, st in zip(s.vehicles, starts):
        first = v.legs[0].start
        last = v.lines[-1].line
        others = [p for leg in v.lines if leg.line in (1, last) for p in (leg.start, leg.end)]
        assert math.dist(first, st) <= min(math.dist(p, st) for p in others) + 1e-6
        kinds = [leg.kind for leg in v.legs]
        assert kinds[0] == "line" and all(a != b for a, b in zip(kinds, kinds[1:]))


@pytest.mark.parametrize(
    "text,msg",
    [
        ("0,0; 1,1", "at least 3 vertices"),
        ("0,0; 100,100; 100,0; 0,100", "crosses itself"),
        ("0,0; 100,x; 0,100", "not a number"),
        ("0,0; 100; 0,100", "expected 'north,east'"),
        ("0,0; 1,0; 2,0", "no area"),
    ],
)
def test_bad_polygons(text, msg):
    with pytest.raises(GeometryError, match=msg):
        parse_polygon(text)


@pytest.mark.parametrize(
    "kw,msg",
    [
        ({"vehicles": 0}, "at least 1"),
        ({"overlap": 1.0}, "overlap"),
        ({"sonar": Sonar(40, 20)}, "nadir gap"),
        ({"sonar": Sonar(0, 0)}, "range must be > 0"),
    ],
)
def test_bad_parameters(kw, msg):
    args = {"vehicles": 2, "heading_rad": 0.0, "sonar": Sonar(40, 4), "overlap": 0.1, **kw}
    with pytest.raises(GeometryError, match=msg):
        plan_survey(CONVEX, **args)


def test_polygon_text_round_trip():
    assert parse_polygon("0,0; 400,-60; 520,250; 0,0") == [(0, 0), (400, -60), (520, 250)]
