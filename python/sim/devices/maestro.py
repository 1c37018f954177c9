"""The fins-and-thruster controller at the wire: a Pololu Maestro, I/O-free.

Bytes in (the compact protocol, or the Pololu protocol: 0xAA, device number,
the command with its MSB cleared), channel targets and positions out, replies
to Get Position, Get Moving State and Get Errors; the published semantics of
Pololu's "Maestro Servo Controller User's Guide":

- targets and positions in quarter-microseconds; a target of 0 switches a
  channel's pulses off, and a channel that was off jumps to its next target;
  a target outside the channel's range is clamped to it (the device's own
  settings, here ``ServoChannel.min_qus``/``max_qus``);
- speed: at most ``speed`` quarter-us per 10 ms toward the target (0: no
  limit); acceleration: the speed changes by at most ``accel`` per 80 ms, up
  and down (0: no limit); Get Position reports the ramping pulse, not the
  target;
- a malformed packet (an unknown command byte, a data byte with no command, a
  command cut by the next one, a channel it does not have) sets the serial
  protocol error bit; Get Errors reports the bits and clears them.

Then the inverse of the fins-and-thruster channel table (the file the C driver
reads, docs/drivers.md "Fins and thruster"): pulses back to rudder, stern-plane
and propeller commands for sim.actuators. The driver's process and the
simulator's port wrap these; nothing here touches a port.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import Sequence

from sim.actuators import Command

SET_TARGET = 0x84
SET_SPEED = 0x87
SET_ACCELERATION = 0x89
GET_POSITION = 0x90
GET_MOVING_STATE = 0x93
SET_MULTIPLE_TARGETS = 0x9F
GET_ERRORS = 0xA1
GO_HOME = 0xA2
POLOLU_START = 0xAA

# data bytes after the command byte (Set Multiple Targets: after its count, 1 + 2 per target)
_DATA_BYTES = {
    SET_TARGET: 3,
    SET_SPEED: 3,
    SET_ACCELERATION: 3,
    GET_POSITION: 1,
    GET_MOVING_STATE: 0,
    SET_MULTIPLE_TARGETS: 1,
    GET_ERRORS: 0,
    GO_HOME: 0,
}

ERR_SERIAL_SIGNAL = 1 << 0
ERR_SERIAL_OVERRUN = 1 << 1
ERR_SERIAL_BUFFER_FULL = 1 << 2
ERR_SERIAL_CRC = 1 << 3
ERR_SERIAL_PROTOCOL = 1 << 4
ERR_SERIAL_TIMEOUT = 1 << 5

MAX_TARGET = 16383  # 14 bits
TICK_S = 0.010  # the units of speed: (0.25 us)/(10 ms)
ACCEL_TICKS = 8  # acceleration: (0.25 us)/(10 ms)/(80 ms), so per tick accel/8


@dataclass
class ServoChannel:
    """One channel: the device's settings for it, and its state."""

    min_qus: int = 3968  # the Maestro's default range, 992..2000 us
    max_qus: int = 8000
    home_qus: int = 0  # Go Home's target; 0: off
    target: int = 0
    position: float = 0.0
    speed: int = 0
    accel: int = 0
    velocity: float = 0.0  # quarter-us per tick, toward the target


@dataclass
class Maestro:
    """A Maestro of ``n_channels`` (6, 12, 18 or 24) answering ``device`` in the Pololu protocol."""

    n_channels: int = 24
    device: int = 12
    channels: list[ServoChannel] = field(default_factory=list)
    errors: int = 0
    protocol_errors: int = 0  # packets refused since the start (the bit is cleared when read)
    target_commands: int = 0  # Set Target, Set Multiple Targets and Go Home obeyed: the host's commands
    _packet: list[int] = field(default_factory=list)  # command byte then data
    _pololu: list[int] | None = None  # header bytes of a Pololu packet under way
    _clock: float = 0.0

    def __post_init__(self) -> None:
        while len(self.channels) < self.n_channels:
            self.channels.append(ServoChannel())

    # ------------------------------------------------------------ bytes in
    def feed(self, data: bytes) -> bytes:
        """Bytes from the host, in order; returns the replies they ask for."""
        out = bytearray()
        for b in data:
            self._byte(b, out)
        return bytes(out)

    def _protocol_error(self) -> None:
        self.errors |= ERR_SERIAL_PROTOCOL
        self.protocol_errors += 1

    def _byte(self, b: int, out: bytearray) -> None:
        if b & 0x80:
            if self._packet or self._pololu is not None:
                self._protocol_error()  # a command cut by the next one
            self._packet = []
            self._pololu = None
            if b == POLOLU_START:
                self._pololu = []
            elif b in _DATA_BYTES:
                self._packet = [b]
                self._maybe_run(out)
            else:
                self._protocol_error()
            return
        if self._pololu is not None and not self._packet:
            self._pololu.append(b)
            if len(self._pololu) == 2:  # device number, then the command with its MSB cleared
                cmd = b | 0x80
                if cmd not in _DATA_BYTES:
                    self._pololu = None
                    self._protocol_error()
                    return
                self._packet = [cmd]
                self._maybe_run(out)
            return
        if not self._packet:
            self._protocol_error()  # a data byte with no command
            return
        self._packet.append(b)
        self._maybe_run(out)

    def _needed(self) -> int:
        cmd = self._packet[0]
        if cmd == SET_MULTIPLE_TARGETS and len(self._packet) >= 2:
            return 3 + 2 * self._packet[1]  # command, count, first channel, 2 bytes a target
        return 1 + _DATA_BYTES[cmd]

    def _maybe_run(self, out: bytearray) -> None:
        if len(self._packet) < self._needed():
            return
        packet, header = self._packet, self._pololu
        self._packet, self._pololu = [], None
        if header is not None and header[0] != self.device:
            return  # another device's packet on a shared line
        self._run(packet, out)

    def _channel_ok(self, ch: int) -> bool:
        if ch < self.n_channels:
            return True
        self._protocol_error()
        return False

    def _run(self, p: list[int], out: bytearray) -> None:
        cmd = p[0]
        if cmd in (SET_TARGET, SET_SPEED, SET_ACCELERATION):
            ch, value = p[1], p[2] | p[3] << 7
            if not self._channel_ok(ch):
                return
            if cmd == SET_TARGET:
                self._set_target(ch, value)
                self.target_commands += 1
            elif cmd == SET_SPEED:
                self.channels[ch].speed = value
            elif value > 255:
                self._protocol_error()  # acceleration is 0..255
            else:
                self.channels[ch].accel = value
        elif cmd == SET_MULTIPLE_TARGETS:
            n, first = p[1], p[2]
            if n == 0 or first + n > self.n_channels:
                self._protocol_error()
                return
            for k in range(n):
                self._set_target(first + k, p[3 + 2 * k] | p[4 + 2 * k] << 7)
            self.target_commands += 1
        elif cmd == GET_POSITION:
            if self._channel_ok(p[1]):
                pos = round(self.channels[p[1]].position)
                out += bytes((pos & 0xFF, pos >> 8))
        elif cmd == GET_MOVING_STATE:
            out.append(1 if self.moving() else 0)
        elif cmd == GET_ERRORS:
            out += bytes((self.errors & 0xFF, self.errors >> 8 & 0xFF))
            self.errors = 0
        elif cmd == GO_HOME:
            for ch, c in enumerate(self.channels):
                self._set_target(ch, c.home_qus)
            self.target_commands += 1

    def _set_target(self, ch: int, value: int) -> None:
        c = self.channels[ch]
        if value == 0:
            c.target, c.position, c.velocity = 0, 0.0, 0.0
            return
        c.target = min(max(value, c.min_qus), c.max_qus)
        if c.position == 0.0:
            c.position = float(c.target)  # from off: the first pulse is the target

    # ------------------------------------------------------------ time
    def moving(self) -> bool:
        return any(c.target and c.position != c.target for c in self.channels)

    def advance(self, dt: float) -> None:
        """Let dt seconds pass: positions ramp toward targets in 10 ms updates."""
        self._clock += dt
        while self._clock >= TICK_S - 1e-12:
            self._clock -= TICK_S
            for c in self.channels:
                _tick(c)

    def positions(self) -> list[int]:
        return [round(c.position) for c in self.channels]

    def targets(self) -> list[int]:
        return [c.target for c in self.channels]


def _tick(c: ServoChannel) -> None:
    dist = c.target - c.position
    if c.target == 0 or dist == 0.0:
        c.velocity = 0.0
        return
    if c.speed == 0 and c.accel == 0:
        c.position = float(c.target)
        return
    vmax = float(c.speed) if c.speed else math.inf
    if c.accel:
        a = c.accel / ACCEL_TICKS
        if c.velocity * dist < 0.0:
            c.velocity = 0.0  # the target moved behind it: start again from rest
        # speed up by a, and no faster than it can still stop at the target slowing by a
        # a tick: moving v, v - a, ... covers v * v / (2 a) + v / 2
        brake = math.sqrt(a * a / 4.0 + 2.0 * a * abs(dist)) - a / 2.0
        v = min(abs(c.velocity) + a, vmax, brake)
        v = max(v, min(a, abs(dist), vmax))  # never stall short of the target
    else:
        v = vmax
    step = min(v, abs(dist))
    c.position += math.copysign(step, dist)
    c.velocity = math.copysign(step, dist) if c.position != c.target else 0.0


# ------------------------------------------------------------ the channel table

ACTUATORS = ("rudder", "stern_plane", "prop")
MAX_PULSE_US = MAX_TARGET / 4.0
MAX_LINE = 512
# a plain decimal number, as the C reader takes it: no hex, inf, nan or underscores
_DECIMAL = re.compile(r"[+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?")


class TableError(ValueError):
    """A channel table's error, as ``file:line:col: message``."""


@dataclass(frozen=True)
class TableChannel:
    channel: int
    actuator: str  # one of ACTUATORS
    neutral_us: float
    us_per_unit: float  # per radian (fins) or per rpm (prop)
    min_us: float
    max_us: float
    reversed: bool = False
    speed: int = 0
    accel: int = 0

    def value(self, pulse_us: float) -> float:
        """The actuator's command this pulse stands for (the driver's map, inverted)."""
        sign = -1.0 if self.reversed else 1.0
        return sign * (pulse_us - self.neutral_us) / self.us_per_unit


@dataclass(frozen=True)
class ChannelTable:
    channels: tuple[TableChannel, ...]
    watchdog_s: float
    pololu: bool = False
    device: int = 12

    def command(self, positions_qus: Sequence[int]) -> Command:
        """Rudder, stern plane and prop from the channels' pulses (quarter-us, indexed by
        channel): the mean over an actuator's channels that are on; 0 when none is (a
        channel off drives nothing)."""
        sums = {a: [0.0, 0] for a in ACTUATORS}
        for c in self.channels:
            q = positions_qus[c.channel]
            if q:
                s = sums[c.actuator]
                s[0] += c.value(q / 4.0)
                s[1] += 1
        v = {a: (s[0] / s[1] if s[1] else 0.0) for a, s in sums.items()}
        return Command(rudder_rad=v["rudder"], stern_plane_rad=v["stern_plane"], prop_rpm=v["prop"])

    def maestro(self, n_channels: int = 24) -> Maestro:
        """A Maestro set up as this table expects: each channel's range its limits."""
        m = Maestro(n_channels=n_channels, device=self.device)
        for c in self.channels:
            m.channels[c.channel].min_qus = math.ceil(c.min_us * 4.0)
            m.channels[c.channel].max_qus = math.floor(c.max_us * 4.0)
        return m


def parse_table(text: str, file: str = "<table>") -> ChannelTable:
    """The channel table the C driver reads (c/drivers/servo/am_config.c), with the same rules."""
    channels: list[TableChannel] = []
    watchdog: float | None = None
    protocol: tuple[bool, int] | None = None
    for ln, line in enumerate(text.split("\n"), 1):
        if len(line) > MAX_LINE:
            raise TableError(f"{file}:{ln}:{MAX_LINE + 1}: line longer than {MAX_LINE} characters")
        words = _split(line.split("#", 1)[0], file, ln)
        if not words:
            continue

        def fail(k: int, msg: str) -> TableError:
            return TableError(f"{file}:{ln}:{words[min(k, len(words) - 1)][0]}: {msg}")

        def num(k: int, lo: float, hi: float, what: str, whole: bool = False) -> float:
            if k >= len(words):
                raise fail(k, f"{what}: a number is missing after '{words[-1][1]}'")
            v = float(words[k][1]) if _DECIMAL.fullmatch(words[k][1]) else math.nan
            if not math.isfinite(v):
                raise fail(k, f"{what}: '{words[k][1]}' is not a number")
            if not lo <= v <= hi:
                raise fail(k, f"{what}: {words[k][1]} is outside {lo:g}..{hi:g}")
            if whole and v != math.floor(v):
                raise fail(k, f"{what}: {words[k][1]} is not a whole number")
            return v

        key = words[0][1]
        if key == "watchdog":
            if watchdog is not None:
                raise fail(0, "watchdog is already set")
            watchdog = num(1, 0.01, 3600, "watchdog [s]")
            if len(words) > 2:
                raise fail(2, f"unexpected '{words[2][1]}' (the watchdog's timeout is in seconds)")
        elif key == "protocol":
            if protocol is not None:
                raise fail(0, "protocol is already set")
            if len(words) == 2 and words[1][1] == "compact":
                protocol = (False, 12)
            elif len(words) >= 2 and words[1][1] == "pololu":
                if len(words) > 3:
                    raise fail(3, f"unexpected '{words[3][1]}'")
                protocol = (True, int(num(2, 0, 127, "device number", True)) if len(words) == 3 else 12)
            else:
                raise fail(1, "protocol: 'compact' or 'pololu [DEVICE]'")
        elif key == "channel":
            channels.append(_channel(words, num, fail, channels))
        else:
            raise fail(0, f"unknown keyword '{key}' (protocol, watchdog, channel)")
    if watchdog is None:
        raise TableError(f"{file}:1:1: no 'watchdog SECONDS' line: how long without commands before neutral?")
    if not channels:
        raise TableError(f"{file}:1:1: no 'channel' line: the table is empty")
    pololu, device = protocol or (False, 12)
    return ChannelTable(tuple(channels), watchdog, pololu, device)


def _split(line: str, file: str, ln: int) -> list[tuple[int, str]]:
    """(column, word) pairs; a byte outside printable ASCII is refused, as in C."""
    for i, ch in enumerate(line):
        if ch not in " \t\r" and not " " <= ch <= "~":
            raise TableError(f"{file}:{ln}:{i + 1}: a byte outside printable ASCII (0x{ord(ch):02x})")
    words, i = [], 0
    while i < len(line):
        if line[i] in " \t\r":
            i += 1
            continue
        j = i
        while j < len(line) and line[j] not in " \t\r":
            j += 1
        words.append((i + 1, line[i:j]))
        i = j
    return words


def _channel(words, num, fail, channels: list[TableChannel]) -> TableChannel:
    if len(channels) == 24:
        raise fail(0, "more than 24 channels")
    ch = int(num(1, 0, 23, "channel number", True))
    if any(c.channel == ch for c in channels):
        raise fail(1, f"channel {ch} is already in the table")
    if len(words) < 3:
        raise fail(1, "the actuator is missing (rudder, stern_plane or prop)")
    actuator = words[2][1]
    if actuator not in ACTUATORS:
        raise fail(2, f"unknown actuator '{actuator}' (rudder, stern_plane or prop)")
    neutral = num(3, 1, MAX_PULSE_US, "neutral [us]")
    scale = num(4, 0, 1e9, "microseconds per unit")
    lo = num(5, 1, MAX_PULSE_US, "min [us]")
    hi = num(6, 1, MAX_PULSE_US, "max [us]")
    if scale <= 0:
        raise fail(4, "microseconds per unit must be above 0 (a reversed servo: 'reversed')")
    if lo >= hi:
        raise fail(5, f"min {lo:g} us is not below max {hi:g} us")
    if not lo <= neutral <= hi:
        raise fail(3, f"neutral {neutral:g} us is outside min..max ({lo:g}..{hi:g} us)")
    rev, speed, accel, k = False, 0, 0, 7
    while k < len(words):
        w = words[k][1]
        if w == "reversed" and not rev:
            rev = True
        elif w == "speed":
            k += 1
            speed = int(num(k, 0, MAX_TARGET, "speed", True))
        elif w == "accel":
            k += 1
            accel = int(num(k, 0, 255, "accel", True))
        else:
            raise fail(k, f"unexpected '{w}' (options: reversed, speed N, accel N)")
        k += 1
    return TableChannel(ch, actuator, neutral, scale, lo, hi, rev, speed, accel)
