"""Clock modes (sim.clock_modes): real time, scaled (warp), lockstep on an external global clock.

The simulator never reads the wall clock for its physics: sim time is the
count of physics steps times dt. The wall clock only paces those steps in
real-time and scaled modes; in lockstep the pace comes from SIM.CLOCK.
"""

from __future__ import annotations

import time
from typing import Callable, Protocol

from sim.clock_modes import LOCKSTEP, REALTIME


class ClockSource(Protocol):
    """A global clock a free-running simulator keeps pace with (multi-HIL: its
    environment node) instead of its own wall clock."""

    def global_now_s(self) -> float | None:
        """The global time now [s]; None while there is none (the pacer waits)."""


class Pacer:
    """When the next physics step may run, in wall time (monotonic)."""

    def __init__(self, mode: str, warp: float, dt: float, fast: bool = False) -> None:
        self.mode = mode
        self.warp = 1.0 if mode == REALTIME else warp
        self.dt = dt
        self.fast = fast  # scaled, as fast as the CPU allows
        self.wall0 = time.monotonic()
        self.sim0 = 0.0
        self.target_t: float | None = None  # lockstep: advance up to here
        self.late_steps = 0  # steps that ran behind their wall deadline
        # multi-HIL free-running: the process's global clock [s] (None before it has one)
        # paces the steps instead of this process's own wall clock (set_clock_source)
        self._global_now: Callable[[], float | None] | None = None

    def set_clock_source(self, source: ClockSource) -> None:
        """Pace free-running steps by source's global time from now on (lockstep
        keeps following SIM.CLOCK)."""
        self._global_now = source.global_now_s

    def restart(self, sim_t: float) -> None:
        self.wall0 = time.monotonic()
        self.sim0 = sim_t

    def wall_deadline(self, sim_t: float) -> float:
        """Wall time (monotonic) at which sim time sim_t is due."""
        return self.wall0 + (sim_t - self.sim0) / self.warp

    def may_step(self, sim_t: float, now: float) -> bool:
        """Whether the step that ends at sim_t + dt may run now."""
        if self.mode == LOCKSTEP:
            return self.target_t is not None and sim_t + 0.5 * self.dt <= self.target_t
        if self._global_now is not None:
            g = self._global_now()
            return g is not None and g >= sim_t + self.dt
        if self.fast:
            return True
        return now >= self.wall_deadline(sim_t + self.dt)

    def wait_s(self, sim_t: float, now: float) -> float:
        """How long to wait for LCM traffic before the next step is due."""
        if self.mode == LOCKSTEP:
            return 0.1
        if self._global_now is not None:
            g = self._global_now()
            return 0.05 if g is None else max(0.0, (sim_t + self.dt - g) / self.warp)
        if self.fast:
            return 0.0
        return max(0.0, self.wall_deadline(sim_t + self.dt) - now)
