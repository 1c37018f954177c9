"""A scripted survey controller for making navigation test data.

Not the vehicle's pilot or navigator (those are CHASM managers): this is test
tooling that flies a lawnmower from a navigation solution so the simulator
produces realistic sensor logs. It follows straight lines with a lookahead
law, holds depth with sim.autopilot's depth -> pitch -> stern-plane loops and
starts with a run on the surface (GPS fixes), as a survey vehicle does.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from sim.autopilot import Autopilot


@dataclass
class Survey:
    """A lawnmower: lines parallel to `heading_deg` from the corner (north, east)."""

    north_m: float = 0.0
    east_m: float = 0.0
    length_m: float = 460.0
    spacing_m: float = 50.0
    lines: int = 4
    heading_deg: float = 0.0
    depth_m: float = 12.0
    speed_rpm: float = 1500.0
    surface_s: float = 60.0  # first part of line 1 on the surface (GPS)
    final_surface: bool = False  # come up after the last line (GPS again)
    surface_crossovers: bool = False  # come up between lines for GPS fixes ...
    fix_s: float = 30.0  # ... and stay this long on the surface

    def waypoints(self) -> list[tuple[float, float]]:
        h = math.radians(self.heading_deg)
        along = (math.cos(h), math.sin(h))
        across = (-math.sin(h), math.cos(h))  # lines step to starboard of the heading
        pts = []
        for i in range(self.lines):
            ends = (0.0, self.length_m) if i % 2 == 0 else (self.length_m, 0.0)
            for a in ends:
                c = i * self.spacing_m
                pts.append((self.north_m + a * along[0] + c * across[0], self.east_m + a * along[1] + c * across[1]))
        return pts

    def path_length_m(self) -> float:
        p = self.waypoints()
        return sum(math.dist(p[i], p[i + 1]) for i in range(len(p) - 1))


@dataclass
class Nav:
    north: float = 0.0
    east: float = 0.0
    depth: float = 0.0
    heading: float = 0.0
    pitch: float = 0.0
    q: float = 0.0
    r: float = 0.0


SURFACE_RPM_FRACTION = 0.55  # of speed_rpm while running awash


@dataclass
class SurveyPilot:
    survey: Survey
    lookahead_m: float = 15.0
    ap: Autopilot = field(default_factory=Autopilot)
    leg: int = 0  # index of the waypoint the vehicle is heading to
    done: bool = False
    fixing: bool = False  # surfacing or on the surface for fixes between lines
    fix_time: float = 0.0  # time spent on the surface so far in this stop
    last_t: float = 0.0

    def __post_init__(self) -> None:
        self.wps = self.survey.waypoints()
        # the vehicle starts wherever it is and joins line 1 at its start
        self.leg = 1

    def _line(self) -> tuple[tuple[float, float], tuple[float, float]]:
        return self.wps[self.leg - 1], self.wps[self.leg]

    def command(self, t: float, nav: Nav) -> tuple[float, float, float]:
        """(rudder, stern plane, rpm) for the navigation solution at time t."""
        s = self.survey
        (n0, e0), (n1, e1) = self._line()
        dn, de = n1 - n0, e1 - e0
        length = math.hypot(dn, de)
        ux, uy = dn / length, de / length
        along = (nav.north - n0) * ux + (nav.east - e0) * uy
        cross = -(nav.north - n0) * uy + (nav.east - e0) * ux  # + to starboard of the line
        if along >= length and not self.done:
            if self.leg + 1 < len(self.wps):
                self.leg += 1
                return self.command(t, nav)
            self.done = True
        bearing = math.atan2(de, dn)
        heading_cmd = bearing - math.atan2(cross, self.lookahead_m)
        rudder = self.ap.rudder(heading_cmd, nav.heading, nav.r)
        # legs 1, 3, 5... are the lines, 2, 4... the crossovers between them:
        # come up on a crossover and stay until fix_s on the surface are done
        dt, self.last_t = t - self.last_t, t
        if s.surface_crossovers and self.leg % 2 == 0 and not self.done and not self.fixing and self.fix_time == 0:
            self.fixing = True
        if self.fixing:
            self.fix_time += dt if nav.depth < 0.3 else 0.0
            if self.fix_time >= s.fix_s and self.leg % 2 == 1:
                self.fixing = False
        if self.leg % 2 == 1 and not self.fixing:
            self.fix_time = 0.0
        surfaced = t < s.surface_s or (self.done and s.final_surface) or self.fixing
        on_top = surfaced and nav.depth <= 1.0
        if surfaced:
            # bow up, steeply on the way up; on top, level and at reduced rpm,
            # the positively buoyant hull stays awash with the GPS antenna out
            # (at full rpm the published hull rides bow-up ~20 deg there, and
            # the DVL, near its range limit, loses the seabed)
            pitch_cmd = math.radians(0.0 if on_top else 20.0)
            stern = self.ap.stern_for_pitch(pitch_cmd, nav.pitch, nav.q)
        else:
            stern = self.ap.stern_for_depth(s.depth_m, nav.depth, nav.pitch, nav.q)
        rpm = 0.0 if self.done and not s.final_surface else s.speed_rpm * (SURFACE_RPM_FRACTION if on_top else 1.0)
        return rudder, stern, rpm
