"""The launcher's global clock: SIM.CLOCK for a world of stepped simulators.

Every simulator runs `--clock stepped` and every manager `--clock sim`, so one
clock drives the whole world. It holds time at 0 until every process is up
(a deterministic start), then advances by `step` at `warp` times real time
(`fast`: as fast as the simulators go), never past the limit the launcher's
watch gives (a little ahead of the slowest simulator and manager,
tools/mission_watch.py): an overloaded machine slows the clock down instead of
leaving a vehicle or its pilot behind.
"""

from __future__ import annotations

import math
import time

import lcm
from auv import sim_clock_t

MODES = {"realtime": sim_clock_t.MODE_REALTIME, "scaled": sim_clock_t.MODE_SCALED,
         "fast": sim_clock_t.MODE_SCALED}


class WorldClock:
    def __init__(self, lc: lcm.LCM, mode: str, warp: float, step_s: float) -> None:
        self.lc = lc
        self.mode = mode
        self.warp = 1.0 if mode == "realtime" else (math.inf if mode == "fast" else warp)
        self.step_us = max(1, round(step_s * 1e6))
        self.now_us = 0
        self.running = False
        self._wall0 = 0.0
        self._sim0_us = 0
        self.ticks = 0

    def _publish(self) -> None:
        c = sim_clock_t()
        c.utime, c.server_id, c.term = self.now_us, "launcher", 0
        c.mode = MODES[self.mode]
        c.warp = 0.0 if math.isinf(self.warp) else self.warp
        c.step, c.step_us = 0, self.step_us
        self.lc.publish("SIM.CLOCK", c.encode())
        self.ticks += 1

    def hold(self) -> None:
        """Repeat the current time (before the start): late joiners learn it."""
        self._publish()

    def start(self) -> None:
        self.running = True
        self._rebase(time.monotonic())

    def _rebase(self, wall: float) -> None:
        self._wall0, self._sim0_us = wall, self.now_us

    def advance(self, limit_us: int | None) -> bool:
        """Publish the ticks that are due up to limit_us; False when held back by it."""
        if not self.running:
            return True
        wall = time.monotonic()
        due = math.inf if math.isinf(self.warp) else self._sim0_us + (wall - self._wall0) * self.warp * 1e6
        limit = math.inf if limit_us is None else limit_us
        gated = False
        while self.now_us + self.step_us <= due:
            if self.now_us + self.step_us > limit:
                gated = True
                break
            self.now_us += self.step_us
            self._publish()
        if gated and not math.isinf(self.warp):
            self._rebase(wall)   # resume at warp from here, no catch-up burst later
        return not gated

    def wait_s(self) -> float:
        """How long until the next tick is due (0 in fast mode)."""
        if not self.running or math.isinf(self.warp):
            return 0.0 if self.running else 0.05
        next_wall = self._wall0 + (self.now_us + self.step_us - self._sim0_us) / 1e6 / self.warp
        return max(0.0, next_wall - time.monotonic())
