"""The surface radio's physics: who can hear whom, when a frame arrives.

A vehicle's antenna sits `antenna_height_m` above its reference depth; it is
clear of the water while its tip is above the wave crests (half the wave
height): depth < antenna_height_m - wave_height_m / 2. The link between two
nodes is up while both antennas are clear and they are within `max_range_m`
of each other (horizontal range; the shore station's antenna is always
clear). Each node sends one frame at a time at `bitrate_bps` (its bytes plus
`frame_overhead_bytes` of preamble and framing); a frame arrives `latency_s`
after its last bit, unless the link was down when it started or is down when
it arrives (a dive cuts it), or it is lost (`loss`, one seeded draw per
frame). A frame handed over while the link is down, or beyond
`queue_bytes` waiting, is dropped: the radio does not store and forward; the
gateways' protocol resends what did not arrive.
"""

from __future__ import annotations

import math
import random
from collections import deque
from dataclasses import dataclass, field

from confcheck import setting

SHORE = "SHORE"


@dataclass
class RadioConfig:
    bitrate_bps: float = setting(115200.0, gt=0.0)  # over the air (Freewave class: 115.2 kbit/s)
    frame_overhead_bytes: int = setting(16, ge=0)  # preamble, addresses, CRC per frame
    latency_s: float = setting(0.02, ge=0.0)  # from the last bit to delivery
    loss: float = setting(0.0, ge=0.0, le=1.0)  # probability a frame is lost
    max_range_m: float = setting(5000.0, gt=0.0)  # horizontal range it reaches
    antenna_height_m: float = setting(0.5, ge=0.0)  # antenna tip above the vehicle's reference depth
    wave_height_m: float = setting(0.2, ge=0.0)  # crest to trough
    max_frame_bytes: int = setting(8192, ge=64)  # larger frames are refused
    queue_bytes: int = setting(65536, ge=0)  # waiting to go on air, per node
    shore_north_m: float = 0.0  # the shore station's position in the world frame [m]
    shore_east_m: float = 0.0
    status_period_s: float = setting(1.0, gt=0.0)
    seed: int = 0


@dataclass
class Frame:
    src: str
    dst: str
    payload: bytes
    t_start: float = 0.0
    t_arrive: float = 0.0


@dataclass
class Node:
    name: str
    north: float = 0.0
    east: float = 0.0
    depth: float = 1e9  # unknown: under water
    queue: deque[Frame] = field(default_factory=deque)
    queued_bytes: int = 0
    busy_until: float = 0.0


@dataclass
class Counts:
    sent: int = 0
    delivered: int = 0
    lost: int = 0
    dropped: int = 0
    bytes_delivered: int = 0


class RadioLink:
    def __init__(self, cfg: RadioConfig, vehicles: list[str]) -> None:
        self.cfg = cfg
        self.rng = random.Random(cfg.seed)
        self.nodes = {v: Node(v) for v in vehicles}
        self.nodes[SHORE] = Node(SHORE, cfg.shore_north_m, cfg.shore_east_m, -cfg.antenna_height_m)
        self.air: list[Frame] = []
        self.counts = {n: Counts() for n in self.nodes}
        self.drop_reasons: dict[str, int] = {}

    def set_position(self, vehicle: str, north: float, east: float, depth: float) -> None:
        n = self.nodes[vehicle]
        n.north, n.east, n.depth = north, east, depth

    def clear(self, name: str) -> bool:
        n = self.nodes[name]
        return name == SHORE or n.depth < self.cfg.antenna_height_m - self.cfg.wave_height_m / 2

    def range_m(self, a: str, b: str) -> float:
        na, nb = self.nodes[a], self.nodes[b]
        return math.hypot(na.north - nb.north, na.east - nb.east)

    def up(self, a: str, b: str) -> bool:
        return self.clear(a) and self.clear(b) and self.range_m(a, b) <= self.cfg.max_range_m

    def _drop(self, f: Frame, reason: str) -> None:
        self.counts[f.src].dropped += 1
        self.drop_reasons[reason] = self.drop_reasons.get(reason, 0) + 1

    def send(self, src: str, dst: str, payload: bytes, now: float) -> str:
        """Hand a frame to src's radio; "" if accepted, else why it was dropped."""
        if src not in self.nodes or dst not in self.nodes or src == dst:
            return f"unknown node {src!r} -> {dst!r}"
        f = Frame(src, dst, payload)
        self.counts[src].sent += 1
        node = self.nodes[src]
        reason = ""
        if len(payload) > self.cfg.max_frame_bytes:
            reason = "too large"
        elif not self.up(src, dst):
            reason = "link down"
        elif node.queued_bytes + len(payload) > self.cfg.queue_bytes:
            reason = "queue full"
        if reason:
            self._drop(f, reason)
            return reason
        node.queue.append(f)
        node.queued_bytes += len(payload)
        self._start(node, now)
        return ""

    def _start(self, node: Node, now: float) -> None:
        if node.queue and node.busy_until <= now:
            f = node.queue.popleft()
            node.queued_bytes -= len(f.payload)
            f.t_start = max(now, node.busy_until)
            airtime = 8.0 * (len(f.payload) + self.cfg.frame_overhead_bytes) / self.cfg.bitrate_bps
            node.busy_until = f.t_start + airtime
            f.t_arrive = node.busy_until + self.cfg.latency_s
            if not self.up(f.src, f.dst):
                self._drop(f, "link down")
                return
            self.air.append(f)

    def step(self, now: float) -> list[Frame]:
        """Advance to now: frames start on air, and those due arrive (returned)."""
        out: list[Frame] = []
        while True:  # one frame at a time per node: a queue drains as its frames leave the air
            ready = [n for n in self.nodes.values() if n.queue and n.busy_until <= now]
            if not ready:
                break
            for node in ready:
                self._start(node, node.busy_until)
        for f in sorted((f for f in self.air if f.t_arrive <= now), key=lambda f: f.t_arrive):
            self.air.remove(f)
            if not self.up(f.src, f.dst):
                self._drop(f, "cut")
            elif self.cfg.loss > 0 and self.rng.random() < self.cfg.loss:
                self.counts[f.src].lost += 1
            else:
                self.counts[f.src].delivered += 1
                self.counts[f.src].bytes_delivered += len(f.payload)
                out.append(f)
        return out

    def queued(self, name: str) -> int:
        return self.nodes[name].queued_bytes
