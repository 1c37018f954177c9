"""A wired sensor in the simulator: its emulator, its port, and what went on the line.

build_devices() makes one Device per sensor whose configuration has a `wire:`
mapping; the simulator (sim.hil) polls such a sensor through Device.poll(),
which hands each measurement to the emulator, queues the bytes on the port and
returns the LCM bytes too, or None (`publish_lcm: false`). Device.step(t), every
physics step, moves a step clock and gives the emulator what the far end wrote.

The time rule (docs/simulator.md, "Devices at the wire"): a measurement made at
sim time t starts on the line at t (or when the line is free), and its bytes
are delivered at t + k * 10 / baud in sim time. Real time and scaled: a writer
thread paces them by the wall clock (scaled: warp times faster). Lockstep, and
a run as fast as the CPU allows: at each step the bytes due by the step's time
go out, in the step. Each burst's sim times are kept in `records`.
"""

from __future__ import annotations

from collections import deque
from typing import Any, Callable, NamedTuple

from sim.devices.clocks import StepClock, WallClock
from sim.devices.config import WireConfig
from sim.devices.emulator import DeviceContext, Emulator
from sim.devices.line import Line
from sim.devices.port import Port
from sim.devices.registry import protocols_of
from sim.devices.transport import PtyTransport, TcpTransport, Transport

RECORDS_KEPT = 1000


class Record(NamedTuple):
    """One burst on the line, in sim time [s]."""

    t_measured: float
    t_start: float  # first bit
    t_end: float  # last byte complete at the far end
    n_bytes: int


def open_transport(wire: WireConfig) -> Transport:
    if wire.pty:
        return PtyTransport(wire.pty)
    return TcpTransport(*wire.tcp_address)


class Device:
    """sensor: the sensor it speaks for, or None for a device the simulator drives
    otherwise (the fin and thruster controller, the modem: Devices.add())."""

    def __init__(self, sensor, emulator: Emulator, port: Port, publish_lcm: bool) -> None:
        self.sensor = sensor
        self.emulator = emulator
        self.port = port
        self.publish_lcm = publish_lcm
        self.records: deque[Record] = deque(maxlen=RECORDS_KEPT)
        emulator.send = self.send

    def send(self, data: bytes, t: float) -> None:
        """Queue bytes measured (or answered) at sim time t."""
        burst = self.port.write(data, t)
        if burst is not None:
            self.records.append(Record(t, burst.t_start, burst.t_end, len(data)))

    def emit(self, msg: Any, truth) -> None:
        for data in self.emulator.encode(msg, truth):
            self.send(data, truth.t)

    def poll(self, truth) -> bytes | None:
        """The sensor's poll(), at the wire: the LCM bytes if it publishes them too."""
        msg = self.sensor.poll(truth)
        if msg is None:
            return None
        self.emit(msg, truth)
        return self.sensor.encode(msg) if self.publish_lcm else None

    def step(self, t: float) -> None:
        data = self.port.take_input()
        if data:
            self.emulator.receive(data, t)

    def close(self) -> None:
        self.port.close()

    def summary(self) -> str:
        return f"{self.emulator.ctx.sensor} {self.emulator.protocol} on {self.port.summary()}"


class Devices:
    """Every wired sensor of one simulator, and the clock their lines share."""

    def __init__(self, items: list[Device], clock) -> None:
        self.items = items
        self.clock = clock
        self._stepped = isinstance(clock, StepClock)

    def __bool__(self) -> bool:
        return bool(self.items)

    def poll_for(self, sensor) -> Callable[[Any], bytes | None]:
        """What the simulator calls to poll this sensor (as bytes for LCM, or None)."""
        for d in self.items:
            if d.sensor is not None and d.sensor is sensor:
                return d.poll
        return sensor.poll_encoded

    def add(self, emulator: Emulator, wire: WireConfig) -> Device:
        """A device no sensor polls (its part of the simulator calls its emulator), on
        this simulator's line clock: what `actuators:` or `modem:` would wire."""
        port = Port(open_transport(wire), Line(wire.baud), self.clock, wire.queue_bytes)
        device = Device(None, emulator, port, wire.publish_lcm)
        self.items.append(device)
        return device

    def step(self, t: float) -> None:
        """Every physics step, after its outputs."""
        if self._stepped:
            self.clock.advance(t)
        for d in self.items:
            d.step(t)  # first: an answer queued now goes out in this step if it is due
            if self._stepped and d.port.pending():
                d.port.flush_due()

    def close(self) -> list[str]:
        """Close every port; a summary line each."""
        lines = [d.summary() for d in self.items]
        for d in self.items:
            d.close()
        return lines


def build_devices(sensors: list, vehicle: str, seed: int, frame, pacer, stepped: bool) -> Devices:
    """A Device for every sensor whose configuration has `wire:`; stepped: the lines
    follow the simulator's steps (lockstep, as fast as the CPU allows, multi-HIL),
    else the pacer's wall clock."""
    clock = StepClock() if stepped else WallClock(pacer)
    items = []
    try:
        for sen in sensors:
            wire: WireConfig | None = getattr(sen.cfg, "wire", None)
            if wire is None:
                continue
            cls = protocols_of(sen.name)[wire.protocol]
            emulator = cls(DeviceContext(vehicle, sen.name, seed, wire.options, frame))
            port = Port(open_transport(wire), Line(wire.baud), clock, wire.queue_bytes)
            items.append(Device(sen, emulator, port, wire.publish_lcm))
    except BaseException:
        for d in items:
            d.close()
        raise
    return Devices(items, clock)
