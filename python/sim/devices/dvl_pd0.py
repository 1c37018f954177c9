"""The DVL at the wire: each measurement of the DVL model as one Teledyne RDI PD0
ensemble (sim.devices.pd0 writes the bytes; c/drivers/dvl reads them, as does
dolfyn in the tests).

A DVL pings on its own: every sample of the model is an ensemble on the line,
in the frame the unit is set to. The ensemble carries the true attitude (its
internal sensors) and the pressure depth; the variable leader's clock is the
sample's sim time on the calendar of sim.devices.pd0.RTC_EPOCH.
"""

from __future__ import annotations

from dataclasses import dataclass

from confcheck import setting
from sim.devices.emulator import Emulator
from sim.devices.pd0 import FRAMES, Pd0Config, Pd0Dvl
from sim.model import Truth


@dataclass
class Pd0Options:
    frame: str = setting("earth", one_of=tuple(FRAMES))  # the coordinate frame of its velocities (EX command)
    n_cells: int = setting(8, ge=1, le=128)  # profile cells in each ensemble
    cell_size_m: float = setting(1.0, gt=0.0, le=64.0)
    serial_number: int = setting(31, ge=0, le=2**32 - 1)


class DvlPd0(Emulator):
    sensor = "dvl"
    protocol = "pd0"
    Options = Pd0Options
    options: Pd0Options

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        o = self.options
        self.unit = Pd0Dvl(
            Pd0Config(frame=o.frame, n_cells=o.n_cells, cell_size_m=o.cell_size_m, serial_number=o.serial_number)
        )

    def encode(self, msg, truth: Truth) -> list[bytes]:
        """One ensemble per sample; a dropout of the model (no lock) is an ensemble
        with the bad-velocity markers, as the unit sends."""
        return [self.unit.bytes_for(msg, truth)]
