"""The sonar in the HIL loop: contacts on <V>.CONTACTS, the true field on SIM.TARGETS.

An output the simulator polls like a sensor (next_due / poll), returning
(channel, bytes) pairs, so hil.py only needs a generic hook for it.
"""

from __future__ import annotations

import math

from sim.devices.emulator import DeviceContext
from sim.devices.lcmframe import SonarFrame
from sim.sensors.base import utime
from sim.sonar import targets as tg
from sim.sonar.sidescan import Sidescan


def build_field(cfg, tc=None) -> tg.TargetField:
    """The configuration's target field (cfg: sim.config.SimConfig; tc: the targets
    section, default the sonar's), on its world's seabed."""
    from sim.environment import Environment

    env = Environment(cfg.env, cfg.path.parent)
    tc = tc if tc is not None else cfg.sonar.targets
    if tc.file:
        return tg.load(cfg.path.parent / tc.file, env.water_depth)
    return tg.place(tc, tc.seed, env.water_depth)


def wire_device(devices, wire, emulator_cls, cfg):
    """A payload's port at the wire (None without `wire:`) and whether its LCM
    messages are published too (`publish_lcm`)."""
    if wire is None or devices is None:
        return None, True
    ctx = DeviceContext(cfg.vehicle_id, emulator_cls.sensor, cfg.sim.seed, wire.options)
    return devices.add(emulator_cls(ctx), wire), wire.publish_lcm


class SonarOutputs:
    """devices: the simulator's (sim.devices.device.Devices), for `sonar.wire`: the
    contacts framed on a line (sim.devices.lcmframe), beside LCM or instead."""

    def __init__(self, cfg, sensors, publish_world: bool, devices=None) -> None:
        sc = cfg.sonar
        self.field = build_field(cfg)
        ins = next((s for s in sensors if s.name == "ins"), None)
        # contacts are georeferenced by the vehicle's navigation: with the
        # simulated INS, its current drift is part of the contact's error
        nav_error = (lambda: (ins.err_n, ins.err_e)) if ins is not None else None
        self.sidescan = Sidescan(sc, self.field, cfg.sim.seed, cfg.vehicle_id, nav_error)
        self.channel = f"{cfg.vehicle_id}.CONTACTS"
        self.world = cfg.env.world
        self.publish_targets = sc.publish_targets == "yes" or (sc.publish_targets == "auto" and publish_world)
        self.targets_period = sc.targets_period_s
        self.next_targets = 0.0 if self.publish_targets else math.inf
        self.device, self.publish_lcm = wire_device(devices, sc.wire, SonarFrame, cfg)

    def restart(self, t: float) -> None:
        """Join a world at time t (stepped mode)."""
        self.sidescan.schedule.restart(t)
        if self.publish_targets:
            self.next_targets = t

    def next_due(self) -> float:
        return min(self.sidescan.next_due(), self.next_targets)

    def poll(self, tr) -> list[tuple[str, bytes]]:
        msgs = self.sidescan.poll(tr)
        if self.device is not None:
            for m in msgs:
                self.device.emit(m, tr)
        out = [(self.channel, m.encode()) for m in msgs] if self.publish_lcm else []
        if tr.t >= self.next_targets - 1e-9:
            out.append(("SIM.TARGETS", self.field.to_lcm(utime(tr.t), self.world).encode()))
            self.next_targets = tr.t + self.targets_period if self.targets_period > 0 else math.inf
        return out
