"""An LCM log as MCAP for Foxglove: `lcmlog.py mcap LOG OUT.mcap`.

Every LCM channel becomes an MCAP channel of the same name, JSON-encoded, with
the JSON Schema of its type (auvlcm.json_schema, generated from lcmtypes/).
Each message's log time is the logging host's receive time and its publish
time the message's own utime (sim time). Derived topics for Foxglove's Map
panel are added under `derived/`: each vehicle's navigation and true
positions as foxglove.LocationFix, and the survey (survey area, operating
area, lines, the true targets) as one foxglove.GeoJSON, placed by the world
origin from SIM.ENV (no GeoJSON without it).

Events that do not decode are counted and left out (exit status 1, as the
other lcmlog commands).
"""

from __future__ import annotations

import argparse
import json
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import lcm
from mcap.writer import CompressionType, Writer

from auvlcm.decode import DecodeError, decode_strict
from auvlcm.json_schema import schema_of, to_json
from auvlcm.log import LCM_INTERNAL_CHANNELS
from auvlcm.types import type_of

DERIVED = "derived/"
LOCATION_FIX = {
    "$schema": "https://json-schema.org/draft/2020-12/schema", "title": "foxglove.LocationFix",
    "type": "object", "required": ["timestamp", "frame_id", "latitude", "longitude", "altitude"],
    "properties": {
        "timestamp": {"type": "object", "required": ["sec", "nsec"],
                      "properties": {"sec": {"type": "integer"}, "nsec": {"type": "integer"}}},
        "frame_id": {"type": "string"},
        "latitude": {"type": "number"}, "longitude": {"type": "number"}, "altitude": {"type": "number"},
        "position_covariance": {"type": "array", "items": {"type": "number"}, "minItems": 9, "maxItems": 9},
        "position_covariance_type": {"type": "integer", "minimum": 0, "maximum": 3}}}
GEOJSON = {"$schema": "https://json-schema.org/draft/2020-12/schema", "title": "foxglove.GeoJSON",
           "type": "object", "required": ["geojson"], "properties": {"geojson": {"type": "string"}}}


@dataclass
class ExportStats:
    per_channel: dict[str, int] = field(default_factory=dict)
    derived: dict[str, int] = field(default_factory=dict)
    undecodable: int = 0


class _Out:
    def __init__(self, writer: Writer) -> None:
        self.w = writer
        self.schemas: dict[str, int] = {}
        self.channels: dict[str, int] = {}

    def channel(self, topic: str, schema_name: str, schema: dict[str, Any]) -> int:
        if topic not in self.channels:
            if schema_name not in self.schemas:
                self.schemas[schema_name] = self.w.register_schema(
                    schema_name, "jsonschema", json.dumps(schema).encode())
            self.channels[topic] = self.w.register_channel(topic, "json", self.schemas[schema_name])
        return self.channels[topic]

    def write(self, topic: str, schema_name: str, schema: dict, obj: Any, log_ns: int, pub_ns: int) -> None:
        cid = self.channel(topic, schema_name, schema)
        self.w.add_message(cid, log_ns, json.dumps(obj, separators=(",", ":")).encode(), pub_ns)


def export(log_path: Path, out_path: Path) -> ExportStats:
    stats = ExportStats()
    geo = None
    survey: dict | None = None
    targets: list = []
    last_ns = 0
    with open(out_path, "wb") as f:
        writer = Writer(f, compression=CompressionType.ZSTD)
        writer.start(profile="", library="chasm-auv lcmlog")
        out = _Out(writer)
        log = lcm.EventLog(str(log_path), "r")
        try:
            for ev in log:
                if ev.channel in LCM_INTERNAL_CHANNELS:
                    continue
                cls = type_of(ev.data)
                try:
                    if cls is None:
                        raise DecodeError("unknown fingerprint", "wrong_fingerprint")
                    msg = decode_strict(cls, ev.data)
                except DecodeError:
                    stats.undecodable += 1
                    continue
                log_ns = ev.timestamp * 1000
                last_ns = max(last_ns, log_ns)
                utime = getattr(msg, "utime", 0)
                # MCAP times are unsigned 64-bit ns: a utime that does not fit takes the log time
                pub_ns = utime * 1000 if 0 < utime * 1000 < 1 << 64 else log_ns
                out.write(ev.channel, f"auv.{cls.__name__}", schema_of(cls), to_json(msg), log_ns, pub_ns)
                stats.per_channel[ev.channel] = stats.per_channel.get(ev.channel, 0) + 1
                name = cls.__name__
                if name == "env_model_t" and geo is None:
                    from sim.geo import LocalFrame
                    geo = LocalFrame(msg.origin_latitude_deg, msg.origin_longitude_deg)
                elif name == "log_annotation_t" and msg.kind == 0 and msg.name.endswith("survey.json"):
                    try:
                        survey = json.loads(msg.text)
                    except ValueError:
                        pass
                elif name == "target_field_t":
                    targets = [(t.north_m, t.east_m, "mine_like" if t.kind == 0 else "clutter", t.id)
                               for t in msg.targets]
                elif name in ("nav_solution_t", "ground_truth_t"):
                    kind = "nav_position" if name == "nav_solution_t" else "true_position"
                    topic = f"{DERIVED}{ev.channel.split('.')[0]}/{kind}"
                    out.write(topic, "foxglove.LocationFix", LOCATION_FIX,
                              _fix(msg, pub_ns), log_ns, pub_ns)
                    stats.derived[topic] = stats.derived.get(topic, 0) + 1
        finally:
            log.close()
        if geo is not None and (survey or targets):
            topic = f"{DERIVED}survey_geojson"
            out.write(topic, "foxglove.GeoJSON", GEOJSON,
                      {"geojson": json.dumps(_geojson(geo, survey or {}, targets))}, last_ns, last_ns)
            stats.derived[topic] = 1
        writer.finish()
    return stats


def _fix(msg: Any, pub_ns: int) -> dict[str, Any]:
    """Both types carry WGS-84 positions (from the world origin) and a depth."""
    if type(msg).__name__ == "nav_solution_t":
        d = msg.depth_m
        cov = [msg.position_cov_m2[i][j] for i in (1, 0, 2) for j in (1, 0, 2)]   # east, north, up order
        cov_type = 3
    else:
        d = msg.eta[2]
        cov, cov_type = [0.0] * 9, 0
    lat, lon = msg.latitude_deg, msg.longitude_deg
    return {"timestamp": {"sec": pub_ns // 1_000_000_000, "nsec": pub_ns % 1_000_000_000},
            "frame_id": "world", "latitude": lat, "longitude": lon, "altitude": -d,
            "position_covariance": [c if c == c else 0.0 for c in cov], "position_covariance_type": cov_type}


def _geojson(geo: Any, survey: dict, targets: list) -> dict[str, Any]:
    def ring(pts: list) -> list:
        out = [list(reversed(geo.to_latlon(n, e))) for n, e in pts]
        return out + out[:1]
    feats = []
    for key, name in (("polygon", "survey area"), ("operating_area", "operating area")):
        if survey.get(key):
            feats.append({"type": "Feature", "properties": {"name": name},
                          "geometry": {"type": "Polygon", "coordinates": [ring(survey[key])]}})
    for vid, plan in (survey.get("vehicles") or {}).items():
        lines = [[list(reversed(geo.to_latlon(*leg["start"]))), list(reversed(geo.to_latlon(*leg["end"])))]
                 for leg in plan.get("legs", []) if leg.get("kind") == "line"]
        if lines:
            feats.append({"type": "Feature", "properties": {"name": f"{vid} lines"},
                          "geometry": {"type": "MultiLineString", "coordinates": lines}})
    for n, e, kind, tid in targets:
        feats.append({"type": "Feature", "properties": {"name": f"target {tid} ({kind})"},
                      "geometry": {"type": "Point", "coordinates": list(reversed(geo.to_latlon(n, e)))}})
    return {"type": "FeatureCollection", "features": feats}


# ----------------------------------------------------------------- lcmlog.py hook
def add_parser(sub: Any) -> None:
    p = sub.add_parser("mcap", help="the log as MCAP (JSON + JSON Schema) for Foxglove")
    p.add_argument("log", type=Path)
    p.add_argument("out", type=Path)


def run(args: argparse.Namespace) -> int:
    try:
        stats = export(args.log, args.out)
    except OSError as exc:
        print(f"lcmlog: {exc}", file=sys.stderr)
        return 2
    n = sum(stats.per_channel.values())
    print(f"{args.out}: {n} messages on {len(stats.per_channel)} channels, "
          f"{sum(stats.derived.values())} derived on {len(stats.derived)} topics")
    if stats.undecodable:
        print(f"{args.log}: {stats.undecodable} undecodable event(s) left out", file=sys.stderr)
        return 1
    return 0
