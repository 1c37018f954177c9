"""The compass/AHRS at the wire: NMEA 0183 $PASHR and $--HDT for each ahrs_t.

One burst per ahrs_t the AHRS model (sim.sensors.instruments.Ahrs) makes, at its
rate: the sentences in `sentences`, in that order. PASHR carries the time (the
message's stamp on the UTC calendar starting at `start_utc`, sim time 0), the
true heading, roll and pitch in the project's convention (roll positive
starboard down, pitch positive bow up: the published PASHR one), no heave (the
model has none: an empty field, as receivers that call it reserved), the roll,
pitch and heading accuracies (`attitude_sigma_deg`, `heading_sigma_deg`: the
device's claim, not computed from the model), GNSS quality 0 (under water) and
IMU status `imu_status`. HDT carries the same heading from the `talker`.
Neither sentence carries body rates: the message's p, q and r go nowhere.
A dropout (valid false) sends nothing, as a device that stopped talking.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from confcheck import setting
from sim.devices import nmea
from sim.devices.emulator import Emulator
from sim.model import Truth

SENTENCES = ("PASHR", "HDT")


@dataclass
class AhrsNmeaOptions:
    talker: str = setting("HE", one_of=("HE", "HC", "GP", "IN"))  # of HDT: HE gyro, HC compass, IN integrated
    sentences: list = setting(factory=lambda: list(SENTENCES), one_of=SENTENCES)  # in this order each sample
    start_utc: str = setting(
        "2025-06-01T00:00:00Z",
        pattern=r"\d{4}-\d{2}-\d{2}T\d{2}:\d{2}:\d{2}Z",
        pattern_hint="a UTC time YYYY-MM-DDTHH:MM:SSZ",
    )  # the UTC time of sim time 0
    attitude_sigma_deg: float = setting(0.1, ge=0.0, le=180.0)  # PASHR's roll and pitch accuracy
    heading_sigma_deg: float = setting(0.5, ge=0.0, le=180.0)  # PASHR's heading accuracy
    imu_status: int = setting(1, ge=0, le=4)  # PASHR's last field


def heading_deg(rad: float) -> str:
    """hhh.hh in [0, 360): a heading that rounds up to 360.00 is 000.00."""
    d = round(math.degrees(rad) % 360.0, 2)
    return f"{0.0 if d >= 360.0 else d:06.2f}"


class AhrsNmea(Emulator):
    sensor = "ahrs"
    protocol = "nmea"
    Options = AhrsNmeaOptions
    options: AhrsNmeaOptions

    @classmethod
    def problems(cls, options: AhrsNmeaOptions) -> dict[str, str]:
        out = {}
        try:
            nmea.parse_utc(options.start_utc)
        except ValueError:
            out["start_utc"] = f"not a calendar date and time: {options.start_utc!r}"
        if not options.sentences:
            out["sentences"] = "name at least one sentence"
        elif len(set(options.sentences)) != len(options.sentences):
            out["sentences"] = "a sentence is named twice"
        return out

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.start = nmea.parse_utc(self.options.start_utc)

    def encode(self, msg, truth: Truth) -> list[bytes]:
        """The sentences of one sample (msg: an ahrs_t)."""
        if not msg.valid:
            return []
        out = []
        for name in self.options.sentences:
            if name == "PASHR":
                out.append(nmea.sentence("PASHR", self._pashr(msg)))
            else:
                out.append(nmea.sentence(self.options.talker + "HDT", [heading_deg(msg.heading_rad), "T"]))
        return out

    def _pashr(self, msg) -> list[str]:
        utc = nmea.utc_at(self.start, msg.utime)
        o = self.options
        return [
            nmea.hhmmss(utc),
            heading_deg(msg.heading_rad),
            "T",
            f"{math.degrees(msg.roll_rad):.2f}",
            f"{math.degrees(msg.pitch_rad):.2f}",
            "",
            f"{o.attitude_sigma_deg:.3f}",
            f"{o.attitude_sigma_deg:.3f}",
            f"{o.heading_sigma_deg:.3f}",
            "0",
            str(o.imu_status),
        ]
