"""A planned `lose` fault at an exact step of a lockstep world (tools/scenario/faults.py).

A vehicle lost at `at` must be killed between two steps: after each of its
processes reported the last step before `at`, and before any of them hears
the first step at or after it. Killed while it works on a step, it may or may
not have published part of that step, and two runs of one scenario would
differ (issue 14: the same scenario and seed give the same log).

- The launcher's own clock (time.source: launcher) calls the launcher before
  it publishes a new step (tools/launch/worldclock.py, `before_step`): every
  participant has reported the step before, so the vehicle is idle there.
- A world stepped by the simulators (multi-HIL lockstep) has its clock in a
  simulator. The launcher then takes part in the lockstep as `SIM.FAULTS`
  (this module): at clock k it reports step k done only once the vehicles
  whose fault is due by step k + 1 were killed, after their own processes
  reported step k; the server cannot publish step k + 1 before that. Each
  simulator's configuration counts it among the participants to wait for
  (tools/launch/simconfig.py).
"""

from __future__ import annotations

from pathlib import Path
from typing import Callable

import lcm
import yaml

from auv import lockstep_t, sim_clock_t
from auvlcm.rx import Receiver
from sim import clock_modes
from sim.multihil.lockstep import LockstepTracker, Participation

NAME = "SIM.FAULTS"


def loses_vehicles(sc) -> bool:
    return any(f.do == "lose" for f in sc.faults)


def is_lockstep_multihil(cfg: dict) -> bool:
    """Whether a merged simulator configuration steps a multi-HIL lockstep world."""
    mh, sim = cfg.get("multihil") or {}, cfg.get("simulation") or {}
    try:
        clock = clock_modes.canonical(str(sim.get("clock", clock_modes.REALTIME)))
    except ValueError:
        return False  # the simulator's own check names a bad mode
    return bool(mh.get("enabled")) and clock == clock_modes.LOCKSTEP


def takes_part(sc, host: str | None, sim_configs) -> bool:
    """Whether this host's launcher takes part in the world's lockstep for the
    planned faults: it loses a vehicle, the simulators step a lockstep world, and
    this is the one launcher (or the logging host's, with several)."""
    if not loses_vehicles(sc) or (host is not None and host != sc.log_host):
        return False
    configs = [yaml.safe_load(Path(p).read_text()) or {} for p in sim_configs]
    return bool(configs) and all(is_lockstep_multihil(c) for c in configs)


def count_in(sc, cfg: dict) -> dict:
    """A merged simulator configuration that waits for the launcher as well,
    before step 0, when the launcher takes part (takes_part)."""
    mh = cfg.get("multihil") or {}
    if loses_vehicles(sc) and is_lockstep_multihil(cfg) and int(mh.get("lockstep_participants") or 0) > 0:
        cfg["multihil"] = {**mh, "lockstep_participants": int(mh["lockstep_participants"]) + 1}
    return cfg


class FaultStepper:
    """The launcher's part in a lockstep world stepped by the simulators."""

    def __init__(
        self,
        lc: lcm.LCM,
        lost_by: Callable[[int], set[str]],
        settled: Callable[[str], bool],
        apply: Callable[[int], None],
    ) -> None:
        """lost_by(t_us): the participants of the vehicles lost at or before t_us;
        settled(name): that participant's process is gone (it will report nothing);
        apply(t_us): kill them, from step time t_us on."""
        self.part = Participation(NAME, lambda m: lc.publish("SIM.LOCKSTEP", m.encode()))
        self.tracker = LockstepTracker(timeout_s=None)
        self.lost_by, self.settled, self.apply = lost_by, settled, apply
        self.step_us = 0
        self.rx = Receiver(lc)  # typed: what does not decode is counted and dropped
        self.rx.subscribe("SIM.CLOCK", sim_clock_t, self._on_clock, queue_capacity=1000)
        self.rx.subscribe("SIM.LOCKSTEP", lockstep_t, self._on_lockstep, queue_capacity=1000)

    def _on_clock(self, _ch: str, m: sim_clock_t) -> None:
        if m.mode == sim_clock_t.MODE_LOCKSTEP and m.step_us > 0:
            self.step_us = m.step_us
            self.part.on_clock(m.step, m.utime)

    def _on_lockstep(self, _ch: str, m: lockstep_t) -> None:
        if m.participant != NAME:
            self.tracker.on_message(m)

    def poll(self) -> None:
        """Each turn of the launcher's loop: register, or finish the pending step."""
        self.part.poll()
        if self.part.pending is None:
            return
        step, utime = self.part.pending
        t_next = utime + self.step_us
        for name in self.lost_by(t_next):
            p = self.tracker.parts.get(name)
            if (p is None or p.last_done < step) and not self.settled(name):
                return  # still working on step k: killed mid-step, it would leave half a step
        self.apply(t_next)
        self.part.done()

    def close(self) -> None:
        if self.part.seen_clock:
            self.part.leave()
