"""The one list of device emulators: a new device is its module and one line here.

Each class names the sensor it speaks for and its protocol
(sim.devices.emulator.Emulator); a sensor's `wire.protocol` may be any of the
protocols registered for it, and docs/simulator.md ("Devices at the wire")
lists them. A device no sensor polls names the part of the simulator that
drives it instead (`modem`, `actuators`: those sections' `wire:`).
"""

from __future__ import annotations

from sim.devices.ahrs_nmea import AhrsNmea
from sim.devices.bluefin_frontseat import BluefinFrontseat
from sim.devices.digiquartz import Digiquartz
from sim.devices.dvl_pd0 import DvlPd0
from sim.devices.emulator import Emulator
from sim.devices.iver3_frontseat import Iver3Frontseat
from sim.devices.lcmframe import IdentifyFrame, SonarFrame
from sim.devices.maestro_wire import MaestroWire
from sim.devices.micromodem import MicroModemWire
from sim.devices.nmea_gps import NmeaGps
from sim.devices.sbe49 import Sbe49
from sim.devices.time_link import TimeLink

# (the modem, the fins, the sonar, the identify sensor, the time link and the frontseat are no `sensors:`
# entries: their `sensor` is their section's name)
EMULATORS: tuple[type[Emulator], ...] = (
    NmeaGps,
    AhrsNmea,
    Digiquartz,
    DvlPd0,
    Sbe49,
    MicroModemWire,
    MaestroWire,
    SonarFrame,
    IdentifyFrame,
    TimeLink,
    Iver3Frontseat,
    BluefinFrontseat,
)


def protocols_of(sensor: str) -> dict[str, type[Emulator]]:
    """The protocols a sensor can speak at the wire, by name."""
    return {e.protocol: e for e in EMULATORS if e.sensor == sensor}
