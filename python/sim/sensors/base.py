"""What every sensor shares: a rate, noise, bias, dropouts and its own RNG.

Each sensor draws from its own stream (sim.noise.Noise) seeded with the
scenario seed and the sensor's name, so adding or removing one sensor does
not change the noise of another, and the same seed gives the same
measurements.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from sim.model import Truth
from sim.noise import Noise

TWO_PI = 2.0 * math.pi


@dataclass
class SensorConfig:
    enabled: bool = True
    rate_hz: float = 1.0
    noise: float = 0.0        # 1-sigma white noise, in the sensor's unit
    bias: float = 0.0         # constant offset, in the sensor's unit
    dropout: float = 0.0      # probability that one sample is lost [0, 1)
    phase_s: float = 0.0      # offset of the first sample, to spread load


class Sensor:
    name = "sensor"
    topic = "SENSOR"          # channel suffix: <VEHICLE>.<topic>

    def __init__(self, cfg: SensorConfig, seed: int, vehicle: str) -> None:
        self.cfg = cfg
        self.vehicle = vehicle
        self.rng = Noise(f"{seed}:{self.name}")
        self.gauss = self.rng.gauss     # gauss(sigma): N(0, sigma^2), 0 if sigma <= 0
        self.period = 1.0 / cfg.rate_hz
        self.next_t = cfg.phase_s
        self.samples = 0
        self.dropped = 0

    def due(self, t: float) -> bool:
        return self.cfg.enabled and t >= self.next_t - 1e-9

    def next_due(self) -> float:
        """Sim time of the next poll() that can return something."""
        return self.next_t if self.cfg.enabled else math.inf

    def poll(self, truth: Truth) -> Any | None:
        """A message if one is due at truth.t (and not dropped), else None."""
        t = truth.t
        if not self.due(t):
            return None
        # schedule on the grid, never drifting, skipping missed slots
        self.next_t += self.period * max(1, math.floor((t - self.next_t) / self.period + 1e-9) + 1)
        self.samples += 1
        if self.cfg.dropout > 0.0 and self.rng.random() < self.cfg.dropout:
            self.dropped += 1
            return self.dropout_message(truth)
        return self.measure(truth)

    def measure(self, truth: Truth) -> Any | None:  # pragma: no cover - abstract
        raise NotImplementedError

    def dropout_message(self, truth: Truth) -> Any | None:
        """What a lost sample looks like on the wire: nothing, by default."""
        return None


def utime(t: float) -> int:
    return int(round(t * 1e6))


def wrap_2pi(a: float) -> float:
    return a % TWO_PI


def wrap_pi(a: float) -> float:
    return (a + math.pi) % TWO_PI - math.pi
