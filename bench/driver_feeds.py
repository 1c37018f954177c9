"""The devices of bench/driver_bench.py: each driver's device, its bytes made by the
simulator's own emulators (python/sim/devices/*.py) from the simulator's sensor
models, at the device's real rate.

A Feed is one device on one driver: `burst(i)` is what the device says at its
i-th tick (ticks at `rate_hz`), `answer(data, t)` what it replies to the
driver's bytes, `idle(t)` what it says unasked between ticks, `command(i)` an
LCM input of the driver at tick i (a commanded device: the servo's actuators_t,
the modem's modem_tx_t). `fast` is how the bench measures the parse speed:
"pty" (bursts written as fast as the driver takes them), "lcm" (commands
published as fast as possible) or "replay" (a polled sensor says nothing
unasked: its answers go through auv-driver-replay from a recorded raw log).
"""

from __future__ import annotations

import math
import time
from pathlib import Path
from typing import Any

from auv import actuators_t, modem_tx_t, sidescan_contact_t
from auvlcm import programs
from sim.devices.ahrs_nmea import AhrsNmea, AhrsNmeaOptions
from sim.devices.digiquartz import Digiquartz, DigiquartzOptions
from sim.devices.dvl_pd0 import DvlPd0, Pd0Options
from sim.devices.emulator import DeviceContext
from sim.devices.lcmframe import SonarFrame
from sim.devices.maestro import Maestro
from sim.devices.micromodem import MicroModem
from sim.devices.nmea_gps import NmeaGps, NmeaGpsOptions
from sim.devices.time_link import stamped_sentence
from sim.geo import LocalFrame
from sim.model import Truth
from sim.sensors import Ahrs, AhrsConfig, DepthConfig, DepthSensor, Dvl, DvlConfig, Gps, GpsConfig

VEHICLE = "BENCH"
SEED = 11
ORIGIN = (48.1, 11.5)
# the servo's channel table (tests/drivers/test_servo_driver.py's): fins and thruster
SERVO_TABLE = """\
protocol compact
watchdog 0.5
#       ch actuator     neutral us/unit  min   max   options
channel 0  rudder       1500    500      1100  1900
channel 1  stern_plane  1500    500      1100  1900  reversed speed 100 accel 4
channel 2  prop         1490    0.25     1000  2000
"""
MODEM_TABLE = {VEHICLE: 1, "AUV2": 2, "AUV3": 3, "AUV4": 4}


def truth(t: float, depth_m: float = 5.0) -> Truth:
    """A vehicle at 1.5 m/s on a slow turn, rolling and pitching a little, 12 m above a flat seabed."""
    roll, pitch = math.radians(3.0 * math.sin(0.7 * t)), math.radians(2.0 * math.sin(0.3 * t))
    heading = (0.02 * t) % (2 * math.pi)
    eta = (1.5 * t * math.cos(heading), 1.5 * t * math.sin(heading), depth_m, roll, pitch, heading)
    nu = (1.5, 0.02, 0.01, 0.03 * math.cos(0.7 * t), 0.01 * math.cos(0.3 * t), 0.02)
    return Truth(t=t, eta=eta, nu=nu, water_depth_m=depth_m + 12.0, altitude_m=12.0, current_ned=(0.2, 0.1, 0.0))


def ctx(sensor: str, options: Any) -> DeviceContext:
    return DeviceContext(VEHICLE, sensor, SEED, options)


class Feed:
    label = ""  # the table's row
    program = ""  # auv-<program>
    device = ""  # its <V>.DRIVER.<DEVICE>
    baud = 115200
    rate_hz = 1.0  # ticks of the at-rate run
    rate_text = ""  # the device's real rate, as the table says it
    fast = "pty"
    min_seconds = 0.0  # the at-rate run lasts at least this long (a slow schedule)

    def flags(self, tmp: Path) -> list[str]:
        return []

    def burst(self, i: int) -> bytes:
        return b""

    def fast_burst(self, i: int) -> bytes:
        return self.burst(i)

    def answer(self, data: bytes, t: float) -> bytes:
        return b""

    def idle(self, t: float) -> bytes:
        return b""

    def command(self, i: int) -> tuple[str, bytes] | None:
        return None

    def recorded(self, n_bytes: int) -> tuple[bytes, int]:
        """A polled device's answers as a driver reads them (at least n_bytes), and their count."""
        raise NotImplementedError


def concat(parts: list[bytes]) -> bytes:
    return b"".join(parts)


class GpsFeed(Feed):
    label, program, device = "auv-gps", "gps", "GPS"
    rate_hz = 10.0
    rate_text = "10 Hz epochs RMC+VTG+GGA+GSA+ZDA, 115200 Bd"

    def __init__(self) -> None:
        self.model = Gps(GpsConfig(rate_hz=self.rate_hz), SEED, VEHICLE, LocalFrame(*ORIGIN))
        self.emu = NmeaGps(ctx("gps", NmeaGpsOptions(talker="GN")))

    def flags(self, tmp: Path) -> list[str]:
        return programs.gps_origin_flags(*ORIGIN)

    def burst(self, i: int) -> bytes:
        tr = truth(i / self.rate_hz, depth_m=0.0)  # at the surface: a fix
        return concat(self.emu.encode(self.model.measure(tr), tr))


class DvlFeed(Feed):
    label, program, device = "auv-dvl", "dvl", "DVL"
    rate_hz = 5.0
    rate_text = "5 Hz PD0 ensembles (8 cells, bottom track), 115200 Bd"

    def __init__(self) -> None:
        self.model = Dvl(DvlConfig(rate_hz=self.rate_hz), SEED, VEHICLE)
        self.emu = DvlPd0(ctx("dvl", Pd0Options()))

    def burst(self, i: int) -> bytes:
        tr = truth(i / self.rate_hz)
        return concat(self.emu.encode(self.model.measure(tr), tr))


class AhrsFeed(Feed):
    program, device = "ahrs", "AHRS"
    rate_hz = 50.0

    def __init__(self, sentences: tuple[str, ...]) -> None:
        self.label = f"auv-ahrs {'+'.join(sentences)}"
        self.rate_text = f"50 Hz {'+'.join(sentences)}, 115200 Bd"
        self.model = Ahrs(AhrsConfig(rate_hz=self.rate_hz), SEED, VEHICLE)
        self.emu = AhrsNmea(ctx("ahrs", AhrsNmeaOptions(sentences=list(sentences))))

    def burst(self, i: int) -> bytes:
        tr = truth(i / self.rate_hz)
        return concat(self.emu.encode(self.model.measure(tr), tr))


class DepthFeed(Feed):
    """Polled: the driver asks (P3 at --rate 4, Q3 every 10th), the emulator answers."""

    label, program, device = "auv-depth", "depth", "DEPTH"
    baud = 9600
    rate_hz = 4.0
    rate_text = "4 Hz P3 polls (+Q3 every 10th), 9600 Bd"
    fast = "replay"

    def __init__(self) -> None:
        self.model = DepthSensor(DepthConfig(rate_hz=10.0), SEED, VEHICLE)
        self.emu = Digiquartz(ctx("depth", DigiquartzOptions()))
        self._out = bytearray()
        self.emu.send = lambda data, t: self._out.extend(data)

    def flags(self, tmp: Path) -> list[str]:
        return ["--rate", f"{self.rate_hz:g}"]

    def burst(self, i: int) -> bytes:
        self.emu.encode(self.model.measure(truth(i / self.rate_hz)), None)  # the newest sample, kept
        return b""

    def answer(self, data: bytes, t: float) -> bytes:
        self.emu.receive(data, t)
        out, self._out = bytes(self._out), bytearray()
        return out

    def recorded(self, n_bytes: int) -> tuple[bytes, int]:
        """The sensor's answers to polls as auv-depth makes them (a Q3 after every 10th P3)."""
        out, i = bytearray(), 0
        while len(out) < n_bytes:
            self.burst(i)
            out += self.answer(b"*0100Q3\r\n" if i % 11 == 10 else b"*0100P3\r\n", i / self.rate_hz)
            i += 1
        return bytes(out), i


class ServoFeed(Feed):
    """actuators_t at the pilot's 20 Hz over LCM; the Maestro emulator answers Get Errors."""

    label, program, device = "auv-servo", "servo", "SERVO"
    rate_hz = 20.0
    rate_text = "20 Hz actuators_t in, Maestro out, 115200 Bd"
    fast = "lcm"

    def __init__(self) -> None:
        self.maestro = Maestro()
        for c in self.maestro.channels:
            c.min_qus, c.max_qus = 4, 16383
        self._last_utime = 0

    def flags(self, tmp: Path) -> list[str]:
        table = tmp / "fins.table"
        table.write_text(SERVO_TABLE)
        return programs.servo_table_flags(table)

    def answer(self, data: bytes, t: float) -> bytes:
        return self.maestro.feed(data)

    def command(self, i: int) -> tuple[str, bytes] | None:
        m = actuators_t()
        # strictly increasing: a command as old as the previous one is "out of order"
        self._last_utime = m.utime = max(time.time_ns() // 1000, self._last_utime + 1)
        m.vehicle, m.seq = VEHICLE, i + 1
        m.rudder_rad, m.stern_plane_rad = 0.2 * math.sin(0.1 * i), -0.1 * math.cos(0.07 * i)
        m.prop_rpm = 1200.0 + 50.0 * math.sin(0.01 * i)
        return "ACTUATORS", m.encode()


class ModemFeed(Feed):
    """A team of four in 5 s TDMA slots: three frames heard, one sent per 20 s."""

    label, program, device = "auv-modem", "modem", "MODEM"
    baud = 19200
    rate_hz = 0.2
    rate_text = "32 B frame per 5 s slot (3 heard, 1 sent), CAREV 10 s, 19200 Bd"
    min_seconds = 20.0

    def __init__(self) -> None:
        self.modem = MicroModem(address=MODEM_TABLE[VEHICLE])

    def flags(self, tmp: Path) -> list[str]:
        return programs.modem_flags(MODEM_TABLE)

    def _heard(self, i: int) -> bytes:
        frame = bytes((i + k) % 256 for k in range(32))
        return self.modem.hear(time.time(), 2 + i % 3, 0, 0, [frame], 12.5)

    def fast_burst(self, i: int) -> bytes:
        return self._heard(i)

    def burst(self, i: int) -> bytes:
        return b"" if i % 4 == 3 else self._heard(i)

    def command(self, i: int) -> tuple[str, bytes] | None:
        if i % 4 != 3:
            return None
        m = modem_tx_t()
        m.utime, m.vehicle, m.dst_vehicle, m.seq = time.time_ns() // 1000, "", "", i
        m.kind, m.n_bytes, m.payload = modem_tx_t.KIND_TEAM, 32, bytes(range(32))
        return "MODEM_TX", m.encode()

    def answer(self, data: bytes, t: float) -> bytes:
        return self.modem.feed(data, t)

    def idle(self, t: float) -> bytes:
        return self.modem.tick(t)


class TimesyncFeed(Feed):
    label, program, device = "auv-timesync", "timesync", "TIMESYNC"
    rate_hz = 50.0
    rate_text = "50 Hz $PAUVT, 115200 Bd"

    def burst(self, i: int) -> bytes:
        return stamped_sentence(1000.0 + i / self.rate_hz, 1.0, 10.0 / self.baud)


class PayloadFeed(Feed):
    label, program, device = "auv-payload", "payload", "PAYLOAD"
    rate_hz = 1.0
    rate_text = "1 Hz contacts (lcmframe), 115200 Bd"

    def __init__(self) -> None:
        self.emu = SonarFrame(ctx("sonar", None))

    def burst(self, i: int) -> bytes:
        m = sidescan_contact_t()
        m.utime, m.vehicle, m.contact_id = int(1e9) + i * 1000000, VEHICLE, i + 1
        m.side = i % 2
        m.ground_range_m, m.vehicle_altitude_m = 20.0 + i % 30, 8.0
        m.slant_range_m = math.hypot(m.ground_range_m, m.vehicle_altitude_m)
        m.north_m, m.east_m, m.position_sigma_m = 100.0 + i, -40.0 + 0.5 * i, 2.5
        m.confidence, m.classification = 0.8, "mine_like" if i % 3 else "clutter"
        return concat(self.emu.encode(m, None))


def feeds() -> list[Feed]:
    """Every driver of c/drivers/ that has a program, in the table's order."""
    return [
        GpsFeed(),
        DvlFeed(),
        AhrsFeed(("PASHR", "HDT")),
        AhrsFeed(("VNYMR",)),
        DepthFeed(),
        ServoFeed(),
        ModemFeed(),
        TimesyncFeed(),
        PayloadFeed(),
    ]
