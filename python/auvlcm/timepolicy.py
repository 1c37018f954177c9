"""The project's rule for message timestamps, for Python receivers.

docs/channels.md ("Time and timestamps") states the rule; the C side
(libchasm, managers, auv-nav) implements the same numbers. In short:

- a utime is valid in [0, UTIME_MAX] (2100-01-01 in Unix time); anything
  else is dropped before it reaches a clock, a variable or an age;
- a clock never runs backwards; a clock from an older election term is
  refused; a forward jump of more than MAX_CLOCK_JUMP_US is refused until a
  second message confirms it (not older than it and within the jump of it);
- a data message more than FUTURE_TOLERANCE_US ahead of the receiver's clock
  is "from the future", one older than the newest accepted on the same input
  is "out of order": both dropped;
- every drop is counted per reason, and the first of each reason is logged.

All arithmetic here is on Python ints: nothing overflows, whatever arrives.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass, field
from typing import Callable

UTIME_MAX = 4_102_444_800_000_000  # 2100-01-01T00:00:00Z [us]
MAX_CLOCK_JUMP_US = 60_000_000  # global time a clock may move forward unconfirmed
FUTURE_TOLERANCE_US = 1_000_000  # how far ahead of `now` a data stamp may be

# the reasons, as counters and log lines name them
INVALID = "invalid"  # outside [0, UTIME_MAX]
FUTURE = "future"  # more than the tolerance ahead of the receiver's clock
OUT_OF_ORDER = "out_of_order"  # older than the newest accepted on the same input
REGRESSION = "regression"  # a clock value behind the current one
JUMP = "jump"  # a clock jump not (yet) confirmed
OLD_TERM = "old_term"  # a clock (or world message) from an election term already over
REASONS = (INVALID, FUTURE, OUT_OF_ORDER, REGRESSION, JUMP, OLD_TERM)


def valid_utime(utime: object) -> bool:
    return isinstance(utime, int) and 0 <= utime <= UTIME_MAX


def _stderr(line: str) -> None:
    print(line, file=sys.stderr, flush=True)


@dataclass
class TimeDrops:
    """Per-reason counts of dropped timestamps; one log line per reason, the first time."""

    who: str  # log prefix, e.g. "sim: AUV1"
    log: Callable[[str], None] = _stderr
    counts: dict[str, int] = field(default_factory=lambda: dict.fromkeys(REASONS, 0))

    def drop(self, reason: str, what: str, detail: str) -> None:
        self.counts[reason] = self.counts.get(reason, 0) + 1
        if self.counts[reason] == 1:
            self.log(f"{self.who}: {what}: dropped a message: {detail} ({reason}; counted, logged once)")

    @property
    def total(self) -> int:
        return sum(self.counts.values())

    def summary(self) -> str:
        """'time drops: future 2, jump 1' or 'no time drops' (for a summary line)."""
        parts = [f"{r} {n}" for r, n in self.counts.items() if n]
        return "time drops: " + ", ".join(parts) if parts else "no time drops"


class ClockGate:
    """A receiver's clock: what it accepts from a stream of (utime, term).

    The first valid value sets it (there is nothing to compare it with; a
    lockstep world publishes each step once, so it cannot wait for a second).
    Afterwards: an older term, a value behind the clock, or an unconfirmed
    jump is dropped. A new term is taken when its message is accepted: the
    next term (or one the process knows started) at once, a term further on
    (a node that missed elections, or a corrupt message) only once a second
    message of it confirms it. The first value stays provisional until a
    message consistent with it arrives: if it was corrupt (2096, a term of
    2^31 - 1), two consistent messages replace it, so even a bad first
    message cannot stop the clock (the receiver's clock then steps back once,
    the only way it ever does). A term the process knows started
    (raise_term) is never undercut.
    """

    def __init__(self, drops: TimeDrops, what: str = "SIM.CLOCK", max_jump_us: int = MAX_CLOCK_JUMP_US) -> None:
        self.drops = drops
        self.what = what
        self.max_jump_us = max_jump_us
        self.now: int | None = None
        self.term = 0
        self.term_floor = 0  # raised by what else the process knows
        self._pending: tuple[int, int] | None = None  # (utime, term) waiting for confirmation
        self._provisional = False  # the first value, not yet confirmed

    def raise_term(self, term: int) -> None:
        """A term known to have started (e.g. its server's heartbeat): older ones are over."""
        self.term_floor = max(self.term_floor, term)

    def offer(self, utime: int, term: int = 0) -> bool:
        """True if the clock takes this value (and now is it); False if dropped (counted)."""
        if not valid_utime(utime):
            self.drops.drop(INVALID, self.what, f"utime {utime} outside [0, {UTIME_MAX}]")
            return False
        if term < self.term_floor:
            self.drops.drop(OLD_TERM, self.what, f"term {term} after term {self.term_floor} (utime {utime})")
            return False
        if self.now is None:
            self._take(utime, term)
            self._provisional = True
            return True
        reason, detail = self._refusal(utime, term)
        if not reason:
            self._take(utime, term)
            return True
        confirmable = reason == JUMP or self._provisional
        p = self._pending
        if confirmable and p is not None and p[1] == term and 0 <= utime - p[0] <= self.max_jump_us:
            self._take(utime, term)  # the second message confirms the first
            return True
        if confirmable:
            self._pending = (utime, term)
            detail += ": waits for a second message to confirm it"
        self.drops.drop(reason, self.what, detail)
        return False

    def _refusal(self, utime: int, term: int) -> tuple[str, str]:
        assert self.now is not None
        if term < self.term:
            return OLD_TERM, f"term {term} after term {self.term} (utime {utime})"
        if utime < self.now:
            return REGRESSION, f"utime {utime} behind the clock's {self.now}"
        if utime - self.now > self.max_jump_us or term > max(self.term, self.term_floor) + 1:
            return JUMP, f"utime {utime} term {term} from {self.now} term {self.term}"
        return "", ""

    def _take(self, utime: int, term: int) -> None:
        self.now, self.term, self._pending, self._provisional = utime, term, None, False


class InputGate:
    """One data input (a channel, a sender): stamps valid, not from the future, in order."""

    def __init__(self, drops: TimeDrops, what: str, tolerance_us: int = FUTURE_TOLERANCE_US) -> None:
        self.drops = drops
        self.what = what
        self.tolerance_us = tolerance_us
        self.newest: int | None = None

    def offer(self, utime: int, now_us: int | float | None) -> bool:
        """True if the value may be used. now_us: the receiver's clock (None: it has none yet)."""
        if not valid_utime(utime):
            self.drops.drop(INVALID, self.what, f"utime {utime} outside [0, {UTIME_MAX}]")
            return False
        if now_us is not None and utime > now_us + self.tolerance_us:
            self.drops.drop(
                FUTURE,
                self.what,
                f"utime {utime} is more than {self.tolerance_us / 1e6:g} s ahead of the clock's {int(now_us)}",
            )
            return False
        if self.newest is not None and utime < self.newest:
            self.drops.drop(OUT_OF_ORDER, self.what, f"utime {utime} older than the newest accepted {self.newest}")
            return False
        self.newest = utime
        return True

    def judge_held(self, now_us: int | float) -> bool:
        """Once a clock exists: is the value held before it (the newest) still acceptable?"""
        if self.newest is not None and self.newest > now_us + self.tolerance_us:
            self.drops.drop(
                FUTURE,
                self.what,
                f"utime {self.newest}, held before the clock "
                f"started, is more than {self.tolerance_us / 1e6:g} s ahead of "
                f"its {int(now_us)}",
            )
            self.newest = None
            return False
        return True
