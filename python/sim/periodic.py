"""The schedule of one periodic task in sim time: its period and when it is next due.

Every output of the simulator (each sensor, TRUTH, ACTUATOR_STATE, SIM.CLOCK,
HEALTH, the sidescan's updates, the identify looks) keeps to a fixed grid
first + k period: it never drifts with the physics step, and slots it missed
(a period shorter than the step, a join in the middle of the world) are
skipped, not caught up one per step.
"""

from __future__ import annotations

import math

# A slot this close ahead of t is due at t: sim time is a sum of float steps,
# so the step that should land on a slot may land a rounding error short of it.
DUE_SLACK_S = 1e-9


class Periodic:
    """One periodic task: due(t) when its slot came, then advance(t) past t.

    skip_slack (in periods) decides whether a later slot a rounding error
    ahead of t counts as passed by advance(): the sensors, the sidescan and
    the identify looks use 1e-9, the simulator's own outputs 0 (as they
    always had: changing either would move a message by a step in the rare
    case a slot and a step coincide).
    """

    __slots__ = ("period", "next_t", "skip_slack")

    def __init__(self, period: float, first_t: float = 0.0, skip_slack: float = 0.0) -> None:
        self.period = period
        self.next_t = first_t
        self.skip_slack = skip_slack

    def due(self, t: float) -> bool:
        return t >= self.next_t - DUE_SLACK_S

    def advance(self, t: float) -> None:
        """Move to the first slot of the grid after t (missed slots skipped)."""
        p = self.period
        self.next_t += p * max(1, math.floor((t - self.next_t) / p + self.skip_slack) + 1)

    def restart(self, t: float) -> None:
        """Next due at t, the grid starting there (joining a world in the middle)."""
        self.next_t = t
