"""The GPS receiver at the wire: NMEA 0183 RMC, VTG, GGA, GSA and ZDA for each fix.

One epoch of sentences per gps_fix_t the GPS model (sim.sensors.instruments.Gps)
makes, at its rate, only while the antenna is out of the water (the model makes
no fix below: the receiver then says nothing). Position, HDOP and satellites
are the fix's; the time is the fix's stamp on the UTC calendar that starts at
`start_utc` (sim time 0). Speed and course over ground are the vehicle's true
velocity plus white noise (`speed_noise_mps` per axis, the emulator's own
stream: the GPS message on LCM is the same with or without the wire).
GSA lists `satellites` PRNs (1, 2, ...; at most 12) with VDOP = 1.5 HDOP and
PDOP = sqrt(HDOP^2 + VDOP^2); GGA's altitude is the antenna's (minus the
vehicle's depth).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from confcheck import setting
from sim.devices import nmea
from sim.devices.emulator import Emulator
from sim.model import Truth

SENTENCES = ("RMC", "VTG", "GGA", "GSA", "ZDA")
KNOTS_PER_MPS = 3600.0 / 1852.0
VDOP_PER_HDOP = 1.5


@dataclass
class NmeaGpsOptions:
    talker: str = setting("GP", one_of=("GP", "GN"))  # GP: GPS only; GN: several constellations
    sentences: list = setting(factory=lambda: list(SENTENCES), one_of=SENTENCES)  # in this order each fix
    start_utc: str = setting(
        "2025-06-01T00:00:00Z",
        pattern=r"\d{4}-\d{2}-\d{2}T\d{2}:\d{2}:\d{2}Z",
        pattern_hint="a UTC time YYYY-MM-DDTHH:MM:SSZ",
    )  # the UTC time of sim time 0
    speed_noise_mps: float = setting(0.05, ge=0.0)  # 1-sigma per axis of the velocity over ground


class NmeaGps(Emulator):
    sensor = "gps"
    protocol = "nmea"
    Options = NmeaGpsOptions
    options: NmeaGpsOptions

    @classmethod
    def problems(cls, options: NmeaGpsOptions) -> dict[str, str]:
        out = {}
        try:
            start = nmea.parse_utc(options.start_utc)
        except ValueError:
            out["start_utc"] = f"not a calendar date and time: {options.start_utc!r}"
        else:
            if not 1980 <= start.year <= 2079:  # ddmmyy: 80..99 are 19xx, 00..79 20xx
                out["start_utc"] = "the year must be in 1980..2079 (two-digit years in RMC)"
        if not options.sentences:
            out["sentences"] = "name at least one sentence"
        elif len(set(options.sentences)) != len(options.sentences):
            out["sentences"] = "a sentence is named twice"
        return out

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.start = nmea.parse_utc(self.options.start_utc)
        self._build = {
            "RMC": self._rmc,
            "VTG": self._vtg,
            "GGA": self._gga,
            "GSA": self._gsa,
            "ZDA": self._zda,
        }

    def encode(self, msg, truth: Truth) -> list[bytes]:
        """The sentences of one fix (msg: a gps_fix_t)."""
        sigma = self.options.speed_noise_mps
        vn, ve, _ = truth.velocity_ned()
        vn, ve = vn + self.rng.gauss(sigma), ve + self.rng.gauss(sigma)
        fix = _Fix(
            utc=nmea.utc_at(self.start, msg.utime),
            lat=nmea.latitude(msg.latitude_deg),
            lon=nmea.longitude(msg.longitude_deg),
            knots=math.hypot(vn, ve) * KNOTS_PER_MPS,
            course=math.degrees(math.atan2(ve, vn)) % 360.0,
            msg=msg,
            altitude=0.0 - truth.depth,  # never "-0.0"
        )
        talker = self.options.talker
        return [nmea.sentence(talker + name, self._build[name](fix)) for name in self.options.sentences]

    # each sentence's fields, after its address
    @staticmethod
    def _rmc(f: "_Fix") -> list[str]:
        return [
            nmea.hhmmss(f.utc),
            "A",
            *f.lat,
            *f.lon,
            f"{f.knots:.2f}",
            f"{f.course:.1f}",
            nmea.ddmmyy(f.utc),
            "",
            "",
            "A",
        ]

    @staticmethod
    def _vtg(f: "_Fix") -> list[str]:
        kmh = f.knots * 1.852
        return [f"{f.course:.1f}", "T", "", "M", f"{f.knots:.2f}", "N", f"{kmh:.2f}", "K", "A"]

    @staticmethod
    def _gga(f: "_Fix") -> list[str]:
        m = f.msg
        return [
            nmea.hhmmss(f.utc),
            *f.lat,
            *f.lon,
            "1",
            f"{max(min(m.satellites, 99), 0):02d}",
            f"{m.hdop:.1f}",
            f"{f.altitude:.1f}",
            "M",
            "0.0",
            "M",
            "",
            "",
        ]

    @staticmethod
    def _gsa(f: "_Fix") -> list[str]:
        m = f.msg
        n = max(min(m.satellites, 12), 0)
        prns = [f"{i:02d}" for i in range(1, n + 1)] + [""] * (12 - n)
        vdop = VDOP_PER_HDOP * m.hdop
        mode = "3" if m.fix_type == 3 else "2"
        return ["A", mode, *prns, f"{math.hypot(m.hdop, vdop):.1f}", f"{m.hdop:.1f}", f"{vdop:.1f}"]

    @staticmethod
    def _zda(f: "_Fix") -> list[str]:
        u = f.utc
        return [nmea.hhmmss(u), f"{u.day:02d}", f"{u.month:02d}", f"{u.year:04d}", "00", "00"]


@dataclass
class _Fix:
    utc: object
    lat: tuple[str, str]
    lon: tuple[str, str]
    knots: float
    course: float
    msg: object
    altitude: float
