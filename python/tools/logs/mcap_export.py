"""An LCM log as MCAP for Foxglove: `auv-lcmlog mcap LOG OUT.mcap`.

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
from tools.bridges.foxglove_topics import DERIVED, GEOJSON, LOCATION_FIX, geojson, location_fix


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
                    schema_name, "jsonschema", json.dumps(schema).encode()
                )
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
                    targets = [
                        (t.north_m, t.east_m, "mine_like" if t.kind == 0 else "clutter", t.id) for t in msg.targets
                    ]
                elif name in ("nav_solution_t", "ground_truth_t"):
                    kind = "nav_position" if name == "nav_solution_t" else "true_position"
                    topic = f"{DERIVED}{ev.channel.split('.')[0]}/{kind}"
                    fix = location_fix(msg, pub_ns)
                    if fix is not None:
                        out.write(topic, "foxglove.LocationFix", LOCATION_FIX, fix, log_ns, pub_ns)
                        stats.derived[topic] = stats.derived.get(topic, 0) + 1
        finally:
            log.close()
        if geo is not None and (survey or targets):
            topic = f"{DERIVED}survey_geojson"
            out.write(
                topic,
                "foxglove.GeoJSON",
                GEOJSON,
                {"geojson": json.dumps(geojson(geo, survey or {}, targets))},
                last_ns,
                last_ns,
            )
            stats.derived[topic] = 1
        writer.finish()
    return stats


# ----------------------------------------------------------------- auv-lcmlog hook
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
    print(
        f"{args.out}: {n} messages on {len(stats.per_channel)} channels, "
        f"{sum(stats.derived.values())} derived on {len(stats.derived)} topics"
    )
    if stats.undecodable:
        print(f"{args.log}: {stats.undecodable} undecodable event(s) left out", file=sys.stderr)
        return 1
    return 0
