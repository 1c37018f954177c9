"""What a device emulator is: a sensor's measurement in its device's bytes.

One module per device, one class each, registered in sim.devices.registry:

    class NmeaGps(Emulator):
        sensor = "gps"            # the sensor (its key under `sensors:`) it speaks for
        protocol = "nmea"         # its name in `wire.protocol`
        Options = NmeaGpsOptions  # a dataclass of its own `wire:` keys (confcheck settings)

        def encode(self, msg, truth) -> list[bytes]:
            ...                   # the sensor's message -> the device's messages

A commanded device (a servo controller, a modem) also overrides receive(data, t):
the bytes the far end wrote, in the order they came, handed over at each
physics step; it answers with self.send(data, t), which queues bytes on the
same line. Everything else (the port, the line's timing, the configuration's
common keys, LCM beside or instead) is the framework's.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable

from sim.model import Truth
from sim.noise import Noise


@dataclass
class NoOptions:
    """A protocol with no keys of its own."""


@dataclass
class DeviceContext:
    """What an emulator is built with."""

    vehicle: str  # vehicle id
    sensor: str  # its sensor's key under `sensors:`
    seed: int  # the simulation's seed: the emulator's own noise stream derives from it
    options: Any  # its Options, filled from the `wire:` mapping
    frame: Any = None  # the world's geodetic frame (sim.geo.LocalFrame)


class Emulator:
    sensor = ""
    protocol = ""
    Options: type = NoOptions

    @classmethod
    def problems(cls, options: Any) -> dict[str, str]:
        """Option key -> what is wrong with it, for what its setting() rules cannot say
        (reported at the key's file:line:col)."""
        return {}

    def __init__(self, ctx: DeviceContext) -> None:
        self.ctx = ctx
        self.options = ctx.options
        # its own stream: a wired sensor's LCM measurements are those of an unwired one
        self.rng = Noise(f"{ctx.seed}:{ctx.sensor}:wire:{self.protocol}")
        self.ignored = 0  # bytes received that mean nothing to it
        self.send: Callable[[bytes, float], object] = lambda data, t: None  # set by the device

    def encode(self, msg: Any, truth: Truth) -> list[bytes]:  # pragma: no cover - abstract
        """The device's messages for one measurement (msg: what the sensor's poll()
        returned, at truth.t): each a burst on the line, in order."""
        raise NotImplementedError

    def receive(self, data: bytes, t: float) -> None:
        """Bytes the far end wrote, at the simulator's step t. A device that takes no
        commands ignores them (and counts them)."""
        self.ignored += len(data)
