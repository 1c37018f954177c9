"""The pressure depth sensor at the wire: a Digiquartz-style ASCII query and answer.

A commanded device: it says nothing unless asked (c/drivers/pressure/digiquartz.h
is the protocol, auv-depth its driver). The host writes `*ddssCC` CR LF, dd this
sensor's `address`, ss the host's; the sensor answers `*ssddVALUE` CR LF:

  P3     the pressure of the newest depth_t the depth model made, in the current
         unit (absolute: the model's pressure_pa, which is the atmosphere plus
         rho g depth), 10 significant digits
  Q3     the model's water temperature [C], 3 decimals
  EW     enables the next write command (no answer)
  UN=n   after EW: sets the unit (1 psi, 2 hPa, 3 bar, 4 kPa, 5 MPa, 6 inHg,
         7 mmHg, 8 mH2O) and echoes `*ssddUN=n`; without EW, or an unknown n, it
         is ignored, as the sensor ignores it

The answer goes out at the step the query arrived (the line's timing is the
framework's; the sensor's integration time is not modelled). A dropout of the
depth model (valid false) leaves the sensor mute until its next sample: the
driver sees "no answer". Commands for another address, and anything that is not
a command line, are ignored (and counted in `ignored`).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from confcheck import setting
from sim.devices.emulator import Emulator
from sim.model import Truth

# pascals per unit, as c/drivers/pressure/digiquartz.c
PASCALS_PER_UNIT = {
    1: 6894.757293168,
    2: 100.0,
    3: 1e5,
    4: 1e3,
    5: 1e6,
    6: 3386.389,
    7: 133.322387415,
    8: 9806.65,
}
MAX_LINE = 64
COMMAND = re.compile(rb"\*(\d\d)(\d\d)([A-Z0-9=]+)")


@dataclass
class DigiquartzOptions:
    address: int = setting(1, ge=1, le=99)  # the sensor's
    unit: int = setting(1, ge=1, le=8)  # the unit at power-on (factory: psi) until a UN


class Digiquartz(Emulator):
    sensor = "depth"
    protocol = "digiquartz"
    Options = DigiquartzOptions
    options: DigiquartzOptions

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.unit = self.options.unit
        self.write_enabled = False
        self.latest = None  # the newest valid depth_t
        self._line = bytearray()

    def encode(self, msg, truth: Truth) -> list[bytes]:
        """A sample of the depth model: kept for the next query, nothing sent."""
        self.latest = msg if msg.valid else None
        return []

    def receive(self, data: bytes, t: float) -> None:
        for b in data:
            if b in b"\r\n":
                line, self._line = bytes(self._line), bytearray()
                if line:
                    self._command(line, t)
            elif len(self._line) < MAX_LINE:
                self._line.append(b)
            else:
                self.ignored += 1

    def _command(self, line: bytes, t: float) -> None:
        m = COMMAND.fullmatch(line)
        if not m or int(m.group(1)) != self.options.address:
            self.ignored += len(line)
            return
        host, cmd = int(m.group(2)), m.group(3).decode("ascii")
        enabled, self.write_enabled = self.write_enabled, False  # EW holds for the next command only
        if cmd == "P3" and self.latest is not None:
            value = f"{self.latest.pressure_pa / PASCALS_PER_UNIT[self.unit]:.10g}"
        elif cmd == "Q3" and self.latest is not None:
            value = f"{self.latest.temperature_c:.3f}"
        elif cmd == "EW":
            self.write_enabled = True
            return
        elif cmd.startswith("UN=") and enabled and cmd[3:].isdigit() and int(cmd[3:]) in PASCALS_PER_UNIT:
            self.unit = int(cmd[3:])
            value = f"UN={self.unit}"
        else:
            self.ignored += len(line)
            return
        self.send(f"*{host:02d}{self.options.address:02d}{value}\r\n".encode("ascii"), t)
