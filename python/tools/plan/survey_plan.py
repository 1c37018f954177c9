"""Survey planning: split a polygon among vehicles by area and lay sidescan lines.

Sonar model (the planner's, deliberately simple): each side images ground
ranges from `nadir_gap` to `range` across track. A point is covered if some
line passes at a distance d with nadir_gap <= |d| <= range.

- Full coverage spacing: with no nadir gap, lines 2*range apart cover
  everything. With a gap, the strip under each line must be seen by a
  neighbour, which is at most `range` away: spacing = range (and the gap
  must be under half the range for that neighbour to see it).
- Overlap o: spacing = full * (1 - o). Every line may then be off its track
  by o * full / 2 across (e.g. navigation drift) and the area stays covered;
  the edge lines keep the same margin outside the area.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from tools.plan.survey_geometry import (
    Frame,
    GeometryError,
    Point,
    area,
    band_extent,
    buffer_convex,
    check_polygon,
    clip_v,
    convex_hull,
    simplify_convex_outer,
    split_by_area,
)


@dataclass
class Sonar:
    range_m: float  # largest useful ground range per side
    nadir_gap_m: float = 0.0  # blind half-width under the track

    def full_spacing(self) -> float:
        return 2 * self.range_m if self.nadir_gap_m == 0 else self.range_m


@dataclass
class Leg:
    kind: str  # "line" or "turn"
    start: Point  # (north, east)
    end: Point
    line: int = 0  # 1-based line number of the vehicle ("turn": the next line)

    @property
    def length(self) -> float:
        return math.dist(self.start, self.end)


@dataclass
class VehicleSurvey:
    index: int
    strip: tuple[float, float]  # across-track limits of its share [m]
    area_m2: float
    polygon: list[Point]  # its share of the area (north, east)
    offsets: list[float]  # across-track position of each line [m]
    legs: list[Leg] = field(default_factory=list)

    @property
    def lines(self) -> list[Leg]:
        return [leg for leg in self.legs if leg.kind == "line"]

    def length_m(self) -> float:
        return sum(leg.length for leg in self.legs)


@dataclass
class Survey:
    polygon: list[Point]
    heading_rad: float
    sonar: Sonar
    overlap: float
    spacing_m: float
    margin_m: float  # tolerated cross-track error per line [m]
    run_in_m: float
    vehicles: list[VehicleSurvey]
    operating_area: list[Point]

    @property
    def area_m2(self) -> float:
        return area(self.polygon)


def line_offsets(lo: float, hi: float, sonar: Sonar, spacing: float, margin: float) -> list[float]:
    """Across-track positions of the lines that cover lo..hi with the margin."""
    r, g = sonar.range_m, sonar.nadir_gap_m
    if g == 0:
        first, last = lo + r - margin, hi - (r - margin)
        if last <= first:
            return [(lo + hi) / 2]
    else:  # an edge line's own nadir gap cannot be filled from outside: put it beyond the edge
        first, last = lo - g - margin, hi + g + margin
    n = math.ceil((last - first) / spacing - 1e-9) + 1
    return [first + (last - first) * i / (n - 1) for i in range(n)]


def _legs(
    poly_uv: list[Point],
    frame: Frame,
    strip: tuple[float, float],
    offsets: list[float],
    sonar: Sonar,
    run_in: float,
    start_uv: Point | None,
) -> list[Leg]:
    """Boustrophedon legs: each line spans what its swath sees of the strip."""
    lo, hi = strip
    per_line = []
    for v in offsets:
        ivs = band_extent(poly_uv, max(lo, v - sonar.range_m), min(hi, v + sonar.range_m))
        segs: list[list[float]] = []
        for a, b in ivs:
            a, b = a - run_in, b + run_in
            if segs and a <= segs[-1][1]:
                segs[-1][1] = max(segs[-1][1], b)
            else:
                segs.append([a, b])
        if segs:
            per_line.append((v, segs))
    forward = True
    if start_uv is not None and per_line:  # begin at the line end nearest the vehicle
        ends = {
            (rev, fwd): (
                per_line[-1 if rev else 0][1][0 if fwd else -1][0 if fwd else 1],
                per_line[-1 if rev else 0][0],
            )
            for rev in (False, True)
            for fwd in (True, False)
        }
        rev, forward = min(ends, key=lambda k: math.dist(ends[k], start_uv))
        if rev:
            per_line.reverse()
    legs: list[Leg] = []
    for k, (v, segs) in enumerate(per_line, start=1):
        pieces = [(a, b) for a, b in segs] if forward else [(b, a) for a, b in reversed(segs)]
        for a, b in pieces:
            s, e = frame.to_ne((a, v)), frame.to_ne((b, v))
            if legs:
                legs.append(Leg("turn", legs[-1].end, s, k))
            legs.append(Leg("line", s, e, k))
        forward = not forward
    return legs


def plan_survey(
    polygon: list[Point],
    vehicles: int,
    heading_rad: float,
    sonar: Sonar,
    overlap: float,
    run_in_m: float = 20.0,
    area_margin_m: float | None = None,
    starts: list[Point] | None = None,
    area_max_vertices: int | None = None,
) -> Survey:
    """Split the polygon among `vehicles` (equal areas, cuts along the lines) and lay each one's lines.
    The operating area (every leg, grown by area_margin_m) is bounded by
    area_max_vertices: the most the plugin that tests it accepts."""
    check_polygon(polygon)
    if vehicles < 1:
        raise GeometryError("the number of vehicles must be at least 1")
    if not 0 <= overlap < 1:
        raise GeometryError(f"overlap {overlap} must be in [0, 1)")
    if sonar.range_m <= 0 or sonar.nadir_gap_m < 0:
        raise GeometryError("the sonar range must be > 0 and its nadir gap >= 0")
    if sonar.nadir_gap_m >= sonar.range_m / 2:
        raise GeometryError(
            f"a nadir gap of {sonar.nadir_gap_m:g} m cannot be filled by neighbouring lines "
            f"with a range of {sonar.range_m:g} m (it must be under half the range)"
        )
    if run_in_m < 0:
        raise GeometryError("the run-in must be >= 0")
    full = sonar.full_spacing()
    spacing, margin = full * (1 - overlap), overlap * full / 2
    frame = Frame(heading_rad)
    poly_uv = [frame.to_uv(p) for p in polygon]
    cuts = split_by_area(poly_uv, vehicles)
    out = []
    for k in range(vehicles):
        strip = (cuts[k], cuts[k + 1])
        share = clip_v(poly_uv, *strip)
        offsets = line_offsets(*strip, sonar, spacing, margin)
        start = frame.to_uv(starts[k]) if starts else None
        vs = VehicleSurvey(k, strip, area(share), [frame.to_ne(q) for q in share], offsets)
        vs.legs = _legs(poly_uv, frame, strip, offsets, sonar, run_in_m, start)
        out.append(vs)
    reach = sonar.range_m + sonar.nadir_gap_m + margin + run_in_m
    if area_margin_m is None:
        area_margin_m = reach + 50.0
    hull = convex_hull(polygon + [p for v in out for leg in v.legs for p in (leg.start, leg.end)])
    operating = buffer_convex(hull, area_margin_m)
    if area_max_vertices is not None:
        operating = simplify_convex_outer(operating, area_max_vertices)
    return Survey(polygon, heading_rad, sonar, overlap, spacing, margin, run_in_m, out, operating)
