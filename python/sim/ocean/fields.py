"""The ocean's temperature and salinity as functions of time, position and depth.

Deterministic from the parameters and the seed, with no hidden state, like the
rest of the world (sim.environment): any simulator can serve it and a new
server continues it without a jump.

The analytic ocean (docs/sampling.md, "The ocean's fields"):

- **a front** between two upper water masses a (left of the front, looking
  along `angle_rad`) and b (right). Across-front distance at a point:
  x = r . (n, e) - offset - drift t - A sin(2 pi (s / L - t / P) + phi),
  with r the unit vector to the right of the front, s the distance along it,
  A, L, P the meander's amplitude, wavelength and period (P = 0: standing) and
  phi the meander's phase, drawn from the seed. The upper water is
  a + w (b - a) with w = (1 + tanh(x / width)) / 2.
- **a thermocline** between the upper water and the deep water mass:
  value = deep + (upper - deep) (1 - tanh((z - depth) / thickness)) / 2.
- **plumes**, each a Gaussian anomaly (temperature and salinity) released at
  a point and time, its centre carried by the current at its depth (the
  environment's profile and slow variation, integrated in closed form), its
  horizontal variance growing by 2 K t and its peak falling as the variance
  grows (what it carries is conserved).

Or a grid file (sim.ocean.grid) in place of front, water masses and
thermocline; plumes are added to either.
"""

from __future__ import annotations

import math
import random
from pathlib import Path
from typing import Callable

import numpy as np

import sim.ocean.teos10 as teos10
from sim.ocean.grid import OceanGrid, load_grid
from sim.ocean.params import OceanParams

# (depth, north, east, t0, t1) -> the water's horizontal displacement over [t0, t1] [m]
Drift = Callable[[float, float, float, float, float], tuple[float, float]]
# samples along a straight acoustic path (harmonic mean: the travel time)
PATH_SAMPLES = 16


def _no_drift(depth: float, north: float, east: float, t0: float, t1: float) -> tuple[float, float]:
    return 0.0, 0.0


class Ocean:
    def __init__(
        self,
        params: OceanParams,
        seed: int,
        lat0: float,
        lon0: float,
        drift: Drift | None = None,
        base_dir: Path | None = None,
    ) -> None:
        self.params = params
        self.lat0, self.lon0 = lat0, lon0
        self.drift = drift or _no_drift
        rng = random.Random(f"{seed}:ocean")
        self.meander_phase = rng.uniform(0.0, 2.0 * math.pi)
        f = params.front
        self._along = (math.cos(f.angle_rad), math.sin(f.angle_rad))
        self._right = (-math.sin(f.angle_rad), math.cos(f.angle_rad))
        self.grid: OceanGrid | None = None
        if params.grid:
            self.grid = load_grid(grid_path(params, base_dir), lat0, lon0, params.grid_start)

    # ------------------------------------------------------------ fields
    def front_position(self, t: float, along_m: float) -> float:
        """Where the front is, across it, at a distance along it [m] (its x = 0)."""
        f = self.params.front
        x = f.offset_m + f.drift_mps * t
        if f.amplitude_m > 0.0:
            x += f.amplitude_m * math.sin(self._meander_arg(t, along_m))
        return x

    def _meander_arg(self, t, s):
        f = self.params.front
        arg = 2.0 * math.pi * np.asarray(s, float) / f.wavelength_m + self.meander_phase
        if f.period_s > 0.0:
            arg = arg - 2.0 * math.pi * np.asarray(t, float) / f.period_s
        return arg

    def fields(self, t, north, east, depth) -> tuple[np.ndarray, np.ndarray]:
        """In-situ temperature [degC] and practical salinity [PSU] (numpy broadcasting)."""
        t, north, east, depth = np.broadcast_arrays(
            np.asarray(t, float), np.asarray(north, float), np.asarray(east, float), np.asarray(depth, float)
        )
        if self.grid is not None:
            temp, salt = self.grid.sample(t, north, east, depth)
        else:
            temp, salt = self._analytic(t, north, east, depth)
        if self.params.plumes:
            temp, salt = self._plumes(t, north, east, depth, temp, salt)
        return temp, salt

    def _analytic(self, t, north, east, depth):
        p = self.params
        f = p.front
        s = north * self._along[0] + east * self._along[1]
        x = north * self._right[0] + east * self._right[1] - f.offset_m - f.drift_mps * t
        if f.amplitude_m > 0.0:
            x = x - f.amplitude_m * np.sin(self._meander_arg(t, s))
        w = 0.5 * (1.0 + np.tanh(x / f.width_m))
        a, b, deep = p.water_a, p.water_b, p.deep
        upper_t = a.temperature_c + w * (b.temperature_c - a.temperature_c)
        upper_s = a.salinity_psu + w * (b.salinity_psu - a.salinity_psu)
        th = p.thermocline
        up = 0.5 * (1.0 - np.tanh((depth - th.depth_m) / th.thickness_m))
        return (
            deep.temperature_c + (upper_t - deep.temperature_c) * up,
            deep.salinity_psu + (upper_s - deep.salinity_psu) * up,
        )

    def plume_centre(self, index: int, t: float) -> tuple[float, float, float] | None:
        """Where plume `index` is at time t (None before it is released)."""
        pl = self.params.plumes[index]
        if t < pl.start_s:
            return None
        dn, de = self.drift(pl.depth_m, pl.north_m, pl.east_m, pl.start_s, t)
        return pl.north_m + dn, pl.east_m + de, pl.depth_m

    def _plumes(self, t, north, east, depth, temp, salt):
        temp, salt = np.array(temp, float), np.array(salt, float)
        flat = t.reshape(-1)
        if flat.size == 0 or bool(np.all(flat == flat[0])):  # one time (a sample, a path): no masks
            groups = [(float(flat[0]) if flat.size else 0.0, None)]
        else:
            groups = [(float(tk), t == tk) for tk in np.unique(flat)]
        for i, pl in enumerate(self.params.plumes):
            for tk, mask in groups:
                c = self.plume_centre(i, tk)
                if c is None:
                    continue
                var = pl.radius_m**2 + 2.0 * pl.diffusivity_m2ps * (tk - pl.start_s)
                q = ((north - c[0]) ** 2 + (east - c[1]) ** 2) / var + ((depth - c[2]) / pl.thickness_m) ** 2
                g = pl.radius_m**2 / var * np.exp(-0.5 * q)  # far away it underflows to 0
                if mask is not None:
                    g = np.where(mask, g, 0.0)
                temp += g * pl.temperature_c
                salt += g * pl.salinity_psu
        return temp, np.maximum(salt, 0.0)

    def temperature_salinity(self, t: float, north: float, east: float, depth: float) -> tuple[float, float]:
        temp, salt = self.fields(t, north, east, depth)
        return float(temp), float(salt)

    # ------------------------------------------------------------ sound
    def sound_speeds(self, t, north, east, depth) -> np.ndarray:
        """TEOS-10 sound speed of the local water [m/s] (depth above the surface read as 0)."""
        depth = np.maximum(np.asarray(depth, float), 0.0)
        temp, salt = self.fields(t, north, east, depth)
        return teos10.sound_speed(temp, salt, depth, self.lat0, self.lon0)

    def sound_speed(self, t: float, north: float, east: float, depth: float) -> float:
        return float(self.sound_speeds(t, north, east, depth))

    def path_sound_speed(
        self, t: float, a: tuple[float, float, float], b: tuple[float, float, float], samples: int = PATH_SAMPLES
    ) -> float:
        """The speed that gives the travel time along the straight path a -> b
        (north, east, depth): its length over the integral of 1/c along it, the
        harmonic mean of the speeds at `samples` midpoints of equal segments
        (straight rays: no refraction)."""
        if math.dist(a, b) < 1e-9:
            return self.sound_speed(t, *a)
        f = (np.arange(samples) + 0.5) / samples
        pts = [a[k] + f * (b[k] - a[k]) for k in range(3)]
        c = self.sound_speeds(t, pts[0], pts[1], pts[2])
        return float(1.0 / np.mean(1.0 / c))

    def profile_fit(self, max_depth_m: float) -> tuple[float, float]:
        """A linear sound-speed profile (speed at the surface, gradient per metre)
        fitted to the ocean at the world origin at time 0: a cast before the run."""
        d = np.linspace(0.0, max(max_depth_m, 1.0), 21)
        c = self.sound_speeds(0.0, 0.0, 0.0, d)
        g, c0 = np.polyfit(d, c, 1)
        return float(c0), float(g)


def grid_path(params: OceanParams, base_dir: Path | None = None) -> Path:
    """Where a grid file is on this host: as written if absolute, else in base_dir
    (the configuration's folder), else in params.base_dir, else the working folder."""
    path = Path(params.grid)
    if path.is_absolute():
        return path
    if base_dir is not None:
        return base_dir / path
    if params.base_dir:
        return Path(params.base_dir) / path
    return path
