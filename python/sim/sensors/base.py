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

from confcheck import setting
from sim.model import Truth
from sim.noise import Noise
from sim.periodic import Periodic
from sim.wire import encoder_for

TWO_PI = 2.0 * math.pi
# A channel suffix a sensor may be moved to: <VEHICLE>.<this>
CHANNEL_SUFFIX = r"[A-Z][A-Z0-9_]{0,31}"
CHANNEL_HINT = "a channel name (upper-case letters, digits, '_', e.g. NAV or NAV_INS)"


@dataclass
class SensorConfig:
    enabled: bool = True
    rate_hz: float = setting(1.0, gt=0.0, unit="Hz")
    noise: float = setting(0.0, ge=0.0)  # 1-sigma white noise, in the sensor's unit
    bias: float = 0.0  # constant offset, in the sensor's unit
    dropout: float = setting(0.0, ge=0.0, lt=1.0)  # probability that one sample is lost [0, 1)
    phase_s: float = 0.0  # offset of the first sample, to spread load
    # its device at the wire (sim.devices.config.WireConfig); None: LCM only
    wire: Any = None


class Sensor:
    """A sensor model, declared once: its registry entry (sim.sensors.SENSORS)
    is this class, and everything else that names sensors derives from these
    attributes (the configuration's `sensors:` keys, the channels an INS may
    not move onto, the navigation filter's figures, the world it is given)."""

    name = "sensor"  # its key under `sensors:` in a simulator configuration
    topic = "SENSOR"  # channel suffix: <VEHICLE>.<topic>
    config_class: type = None  # type: ignore[assignment]  # its SensorConfig subclass
    # The environment variables it reads (sim.environment.ENV_VARIABLES): a
    # multi-HIL vehicle must ask the world for them (multihil.needs).
    env_needs: tuple[str, ...] = ()
    # The parts of the simulated world its constructor takes, as keywords:
    # "env" (sim.environment.Environment), "frame" (the geodetic frame).
    uses: tuple[str, ...] = ()
    # Built when a configuration lists no sensors (`sensors:` absent): the
    # vehicle's own instruments. A payload not every vehicle carries (the CTD)
    # says False and is fitted only where a configuration lists it.
    fitted_unless_listed: bool = True

    @classmethod
    def nav_config(cls, cfg: "SensorConfig", env: Any) -> list[str]:
        """Its lines of the navigation filter's config (tools.nav.navconf), from its
        configuration and the world's parameters (sim.environment.EnvParams): its
        noise as the filter's specification; none if the filter does not fuse it."""
        return []

    def __init__(self, cfg: SensorConfig, seed: int, vehicle: str) -> None:
        self.cfg = cfg
        self.vehicle = vehicle
        self.rng = Noise(f"{seed}:{self.name}")
        self.gauss = self.rng.gauss  # gauss(sigma): N(0, sigma^2), 0 if sigma <= 0
        self.schedule = Periodic(1.0 / cfg.rate_hz, cfg.phase_s, skip_slack=1e-9)
        self.samples = 0
        self.dropped = 0
        self._encoders: dict[type, Any] = {}

    def due(self, t: float) -> bool:
        return self.cfg.enabled and self.schedule.due(t)

    def next_due(self) -> float:
        """Sim time of the next poll() that can return something."""
        return self.schedule.next_t if self.cfg.enabled else math.inf

    def restart(self, t: float) -> None:
        """Join a world at time t: the first sample at t + phase_s."""
        self.schedule.restart(t + self.cfg.phase_s)

    def _take(self, t: float) -> int:
        """Whether a sample is due at t: 0 no, 1 a measurement, 2 a dropout.

        Schedules the next one on the grid (never drifting, skipping missed
        slots) and draws the dropout, so call it once per poll.
        """
        if not self.due(t):
            return 0
        self.schedule.advance(t)
        self.samples += 1
        if self.cfg.dropout > 0.0 and self.rng.random() < self.cfg.dropout:
            self.dropped += 1
            return 2
        return 1

    def poll(self, truth: Truth) -> Any | None:
        """A message if one is due at truth.t (and not dropped), else None."""
        take = self._take(truth.t)
        if take == 0:
            return None
        return self.measure(truth) if take == 1 else self.dropout_message(truth)

    def poll_encoded(self, truth: Truth) -> bytes | None:
        """poll() as the bytes the simulator publishes.

        Sensors sampled at high rates override measure_encoded() to pack their
        values straight into bytes (sim.wire), with no message object.
        """
        take = self._take(truth.t)
        if take == 0:
            return None
        if take == 1:
            return self.measure_encoded(truth)
        msg = self.dropout_message(truth)
        return None if msg is None else self.encode(msg)

    def measure_encoded(self, truth: Truth) -> bytes | None:
        msg = self.measure(truth)
        return None if msg is None else self.encode(msg)

    def encode(self, msg) -> bytes:
        """A message of this sensor as bytes: a precompiled struct where the layout allows."""
        cls = type(msg)
        enc = self._encoders.get(cls, False)
        if enc is False:
            enc = self._encoders[cls] = encoder_for(cls, self.vehicle)
        return enc.encode(msg) if enc is not None else msg.encode()

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
