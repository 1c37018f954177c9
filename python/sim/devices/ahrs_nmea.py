"""The compass/AHRS at the wire: NMEA 0183 $PASHR, $--HDT, RDI's $PRDID and VectorNav's $VNYMR for each ahrs_t.

One burst per ahrs_t the AHRS model (sim.sensors.instruments.Ahrs) makes, at its
rate: the sentences in `sentences`, in that order. PASHR carries the time (the
message's stamp on the UTC calendar starting at `start_utc`, sim time 0), the
true heading, roll and pitch in the project's convention (roll positive
starboard down, pitch positive bow up: the published PASHR one), no heave (the
model has none: an empty field, as receivers that call it reserved), the roll,
pitch and heading accuracies (`attitude_sigma_deg`, `heading_sigma_deg`: the
device's claim, not computed from the model), GNSS quality 0 (under water) and
IMU status `imu_status`. HDT carries the same heading from the `talker`.
$PRDID (Teledyne RDI's attitude sentence) carries pitch, roll and heading, in
that order, to 0.01 degree, in the same signs. None of those carries body rates. $VNYMR does: VectorNav's ASCII "Yaw, Pitch,
Roll, Magnetic, Acceleration and Angular Rates" output (register 27, async header
YMR; the VN-100 User Manual, UM001, section 7.2.3): yaw, pitch, roll [deg] (a 3-2-1
Euler sequence from NED: the project's heading, pitch and roll; yaw in -180..180),
the magnetic field x, y, z [Gauss], the acceleration x, y, z [m/s^2] and the angular
rates x, y, z [rad/s], all in the body frame (x forward, y starboard, z down: the
rates are p, q, r), in its fixed-width fields. The model's sample gives attitude,
heading and rates; the rest is derived and documented: the acceleration is the
specific force an accelerometer at the body origin measures (the truth's body
acceleration, the transport term w x v, minus gravity, through the sample's roll and
pitch: level and still it reads z = -9.81), the magnetic field a constant Earth
field (MAG_NED_GAUSS) seen through the sample's attitude and heading, both without
noise of their own.
A dropout (valid false) sends nothing, as a device that stopped talking.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from confcheck import setting
from sim.devices import nmea
from sim.devices.emulator import Emulator
from sim.model import Truth

SENTENCES = ("PASHR", "HDT", "PRDID", "VNYMR")
DEFAULT_SENTENCES = ("PASHR", "HDT")
G = 9.80665  # m/s^2, what a still accelerometer reads (VectorNav's own figure of g)
# a mid-latitude Earth field, north and down [Gauss] (Massachusetts, roughly: 0.2 G
# horizontal, 0.47 G vertical); east 0: the heading is its own declination-free truth
MAG_NED_GAUSS = (0.20, 0.0, 0.47)


@dataclass
class AhrsNmeaOptions:
    talker: str = setting("HE", one_of=("HE", "HC", "GP", "IN"))  # of HDT: HE gyro, HC compass, IN integrated
    sentences: list = setting(factory=lambda: list(DEFAULT_SENTENCES), one_of=SENTENCES)  # in this order each sample
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
            elif name == "VNYMR":
                out.append(nmea.sentence("VNYMR", vnymr_fields(msg, truth)))
            elif name == "PRDID":
                pitch, roll = math.degrees(msg.pitch_rad), math.degrees(msg.roll_rad)
                out.append(nmea.sentence("PRDID", [f"{pitch:.2f}", f"{roll:.2f}", heading_deg(msg.heading_rad)]))
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


def _to_body(v: tuple[float, float, float], roll: float, pitch: float, yaw: float) -> tuple[float, float, float]:
    """A NED vector in the body frame (the transpose of the ZYX rotation body -> NED)."""
    cr, sr, cp, sp, cy, sy = (
        math.cos(roll),
        math.sin(roll),
        math.cos(pitch),
        math.sin(pitch),
        math.cos(yaw),
        math.sin(yaw),
    )
    n, e, d = v
    x = cp * cy * n + cp * sy * e - sp * d
    y = (sr * sp * cy - cr * sy) * n + (sr * sp * sy + cr * cy) * e + sr * cp * d
    z = (cr * sp * cy + sr * sy) * n + (cr * sp * sy - sr * cy) * e + cr * cp * d
    return x, y, z


def specific_force(roll: float, pitch: float, truth: Truth | None) -> tuple[float, float, float]:
    """What a body-fixed accelerometer at the origin reads [m/s^2]: the acceleration
    (d nu/dt + w x v, from the truth; none without one) minus gravity, in body axes."""
    gx, gy, gz = _to_body((0.0, 0.0, G), roll, pitch, 0.0)  # gravity has no heading
    ax = ay = az = 0.0
    if truth is not None:
        u, v, w, p, q, r = truth.nu
        du, dv, dw = truth.nu_dot[0:3]
        ax, ay, az = du + q * w - r * v, dv + r * u - p * w, dw + p * v - q * u
    return ax - gx, ay - gy, az - gz


def vnymr_fields(msg, truth: Truth | None) -> list[str]:
    """$VNYMR's 12 fields for an ahrs_t, in VectorNav's widths: +ddd.ddd degrees,
    +d.dddd Gauss, +dd.ddd m/s^2, +d.dddddd rad/s."""
    yaw = (math.degrees(msg.heading_rad) + 180.0) % 360.0 - 180.0
    mag = _to_body(MAG_NED_GAUSS, msg.roll_rad, msg.pitch_rad, msg.heading_rad)
    acc = specific_force(msg.roll_rad, msg.pitch_rad, truth)
    return [
        f"{yaw:+08.3f}",
        f"{math.degrees(msg.pitch_rad):+08.3f}",
        f"{math.degrees(msg.roll_rad):+08.3f}",
        *(f"{m:+07.4f}" for m in mag),
        *(f"{a:+07.3f}" for a in acc),
        *(f"{w:+09.6f}" for w in (msg.p_radps, msg.q_radps, msg.r_radps)),
    ]
