"""The launcher's global clock: a lockstep server for a world of stepped simulators.

Every simulator runs `--clock stepped`, every manager and filter `--clock sim`,
and the recorder takes part too: each is a lockstep participant
(docs/multihil.md, "Lockstep"; sim/lockstep_follow.py, c/managers/mgr_lockstep.c).
The clock publishes step 0 once every participant of the scenario has
registered, and step n + 1 only after every participant reported step n
(STEP_DONE): so the same scenario and seed give the same messages, whatever
the machine's load. An overloaded machine slows time down; it never leaves a
vehicle, its pilot or its filter behind (no gate on progress reports that a
lost datagram could close for ever).

What the modes change is only the pace (time.mode):
- `lockstep` (also `fast`, the old name): as fast as the slowest participant;
- `scaled`: at most `warp` times real time; `realtime`: at most real time.

The end (docs/scenarios.md, "End"): once every participant reported a step,
the clock asks hold(utime) before it goes on; if the mission ended by then,
the world stops at that step, whole, and nothing after it is simulated.

Lost datagrams are repeated, never waited for (sim/multihil/lockstep.py): a
participant repeats its last report while no newer clock comes, and a report
of the previous step from one that owes the current step makes the clock
publish that step again.
"""

from __future__ import annotations

import math
import time
from typing import Callable

import lcm

from auv import lockstep_t, sim_clock_t
from auvlcm import lockstep_board
from sim import clock_modes
from sim.multihil.board_tracker import BoardTracker
from sim.multihil.lockstep import RESEND_S, LockstepTracker, decode_lockstep
from sim.multihil.server import LockstepServer

PACE = {clock_modes.REALTIME: 1.0, clock_modes.SCALED: None, clock_modes.LOCKSTEP: math.inf}


class WorldClock:
    def __init__(
        self,
        lc: lcm.LCM,
        mode: str,
        warp: float,
        step_s: float,
        participants: set[str] | None = None,
        log=print,
        before_step: Callable[[int], None] | None = None,
        hold: Callable[[int], bool] | None = None,
    ) -> None:
        """before_step(utime): called before a new step is published, when every
        participant has reported the one before (planned faults act there).
        hold(utime): asked then first, with the time of the step every participant
        reported; True: the world ends at that step (held_us), no step follows."""
        self.lc = lc
        self.before_step = before_step
        self.hold = hold
        self.held_us: int | None = None  # the time of the step the world ended at
        self.mode = mode
        self.warp = PACE[mode] if PACE[mode] is not None else warp
        self.step_us = max(1, round(step_s * 1e6))
        # On its own socket the clock lets a board in C take the participants'
        # ordinary reports (auvlcm/lockstep_board.py): half of its CPU was
        # decoding and tracking them in Python, one per participant per step.
        self.board = lockstep_board.attach(lc, "SIM.LOCKSTEP", lockstep_t._get_packed_fingerprint())
        self.tracker = (
            LockstepTracker(timeout_s=None, log=log)
            if self.board is None
            else BoardTracker(self.board, timeout_s=None, log=log)
        )
        self.server = LockstepServer(
            self.tracker, self.step_us, len(participants or ()), log, expect_names=participants
        )
        self.now_us = 0
        self.running = False
        self._wall0 = 0.0
        self._sim0_us = 0
        self.ticks = 0
        self.future_reports = 0  # STEP_DONE for a step never published: counted, dropped
        self.gone: set[str] = set()  # participants lost by a planned fault: never waited for again
        lc.subscribe("SIM.LOCKSTEP", self._on_lockstep).set_queue_capacity(1000)

    def _on_lockstep(self, _ch: str, data: bytes) -> None:
        try:
            m = decode_lockstep(data)
        except ValueError:
            return
        if m.participant in self.gone:
            return  # a report still in flight from a killed process
        if m.kind == lockstep_t.KIND_STEP_DONE and not 0 <= m.step <= self.server.step + 1:
            self.future_reports += 1  # a participant cannot be done with a step not yet sent
            return
        self.tracker.on_message(m)

    def _publish(self, step: int) -> None:
        c = sim_clock_t()
        c.utime, c.server_id, c.term = self.now_us, "launcher", 0
        c.mode = sim_clock_t.MODE_LOCKSTEP
        c.warp = 0.0 if math.isinf(self.warp) else self.warp
        c.step, c.step_us = step, self.step_us
        if self.board is not None:  # what _on_lockstep accepts: no report of a step never published
            self.board.set_limit(self.server.step + 1)
            self.board.set_watch(self.server.step)
        self.lc.publish("SIM.CLOCK", c.encode())
        self.ticks += 1

    def lose(self, names: set[str]) -> None:
        """Stop waiting for these participants, now and for good (their
        processes were killed: tools/scenario/faults.py)."""
        self.gone |= names
        self.server.expect_names -= names
        for n in names:
            self.tracker.remove(n)

    def ready(self) -> bool:
        """Every participant of the scenario registered: step 0 may go."""
        return self.server.ready()

    def not_ready(self) -> list[str]:
        return sorted(self.server.expect_names - self.tracker.parts.keys())

    def waiting_for(self) -> list[str]:
        """Who the current step waits for (the progress line says so)."""
        return self.tracker.waiting_for(self.server.step) if self.running else self.not_ready()

    def start(self) -> None:
        self.running = True
        self._wall0, self._sim0_us = time.monotonic(), 0

    def advance(self) -> None:
        """Publish the next step if every participant is done and its time is due
        (or the current step again, if a participant missed it)."""
        if not self.running or self.held_us is not None:
            return
        if (
            self.server.started
            and not self.tracker.owes(self.server.step)
            and not math.isinf(self.warp)
            and time.monotonic() < self._due(self.server.step + 1)
        ):
            return
        if self.hold is not None and self.ticks and not self.tracker.owes(self.server.step):
            if self.hold(self.now_us):
                self.held_us = self.now_us
                return
        previous = self.server.step if self.ticks else None  # the step published last
        step = self.server.poll()
        if step is None:
            return
        self.now_us = self.server.utime(step)
        if self.before_step is not None and (previous is None or step > previous):
            self.before_step(self.now_us)  # a new step, not one published again
        self._publish(step)
        if not math.isinf(self.warp) and time.monotonic() > self._due(step) + 0.5:
            # far behind the pace (an overloaded machine): go on from here, no burst
            self._wall0, self._sim0_us = time.monotonic(), self.now_us

    def _due(self, step: int) -> float:
        """Wall time (monotonic) at which step's time is due at the pace."""
        return self._wall0 + (self.server.utime(step) - self._sim0_us) / 1e6 / self.warp

    def wait_s(self) -> float:
        """How long the launcher may block on LCM: until the next step is due, or
        until something could need repeating; a message wakes it earlier."""
        if not self.running:
            return 0.05
        if self.server.started and not self.tracker.owes(self.server.step) and not math.isinf(self.warp):
            return max(0.0, min(RESEND_S, self._due(self.server.step + 1) - time.monotonic()))
        return RESEND_S
