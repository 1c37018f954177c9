"""The `environment.ocean:` section, checked key by key (file:line:col), and a
grid file's own checks, reported at its `grid:` key before anything starts.

    environment:
      ocean:
        front: {offset_m: 300, angle_rad: 0.3, amplitude_m: 80, wavelength_m: 1500, period_s: 3600, width_m: 30}
        water_a: {temperature_c: 16, salinity_psu: 32.5}     # left of the front
        water_b: {temperature_c: 12, salinity_psu: 34.5}     # right of it
        deep: {temperature_c: 8, salinity_psu: 35}           # below the thermocline
        thermocline: {depth_m: 25, thickness_m: 5}
        plumes:
          - {north_m: 100, east_m: 0, depth_m: 6, temperature_c: 2, salinity_psu: -3}

    environment:
      ocean:
        grid: worlds/bay_ocean.nc         # relative to this file
        grid_start: "2024-06-01T00:00"    # the file's time at sim time 0; default its first
        area: {north_m: [-500, 500], east_m: [-500, 500], max_depth_m: 60, duration_s: 3600}
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from typing import Any

import yaml

from confcheck import Checker
from sim.ocean.fields import grid_path
from sim.ocean.grid import OceanError, load_grid
from sim.ocean.params import Area, OceanParams, Plume

ANALYTIC_KEYS = ("front", "water_a", "water_b", "deep", "thermocline")
KEY = "environment.ocean"


def _range(doc: Checker, node, key: str) -> list | Any:
    """[min, max]: two finite numbers, min <= max."""
    items = doc.sequence(node, key)
    vals = [doc.scalar(n) for n in items]
    if (
        len(vals) != 2
        or not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in vals)
        or vals[0] > vals[1]
    ):
        doc.err(node, key, "expected [min, max]: two finite numbers, min <= max")
        return dataclasses.MISSING
    return [float(v) for v in vals]


def check_ocean(
    doc: Checker,
    node,
    base: Path,
    lat0: float,
    lon0: float,
    start: tuple[float, float, float],
    transponders: list,
    duration_s: float,
) -> OceanParams | None:
    """The section as OceanParams (None if empty or refused); a grid file is read
    and checked here, and must cover the area (`area:`, else the vehicle's start
    and the transponders, over simulation.duration_s)."""
    if doc.is_empty(node):
        return OceanParams()
    if not isinstance(node, yaml.MappingNode):
        doc.err(node, KEY, "expected a mapping of keys (front, water_a, water_b, deep, thermocline, plumes, grid, ...)")
        return None
    o = OceanParams()
    special = {
        "plumes": lambda n, k: [doc.fill(x, f"{k}[{i}]", Plume()) for i, x in enumerate(doc.sequence(n, k))],
        "area": lambda n, k: doc.fill(
            n, k, Area(), special={"north_m": lambda m, j: _range(doc, m, j), "east_m": lambda m, j: _range(doc, m, j)}
        ),
    }
    doc.fill(node, KEY, o, special=special)
    items = doc.mapping(node, KEY)
    o.base_dir = str(base)
    if not o.grid:
        for k in ("grid_start", "area"):
            if k in items:
                doc.err(items[k][0], f"{KEY}.{k}", "only for a grid file (ocean.grid)")
        return o
    beside = [k for k in ANALYTIC_KEYS if k in items]
    for k in beside:
        doc.err(
            items[k][0],
            f"{KEY}.{k}",
            "the grid file gives the water: no analytic front, water masses or thermocline beside it",
        )
    gnode = items["grid"][1]
    try:
        grid = load_grid(grid_path(o, base), lat0, lon0, o.grid_start)
    except OceanError as exc:
        doc.err(gnode, f"{KEY}.grid", str(exc))
        return None
    a = o.area
    points = [start] + [(t.north_m, t.east_m, t.depth_m) for t in transponders]
    north = tuple(a.north_m) if a.north_m else (min(p[0] for p in points), max(p[0] for p in points))
    east = tuple(a.east_m) if a.east_m else (min(p[1] for p in points), max(p[1] for p in points))
    depth = a.max_depth_m if a.max_depth_m >= 0.0 else max(p[2] for p in points)
    duration = a.duration_s if a.duration_s >= 0.0 else duration_s
    problem = grid.coverage_problem(north, east, depth, duration)
    if problem:
        whose = "the area (ocean.area)" if "area" in items else "the vehicle's start and the transponders"
        doc.err(gnode, f"{KEY}.grid", f"{grid.path}: does not cover {whose}: {problem}")
        return None
    return o
