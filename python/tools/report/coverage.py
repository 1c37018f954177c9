"""Sidescan coverage of a run: looks per grid cell, from the true tracks.

A look is one pass over a cell: a cell seen several times during one leg
(one state of the navigator) counts once; seen from two legs, twice. While
a vehicle is submerged (depth > 1 m and a known altitude), each side images
ground ranges [nadir_gap, range] perpendicular to its heading: the
planner's sonar model (tools/plan/survey_plan.py), so the report measures what
the planner promised.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tools.report.run_data import RunData

MIN_DEPTH_M = 1.0


@dataclass
class Grid:
    north0: float
    east0: float
    cell: float
    looks: np.ndarray  # (n_north, n_east) looks per cell
    inside: np.ndarray  # cells whose centre is inside the survey polygon

    def centres(self) -> tuple[np.ndarray, np.ndarray]:
        n = self.north0 + (np.arange(self.looks.shape[0]) + 0.5) * self.cell
        e = self.east0 + (np.arange(self.looks.shape[1]) + 0.5) * self.cell
        return n, e

    def area_with(self, at_least: int) -> float:
        return float(np.count_nonzero((self.looks >= at_least) & self.inside)) * self.cell**2


def point_in_polygon(poly, n: np.ndarray, e: np.ndarray) -> np.ndarray:
    res = np.zeros(n.shape, bool)
    for (n1, e1), (n2, e2) in zip(poly, poly[1:] + poly[:1]):
        crosses = (e1 > e) != (e2 > e)
        with np.errstate(divide="ignore", invalid="ignore"):
            nc = n1 + (e - e1) * (n2 - n1) / (e2 - e1)
        res ^= crosses & (n < nc)
    return res


def _passes(run: RunData, vid: str, t: np.ndarray) -> np.ndarray:
    """A pass number per truth sample: the navigator's state segment it falls in."""
    segs = run.timelines.get(f"{vid}.NAVIGATOR")
    if not segs:
        return np.zeros(len(t), int)
    starts = np.array([s.start for s in segs])
    return np.searchsorted(starts, t, side="right")


def coverage_grid(run: RunData, polygon, range_m: float, nadir_gap_m: float, cell: float = 2.0) -> Grid:
    poly = [tuple(p) for p in polygon]
    pn, pe = np.array([p[0] for p in poly]), np.array([p[1] for p in poly])
    pad = range_m + cell
    n0, e0 = pn.min() - pad, pe.min() - pad
    shape = (int(np.ceil((pn.max() + pad - n0) / cell)), int(np.ceil((pe.max() + pad - e0) / cell)))
    looks = np.zeros(shape, np.int32)
    ranges = np.arange(nadir_gap_m + cell / 4, range_m, cell / 2)  # half-cell steps, inside [gap, range]
    ranges = np.concatenate([ranges, -ranges])
    for vid in run.vehicles:
        tr = run.truth(vid)
        t, north, east, depth, yaw = tr.t, tr["eta[0]"], tr["eta[1]"], tr["eta[2]"], tr["eta[5]"]
        ok = (depth > MIN_DEPTH_M) & (tr["altitude_m"] > 0)
        passes = _passes(run, vid, t)
        # samples about half a cell apart along the track are enough
        step = max(1, int(len(t) / max(1.0, np.sum(np.hypot(np.diff(north), np.diff(east))) / (cell / 2))))
        idx = np.nonzero(ok)[0][::step]
        for p in np.unique(passes[idx]):
            sel = idx[passes[idx] == p]
            cn = north[sel, None] - np.sin(yaw[sel])[:, None] * ranges[None, :]
            ce = east[sel, None] + np.cos(yaw[sel])[:, None] * ranges[None, :]
            i = ((cn - n0) / cell).astype(int).ravel()
            j = ((ce - e0) / cell).astype(int).ravel()
            keep = (i >= 0) & (i < shape[0]) & (j >= 0) & (j < shape[1])
            seen = np.zeros(shape, bool)
            seen[i[keep], j[keep]] = True
            looks += seen
    g = Grid(n0, e0, cell, looks, np.zeros(shape, bool))
    cn, ce = g.centres()
    nn, ee = np.meshgrid(cn, ce, indexing="ij")
    g.inside = point_in_polygon(poly, nn, ee)
    return g
