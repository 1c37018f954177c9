"""The CTD at the wire: a Sea-Bird SBE 49 FastCAT's scans (its user's manual, "Data
Output Formats"; c/drivers/ctd/sbe49.h is the driver's side, auv-ctd the driver).

Sampling (from power-on with `autorun`, the instrument's AutoRun=Y, or after `Start`),
each sample of the CTD model is one scan line ended by CR LF:

  output_format 3 (engineering units, decimal): "ttt.tttt, cc.ccccc, pppp.ppp" then
      ", sss.ssss" (salinity) if output_sal and ", vvvv.vvv" (sound velocity) if
      output_sv, leading zeros suppressed but one;
  output_format 1 (engineering units, hex): ttttttccccccpppppp with t = (T + 10) 1e5,
      c = (C + 1) 1e6, p = (P + 100) 1e3 as 6 hex digits each (no salinity, no sound
      velocity: the driver computes salinity by PSS-78).

A lost sample (the model's valid false) is no scan. Commands, each a line: `Start`,
`Stop`, `OutputFormat=n` (1 or 3; 0 and 2 are the raw formats the instrument has but
this emulator does not: refused as the instrument refuses a bad value), `OutputSal=Y|N`,
`OutputSV=Y|N`, `DS` (a status line); each answered with the `S>` prompt on its own line.
Anything else is ignored and counted.
"""

from __future__ import annotations

from dataclasses import dataclass

from confcheck import setting
from sim.devices.emulator import Emulator
from sim.model import Truth

MAX_LINE = 64


@dataclass
class Sbe49Options:
    output_format: int = setting(3, one_of=(1, 3))  # at power-on, until an OutputFormat=
    output_sal: bool = True  # format 3: a salinity field
    output_sv: bool = False  # format 3: a sound velocity field
    autorun: bool = True  # sampling from power-on (AutoRun=Y); else after Start


def scan_line(msg, output_format: int, sal: bool, sv: bool) -> bytes:
    """One scan of a ctd_t in the instrument's format."""
    t, c, p = msg.temperature_c, msg.conductivity_s_per_m, msg.pressure_dbar
    if output_format == 1:
        fields = (round((t + 10.0) * 1e5), round((c + 1.0) * 1e6), round((p + 100.0) * 1e3))
        return "".join(f"{max(0, min(v, 0xFFFFFF)):06X}" for v in fields).encode("ascii") + b"\r\n"
    parts = [f"{t:.4f}", f"{c:.5f}", f"{p:.3f}"]
    if sal:
        parts.append(f"{msg.salinity_psu:.4f}")
    if sv:
        parts.append(f"{msg.sound_speed_mps:.3f}")
    return ", ".join(parts).encode("ascii") + b"\r\n"


class Sbe49(Emulator):
    sensor = "ctd"
    protocol = "sbe49"
    Options = Sbe49Options
    options: Sbe49Options

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        o = self.options
        self.output_format, self.sal, self.sv = o.output_format, o.output_sal, o.output_sv
        self.sampling = o.autorun
        self._line = bytearray()

    def encode(self, msg, truth: Truth) -> list[bytes]:
        if not self.sampling or not msg.valid:
            return []
        return [scan_line(msg, self.output_format, self.sal, self.sv)]

    def receive(self, data: bytes, t: float) -> None:
        for b in data:
            if b in b"\r\n":
                line, self._line = bytes(self._line).strip(), bytearray()
                if line or b == 13:
                    self._command(line.decode("ascii", "replace"), t)
            elif len(self._line) < MAX_LINE:
                self._line.append(b)
            else:
                self.ignored += 1

    def _command(self, line: str, t: float) -> None:
        key, _, value = line.partition("=")
        key = key.strip().lower()
        value = value.strip().upper()
        if key == "":
            pass  # a bare return: the prompt
        elif key == "start":
            self.sampling = True
        elif key == "stop":
            self.sampling = False
        elif key == "outputformat" and value in ("1", "3"):
            self.output_format = int(value)
        elif key == "outputsal" and value in ("Y", "N"):
            self.sal = value == "Y"
        elif key == "outputsv" and value in ("Y", "N"):
            self.sv = value == "Y"
        elif key == "ds":
            self.send(
                f"SBE 49 FastCAT (simulated)  OutputFormat={self.output_format}  OutputSal={'YN'[not self.sal]}"
                f"  OutputSV={'YN'[not self.sv]}  {'sampling' if self.sampling else 'stopped'}\r\n".encode(),
                t,
            )
        else:
            self.ignored += len(line) + 1
            self.send(b"?CMD\r\n", t)
        self.send(b"S>\r\n", t)
