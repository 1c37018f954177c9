"""Seabed depth as a function of (north, east): analytic shapes or a grid file.

A bathymetry is named by a reference string that travels in env_model_t
(`bathymetry_ref`), so every simulator builds the same seabed from it:

    flat:depth=40
    slope:depth=40,dn=0.01,de=-0.02          depth + dn*north + de*east
    hill:depth=40,height=25,north=100,east=50,radius=30   Gaussian seamount
    ripple:depth=40,amplitude=2,wavelength=50,direction=0.3
    grid:missions/sim/worlds/bay.npz        arrays north_m (N), east_m (E), depth_m (N x E)

Grids are interpolated bilinearly and clamped at their edges; their SHA-256
goes with the reference so a server and its clients can check they agree.
"""

from __future__ import annotations

import hashlib
import math
from pathlib import Path

import numpy as np

SHAPES = {
    "flat": {"depth"},
    "slope": {"depth", "dn", "de"},
    "hill": {"depth", "height", "north", "east", "radius"},
    "ripple": {"depth", "amplitude", "wavelength", "direction"},
}


class BathymetryError(ValueError):
    pass


def parse_ref(ref: str) -> tuple[str, dict[str, float] | str]:
    kind, _, rest = ref.partition(":")
    if kind == "grid":
        if not rest:
            raise BathymetryError("grid bathymetry needs a file: 'grid:PATH.npz'")
        return kind, rest
    if kind not in SHAPES:
        raise BathymetryError(f"unknown bathymetry shape {kind!r}; one of {', '.join(sorted(SHAPES) + ['grid'])}")
    params: dict[str, float] = {}
    for item in filter(None, rest.split(",")):
        key, eq, val = item.partition("=")
        if not eq or key.strip() not in SHAPES[kind]:
            raise BathymetryError(f"{kind}: unknown parameter {item!r}; expected {', '.join(sorted(SHAPES[kind]))}")
        try:
            params[key.strip()] = float(val)
        except ValueError:
            raise BathymetryError(f"{kind}: {key} must be a number, got {val!r}") from None
    if "depth" not in params:
        raise BathymetryError(f"{kind}: 'depth' is required")
    return kind, params


def make_ref(kind: str, params: dict[str, float]) -> str:
    return f"{kind}:" + ",".join(f"{k}={params[k]:g}" for k in sorted(params))


class Bathymetry:
    def __init__(self, ref: str, base_dir: Path | None = None) -> None:
        self.ref = ref
        self.sha256 = ""
        kind, params = parse_ref(ref)
        self.kind = kind
        if kind == "grid":
            path = Path(params)
            if not path.is_absolute() and base_dir is not None:
                path = base_dir / path
            try:
                raw = path.read_bytes()
                with np.load(path) as data:
                    self._n = np.asarray(data["north_m"], float)
                    self._e = np.asarray(data["east_m"], float)
                    self._d = np.asarray(data["depth_m"], float)
            except (OSError, KeyError, ValueError) as exc:
                raise BathymetryError(
                    f"{path}: cannot load bathymetry grid ({exc}); expected arrays north_m, east_m, depth_m"
                ) from None
            if self._d.shape != (self._n.size, self._e.size) or self._n.size < 2 or self._e.size < 2:
                raise BathymetryError(f"{path}: depth_m must be len(north_m) x len(east_m), at least 2 x 2")
            if np.any(np.diff(self._n) <= 0) or np.any(np.diff(self._e) <= 0):
                raise BathymetryError(f"{path}: north_m and east_m must increase")
            self.sha256 = hashlib.sha256(raw).hexdigest()
            self._dn = float(self._n[1] - self._n[0])
            self._de = float(self._e[1] - self._e[0])
            self._uniform = np.allclose(np.diff(self._n), self._dn) and np.allclose(np.diff(self._e), self._de)
        else:
            self.p = params

    def depth(self, north: float, east: float) -> float:
        """Water depth (seabed below the surface) at a point [m]."""
        k = self.kind
        p = getattr(self, "p", None)
        if k == "flat":
            return p["depth"]
        if k == "slope":
            return p["depth"] + p.get("dn", 0.0) * north + p.get("de", 0.0) * east
        if k == "hill":
            rr = p.get("radius", 1.0)
            d2 = (north - p.get("north", 0.0)) ** 2 + (east - p.get("east", 0.0)) ** 2
            return p["depth"] - p.get("height", 0.0) * math.exp(-0.5 * d2 / (rr * rr))
        if k == "ripple":
            a = p.get("direction", 0.0)
            s = north * math.cos(a) + east * math.sin(a)
            return p["depth"] + p.get("amplitude", 0.0) * math.sin(2.0 * math.pi * s / p.get("wavelength", 1.0))
        return self._grid(north, east)

    def _grid(self, north: float, east: float) -> float:
        n, e, d = self._n, self._e, self._d
        north = min(max(north, n[0]), n[-1])
        east = min(max(east, e[0]), e[-1])
        if self._uniform:
            i = min(int((north - n[0]) / self._dn), n.size - 2)
            j = min(int((east - e[0]) / self._de), e.size - 2)
        else:
            i = min(max(int(np.searchsorted(n, north)) - 1, 0), n.size - 2)
            j = min(max(int(np.searchsorted(e, east)) - 1, 0), e.size - 2)
        fn = (north - n[i]) / (n[i + 1] - n[i])
        fe = (east - e[j]) / (e[j + 1] - e[j])
        d00, d01, d10, d11 = d[i, j], d[i, j + 1], d[i + 1, j], d[i + 1, j + 1]
        return float((1 - fn) * ((1 - fe) * d00 + fe * d01) + fn * ((1 - fe) * d10 + fe * d11))
