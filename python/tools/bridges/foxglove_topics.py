"""Topics derived for Foxglove's Map panel, shared by the MCAP export and the
live bridge: positions as foxglove.LocationFix, the survey as foxglove.GeoJSON."""

from __future__ import annotations

import math
from typing import Any

DERIVED = "derived/"
LOCATION_FIX = {
    "$schema": "https://json-schema.org/draft/2020-12/schema",
    "title": "foxglove.LocationFix",
    "type": "object",
    "required": ["timestamp", "frame_id", "latitude", "longitude", "altitude"],
    "properties": {
        "timestamp": {
            "type": "object",
            "required": ["sec", "nsec"],
            "properties": {"sec": {"type": "integer"}, "nsec": {"type": "integer"}},
        },
        "frame_id": {"type": "string"},
        "latitude": {"type": "number"},
        "longitude": {"type": "number"},
        "altitude": {"type": "number"},
        "position_covariance": {"type": "array", "items": {"type": "number"}, "minItems": 9, "maxItems": 9},
        "position_covariance_type": {"type": "integer", "minimum": 0, "maximum": 3},
    },
}
GEOJSON = {
    "$schema": "https://json-schema.org/draft/2020-12/schema",
    "title": "foxglove.GeoJSON",
    "type": "object",
    "required": ["geojson"],
    "properties": {"geojson": {"type": "string"}},
}


def location_fix(msg: Any, pub_ns: int) -> dict[str, Any] | None:
    """A nav_solution_t or ground_truth_t as a fix (both carry WGS-84 positions
    from the world origin, and a depth); None when the position is not finite."""
    if type(msg).__name__ == "nav_solution_t":
        d = msg.depth_m
        cov = [msg.position_cov_m2[i][j] for i in (1, 0, 2) for j in (1, 0, 2)]  # east, north, up order
        cov_type = 3
    else:
        d = msg.eta[2]
        cov, cov_type = [0.0] * 9, 0
    lat, lon = msg.latitude_deg, msg.longitude_deg
    if not all(math.isfinite(x) for x in (lat, lon, d)):
        return None
    return {
        "timestamp": {"sec": pub_ns // 1_000_000_000, "nsec": pub_ns % 1_000_000_000},
        "frame_id": "world",
        "latitude": lat,
        "longitude": lon,
        "altitude": -d,
        "position_covariance": [c if c == c else 0.0 for c in cov],
        "position_covariance_type": cov_type,
    }


def geojson(geo: Any, survey: dict, targets: list) -> dict[str, Any]:
    def ring(pts: list) -> list:
        out = [list(reversed(geo.to_latlon(n, e))) for n, e in pts]
        return out + out[:1]

    feats = []
    for key, name in (("polygon", "survey area"), ("operating_area", "operating area")):
        if survey.get(key):
            feats.append(
                {
                    "type": "Feature",
                    "properties": {"name": name},
                    "geometry": {"type": "Polygon", "coordinates": [ring(survey[key])]},
                }
            )
    for vid, plan in (survey.get("vehicles") or {}).items():
        lines = [
            [list(reversed(geo.to_latlon(*leg["start"]))), list(reversed(geo.to_latlon(*leg["end"])))]
            for leg in plan.get("legs", [])
            if leg.get("kind") == "line"
        ]
        if lines:
            feats.append(
                {
                    "type": "Feature",
                    "properties": {"name": f"{vid} lines"},
                    "geometry": {"type": "MultiLineString", "coordinates": lines},
                }
            )
    for n, e, kind, tid in targets:
        feats.append(
            {
                "type": "Feature",
                "properties": {"name": f"target {tid} ({kind})"},
                "geometry": {"type": "Point", "coordinates": list(reversed(geo.to_latlon(n, e)))},
            }
        )
    return {"type": "FeatureCollection", "features": feats}
