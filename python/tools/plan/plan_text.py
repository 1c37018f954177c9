"""Write one vehicle's survey as a CHASM navigator plan (docs/chasm.md).

Shape (the vehicle software contract): dive to the first line, then one
state per line (`track` + `hold_altitude`, or `hold_depth` with a survey
depth) and per turn between lines; a GPS
fix (`surface_fix`) every `fix_every` of survey, resuming the same line;
safety from the shared rules (missions/common/safety.chasm, root `abort
when` transitions to `emergency`, which surfaces): max depth, min altitude,
stale navigation, leaving the operating area, mission timeout, with this
survey's limits as parameters.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

from auvlcm.paths import ROOT
from tools.plan.survey_geometry import format_polygon
from tools.plan.survey_plan import Survey, VehicleSurvey

NAVIGATOR_IO = ROOT / "missions" / "common" / "navigator_io.chasm"
SAFETY = ROOT / "missions" / "common" / "safety.chasm"  # the shared `abort when` rules
TEAM_SAFETY = ROOT / "missions" / "common" / "team_safety.chasm"  # ... whose emergency tells the team


@dataclass
class Limits:
    speed_mps: float = 1.5
    altitude_m: float = 8.0
    depth_m: float = 0.0  # > 0: fly the survey at this depth (hold_depth), not at altitude_m
    fix_every_min: float = 20.0
    fix_timeout_s: float = 300.0  # floating up from survey altitude takes minutes
    max_depth_m: float = 60.0
    min_altitude_m: float = 2.0
    nav_timeout_s: float = 5.0
    timeout_s: float = 0.0  # 0: from the estimated duration


def estimated_duration_s(v: VehicleSurvey, start, lim: Limits) -> float:
    """Legs and the run to the first line at survey speed, plus each GPS fix (a dive and a climb)."""
    transit = ((start[0] - v.legs[0].start[0]) ** 2 + (start[1] - v.legs[0].start[1]) ** 2) ** 0.5
    run_s = (v.length_m() + transit) / lim.speed_mps
    fixes = int(run_s // (lim.fix_every_min * 60))
    return run_s + fixes * (lim.fix_timeout_s / 2 + 2 * (lim.depth_m or lim.altitude_m) / 0.2)


def _f(x: float) -> str:
    return f"{x:.1f}"


def plan_text(survey: Survey, v: VehicleSurvey, vid: str, start, lim: Limits, plan_path: Path) -> str:
    est = estimated_duration_s(v, start, lim)
    timeout = lim.timeout_s or 1.5 * est + 600
    include = os.path.relpath(NAVIGATOR_IO, plan_path.parent)
    safety = os.path.relpath(SAFETY, plan_path.parent)
    s = survey.sonar
    vertical = "hold_depth(depth = $depth)" if lim.depth_m > 0 else "hold_altitude(altitude = $altitude)"
    out = [
        f"# {vid}: share {v.index + 1} of {len(survey.vehicles)} of a sidescan survey, written by",
        "# auv-plan-survey (re-run it rather than edit this file).",
        f"# Survey area {survey.area_m2 / 1e6:.3f} km2, this share {v.area_m2 / 1e6:.3f} km2, "
        f"{len(v.lines)} line legs, {v.length_m() / 1000:.2f} km, about {est / 60:.0f} min.",
        f"# Lines at heading {survey.heading_rad * 57.29577951308232:.1f} deg, {survey.spacing_m:.1f} m apart "
        f"(sonar range {s.range_m:g} m, nadir gap {s.nadir_gap_m:g} m, overlap {survey.overlap:g}).",
        f"# survey polygon: {format_polygon(survey.polygon)}",
        f'mission "{vid} survey"',
        "",
        f'include "{include}"',
        "use guidance",
        "",
        f"param speed        = {lim.speed_mps:g} m/s",
        (
            f"param depth        = {lim.depth_m:g} m"
            if lim.depth_m > 0
            else f"param altitude     = {lim.altitude_m:g} m"
        ),
        f"param fix_every    = {lim.fix_every_min:g} min",
        f"param fix_timeout  = {lim.fix_timeout_s:g} s",
        "",
        "# Limits of the shared safety rules (included at the end).",
        f"param max_depth       = {lim.max_depth_m:g} m",
        f"param min_altitude    = {lim.min_altitude_m:g} m",
        f"param nav_timeout     = {lim.nav_timeout_s:g} s",
        f"param mission_timeout = {timeout / 60:.0f} min",
        f'param area            = "{format_polygon(survey.operating_area)}"',
        "",
        "start mission",
        "",
        "# Legs follow each other by `next`: a finished leaf without one would",
        "# complete `mission` itself, ending the plan.",
        "state mission {",
        "    state dive {",
        f"        do goto(north = {_f(v.legs[0].start[0])} m, east = {_f(v.legs[0].start[1])} m, speed = $speed)",
        f"        do {vertical}",
        "        next survey",
        "    }",
        "    state survey {",
        "        test fix_due : elapsed > $fix_every",
        "        when fix_due -> gps_fix",
    ]
    names = []
    for i, leg in enumerate(v.legs):
        names.append(f"line{leg.line}" if leg.kind == "line" else f"turn{leg.line}")
        if names.count(names[-1]) > 1:
            names[-1] += f"_{names.count(names[-1])}"
    for i, leg in enumerate(v.legs):
        nxt = names[i + 1] if i + 1 < len(names) else "recover"
        out += [
            f"        state {names[i]} {{",
            f"            do track(from_north = {_f(leg.start[0])} m, from_east = {_f(leg.start[1])} m, "
            f"to_north = {_f(leg.end[0])} m, to_east = {_f(leg.end[1])} m, speed = $speed)",
            f"            do {vertical}",
            f"            next {nxt}",
            "        }",
        ]
    out += [
        "    }",
        "    state recover {",
        "        do surface()",
        "    }",
        "}",
        "",
        "# A root of its own: a missed fix marks only this state failed, and the",
        "# survey's states are entered afresh on the way back. (Inside `mission`,",
        "# the failure flag would stay on `mission` after being caught.)",
        "state gps_fix {",
        "    do surface_fix(timeout = $fix_timeout)",
        "    when done -> resume deep survey       # the interrupted leg, from where the vehicle is",
        "    when failed -> resume deep survey     # no fix this time: carry on, try again later",
        "}",
        "",
        f'include "{safety}"',
        "",
    ]
    return "\n".join(out)
