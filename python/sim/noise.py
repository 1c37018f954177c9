"""Seeded random streams for sensor and sonar models, drawn in blocks.

Each model draws from its own stream, named by the scenario seed and the
model's name, so adding one sensor does not change another's noise and the
same seed gives the same measurements. A draw is one list index: the numbers
come from numpy's PCG64 a block at a time (random.Random.gauss costs over a
microsecond per call in Python, and a sensor sample needs a dozen draws).
"""

from __future__ import annotations

import hashlib

import numpy as np

BLOCK = 1024


def seed_of(label: str) -> int:
    """A 64-bit seed from a text label such as '42:ahrs'."""
    return int.from_bytes(hashlib.sha256(label.encode("utf-8")).digest()[:8], "little")


class Noise:
    def __init__(self, label: str) -> None:
        self._gen = np.random.Generator(np.random.PCG64(seed_of(label)))
        self._normal: list[float] = []
        self._uniform: list[float] = []
        self._ni = 0
        self._ui = 0

    def gauss(self, sigma: float) -> float:
        """N(0, sigma^2); a sigma <= 0 gives 0.0 and draws nothing."""
        if sigma <= 0.0:
            return 0.0
        i = self._ni
        if i >= len(self._normal):
            self._normal = self._gen.standard_normal(BLOCK).tolist()
            i = 0
        self._ni = i + 1
        return sigma * self._normal[i]

    def random(self) -> float:
        """U[0, 1)."""
        i = self._ui
        if i >= len(self._uniform):
            self._uniform = self._gen.random(BLOCK).tolist()
            i = 0
        self._ui = i + 1
        return self._uniform[i]

    def uniform(self, lo: float, hi: float) -> float:
        return lo + (hi - lo) * self.random()

    def beta(self, a: float, b: float) -> float:
        """Beta(a, b), drawn one at a time (a model's score, a few per second)."""
        return float(self._gen.beta(a, b))

    def poisson(self, lam: float) -> int:
        return int(self._gen.poisson(lam)) if lam > 0.0 else 0
