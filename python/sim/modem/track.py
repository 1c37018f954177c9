"""Where this modem's vehicle was, step by step: a short track of true positions.

Both sides of the modem look back in time. A request that reaches the
simulator after its stamp goes into the water from where the vehicle was at
its stamp; a frame that reaches the simulator after the step at which its
wavefront met the vehicle is judged from where the vehicle was then. So the
answer to "when and where" depends only on the stamps and the physics, never
on the order in which processes happened to run.
"""

from __future__ import annotations

import bisect

Position = tuple[float, float, float]
KEEP_STEPS = 1000  # 20 s at 50 Hz: longer than any lag between a stamp and its handling


class Track:
    def __init__(self, keep: int = KEEP_STEPS) -> None:
        self.keep = keep
        self.times: list[float] = []  # ascending
        self.positions: list[Position] = []

    def add(self, t: float, position: Position) -> None:
        """The vehicle's position after the physics step that ended at t."""
        if self.times and t <= self.times[-1] + 1e-12:
            if t >= self.times[-1] - 1e-12:
                self.positions[-1] = position  # the same step again
                return
            self.times.clear()  # time went back (a new world): the old track is void
            self.positions.clear()
        self.times.append(t)
        self.positions.append(position)
        if len(self.times) > 2 * self.keep:  # trim in blocks: amortised O(1)
            del self.times[: self.keep]
            del self.positions[: self.keep]

    def __len__(self) -> int:
        return len(self.times)

    def first_at_or_after(self, t: float) -> int:
        """Index of the first step at or after t (len(self) when there is none yet)."""
        return bisect.bisect_left(self.times, t - 1e-9)

    def last_at_or_before(self, t: float) -> int:
        """Index of the last step at or before t (-1 when t is before the track)."""
        return bisect.bisect_right(self.times, t + 1e-9) - 1

    def covers(self, t: float) -> bool:
        """Whether the track reaches back to t."""
        return bool(self.times) and t >= self.times[0] - 1e-9
