"""Lockstep: global time advances one step when every participant is done.

Every node tracks the participants it hears on SIM.LOCKSTEP (REGISTER,
STEP_DONE, LEAVE), so whichever node becomes the server already knows whom
to wait for. A STEP_DONE from an unknown participant registers it. A
participant silent for `timeout_s` (wall) while the server waits is dropped
with a message, so one dead process cannot stop the world.

Order inside a step (what makes two runs identical): the server publishes
SIM.CLOCK for step n; each participant does its work for time t_n using only
what was published in earlier steps, publishes its outputs, then STEP_DONE n;
the server publishes step n + 1 only after every STEP_DONE n. Messages of
step n therefore always reach a process before the clock of step n + 1.

Lost datagrams (a full socket buffer under load) cannot stop the world: every
message is idempotent, keyed by its step, and repeated until it had its effect.
A participant that reported step n and heard no newer clock for RESEND_S
reports n again (so a lost STEP_DONE arrives later); a server that hears a
STEP_DONE for the step before the one it waits for knows that participant
missed the clock and publishes that step's clock again (ServerResend). A
repeat changes nothing it already did: a clock for a step already done is only
acknowledged, a STEP_DONE only raises the step a participant is known to have
finished. Repeats happen only after a loss or a step that took RESEND_S.
"""

from __future__ import annotations

import struct
import time
from dataclasses import dataclass, field

from auv import lockstep_t


@dataclass
class Participant:
    name: str
    last_done: int = -1
    last_heard: float = field(default_factory=time.monotonic)
    repeat_at: float = 0.0  # when it last reported a step it had reported before


RESEND_S = 0.25  # wall seconds without progress before a lockstep message is repeated


class LockstepTracker:
    """Who takes part, and what each reported; kept by every node.

    timeout_s None: never drop a participant (the launcher watches its
    children itself; a slow one must slow time, never be left behind)."""

    def __init__(self, timeout_s: float | None = 5.0, log=print) -> None:
        self.parts: dict[str, Participant] = {}
        self.timeout_s = timeout_s
        self.dropped = 0
        self.repeats = 0  # STEP_DONE messages for a step already known done
        self.log = log
        # The server asks "does anyone owe this step?" at every wake-up, and
        # wakes for every report: a scan of every participant each time is
        # O(N^2) per step. A participant known to owe answers it at once, and
        # the newest repeat says whether missed_clock needs to look at all.
        self._owing: Participant | None = None
        self._newest_repeat = 0.0

    def on_message(self, msg) -> None:
        if msg.kind == lockstep_t.KIND_LEAVE:
            self.parts.pop(msg.participant, None)
            return
        p = self.parts.get(msg.participant)
        if p is None:
            p = self.parts[msg.participant] = Participant(msg.participant)
        p.last_heard = time.monotonic()
        if msg.kind == lockstep_t.KIND_REGISTER:
            p.repeat_at = self._newest_repeat = p.last_heard  # still registering: it has heard no clock yet
        elif msg.kind == lockstep_t.KIND_STEP_DONE:
            if msg.step <= p.last_done:
                self.repeats += 1
                p.repeat_at = self._newest_repeat = p.last_heard
            p.last_done = max(p.last_done, msg.step)

    def missed_clock(self, step: int, since: float) -> bool:
        """A participant that owes step repeated an older report after `since`:
        it did not get the clock of step (lost), which must be published again."""
        if self._newest_repeat <= since:
            return False
        return any(p.repeat_at > since and p.last_done < step for p in self.parts.values())

    def remove(self, name: str) -> None:
        self.parts.pop(name, None)

    def owes(self, step: int) -> bool:
        """Someone has not reported step yet (waiting_for(step) is not empty)."""
        p = self._owing
        if p is not None and p.last_done < step and self.parts.get(p.name) is p:
            return True
        self._owing = next((p for p in self.parts.values() if p.last_done < step), None)
        return self._owing is not None

    def waiting_for(self, step: int) -> list[str]:
        return sorted(n for n, p in self.parts.items() if p.last_done < step) if self.owes(step) else []

    def drop_silent(self, step: int, since: float) -> None:
        """Drop participants that owe step and were not heard from for timeout_s."""
        if self.timeout_s is None:
            return
        now = time.monotonic()
        for name in self.waiting_for(step):
            p = self.parts[name]
            if now - max(p.last_heard, since) > self.timeout_s:
                del self.parts[name]
                self.dropped += 1
                self.log(f"multihil: lockstep: dropped {name}: silent for {self.timeout_s:g} s at step {step}")


_FINGERPRINT = lockstep_t._get_packed_fingerprint()
_HEAD = struct.Struct(">8sqI")  # fingerprint, utime, participant length (with its NUL)
_TAIL = struct.Struct(">bq")  # kind, step


def decode_lockstep(data: bytes) -> lockstep_t:
    """lockstep_t.decode without a BytesIO, and strict: the launcher's clock
    decodes every participant's report of every step (a quarter of its CPU
    through the generic decoder). ValueError unless data is exactly one
    lockstep_t: its fingerprint, a NUL-terminated participant, nothing more."""
    if len(data) < _HEAD.size + 1 + _TAIL.size:
        raise ValueError("lockstep_t: too short")
    fp, utime, n = _HEAD.unpack_from(data)
    end = _HEAD.size + n
    if fp != _FINGERPRINT or n < 1 or len(data) != end + _TAIL.size or data[end - 1] != 0:
        raise ValueError("not a lockstep_t")
    m = lockstep_t()
    m.utime = utime
    m.participant = data[_HEAD.size : end - 1].decode("utf-8", "replace")
    m.kind, m.step = _TAIL.unpack_from(data, end)
    return m


def lockstep_msg(participant: str, kind: int, step: int, utime: int) -> lockstep_t:
    m = lockstep_t()
    m.utime, m.participant, m.kind, m.step = utime, participant, kind, step
    return m


class Participation:
    """One participant's side: register until a lockstep clock is seen, then
    report each step once its work is done (re-reporting a repeated step), and
    report the last step again while no newer clock comes (a lost report)."""

    REGISTER_PERIOD_S = 1.0

    def __init__(self, name: str, publish, resend_s: float = RESEND_S) -> None:
        self.name = name
        self.publish = publish  # publish(lockstep_t)
        self.pending: tuple[int, int] | None = None  # (step, utime) to report
        self.last_done = -1
        self.last_done_utime = 0
        self.seen_clock = False
        self.resend_s = resend_s
        self.resent = 0
        self._next_register = 0.0
        self._next_resend = 0.0

    def poll(self) -> None:
        """Each turn of the participant's loop: register, or repeat a report nobody acted on."""
        now = time.monotonic()
        if not self.seen_clock:
            if now >= self._next_register:
                self._next_register = now + self.REGISTER_PERIOD_S
                self.publish(lockstep_msg(self.name, lockstep_t.KIND_REGISTER, 0, 0))
        elif self.pending is None and self.last_done >= 0 and now >= self._next_resend:
            self._next_resend = now + self.resend_s
            self.resent += 1
            self.publish(lockstep_msg(self.name, lockstep_t.KIND_STEP_DONE, self.last_done, self.last_done_utime))

    def on_clock(self, step: int, utime: int) -> None:
        self.seen_clock = True
        if step <= self.last_done:
            # a repeated clock (a lost report, or a new server resuming the step
            # it found in flight): the work is done, confirm it again
            self.publish(lockstep_msg(self.name, lockstep_t.KIND_STEP_DONE, step, utime))
            self._next_resend = time.monotonic() + self.resend_s
        else:
            self.pending = (step, utime)

    def done(self) -> None:
        if self.pending is not None:
            step, utime = self.pending
            self.pending = None
            self.last_done, self.last_done_utime = step, utime
            self._next_resend = time.monotonic() + self.resend_s
            self.publish(lockstep_msg(self.name, lockstep_t.KIND_STEP_DONE, step, utime))

    def leave(self) -> None:
        self.publish(lockstep_msg(self.name, lockstep_t.KIND_LEAVE, self.last_done, 0))
