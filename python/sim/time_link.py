"""The time link's part of the simulator: the `time_link:` section and its output.

The link itself (the $PAUVT sentence, stamped with the sim time of its own
last byte at the far end) is sim.devices.time_link; docs/simulator.md, "The
time link". The simulator sends one sentence per period of sim time, at the
physics step the period falls in (sim.hil polls it like the sonar), on a port
of its own (Simulator.devices.add): nothing on the simulator's LCM.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

from confcheck import Checker, setting
from sim.devices.config import parse_wire
from sim.devices.emulator import DeviceContext
from sim.devices.line import BITS_PER_BYTE
from sim.devices.time_link import SENTENCE_MAX_BYTES, Sample, TimeLink
from sim.periodic import Periodic

# at most this share of the line: a sentence finds it idle (its stamp needs it)
LINE_SHARE_MAX = 0.5


@dataclass
class TimeLinkConfig:
    rate_hz: float = setting(20.0, gt=0.0, le=1000.0, unit="Hz")  # sentences per sim second
    wire: Any = None  # its port (sim.devices.config.WireConfig): required


def check_time_link(doc: Checker, node, base: Path) -> TimeLinkConfig | None:
    """The checked `time_link:` section (None: absent or false)."""
    if node is None or (isinstance(node, yaml.ScalarNode) and doc.scalar(node) is False):
        return None
    errors_before = len(doc.errors)
    wire = {"wire": lambda n, k: parse_wire(doc, n, k, "time_link", base)}
    cfg = doc.fill(node, "time_link", TimeLinkConfig(), special=wire)
    items = doc.mapping(node, "time_link")
    if "wire" not in items:
        doc.err(node, "time_link", "missing required key 'wire' ({protocol: pauvt, pty: PATH | tcp: HOST:PORT, ...})")
    elif cfg.wire is None and len(doc.errors) == errors_before:
        doc.err(items["wire"][1], "time_link.wire", "the time link is its wire: give one, or `time_link: false`")
    elif cfg.wire is not None:
        witems = doc.mapping(items["wire"][1], "time_link.wire")
        if "publish_lcm" in witems:
            doc.err(
                witems["publish_lcm"][1],
                "time_link.wire.publish_lcm",
                "the time link has no LCM message of its own (the simulator's SIM.CLOCK is simulation.publish_clock)",
            )
        share = cfg.rate_hz * SENTENCE_MAX_BYTES * BITS_PER_BYTE / cfg.wire.baud
        if share > LINE_SHARE_MAX and "rate_hz" in items:
            doc.err(
                items["rate_hz"][1],
                "time_link.rate_hz",
                f"{cfg.rate_hz:g} sentences a second take {share:.0%} of a {cfg.wire.baud}-baud line "
                f"(at most {LINE_SHARE_MAX:.0%}: each sentence must find the line idle); raise wire.baud",
            )
    return cfg if len(doc.errors) == errors_before else None


class TimeLinkOutputs:
    """The simulator's hook (like sim.sonar.publisher.SonarOutputs): one sentence
    per period, sent at the physics step the period falls in; nothing on LCM."""

    def __init__(self, cfg: TimeLinkConfig, devices, vehicle: str, seed: int, pacer) -> None:
        self.emulator = TimeLink(DeviceContext(vehicle, "time_link", seed, cfg.wire.options))
        self.device = devices.add(self.emulator, cfg.wire)
        self.port = self.device.port
        self.every = Periodic(1.0 / cfg.rate_hz)
        # what SIM.CLOCK says of the pace: 0 for a simulator as fast as the CPU allows
        self.warp = 0.0 if pacer.fast else pacer.warp

    def restart(self, t: float) -> None:
        self.every.restart(t)

    def next_due(self) -> float:
        return self.every.next_t

    def poll(self, tr) -> list[tuple[str, bytes]]:
        t = tr.t
        if self.every.due(t):
            self.every.advance(t)
            # the sentence starts at the step's sim time, the line being idle: the
            # physics' time, which the simulator's SIM.CLOCK and its sensors' stamps
            # carry (a simulator behind its pace writes the bytes later in wall time,
            # when they still arrive at this time of its physics; Line.burst)
            start = max(t, self.port.line.free_at)
            for data in self.emulator.encode(Sample(start, self.warp, self.port.line.byte_s), tr):
                self.device.send(data, start)
        return []
