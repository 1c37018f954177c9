"""Who takes part in a lockstep world, by name: whoever steps it (the launcher's
clock, tools/launch/worldclock.py, or the simulator serving a multi-HIL world) waits
for every one of them before step 0.

A count alone is not enough: it can be met by the wrong set. A team world
counted its simulators, pilots and navigators (3 per vehicle) while the
recorder took part too, so under load the world began with one simulator
still starting, which then joined a step late, and two runs of one scenario
differed from their first step (issue 14).
"""

from __future__ import annotations

from tools.launch.fault_step import NAME as LAUNCHER
from tools.launch.fault_step import is_lockstep_multihil

RADIO = "SHORE.radio"  # the surface radio's model (docs/radio.md), with `radio:`


def participants(sc, recorder: bool) -> set[str]:
    """Each vehicle's simulator, managers and onboard filter, the recorder (if
    the run records with auv-recorder, which takes part) and the radio model."""
    names = {"SIM.RECORDER"} if recorder else set()
    if getattr(sc, "radio", None) is not None:
        names.add(RADIO)
    for v in sc.vehicles:
        names.add(f"{v.id}.sim")
        names |= {f"{v.id}.{m.name}" for m in v.managers}
        if v.nav.source == "ekf":
            names.add(f"{v.id}.NAV")
    return names


def name_them(sc, cfg: dict, recorder: bool) -> dict:
    """A merged simulator configuration of a multi-HIL lockstep world that
    names every participant of the world (multihil.lockstep_names), the
    launcher's SIM.LAUNCHER too (it takes part: tools/launch/fault_step.py); names
    the configuration already lists stay."""
    if not is_lockstep_multihil(cfg):
        return cfg
    names = participants(sc, recorder) | {LAUNCHER}
    mh = cfg.get("multihil") or {}
    cfg["multihil"] = {**mh, "lockstep_names": sorted(set(mh.get("lockstep_names") or ()) | names)}
    return cfg
