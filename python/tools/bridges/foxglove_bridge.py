#!/usr/bin/env python3
"""Every LCM channel, live, to Foxglove (docs/console.md).

    auv-foxglove [--lcm-url URL] [--bind ADDR] [--port N]

Serves the Foxglove WebSocket protocol (foxglove-sdk): open Foxglove and
connect to ws://ADDR:PORT. Each LCM channel is a topic of the same name, JSON
with the JSON Schema of its type (auvlcm.json_schema, as `auv-lcmlog mcap`
writes); plus derived/<VEHICLE>/nav_position and true_position
(foxglove.LocationFix) and derived/survey_geojson (foxglove.GeoJSON, once the
survey and the world origin have been heard, at once to a client that
subscribes to it and every few seconds; Foxglove keeps no latched messages). Messages that do not decode are counted and
dropped. Binds to localhost unless told otherwise.

Exit status: 0 on Ctrl-C or SIGTERM, 1 if LCM stops working, 2 on a usage or address error.
"""

from __future__ import annotations

import argparse
import json
import signal
import sys
import time
from typing import Any

import foxglove
import foxglove.websocket
import lcm

from auvlcm import programs
from auvlcm.json_schema import schema_of, to_json
from auvlcm.log import LCM_INTERNAL_CHANNELS
from auvlcm.url import check_local, default_url
from tools.bridges.foxglove_topics import DERIVED, GEOJSON, LOCATION_FIX, geojson, location_fix
from tools.console.sources import decode

GEOJSON_EVERY_S = 5.0


class SubscribeListener(foxglove.websocket.ServerListener):
    """A panel that subscribes to the survey gets it at the bridge's next tick, not
    after up to GEOJSON_EVERY_S (called on the server's thread: one float written)."""

    def __init__(self, bridge: "Bridge") -> None:
        self.bridge = bridge

    def on_subscribe(self, client, channel) -> None:
        if channel.topic == f"{DERIVED}survey_geojson":
            self.bridge.geojson_sent = 0.0


class Bridge:
    def __init__(self) -> None:
        self.channels: dict[str, foxglove.Channel] = {}
        self.dropped = 0
        self.forwarded = 0
        self.geo = None
        self.survey: dict | None = None
        self.targets: list = []
        self.geojson_sent = 0.0

    def channel(self, topic: str, name: str, schema: dict[str, Any]) -> foxglove.Channel:
        ch = self.channels.get(topic)
        if ch is None:
            ch = self.channels[topic] = foxglove.Channel(
                topic,
                message_encoding="json",
                schema=foxglove.Schema(name=name, encoding="jsonschema", data=json.dumps(schema).encode()),
            )
        return ch

    def on_raw(self, channel: str, data: bytes) -> None:
        if channel in LCM_INTERNAL_CHANNELS:
            return
        msg = decode(data)
        if msg is None:
            self.dropped += 1
            return
        cls = type(msg)
        self.channel(channel, f"auv.{cls.__name__}", schema_of(cls)).log(to_json(msg))
        self.forwarded += 1
        name = cls.__name__
        if name in ("nav_solution_t", "ground_truth_t"):
            fix = location_fix(msg, max(0, msg.utime) * 1000)
            if fix is not None:
                kind = "nav_position" if name == "nav_solution_t" else "true_position"
                self.channel(f"{DERIVED}{channel.split('.')[0]}/{kind}", "foxglove.LocationFix", LOCATION_FIX).log(fix)
        elif name == "env_model_t" and self.geo is None:
            from sim.geo import LocalFrame

            self.geo = LocalFrame(msg.origin_latitude_deg, msg.origin_longitude_deg)
        elif name == "log_annotation_t" and msg.kind == 0 and msg.name.endswith("survey.json"):
            try:
                survey = json.loads(msg.text)
            except ValueError:
                return
            if survey != self.survey:  # a new survey goes out at once, a repeat waits its turn
                self.survey, self.geojson_sent = survey, 0.0
        elif name == "target_field_t":
            self.targets = [(t.north_m, t.east_m, "mine_like" if t.kind == 0 else "clutter", t.id) for t in msg.targets]

    def tick(self) -> None:
        """Repeat the survey's GeoJSON: Foxglove keeps no latched messages."""
        now = time.monotonic()
        if self.geo is not None and (self.survey or self.targets) and now - self.geojson_sent >= GEOJSON_EVERY_S:
            doc = geojson(self.geo, self.survey or {}, self.targets)
            self.channel(f"{DERIVED}survey_geojson", "foxglove.GeoJSON", GEOJSON).log({"geojson": json.dumps(doc)})
            self.geojson_sent = now


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="auv-foxglove", description=__doc__.split("\n\n")[0])
    programs.add_lcm_url_argument(ap, "LCM URL (default $LCM_DEFAULT_URL or the project's)", default=None)
    ap.add_argument("--bind", default="127.0.0.1", help="address to serve on (default 127.0.0.1)")
    ap.add_argument("--port", type=int, default=8765, help="port (default 8765, Foxglove's; 0 picks one)")
    args = ap.parse_args(argv)
    try:
        url = check_local(args.url or default_url())
        lc = lcm.LCM(url)
    except (ValueError, RuntimeError) as exc:
        print(f"foxglove_bridge: {exc}", file=sys.stderr)
        return 2
    bridge = Bridge()
    sub = lc.subscribe(".*", bridge.on_raw)
    sub.set_queue_capacity(5000)
    try:
        server = foxglove.start_server(
            name="chasm-auv", host=args.bind, port=args.port, server_listener=SubscribeListener(bridge)
        )
    except Exception as exc:  # noqa: BLE001 - the SDK raises its own error types
        print(f"foxglove_bridge: cannot serve on {args.bind}:{args.port}: {exc}", file=sys.stderr)
        return 2

    stopping = []
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, lambda signum, frame: stopping.append(signum))
    print(f"foxglove_bridge: serving ws://{args.bind}:{server.port} (LCM {url})", flush=True)
    errors = 0
    try:
        while not stopping:
            try:
                lc.handle_timeout(200)
                errors = 0
            except OSError:  # EINTR from the signal that stops us (checked above)
                errors += 1
                if errors > 10:
                    print("foxglove_bridge: LCM receive keeps failing", file=sys.stderr)
                    return 1
            bridge.tick()
    finally:
        server.stop()
        print(
            f"foxglove_bridge: {bridge.forwarded} messages forwarded on {len(bridge.channels)} topics, "
            f"{bridge.dropped} undecodable dropped",
            flush=True,
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
