"""A stepped simulator's part in a lockstep world (docs/multihil.md, "Lockstep").

Whoever steps the world -- the multi-HIL environment server or the launcher's
clock (tools/launch/worldclock.py) -- publishes SIM.CLOCK with MODE_LOCKSTEP and a
step number, and waits for every participant's STEP_DONE. The simulator is
the participant "<VEHICLE>.sim": it integrates up to the step's time, publishes
what is due, then reports the step. Two rules make a run repeatable:

- a command stamped after the simulator's time waits until the simulator
  reaches that time (whichever arrives first, the clock or the command);
- the report of a step goes out only after every message of that step.

A free-running clock (MODE_REALTIME, MODE_SCALED) asks nothing of this: the
simulator just follows its time.
"""

from __future__ import annotations

import bisect

from auv import lockstep_t, sim_clock_t
from sim.multihil.lockstep import Participation
from sim.wire import Encoder


class LockstepFollower:
    def __init__(self, sim) -> None:
        self.sim = sim
        name = f"{sim.vid}.sim"
        pack = Encoder(lockstep_t, participant=name).pack  # a report each step: no BytesIO encode
        self.part = Participation(name, lambda m: sim.publish_raw("SIM.LOCKSTEP", pack(m.utime, m.kind, m.step)))
        self.active = False  # the clock followed is a lockstep clock
        self._clock: tuple[int, int] | None = None  # (step, utime) not yet passed on
        self._held: list[tuple[float, int, tuple]] = []  # (t, seq, (channel, msg))
        self._held_seq = 0
        # a command that passed the simulator's checks waits for its time stamp
        sim.set_command_filter(self._hold_command)

    def on_clock(self, m: sim_clock_t) -> None:
        """Every SIM.CLOCK the simulator accepted."""
        self.active = m.mode == sim_clock_t.MODE_LOCKSTEP
        if self.active:
            self._clock = (m.step, m.utime)
            if self.sim.modem is not None:  # it judges what the barrier guarantees is in
                self.sim.modem.clock(m.utime)

    def _hold_command(self, channel: str, msg) -> None:
        t = msg.utime / 1e6
        if not self.active or t <= self.sim.model.t + 1e-9:
            self.sim.apply_command(channel, msg)
        else:
            self._held_seq += 1
            bisect.insort(self._held, (t, self._held_seq, (channel, msg)))

    def poll(self) -> None:
        """Each turn of the simulator's loop."""
        sim, part = self.sim, self.part
        if part.pending is None or not part.seen_clock:  # registering, or a report may be repeated
            part.poll()
        while self._held and self._held[0][0] <= sim.model.t + 1e-9:
            _, _, (channel, msg) = self._held.pop(0)
            sim.apply_command(channel, msg)
        if self._clock is not None:
            part.on_clock(*self._clock)
            self._clock = None
        pend = part.pending
        if pend is not None and sim.clock_started and sim.model.t >= pend[1] / 1e6 - 0.5 * sim.dt:
            part.done()  # after the step's messages: the same sender, in order

    def close(self) -> None:
        if self.part.seen_clock or self.part._next_register:
            self.part.leave()
