"""A commercial vehicle's frontseat in the simulator: the `frontseat:` section and the
vehicle it flies (docs/frontseat.md, docs/simulator.md "A frontseat at the wire").

On a commercial AUV (an Iver3, a Bluefin) the vehicle's own computer flies it: its
heading, depth and speed loops, its own mission, its safety rules. The backseat (our
managers, through auv-frontseat) only asks it for a heading, depth and speed. This part
of the simulator is that computer; the protocol is a plug on a port of the simulator
(sim.devices.frontseat_wire: sim.devices.iver3_frontseat, sim.devices.bluefin_frontseat,
chosen by `wire.protocol`). The loops are the project's pilot loops (sim.pilot: the C
law the PILOT flies, through ctypes, with the pilot plan's gains), so the simulated
vehicle answers a request as our own would answer the same setpoint. With a frontseat
the simulator takes no <VEHICLE>.ACTUATORS: the frontseat commands the fins and the
propeller.

Who steers, each physics step (the protocol says it in its words: Iver3's mode
letter, Bluefin's $BFCTL and $BFMIS):
  - an operator abort (`abort_at_s`): stopped (prop off, fins neutral: the vehicle
    rises), with its error word; requests refused for good;
  - an operator's manual override (`manual_at_s` for `manual_for_s`): it flies its
    own mission; requests refused meanwhile;
  - the backseat: a request heard within the request's own timeout, once the vehicle
    is at `control_min_depth_m` (a request at the surface is refused: the vehicle
    dives on its own mission first); held while requests keep coming;
  - else its own mission: `mission_heading_deg`, `mission_depth_m`,
    `mission_speed_mps`.
These rules are written once, here (refusal(), _targets()); a protocol that answers
each request (Bluefin) asks refusal() through its `judge`. A silent frontseat
(`silent_at_s` for `silent_for_s`) neither hears nor answers on its link; it goes on
flying (the backseat's last request until its timeout, then its mission).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

from confcheck import Checker, setting
from sim.actuators import Command
from sim.devices.config import INPUT_DEVICE_KEYS, parse_wire
from sim.devices.emulator import DeviceContext
from sim.devices.frontseat_wire import MANUAL, MISSION, PAYLOAD, STOPPED, FrontseatProtocol
from sim.devices.registry import protocols_of
from sim.model import Truth, VehicleModel
from sim.pilot import Pilot

NEVER = -1.0


@dataclass
class FrontseatConfig:
    control_min_depth_m: float = setting(1.0, ge=0.0, le=1000.0, unit="m")  # requests refused above it
    mission_heading_deg: float = setting(0.0, ge=0.0, lt=360.0, unit="deg")  # its own mission
    mission_depth_m: float = setting(3.0, ge=0.0, le=1000.0, unit="m")
    mission_speed_mps: float = setting(1.5, ge=0.0, le=5.0, unit="m/s")
    abort_at_s: float = setting(NEVER, ge=NEVER, unit="s")  # an operator abort (-1: never)
    # the abort's error word (iver3: $OSI's error field; bluefin says `Aborted`)
    abort_error: str = setting("Stl", pattern=r"[A-Za-z0-9]{1,8}", pattern_hint="its error word, e.g. Stl")
    manual_at_s: float = setting(NEVER, ge=NEVER, unit="s")  # an operator takes it (-1: never)
    manual_for_s: float = setting(0.0, ge=0.0, unit="s")  # ... for this long (0: for good)
    silent_at_s: float = setting(NEVER, ge=NEVER, unit="s")  # its link goes dead (-1: never)
    silent_for_s: float = setting(0.0, ge=0.0, unit="s")  # ... for this long (0: for good)
    wire: Any = None  # its port (sim.devices.config.WireConfig): required


def check_frontseat(doc: Checker, node, base: Path) -> FrontseatConfig | None:
    """The checked `frontseat:` section (None: absent or false)."""
    if node is None or (isinstance(node, yaml.ScalarNode) and doc.scalar(node) is False):
        return None
    errors_before = len(doc.errors)
    wire = {"wire": lambda n, k: parse_wire(doc, n, k, "frontseat", base, common=INPUT_DEVICE_KEYS)}
    cfg = doc.fill(node, "frontseat", FrontseatConfig(), special=wire)
    items = doc.mapping(node, "frontseat")
    if "wire" not in items:
        doc.err(
            node,
            "frontseat",
            "missing required key 'wire' ({protocol: iver3 | bluefin, pty: PATH | tcp: HOST:PORT, ...})",
        )
    elif cfg.wire is None and len(doc.errors) == errors_before:
        doc.err(items["wire"][1], "frontseat.wire", "the frontseat is its wire: give one, or `frontseat: false`")
    return cfg if len(doc.errors) == errors_before else None


def _window(at: float, length: float, t: float) -> bool:
    return at >= 0.0 and t >= at and (length <= 0.0 or t < at + length)


class FrontseatVehicle:
    """The simulator's hook: command(model) before each physics step."""

    def __init__(self, cfg: FrontseatConfig, devices, vehicle: str, seed: int, model: VehicleModel) -> None:
        self.cfg = cfg
        protocol = protocols_of("frontseat")[cfg.wire.protocol]
        ctx = DeviceContext(vehicle, "frontseat", seed, cfg.wire.options, model.frame)
        self.emulator: FrontseatProtocol = protocol(ctx)
        self.emulator.judge = self.refusal
        self.device = devices.add(self.emulator, cfg.wire)
        self.pilot = Pilot(dt=model.dt)
        self.truth = Truth()
        self.depth_m = 0.0  # the vehicle's depth at the newest step
        self.helm = ""
        self.granted = False  # the backseat has control (held while its requests are fresh)
        self.grants = 0
        self.refused_shallow = 0  # steps a fresh request was refused above control_min_depth_m

    def _aborted(self, t: float) -> bool:
        return self.cfg.abort_at_s >= 0.0 and t >= self.cfg.abort_at_s

    def _manual(self, t: float) -> bool:
        return _window(self.cfg.manual_at_s, self.cfg.manual_for_s, t)

    def refusal(self, t: float, depth: float | None = None) -> str | None:
        """Why a request would not be flown now (None: it would), at the vehicle's
        depth (its newest step's if not given)."""
        if self._aborted(t):
            return "aborted"
        if self._manual(t):
            return "manual override"
        depth = self.depth_m if depth is None else depth
        if not self.granted and depth < self.cfg.control_min_depth_m:
            return "above the control depth"
        return None

    def _targets(self, t: float, depth: float) -> tuple[str, str, tuple[float, float, float] | None]:
        """(helm, error word, (heading, depth, speed) or None: stopped)."""
        c = self.cfg
        own = (math.radians(c.mission_heading_deg), c.mission_depth_m, c.mission_speed_mps)
        if self._aborted(t):
            self.granted = False
            return STOPPED, c.abort_error, None
        if self._manual(t):
            self.granted = False
            return MANUAL, "", own
        rq = self.emulator.request
        fresh = rq is not None and t - rq.t <= rq.timeout_s
        if not fresh:
            self.granted = False
        elif not self.granted:
            if self.refusal(t, depth) is None:
                self.granted = True
                self.grants += 1
            else:
                self.refused_shallow += 1
        if self.granted and rq is not None:
            return PAYLOAD, "", None if rq.stop else (rq.heading_rad, rq.depth_m, rq.speed_mps)
        return MISSION, "", own

    def command(self, model: VehicleModel) -> Command:
        tr = model.truth(self.truth)
        t = tr.t
        em = self.emulator
        em.truth = tr
        self.depth_m = tr.eta[2]
        em.silent = _window(self.cfg.silent_at_s, self.cfg.silent_for_s, t)
        helm, error, target = self._targets(t, tr.eta[2])
        em.report.helm, em.report.error = helm, error
        em.update(t)
        act = model.act
        if helm != self.helm:  # a new hand on the helm: the loops take over without a jump
            self.pilot.start(tr.eta[4], act.stern, act.rpm, act.rudder)
            self.helm = helm
        if target is None:
            return Command(0.0, 0.0, 0.0)
        heading, depth, speed = target
        _, _, _, _, pitch, psi = tr.eta
        u, _, _, _, q, r = tr.nu
        p = self.pilot
        return Command(p.rudder(heading, psi, r), p.stern_for_depth(depth, tr.eta[2], pitch, q), p.prop(speed, u))
