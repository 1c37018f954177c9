"""Vehicles flown in backseat mode (docs/frontseat.md, "The team in backseat mode").

A scenario vehicle whose merged simulator configuration has a `frontseat:` section
is a commercial vehicle flown from its backseat: the simulator's frontseat
(python/sim/frontseat.py) flies it with its own loops and takes no <ID>.ACTUATORS,
and the launcher starts auv-frontseat (c/frontseat) where the PILOT would stand, on
the frontseat's port: the navigator's <ID>.SETPOINT in, the frontseat's navigation
out as <ID>.NAV and its state as <ID>.FRONTSEAT. So the simulator's INS moves to
<ID>.NAV_INS (tools/launch/simconfig.py) and no auv-nav runs: one writer of NAV.

Refused before anything starts, each at its file:line:col:
- a lockstep world (the launcher's clock, lockstep in every mode, or the
  simulators' lockstep clock): auv-frontseat is a device driver on a port, and a
  device cannot report the steps of a lockstep world (as at the wire,
  docs/hil.md); the world runs on the simulators' scaled or realtime clock
  (`time.source: simulators`, multi-HIL);
- a manager that writes <ID>.ACTUATORS (a PILOT): the frontseat flies the vehicle;
- `nav: ekf`: the frontseat navigates;
- `backseat:` (auv-frontseat's limits) on a vehicle without a frontseat.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import yaml

from auvlcm import programs
from sim import clock_modes
from tools.launch.annotate import plan_files
from tools.launch.simconfig import backseat, source_position
from tools.scenario.scenario_file import BackseatLimits, Scenario, Vehicle

# `output  prefix  channel  type ...` in a binding file
_OUTPUT = re.compile(r"^\s*output\s+\S+\s+(\S+)", re.M)


@dataclass
class FrontseatPort:
    """Where auv-frontseat reaches the simulator's frontseat, and how it speaks."""

    protocol: str
    pty: str  # the pty's link path (absolute), or ""
    tcp: str  # "HOST:PORT", or ""
    baud: int
    helm_version: int | None
    origin: tuple[float, float]  # the world's origin [deg]: NAV's north and east


def writes(bind: Path, vid: str) -> set[str]:
    """The channels a binding file (and the files it includes) writes, for vehicle vid."""
    out: set[str] = set()
    for p in plan_files(bind):
        out |= {ch.replace("${VEHICLE}", vid) for ch in _OUTPUT.findall(p.read_text())}
    return out


def frontseat_ports(sc: Scenario, sim_configs: dict[str, Path]) -> tuple[dict[str, FrontseatPort], list[str]]:
    """The backseat vehicles among sc's (their merged configuration has `frontseat:`)
    and the scenario's errors about them (module docstring)."""
    from sim.config import load

    ports: dict[str, FrontseatPort] = {}
    errors: list[str] = []
    for v in sc.vehicles:
        path = sim_configs.get(v.id)
        if path is None:
            continue  # its configuration was refused: reported already
        if not backseat(yaml.safe_load(path.read_text()) or {}):  # most vehicles: not loaded again
            if v.backseat is not None:
                errors.append(
                    f"{v.backseat_where}: {v.id}.backseat: auv-frontseat's limits, but the vehicle's "
                    "simulator configuration has no frontseat: (it is flown by its own PILOT)"
                )
            continue
        cfg = load(path)
        where = source_position(v, "frontseat", sc)
        errors += _refusals(sc, v, cfg, where)
        w = cfg.frontseat.wire
        host, port = w.tcp_address if w.tcp else ("", 0)
        ports[v.id] = FrontseatPort(
            protocol=w.protocol,
            pty=w.pty,
            tcp=f"{host or '127.0.0.1'}:{port}" if w.tcp else "",
            baud=w.baud,
            helm_version=getattr(w.options, "helm_version", None),
            origin=(cfg.env.origin_latitude_deg, cfg.env.origin_longitude_deg),
        )
    return ports, errors


def _refusals(sc: Scenario, v: Vehicle, cfg, where: str) -> list[str]:
    out = []
    mode = f"{v.id} is flown in backseat mode (its simulator configuration has a frontseat:)"
    if sc.time.source == "launcher":
        out.append(
            f"{where}: {mode}: the launcher's clock is lockstep in every mode, and auv-frontseat, a device "
            "driver on the frontseat's port, cannot take part in a lockstep world: set time.source: "
            "simulators and each simulator's clock scaled or realtime (multihil: {enabled: true})"
        )
    elif clock_modes.canonical(cfg.sim.clock) == clock_modes.LOCKSTEP:
        out.append(
            f"{where}: {mode}: its simulator's clock is lockstep, and auv-frontseat, a device driver on the "
            "frontseat's port, cannot take part in a lockstep world: simulation: {clock: scaled, warp: W} "
            "(or realtime) in every vehicle's sim: section"
        )
    if v.nav.source == "ekf":
        out.append(f"{v.where}: {v.id}.nav: ekf: {mode}: the frontseat navigates (auv-frontseat publishes {v.id}.NAV)")
    for m in v.managers:
        if f"{v.id}.ACTUATORS" in writes(m.bind, v.id):
            out.append(
                f"{m.where}: {v.id}.{m.name}: writes {v.id}.ACTUATORS ({m.bind.name}), but {mode}: the frontseat "
                "flies it, auv-frontseat stands where the PILOT stands: leave this manager out"
            )
    return out


def frontseat_cmd(build: Path, url: str, vid: str, port: FrontseatPort, limits: BackseatLimits | None) -> list[str]:
    """auv-frontseat's command line for a backseat vehicle, on the simulator's time."""
    lim = limits or BackseatLimits()
    return programs.frontseat(
        build,
        vehicle=vid,
        lcm_url=url,
        port=port.pty or None,
        baud=port.baud if port.pty else None,
        tcp=port.tcp or None,
        protocol=port.protocol,
        origin=port.origin,
        max_depth_m=lim.max_depth_m,
        min_speed_mps=lim.min_speed_mps,
        max_speed_mps=lim.max_speed_mps,
        helm_version=port.helm_version,
        silent_after_s=lim.silent_after_s,
        clock="sim",
    )
