"""The sampling grade: every on-board front estimate of a run against the world's front.

Each vehicle's estimator (auv-front-estimate, docs/sampling.md) publishes its own fit on
`<V>.FRONT_ESTIMATE` and the fit with its teammates' summaries on `<V>.FRONT_TEAM`. The
truth is the world's ocean, rebuilt from the simulator configuration the log carries
(the launcher annotates it), so a log alone is enough. For each estimate it gives:

- the error of each straight-front parameter (offset, angle, the two waters, width)
  against the world's front (its meander, if any, is part of the map error, not of these);
- the map error: the rms difference between the estimate's temperature field and the
  world's, at the estimator's layer depth, over the grading area (the box round every
  vehicle's track, `margin_m` wider, on a `cell_m` grid) at the estimate's time.

The team's map error at a time is the mean over the vehicles of their team estimates'
(a vehicle without an OK estimate then counts the water's spread: it knows nothing).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from tools.report.run_data import RunData

OK = 0  # front_estimate_t.STATUS_OK
PARAMS = ("offset_m", "angle_rad", "temperature_a_c", "temperature_b_c", "width_m")


@dataclass
class Area:
    north: np.ndarray  # grid points (flattened)
    east: np.ndarray
    depth_m: float
    box: tuple[float, float, float, float]  # north min, max, east min, max


def world_ocean(run: RunData):
    """The world's Ocean from the first vehicle's annotated configuration (None: no ocean)."""
    if not run.sim_configs:
        return None
    from sim.config import loads
    from sim.environment import Environment

    cfg = loads(next(iter(run.sim_configs.values())))
    return Environment(cfg.env, Path.cwd()).ocean


def grading_area(
    run: RunData, depth_m: float, margin_m: float = 50.0, cell_m: float = 5.0, box: tuple | None = None
) -> Area:
    """The given box (north min, max, east min, max), or the tracks' box `margin_m` wider."""
    if box is None:
        n = np.concatenate([run.truth(v)["eta[0]"] for v in run.vehicles])
        e = np.concatenate([run.truth(v)["eta[1]"] for v in run.vehicles])
        box = (
            float(n.min()) - margin_m,
            float(n.max()) + margin_m,
            float(e.min()) - margin_m,
            float(e.max()) + margin_m,
        )
    gn, ge = np.meshgrid(np.arange(box[0], box[1] + cell_m / 2, cell_m), np.arange(box[2], box[3] + cell_m / 2, cell_m))
    return Area(gn.ravel(), ge.ravel(), depth_m, box)


def model_temperature(est: dict, north: np.ndarray, east: np.ndarray) -> np.ndarray:
    """The estimate's upper-water temperature (front_estimate_t's model)."""
    th = est["angle_rad"]
    s = north * math.cos(th) + east * math.sin(th)
    x = -north * math.sin(th) + east * math.cos(th) - est["offset_m"]
    if est.get("meander") and est["amplitude_m"] > 0:
        x = x - est["amplitude_m"] * np.sin(2 * math.pi * s / est["wavelength_m"] + est["phase_rad"])
    w = 0.5 * (1 + np.tanh(x / est["width_m"]))
    return est["temperature_a_c"] + w * (est["temperature_b_c"] - est["temperature_a_c"])


def true_front(ocean) -> dict:
    """The world's straight front in the estimate's form: angle in [-pi/2, pi/2), water a on its left."""
    p = ocean.params
    f = {
        "offset_m": p.front.offset_m,
        "angle_rad": p.front.angle_rad,
        "temperature_a_c": p.water_a.temperature_c,
        "temperature_b_c": p.water_b.temperature_c,
        "width_m": p.front.width_m,
    }
    th = math.remainder(f["angle_rad"], 2 * math.pi)
    if not -math.pi / 2 <= th < math.pi / 2:  # the same field seen from the other side
        th = math.remainder(th + math.pi, 2 * math.pi)
        f["offset_m"] = -f["offset_m"]
        f["temperature_a_c"], f["temperature_b_c"] = f["temperature_b_c"], f["temperature_a_c"]
    f["angle_rad"] = th
    return f


def _estimates(run: RunData, channel: str) -> list[tuple[float, dict | None]]:
    arr = run.log.channels.get(channel)
    if arr is None or not len(arr):
        return []
    cols = ("meander", *PARAMS, "amplitude_m", "wavelength_m", "phase_rad")
    out = []
    for i in range(len(arr)):
        ok = int(arr["status"][i]) == OK
        out.append((float(arr["utime"][i]) * 1e-6, {c: float(arr[c][i]) for c in cols} if ok else None))
    return out


def grade_series(run: RunData, ocean, area: Area, channel: str) -> dict:
    """One channel's estimates graded: times, map rms, parameter errors of the OK ones."""
    truth = true_front(ocean)
    t_out, rms, errs = [], [], []
    for t, est in _estimates(run, channel):
        if est is None:
            continue
        true_t = ocean.fields(t, area.north, area.east, area.depth_m)[0]
        rms.append(float(np.sqrt(np.mean((model_temperature(est, area.north, area.east) - true_t) ** 2))))
        t_out.append(t)
        errs.append([est[k] - truth[k] for k in PARAMS])
    return {"t": t_out, "map_rms_c": rms, "errors": errs}


def team_curve(series: dict[str, dict], spread_c: float) -> tuple[list[float], list[float]]:
    """The team's map error at each time any vehicle estimated: the mean over vehicles of
    each one's latest team estimate's error (spread_c for one with none yet)."""
    times = sorted({t for s in series.values() for t in s["t"]})
    curve = []
    for t in times:
        vals = []
        for s in series.values():
            k = np.searchsorted(s["t"], t, side="right") - 1
            vals.append(s["map_rms_c"][k] if k >= 0 else spread_c)
        curve.append(float(np.mean(vals)))
    return times, curve


def first_time_under(times: list[float], curve: list[float], level: float) -> float | None:
    return next((t for t, c in zip(times, curve) if c <= level), None)


def sampling_section(run: RunData, depth_m: float = 5.0, box: tuple | None = None) -> dict | None:
    """The grade, or None when the run has no front estimates or no ocean. `box`: the
    grading area (north min, max, east min, max; default: round the tracks)."""
    if not run.log.matching(r"[A-Z][A-Z0-9]*\.FRONT_TEAM"):
        return None
    ocean = world_ocean(run)
    if ocean is None or ocean.grid is not None:
        return None  # a gridded ocean has no front to grade against (its map error would do: not yet)
    area = grading_area(run, depth_m, box=box)
    t0 = float(run.log["SIM.CLOCK"].t[0]) if "SIM.CLOCK" in run.log and len(run.log["SIM.CLOCK"].t) else 0.0
    true_t = ocean.fields(t0, area.north, area.east, area.depth_m)[0]
    spread = float(np.sqrt(np.mean((true_t - true_t.mean()) ** 2)))  # the error of knowing nothing
    own = {v: grade_series(run, ocean, area, f"{v}.FRONT_ESTIMATE") for v in run.vehicles}
    team = {v: grade_series(run, ocean, area, f"{v}.FRONT_TEAM") for v in run.vehicles}
    times, curve = team_curve(team, spread)
    own_times, own_curve = team_curve(own, spread)
    final = {}
    for v, s in team.items():
        if s["t"]:
            final[v] = {"map_rms_c": s["map_rms_c"][-1], **dict(zip(PARAMS, s["errors"][-1]))}
    return {
        "depth_m": depth_m,
        "area": list(area.box),
        "truth": true_front(ocean),
        "spread_c": spread,
        "team_map_rms_c": curve[-1] if curve else None,
        "own_map_rms_c": own_curve[-1] if own_curve else None,
        "curve": {"t": times, "team": curve},
        "own_curve": {"t": own_times, "own": own_curve},
        "final": final,
        "first_under_half_spread_s": first_time_under(times, curve, spread / 2),
    }


def sampling_text(s: dict) -> list[str]:
    if s is None:
        return []
    lines = []
    team, own = s["team_map_rms_c"], s["own_map_rms_c"]
    if team is None:
        return [f"sampling  no OK front estimate (the water's spread over the area: {s['spread_c']:.2f} degC)"]
    lines.append(
        f"sampling  map error {team:.3f} degC rms at the end with the team's summaries, {own:.3f} from own samples"
        f" alone (the water's spread {s['spread_c']:.2f} degC, area {s['area'][1] - s['area'][0]:.0f} x"
        f" {s['area'][3] - s['area'][2]:.0f} m at {s['depth_m']:g} m)"
    )
    for v, f in s["final"].items():
        lines.append(
            f"          {v}: offset {f['offset_m']:+.1f} m, angle {f['angle_rad']:+.4f} rad, waters"
            f" {f['temperature_a_c']:+.3f}/{f['temperature_b_c']:+.3f} degC, width {f['width_m']:+.1f} m;"
            f" map {f['map_rms_c']:.3f} degC"
        )
    return lines
