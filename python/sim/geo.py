"""Local NED <-> WGS-84 on a flat-earth tangent plane (fine over tens of km)."""

from __future__ import annotations

import math

_A = 6378137.0  # WGS-84 semi-major axis [m]
_E2 = 6.69437999014e-3  # first eccentricity squared


def radii(lat_deg: float) -> tuple[float, float]:
    """Meridian and prime-vertical radii of curvature at a latitude [m]."""
    s = math.sin(math.radians(lat_deg))
    d = 1.0 - _E2 * s * s
    return _A * (1.0 - _E2) / d**1.5, _A / math.sqrt(d)


class LocalFrame:
    def __init__(self, lat0_deg: float, lon0_deg: float) -> None:
        self.re_origin(lat0_deg, lon0_deg)

    def re_origin(self, lat0_deg: float, lon0_deg: float) -> None:
        """Move the origin, in place: whoever holds this frame (the GPS, the INS)
        converts from the new one on."""
        self.lat0 = lat0_deg
        self.lon0 = lon0_deg
        rm, rn = radii(lat0_deg)
        self._dlat = math.degrees(1.0 / rm)
        self._dlon = math.degrees(1.0 / (rn * math.cos(math.radians(lat0_deg))))

    def to_latlon(self, north_m: float, east_m: float) -> tuple[float, float]:
        return self.lat0 + north_m * self._dlat, self.lon0 + east_m * self._dlon

    def to_ned(self, lat_deg: float, lon_deg: float) -> tuple[float, float]:
        return (lat_deg - self.lat0) / self._dlat, (lon_deg - self.lon0) / self._dlon
