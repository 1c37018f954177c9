"""Contacts against the true target field: one rule for the report and the plots.

Each contact goes to the nearest true object within the association radius; a
target is detected if any contact went to it; a contact near no object is a
false alarm.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np


@dataclass
class Association:
    targets: list[Any]  # seabed_target_t, in the order of the field
    contacts: list[tuple[str, Any]]  # (vehicle, sidescan_contact_t)
    mine: np.ndarray  # per target: mine-like
    hit: np.ndarray  # per target: some contact went to it
    nearest: np.ndarray  # per contact: index of its target, -1 for a false alarm

    @property
    def false_alarm(self) -> np.ndarray:
        return self.nearest < 0

    @property
    def missed(self) -> np.ndarray:
        """Mine-like targets no contact went to."""
        return self.mine & ~self.hit


def associate(targets: list[Any], contacts: list[tuple[str, Any]], radius: float) -> Association:
    tpos = np.array([(t.north_m, t.east_m) for t in targets], float).reshape(-1, 2)
    hit = np.zeros(len(targets), bool)
    nearest = np.full(len(contacts), -1, int)
    for i, (_vid, c) in enumerate(contacts):
        if not len(tpos):
            break
        d = np.hypot(tpos[:, 0] - c.north_m, tpos[:, 1] - c.east_m)
        k = int(d.argmin())
        if d[k] <= radius:
            hit[k] = True
            nearest[i] = k
    mine = np.array([t.kind == 0 for t in targets], bool)
    return Association(list(targets), list(contacts), mine, hit, nearest)
