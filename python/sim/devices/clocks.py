"""The line's clock: which sim time the far end of a line has reached, now.

A port's writer thread hands bytes on when their sim time (sim.devices.line)
is reached. Two clocks say when that is:

- WallClock (realtime, scaled): the pacer's mapping of wall time to sim time,
  read by the writer thread itself, so bytes leave at the line's pace between
  physics steps (at `warp` times the baud's pace when scaled: line time is sim
  time);
- StepClock (lockstep, and a scaled run as fast as the CPU allows): the sim
  time of the simulator's last step, moved by the simulator (advance()); the
  bytes due by a step are handed on when the step is done, each burst's sim
  times recorded (sim.devices.device).
"""

from __future__ import annotations

import time
from typing import Protocol


class LineClock(Protocol):
    def now(self) -> float:
        """The sim time the line has reached [s]."""

    def wall_s(self, sim_dt: float) -> float | None:
        """Wall seconds until sim_dt more sim seconds have passed; None: only a
        step of the simulator moves this clock (wait to be woken)."""


class WallClock:
    """Sim time from the wall clock, as the simulator's pacer maps it (sim.clock.Pacer)."""

    def __init__(self, pacer) -> None:
        self.pacer = pacer

    def now(self) -> float:
        p = self.pacer
        return p.sim0 + (time.monotonic() - p.wall0) * p.warp

    def wall_s(self, sim_dt: float) -> float | None:
        return max(sim_dt, 0.0) / self.pacer.warp

    def advance(self, t: float) -> None:
        """Nothing to do: the wall clock moves by itself."""


class StepClock:
    """Sim time as far as the simulator has stepped."""

    def __init__(self, t: float = 0.0) -> None:
        self.t = t

    def now(self) -> float:
        return self.t

    def wall_s(self, sim_dt: float) -> float | None:
        return None

    def advance(self, t: float) -> None:
        self.t = t
