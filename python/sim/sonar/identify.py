"""The reacquire-identify sensor: a short-range high-frequency sonar or camera.

Configuration section `identify:` (docs/simulator.md, "Reacquire-identify
sensor"). Every `period_s` of sim time, while the vehicle is no higher than
`max_altitude_m` above the seabed, each seabed object within `range_m`
(horizontal) is looked at: with probability `p_identify` the look makes the
object out and becomes a reacquire_look_t on <VEHICLE>.LOOKS; its result is
right (mine for a mine-like object, not mine for clutter) with probability
`p_correct`; its position is the truth plus N(0, position_sigma_m) per axis
plus the simulated INS's drift (looks are georeferenced by the vehicle's
navigation, like sidescan contacts). A look that makes nothing out sends
nothing.

The objects are the world's target field: the sonar section's when the
configuration has one, else `identify.targets` (the same keys as
sonar.targets; give it the search vehicles' values so every simulator of a
world builds the same field). Draws come from a stream named by the seed
(`seed`, -1 = simulation.seed), so a rerun gives the same looks.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from confcheck import Checker, setting
from sim.noise import Noise
from sim.periodic import Periodic
from sim.sonar.config import TargetsConfig
from sim.sonar.targets import MINE_LIKE, TargetField

NavError = Callable[[], tuple[float, float]]


@dataclass
class IdentifyConfig:
    enabled: bool = True
    range_m: float = setting(6.0, gt=0.0, le=200.0)  # horizontal range of a look [m]
    p_identify: float = setting(0.5, ge=0.0, le=1.0)  # a look at an object in range makes it out
    p_correct: float = setting(0.9, ge=0.0, le=1.0)  # ... and gets mine / not mine right
    position_sigma_m: float = setting(0.5, ge=0.0, le=100.0)  # 1-sigma position error per axis [m]
    period_s: float = setting(1.0, gt=0.0, le=3600.0)  # one look at every object in range per period
    max_altitude_m: float = setting(10.0, gt=0.0)  # looks only this close to the seabed
    seed: int = -1  # -1 = simulation.seed
    targets: TargetsConfig = field(default_factory=TargetsConfig)  # without a sonar section
    wire: Any = None  # the looks at the wire (sim.devices.lcmframe, protocol lcmframe)


def check_identify(doc: Checker, node, base, has_sonar: bool) -> IdentifyConfig | None:
    """The checked section (None for `identify: false` or enabled: false)."""
    import yaml

    from sim.sonar.config_check import check_targets

    if isinstance(node, yaml.ScalarNode) and doc.scalar(node) is False:
        return None
    from sim.devices.config import parse_wire

    errors_before = len(doc.errors)
    wire = {"wire": lambda n, k: parse_wire(doc, n, k, "identify", base)}
    cfg = doc.fill(node, "identify", IdentifyConfig(), special=wire)
    items = doc.mapping(node, "identify")
    if "targets" in items:
        if has_sonar:
            doc.err(
                items["targets"][0],
                "identify.targets",
                "this configuration has a sonar section: its targets are the field (give the field in one place)",
            )
        else:
            check_targets(
                doc, cfg.targets, items["targets"][1], "identify.targets", base, place=len(doc.errors) == errors_before
            )
    return cfg if cfg.enabled else None


class Identify:
    """The looks of one vehicle, polled with the truth at each due time."""

    def __init__(
        self, cfg: IdentifyConfig, field_: TargetField, seed: int, vehicle: str, nav_error: NavError | None = None
    ) -> None:
        self.cfg = cfg
        self.vehicle = vehicle
        self.rng = Noise(f"{seed}:identify")
        self.nav_error = nav_error
        ts = field_.targets
        self._n = np.array([t.north_m for t in ts], dtype=float)
        self._e = np.array([t.east_m for t in ts], dtype=float)
        self._mine = np.array([t.kind == MINE_LIKE for t in ts], dtype=bool)
        self.schedule = Periodic(cfg.period_s, skip_slack=1e-9)
        self.looks = 0  # reacquire_look_t sent (look_id of the last)
        self.tries = 0  # objects in range at a look, made out or not

    def next_due(self) -> float:
        return self.schedule.next_t

    def poll(self, tr) -> list:
        """The looks of this period (maybe none); [] when no look is due."""
        from auv import reacquire_look_t
        from sim.sensors.base import utime

        t = tr.t
        if not self.schedule.due(t):
            return []
        self.schedule.advance(t)
        if not len(self._n) or not 0.0 <= tr.altitude_m <= self.cfg.max_altitude_m:
            return []
        n0, e0 = tr.eta[0], tr.eta[1]
        rng = np.hypot(self._n - n0, self._e - e0)
        out = []
        for i in np.nonzero(rng <= self.cfg.range_m)[0]:  # in index order: deterministic
            self.tries += 1
            if self.rng.random() >= self.cfg.p_identify:
                continue
            right = self.rng.random() < self.cfg.p_correct
            mine = bool(self._mine[i]) == right
            dn, de = self.nav_error() if self.nav_error is not None else (0.0, 0.0)
            self.looks += 1
            m = reacquire_look_t()
            m.utime, m.vehicle, m.look_id = utime(t), self.vehicle, self.looks
            m.north_m = float(self._n[i]) + self.rng.gauss(self.cfg.position_sigma_m) + dn
            m.east_m = float(self._e[i]) + self.rng.gauss(self.cfg.position_sigma_m) + de
            m.position_sigma_m = self.cfg.position_sigma_m
            m.range_m = float(rng[i])
            m.result = reacquire_look_t.RESULT_MINE if mine else reacquire_look_t.RESULT_NOT_MINE
            m.confidence = self.cfg.p_correct
            out.append(m)
        return out


class IdentifyOutputs:
    """The HIL hook (like sim.sonar.publisher.SonarOutputs): looks on <V>.LOOKS, and
    framed on a line with `identify.wire` (sim.devices.lcmframe)."""

    def __init__(self, cfg, sensors, devices=None) -> None:
        from sim.devices.lcmframe import IdentifyFrame
        from sim.sonar.publisher import build_field, wire_device

        ic = cfg.identify
        self.field = build_field(cfg, cfg.sonar.targets if cfg.sonar is not None else ic.targets)
        ins = next((s for s in sensors if s.name == "ins"), None)
        nav_error = (lambda: (ins.err_n, ins.err_e)) if ins is not None else None
        seed = ic.seed if ic.seed >= 0 else cfg.sim.seed
        self.model = Identify(ic, self.field, seed, cfg.vehicle_id, nav_error)
        self.channel = f"{cfg.vehicle_id}.LOOKS"
        self.device, self.publish_lcm = wire_device(devices, ic.wire, IdentifyFrame, cfg)

    def restart(self, t: float) -> None:
        self.model.schedule.restart(t)

    def next_due(self) -> float:
        return self.model.next_due()

    def poll(self, tr) -> list[tuple[str, bytes]]:
        msgs = self.model.poll(tr)
        if self.device is not None:
            for m in msgs:
                self.device.emit(m, tr)
        return [(self.channel, m.encode()) for m in msgs] if self.publish_lcm else []
