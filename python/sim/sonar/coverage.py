"""Coverage of a track: looks per grid cell, and the chance a mine there was detected.

    cov = coverage_grid(north, east, heading, altitude, curve, cell=2.0)
    cov.looks        # int (n_north, n_east): passes that imaged the cell
    cov.pd           # 1 - prod over passes (1 - P): detection probability of a mine
    cov.area_with(2) # m^2 seen at least twice

Works on any track, in-process (arrays from the model) or from a log (the
report tool passes <V>.TRUTH). A look is one pass over a cell: the samples
of one pass that image a cell count once, with the best P among them. Passes
are split where the heading leaves the pass's initial heading by more than
`turn_rad` (a lawnmower line is one pass, the turn at its end starts the
next) or where imaging stops; or the caller gives pass ids.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from sim.sonar.curve import LateralRangeCurve


@dataclass
class Coverage:
    north0: float
    east0: float
    cell: float
    looks: np.ndarray
    pd: np.ndarray

    def centres(self) -> tuple[np.ndarray, np.ndarray]:
        n = self.north0 + (np.arange(self.looks.shape[0]) + 0.5) * self.cell
        e = self.east0 + (np.arange(self.looks.shape[1]) + 0.5) * self.cell
        return n, e

    def area_with(self, at_least: int, mask: np.ndarray | None = None) -> float:
        sel = self.looks >= at_least
        if mask is not None:
            sel &= mask
        return float(np.count_nonzero(sel)) * self.cell**2

    def index(self, north: float, east: float) -> tuple[int, int]:
        return int((north - self.north0) // self.cell), int((east - self.east0) // self.cell)


def split_passes(heading: np.ndarray, imaging: np.ndarray, turn_rad: float) -> np.ndarray:
    """A pass id per sample (-1 where not imaging)."""
    ids = np.full(len(heading), -1, dtype=int)
    current, ref = -1, math.nan
    for k in range(len(heading)):
        if not imaging[k]:
            ref = math.nan
            continue
        d = abs((heading[k] - ref + math.pi) % (2 * math.pi) - math.pi) if ref == ref else math.inf
        if d > turn_rad:
            current += 1
            ref = heading[k]
        ids[k] = current
    return ids


def coverage_grid(
    north,
    east,
    heading,
    altitude,
    curve: LateralRangeCurve,
    cell: float = 2.0,
    bounds: tuple[float, float, float, float] | None = None,
    pass_id=None,
    turn_rad: float = math.pi / 4,
) -> Coverage:
    """Looks and detection probability per cell; bounds = (n_min, n_max, e_min, e_max)."""
    north, east = np.asarray(north, float), np.asarray(east, float)
    heading, altitude = np.asarray(heading, float), np.asarray(altitude, float)
    far = np.array([curve.imaged_band(h)[1] for h in altitude])
    imaging = far > 0.0
    if pass_id is None:
        pass_id = split_passes(heading, imaging, turn_rad)
    pass_id = np.where(imaging, np.asarray(pass_id), -1)
    reach = float(far.max()) if len(far) and far.max() > 0 else curve.cfg.range_m
    if bounds is None:
        bounds = (north.min() - reach, north.max() + reach, east.min() - reach, east.max() + reach)
    n0, n1, e0, e1 = bounds
    shape = (max(1, int(math.ceil((n1 - n0) / cell))), max(1, int(math.ceil((e1 - e0) / cell))))
    looks = np.zeros(shape, dtype=np.int32)
    miss = np.ones(shape)
    ys = np.arange(cell / 4, reach, cell / 2)
    ys = np.concatenate([-ys[::-1], ys])  # both sides, half-cell steps
    for p in np.unique(pass_id[pass_id >= 0]):
        idx = np.nonzero(pass_id == p)[0]
        # samples about half a cell apart along the pass are enough
        run = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(north[idx]), np.diff(east[idx])))])
        keep = np.unique(np.searchsorted(run, np.arange(0.0, run[-1] + cell / 2, cell / 2)))
        idx = idx[np.minimum(keep, len(idx) - 1)]
        best = np.zeros(shape)
        for k in idx:
            pr = curve.pd(ys, altitude[k])
            on = pr > 0.0
            c, s = math.cos(heading[k]), math.sin(heading[k])
            i = np.floor((north[k] - ys[on] * s - n0) / cell).astype(int)
            j = np.floor((east[k] + ys[on] * c - e0) / cell).astype(int)
            ok = (i >= 0) & (i < shape[0]) & (j >= 0) & (j < shape[1])
            np.maximum.at(best, (i[ok], j[ok]), pr[on][ok])
        looks += best > 0.0
        miss *= 1.0 - best
    return Coverage(n0, e0, cell, looks, 1.0 - miss)
