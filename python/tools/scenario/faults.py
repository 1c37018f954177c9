"""Planned faults of a scenario (docs/scenarios.md, "Faults"): what the
launcher does to a running mission at a given time of the world's clock, so
that a team's answer to losing a vehicle is tried the way it happens at sea,
and the same way in every run.

    faults:
      - {at: 300, vehicle: AUV2, do: lose}

`lose`: every process of the vehicle (simulator, onboard filter, managers) is
killed with SIGKILL at the first clock step at or after `at` [sim s]: the
vehicle falls silent mid-sentence, as one lost at sea would (no last status,
no goodbye on the link). Its outcome is `lost`; the lockstep clock stops
waiting for it at once; the mission ends when the other vehicles end. The
fault is written into the log as a launcher event ("fault").

`leak`: the vehicle's leak probes (the simulator's `leak` sensor) sense water
from `at` on: the launcher sets `sensors.leak.at_s` in the vehicle's
simulator configuration, so the leak comes at the same sim time in every
run; what the vehicle does about it is its plan's (missions/common/
safety.chasm aborts to the surface).
"""

from __future__ import annotations

from dataclasses import dataclass

import yaml

from confcheck import Checker, join, setting

FAULT_KINDS = ("lose", "leak")


@dataclass
class Fault:
    at_s: float = setting(0.0, ge=0.0, key="at")  # sim time [s]
    vehicle: str = ""
    do: str = setting("lose", one_of=FAULT_KINDS)


@dataclass
class PlannedFault:
    at_s: float
    vehicle: str
    do: str
    where: str  # file:line:col of the entry


def check_faults(c: Checker, node, vehicle_ids: list[str], limit_s: float) -> list[PlannedFault]:
    """The checked `faults:` list (errors collect in c)."""
    out: list[PlannedFault] = []
    if node is None or c.is_empty(node):
        return out
    lost: dict[str, str] = {}
    for i, n in enumerate(c.sequence(node, "faults")):
        key = f"faults[{i}]"
        if not isinstance(n, yaml.MappingNode):
            c.err(n, key, "expected a mapping such as {at: 300, vehicle: AUV2, do: lose}")
            continue
        items = c.mapping(n, key)
        c.required(items, ("at", "vehicle"), n, key)
        f = Fault()
        before = len(c.errors)
        c.fill(n, key, f)
        if len(c.errors) > before or "at" not in items or "vehicle" not in items:
            continue
        vnode = items["vehicle"][1]
        if f.vehicle not in vehicle_ids:
            c.err(
                vnode,
                join(key, "vehicle"),
                f"no vehicle '{f.vehicle}' in this scenario; vehicles are: {', '.join(vehicle_ids)}",
            )
            continue
        if f.do == "lose" and f.vehicle in lost:
            c.err(vnode, join(key, "vehicle"), f"{f.vehicle} is already lost by the fault at {lost[f.vehicle]}")
            continue
        if f.at_s >= limit_s:
            c.err(
                items["at"][1],
                join(key, "at"),
                f"at {f.at_s:g} s is not before the mission time limit ({limit_s:g} s): it would never happen",
            )
            continue
        if f.do == "lose":
            lost[f.vehicle] = c.where(n)
        out.append(PlannedFault(f.at_s, f.vehicle, f.do, c.where(n)))
    return sorted(out, key=lambda f: f.at_s)
