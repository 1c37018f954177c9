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
  simulator. The launcher then takes part in the lockstep as `SIM.LAUNCHER`
  (this module): at clock k it reports step k done only once the vehicles
  whose fault is due by step k + 1 were killed, after their own processes
  reported step k; the server cannot publish step k + 1 before that. Each
  simulator's configuration counts it among the participants to wait for
  (tools/launch/simconfig.py).

The same part ends such a world at a defined step (docs/scenarios.md, "End"):
at clock k the launcher asks hold(t_k) (did the mission end before t_k?) and,
if so, never reports step k: every other participant finishes step k, and no
step follows. So the launcher takes part in every lockstep world the
simulators step, planned faults or not.
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

NAME = "SIM.LAUNCHER"


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
    """Whether this host's launcher takes part in the world's lockstep (the end,
    the planned faults): the simulators step a lockstep world, and this is the one
    launcher (or the logging host's, with several)."""
    if host is not None and host != sc.log_host:
        return False
    configs = [yaml.safe_load(Path(p).read_text()) or {} for p in sim_configs]
    return bool(configs) and all(is_lockstep_multihil(c) for c in configs)


def count_in(sc, cfg: dict) -> dict:
    """A merged simulator configuration that waits for the launcher as well,
    before step 0: it takes part in every lockstep world (takes_part)."""
    mh = cfg.get("multihil") or {}
    if is_lockstep_multihil(cfg) and int(mh.get("lockstep_participants") or 0) > 0:
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
        hold: Callable[[int], bool] | None = None,
        track: bool = True,
    ) -> None:
        """lost_by(t_us): the participants of the vehicles lost at or before t_us;
        settled(name): that participant's process is gone (it will report nothing);
        apply(t_us): kill them, from step time t_us on; hold(t_us): the mission
        ended before step time t_us (the world ends at that step, held_at).
        track: follow every participant's reports from the start (planned faults
        need them; the end only once held: a report each step each, in Python)."""
        self.part = Participation(NAME, lambda m: lc.publish("SIM.LOCKSTEP", m.encode()))
        self.tracker = LockstepTracker(timeout_s=None)
        self.lost_by, self.settled, self.apply, self.hold = lost_by, settled, apply, hold
        self.step_us = 0
        self.held_at: tuple[int, int] | None = None  # (step, utime) the world ended at
        self.rx = Receiver(lc)  # typed: what does not decode is counted and dropped
        self.rx.subscribe("SIM.CLOCK", sim_clock_t, self._on_clock, queue_capacity=1000)
        self._tracking = False
        if track:
            self._track()

    def _track(self) -> None:
        if not self._tracking:
            self._tracking = True
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
        if self.part.pending is None or self.held_at is not None:
            return
        step, utime = self.part.pending
        if self.hold is not None and self.hold(utime):
            self.held_at = (step, utime)  # never reported: the world stops at this step
            self._track()  # to know when every other participant finished it
            return
        t_next = utime + self.step_us
        for name in self.lost_by(t_next):
            p = self.tracker.parts.get(name)
            if (p is None or p.last_done < step) and not self.settled(name):
                return  # still working on step k: killed mid-step, it would leave half a step
        self.apply(t_next)
        self.part.done()

    def finished(self, names: set[str], exited: Callable[[str], bool]) -> bool:
        """Every one of names (less those whose process exited) reported the step
        the world was held at: all of that step was published."""
        if self.held_at is None:
            return False
        step = self.held_at[0]
        for n in names:
            p = self.tracker.parts.get(n)
            if (p is None or p.last_done < step) and not exited(n):
                return False
        return True

    def close(self) -> None:
        if self.part.seen_clock:
            self.part.leave()
