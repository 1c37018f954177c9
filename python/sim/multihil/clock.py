"""A simulator's own clock, and the global clock it steers towards.

LocalClock is the host clock as this process sees it. Tests and benchmarks
inject an offset and a drift, so simulators on one machine disagree the way
separate computers do. SteeredClock is the process's estimate of the world's
global time as a linear function of its local clock; it is re-based at every
correction and its rate is always positive, so it never runs backwards.
"""

from __future__ import annotations

import time


def mono_us() -> float:
    """The machine's monotonic clock [us]: the truth every benchmark compares against."""
    return time.monotonic_ns() / 1000.0


class LocalClock:
    """local = true * (1 + drift) + offset, in microseconds."""

    def __init__(self, offset_us: float = 0.0, drift_ppm: float = 0.0) -> None:
        self.offset_us = offset_us
        self.rate = 1.0 + drift_ppm * 1e-6

    def now_us(self) -> float:
        return mono_us() * self.rate + self.offset_us

    def from_true(self, true_us: float) -> float:
        return true_us * self.rate + self.offset_us


class SteeredClock:
    """global = g0 + rate * (local - l0): set once, then only slewed.

    rate is warp * (1 + correction); corrections are bounded by max_slew, so
    the global estimate keeps moving forward while it converges.
    """

    def __init__(self, local: LocalClock, warp: float = 1.0, max_slew: float = 0.05) -> None:
        self.local = local
        self.warp = warp
        self.max_slew = max_slew
        self.g0: float | None = None  # None: not set yet (no global time known)
        self.l0 = 0.0
        self.rate = warp

    @property
    def is_set(self) -> bool:
        return self.g0 is not None

    def at(self, local_us: float) -> float:
        assert self.g0 is not None, "global clock read before it was set"
        return self.g0 + self.rate * (local_us - self.l0)

    def now(self) -> float:
        return self.at(self.local.now_us())

    def set(self, global_us: float, local_us: float | None = None) -> None:
        """Set the clock. Once set, only forward: a later value behind it is refused."""
        local_us = self.local.now_us() if local_us is None else local_us
        if self.g0 is not None and global_us < self.at(local_us):
            return
        self.g0, self.l0 = global_us, local_us

    def steer(self, error_us: float, drift_rate: float, tau_local_us: float = 1e6) -> None:
        """Correct error_us (target - estimate) over about tau, at the estimated base rate.

        drift_rate is the target's rate in global us per local us (warp * (1 + drift)).
        """
        now = self.local.now_us()
        g = self.at(now)
        slew = max(-self.max_slew, min(self.max_slew, error_us / tau_local_us / self.warp))
        self.g0, self.l0 = g, now
        self.rate = max(drift_rate + slew * self.warp, self.warp * (1.0 - self.max_slew))

    def freeze(self) -> None:
        """Keep the current rate for good (this process now defines global time)."""
        now = self.local.now_us()
        self.g0, self.l0 = self.at(now), now
