"""The sidescan's lateral range curve: P(detect) against ground range and altitude.

For a target at ground range y (across track, either side) seen from
altitude h, with the sonar's range setting R:

    g(h)  = nadir_gap_per_altitude * h        nadir gap: no image below it
    F(h)  = min(R, h / tan(min_grazing))     far limit: grazing too shallow
    K(h)  = g + knee_fraction * (F - g)      where the fall-off starts

    P(y) = 0                                  y < g   or  y >= F
         = pd_max                             g <= y <= K
         = pd_max * (F - y) / (F - K)         K <  y <  F

and P = 0 outside [min_altitude, max_altitude]. Flying higher widens the
nadir gap and, up to the range setting, pushes the far limit out. The sweep
width is the integral of the curve over both sides:

    W(h) = 2 pd_max [(K - g) + (F - K) / 2] = pd_max [(F - g) + (K - g)]

(zero when g >= F: too low for the far limit to clear the nadir gap).
"""

from __future__ import annotations

import math

import numpy as np

from sim.sonar.config import SonarConfig


class LateralRangeCurve:
    def __init__(self, cfg: SonarConfig) -> None:
        self.cfg = cfg
        self._tan_graze = math.tan(cfg.min_grazing_rad)

    def limits(self, altitude_m: float) -> tuple[float, float, float]:
        """(nadir gap g, knee K, far limit F) at this altitude [m]; all 0 if it cannot image."""
        c = self.cfg
        h = altitude_m
        if not c.min_altitude_m <= h <= c.max_altitude_m:
            return 0.0, 0.0, 0.0
        g = c.nadir_gap_per_altitude * h
        far = min(c.range_m, h / self._tan_graze) if self._tan_graze > 0.0 else c.range_m
        if far <= g:
            return 0.0, 0.0, 0.0
        return g, g + c.knee_fraction * (far - g), far

    def pd(self, ground_range_m, altitude_m: float, factor: float = 1.0):
        """P(detect) at ground range(s) |y| (scalar or array) and one altitude."""
        g, k, far = self.limits(altitude_m)
        y = np.abs(np.asarray(ground_range_m, dtype=float))
        p = np.zeros_like(y)
        if far > 0.0:
            pmax = min(1.0, self.cfg.pd_max * factor)
            plateau = (y >= g) & (y <= k)
            p[plateau] = pmax
            fall = (y > k) & (y < far)
            p[fall] = pmax * (far - y[fall]) / (far - k)
        return float(p) if p.ndim == 0 else p

    def sweep_width(self, altitude_m: float) -> float:
        """W(h): the integral of the curve over both sides [m]."""
        g, k, far = self.limits(altitude_m)
        if far <= 0.0:
            return 0.0
        return self.cfg.pd_max * ((far - g) + (k - g))

    def imaged_band(self, altitude_m: float) -> tuple[float, float]:
        """Ground ranges [g, F) that are imaged at all (P > 0), per side."""
        g, _, far = self.limits(altitude_m)
        return g, far
