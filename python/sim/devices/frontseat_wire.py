"""What every frontseat protocol of the simulator is: the plug between the vehicle
(sim.frontseat: its loops, its mission, the control rules, the faults) and the wire.

A protocol (sim.devices.iver3_frontseat, sim.devices.bluefin_frontseat) is an
Emulator registered for the `frontseat` section. It is I/O-free and knows no
physics; per physics step the vehicle

  - sets `truth` (the vehicle now), `silent` (its link is dead: nothing heard,
    nothing said) and, once it has decided who flies, `report` (the helm and
    the abort's error word);
  - reads `request`, the newest request the protocol took (None: none yet);
  - calls update(t): a protocol that streams (Bluefin) sends what is due, one
    that only answers (Iver3) does nothing.

A protocol that answers each request (Bluefin's $BFACK) asks `judge(t)` whether
the vehicle takes a request now: None if it does, else why not (the vehicle's
control rules, in sim.frontseat, the only place they are written).

Both protocols are NMEA-style lines, `$BODY*hh` CR LF: the framing, the checksum
and the counting of lines refused are here; a protocol's sentence(fields, t)
gets the fields of each good line.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

from sim.devices.emulator import DeviceContext, Emulator
from sim.devices.nmea import checksum
from sim.model import Truth

# who flies the vehicle (Report.helm)
MISSION = "mission"  # its own mission
PAYLOAD = "payload"  # the backseat's requests: control granted
MANUAL = "manual"  # an operator's override
STOPPED = "stopped"  # aborted: prop off, fins neutral


@dataclass
class Request:
    """One request of the backseat's, taken at sim time t."""

    t: float
    heading_rad: float
    depth_m: float
    speed_mps: float
    timeout_s: float  # the vehicle flies it this long without another
    max_pitch_rad: float = math.nan  # the pitch it may use for the depth (Iver3's $OMS), NaN: its own
    stop: bool = False  # stop (prop off, fins neutral) instead of heading, depth and speed


@dataclass
class Report:
    """What the vehicle is doing, for the protocol to say in its own words."""

    helm: str = MISSION  # MISSION, PAYLOAD, MANUAL or STOPPED
    error: str = ""  # the abort's error word ("": none)


def compose(body: str) -> bytes:
    """$BODY*hh CR LF."""
    return f"${body}*{checksum(body)}\r\n".encode("ascii")


def never_refuse(t: float) -> str | None:
    return None


class FrontseatProtocol(Emulator):
    """The common part: lines in, checked, counted; the vehicle's side of the plug."""

    sensor = "frontseat"  # the simulator's part it belongs to (not a sensor: Devices.add)
    line_max = 250  # a longer line is refused ("too long")

    def __init__(self, ctx: DeviceContext) -> None:
        super().__init__(ctx)
        self._line = bytearray()
        self._in_line = False
        self.request: Request | None = None  # the newest request taken
        self.requests = 0  # requests taken
        self.refused: dict[str, int] = {}  # lines (and requests) it did not take, by reason
        self.report = Report()
        self.truth: Truth | None = None  # the vehicle now (sim.frontseat sets it each step)
        self.silent = False  # the link is dead: nothing heard, nothing said
        self.judge: Callable[[float], str | None] = never_refuse  # why a request is not taken now

    def encode(self, msg, truth) -> list[bytes]:
        return []  # it speaks for itself (update, receive)

    def update(self, t: float) -> None:
        """Each physics step, after the vehicle decided who flies."""

    def sentence(self, fields: list[str], t: float) -> None:  # pragma: no cover - abstract
        """A good line's fields (the address first)."""
        raise NotImplementedError

    def _refuse(self, reason: str) -> None:
        self.refused[reason] = self.refused.get(reason, 0) + 1

    def receive(self, data: bytes, t: float) -> None:
        if self.silent:
            self.ignored += len(data)
            return
        for b in data:
            if b == ord("$"):
                if self._in_line:
                    self._refuse("truncated")
                self._line = bytearray(b"$")
                self._in_line = True
            elif b in (13, 10):
                if self._in_line:
                    self._line_in(self._line.decode("ascii", "replace"), t)
                self._in_line = False
            elif self._in_line:
                if len(self._line) >= self.line_max:
                    self._refuse("too long")
                    self._in_line = False
                else:
                    self._line.append(b)
            else:
                self.ignored += 1

    def _line_in(self, line: str, t: float) -> None:
        if not line.isascii() or not line.isprintable():
            self._refuse("bad character")
            return
        # the checksum is optional (NMEA 0183): checked when a '*' is there
        body, star, cs = line[1:].rpartition("*")
        if not star:
            body = line[1:]
        elif len(cs) != 2 or checksum(body) != cs.upper():
            self._refuse("bad checksum")
            return
        self.sentence(body.split(","), t)
