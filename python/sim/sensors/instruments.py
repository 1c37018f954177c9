"""Compass/AHRS, depth, DVL, altimeter and GPS models."""

from __future__ import annotations

import math
from dataclasses import dataclass

from auv import ahrs_t, altimeter_t, depth_t, dvl_t, gps_fix_t
from confcheck import setting
from sim.model import Truth
from sim.sensors.base import Sensor, SensorConfig, utime, wrap_2pi, wrap_pi
from sim.wire import Encoder

RHO_SEAWATER = 1025.0
P_ATM = 101325.0
G = 9.81
# Below this a configured compass bias is "none"; the filter still gets a small prior.
MIN_BIAS_SIGMA_RAD = math.radians(0.1)


@dataclass
class AhrsConfig(SensorConfig):
    rate_hz: float = setting(20.0, gt=0.0, unit="Hz")
    noise: float = setting(math.radians(0.5), ge=0.0)  # heading noise [rad]
    bias: float = math.radians(1.0)  # heading bias [rad]
    attitude_noise: float = setting(math.radians(0.1), ge=0.0)  # roll / pitch noise [rad]
    rate_noise: float = setting(math.radians(0.05), ge=0.0)  # gyro noise [rad/s]


class Ahrs(Sensor):
    name = "ahrs"
    topic = "AHRS"
    config_class = AhrsConfig
    cfg: AhrsConfig

    @classmethod
    def nav_config(cls, cfg: AhrsConfig, env) -> list[str]:
        # a constant compass bias becomes the 1-sigma prior of the filter's bias state, never its value
        return [
            f"compass_noise_rad {max(cfg.noise, 1e-6):.6g}",
            f"compass_bias_sigma_rad {max(abs(cfg.bias), MIN_BIAS_SIGMA_RAD):.6g}",
            f"gyro_noise_radps {cfg.rate_noise:.6g}",
            f"attitude_noise_rad {cfg.attitude_noise:.6g}",
        ]

    def __init__(self, cfg, seed, vehicle) -> None:
        super().__init__(cfg, seed, vehicle)
        self._pack = Encoder(ahrs_t, vehicle=vehicle).pack

    def measure(self, tr: Truth):
        return ahrs_t.decode(self.measure_encoded(tr))

    def measure_encoded(self, tr: Truth) -> bytes:
        """The ahrs_t as bytes, packed from the values (20 Hz: no object)."""
        c = self.cfg
        gauss = self.gauss
        eta, nu = tr.eta, tr.nu
        att, rate = c.attitude_noise, c.rate_noise
        roll = wrap_pi(eta[3] + gauss(att))
        pitch = eta[4] + gauss(att)
        heading = wrap_2pi(eta[5] + c.bias + gauss(c.noise))
        p = nu[3] + gauss(rate)
        q = nu[4] + gauss(rate)
        r = nu[5] + gauss(rate)
        return self._pack(utime(tr.t), roll, pitch, heading, p, q, r, True)

    def dropout_message(self, tr: Truth):
        m = ahrs_t()
        m.utime, m.vehicle, m.valid = utime(tr.t), self.vehicle, False
        return m


@dataclass
class DepthConfig(SensorConfig):
    rate_hz: float = setting(10.0, gt=0.0, unit="Hz")
    noise: float = setting(0.02, ge=0.0)  # [m]
    bias: float = 0.0  # [m]
    water_temperature_c: float = 12.0


class DepthSensor(Sensor):
    name = "depth"
    topic = "DEPTH"
    config_class = DepthConfig
    env_needs = ("waves",)  # a pressure gauge reads the swell's dynamic pressure
    cfg: DepthConfig

    @classmethod
    def nav_config(cls, cfg: DepthConfig, env) -> list[str]:
        # The gauge also reads the swell's dynamic pressure head (docs/simulator.md,
        # "Waves"): its standard deviation is Hs/4 at the surface, less deeper down
        # (e^-kz); the surface figure is the conservative choice for a filter that
        # does not know the vehicle's depth in advance.
        swell = env.wave_height_m / 4.0 if env.wave_period_s > 0.0 else 0.0
        return [f"depth_noise_m {max(math.hypot(cfg.noise, cfg.bias, swell), 1e-4):.6g}"]

    def measure(self, tr: Truth):
        c = self.cfg
        m = depth_t()
        m.utime, m.vehicle, m.valid = utime(tr.t), self.vehicle, True
        # a pressure gauge: the hydrostatic head plus the waves' dynamic pressure
        m.depth_m = tr.pressure_depth + c.bias + self.gauss(c.noise)
        m.pressure_pa = P_ATM + RHO_SEAWATER * G * max(m.depth_m, 0.0)
        m.temperature_c = c.water_temperature_c
        return m

    def dropout_message(self, tr: Truth):
        m = depth_t()
        m.utime, m.vehicle, m.valid = utime(tr.t), self.vehicle, False
        return m


@dataclass
class DvlConfig(SensorConfig):
    rate_hz: float = setting(5.0, gt=0.0, unit="Hz")
    noise: float = setting(0.01, ge=0.0)  # per-axis velocity noise [m/s]
    bias: float = 0.0  # per-axis velocity offset [m/s]
    scale_error: float = 0.0  # fractional scale factor error [-]
    max_altitude_m: float = setting(30.0, ge=0.0)  # bottom lock only below this altitude
    min_altitude_m: float = 0.5  # too close to the bottom: no lock either
    water_track: bool = True  # above the limit: water track, else nothing
    beam_angle_rad: float = math.radians(30.0)
    range_noise: float = setting(0.05, ge=0.0)  # per-beam range noise [m]


class Dvl(Sensor):
    name = "dvl"
    topic = "DVL"
    config_class = DvlConfig
    env_needs = ("bathymetry", "current")  # bottom lock; water track
    cfg: DvlConfig

    @classmethod
    def nav_config(cls, cfg: DvlConfig, env) -> list[str]:
        return [f"dvl_noise_mps {max(math.hypot(cfg.noise, cfg.bias), 1e-4):.6g}"]

    def measure(self, tr: Truth):
        c = self.cfg
        m = dvl_t()
        m.utime, m.vehicle = utime(tr.t), self.vehicle
        alt = tr.altitude_m
        phi, th = tr.eta[3], tr.eta[4]
        # Janus beams: forward, aft, starboard, port, each tilted beam_angle
        # off the body z axis; the slant range follows the beam's vertical
        # component in the world frame (flat seabed under the vehicle).
        sb, cb = math.sin(c.beam_angle_rad), math.cos(c.beam_angle_rad)
        cphi, sphi, cth, sth = math.cos(phi), math.sin(phi), math.cos(th), math.sin(th)
        ranges = []
        for bx, by in ((sb, 0.0), (-sb, 0.0), (0.0, sb), (0.0, -sb)):
            down = -sth * bx + cth * sphi * by + cth * cphi * cb
            if down > 0.05 and 0.0 < alt / down <= c.max_altitude_m / cb:
                ranges.append(alt / down + self.gauss(c.range_noise))
            else:
                ranges.append(-1.0)
        m.beam_range_m = [float(r) for r in ranges]
        if c.min_altitude_m <= alt <= c.max_altitude_m and all(r > 0 for r in ranges):
            m.mode = dvl_t.MODE_BOTTOM_LOCK
            vel = tr.nu[0:3]
            m.altitude_m = alt + self.gauss(c.range_noise)
        elif c.water_track:
            m.mode = dvl_t.MODE_WATER_TRACK
            vel = self._water_relative(tr)
            m.altitude_m = -1.0
        else:
            return self.dropout_message(tr)
        k = 1.0 + c.scale_error
        m.velocity_mps = [k * v + c.bias + self.gauss(c.noise) for v in vel]
        m.velocity_sigma_mps = c.noise
        return m

    @staticmethod
    def _water_relative(tr: Truth) -> tuple[float, float, float]:
        """Body velocity through the water: nu minus the current in body axes."""
        _, _, _, phi, th, psi = tr.eta
        cn, ce, cd = tr.current_ned
        cphi, sphi, cth, sth = math.cos(phi), math.sin(phi), math.cos(th), math.sin(th)
        cpsi, spsi = math.cos(psi), math.sin(psi)
        uc = cpsi * cth * cn + spsi * cth * ce - sth * cd
        vc = (cpsi * sth * sphi - spsi * cphi) * cn + (cpsi * cphi + sphi * sth * spsi) * ce + cth * sphi * cd
        wc = (spsi * sphi + cpsi * cphi * sth) * cn + (sth * spsi * cphi - cpsi * sphi) * ce + cth * cphi * cd
        return tr.nu[0] - uc, tr.nu[1] - vc, tr.nu[2] - wc

    def dropout_message(self, tr: Truth):
        m = dvl_t()
        m.utime, m.vehicle, m.mode = utime(tr.t), self.vehicle, dvl_t.MODE_NONE
        m.velocity_mps = [0.0, 0.0, 0.0]
        m.velocity_sigma_mps = -1.0
        m.altitude_m = -1.0
        m.beam_range_m = [-1.0] * 4
        return m


@dataclass
class AltimeterConfig(SensorConfig):
    rate_hz: float = setting(5.0, gt=0.0, unit="Hz")
    noise: float = setting(0.05, ge=0.0)  # [m]
    bias: float = 0.0  # [m]
    max_range_m: float = setting(50.0, ge=0.0)


class Altimeter(Sensor):
    name = "altimeter"
    topic = "ALTIMETER"
    config_class = AltimeterConfig
    env_needs = ("bathymetry",)
    cfg: AltimeterConfig

    def measure(self, tr: Truth):
        c = self.cfg
        m = altimeter_t()
        m.utime, m.vehicle, m.max_range_m = utime(tr.t), self.vehicle, c.max_range_m
        tilt = math.cos(tr.eta[3]) * math.cos(tr.eta[4])  # body z axis, vertical part
        alt = tr.altitude_m
        slant = alt / tilt if tilt > 0.05 else float("inf")
        if alt <= 0.0 or slant > c.max_range_m:
            return self.dropout_message(tr)
        m.range_m = slant + c.bias + self.gauss(c.noise)
        m.altitude_m = m.range_m * tilt
        m.valid = True
        return m

    def dropout_message(self, tr: Truth):
        m = altimeter_t()
        m.utime, m.vehicle, m.max_range_m = utime(tr.t), self.vehicle, self.cfg.max_range_m
        m.valid, m.range_m, m.altitude_m = False, -1.0, -1.0
        return m


@dataclass
class GpsConfig(SensorConfig):
    rate_hz: float = setting(1.0, gt=0.0, unit="Hz")
    noise: float = setting(2.0, ge=0.0)  # horizontal 1-sigma per axis [m]
    bias: float = 0.0  # [m], added to north and east
    max_depth_m: float = setting(0.2, ge=0.0)  # antenna out of the water above this depth
    hdop: float = 1.0
    satellites: int = 9


class Gps(Sensor):
    name = "gps"
    topic = "GPS"
    config_class = GpsConfig
    uses = ("frame",)
    cfg: GpsConfig

    @classmethod
    def nav_config(cls, cfg: GpsConfig, env) -> list[str]:
        return [f"gps_noise_m {max(math.hypot(cfg.noise, cfg.bias), 0.01):.6g}"]

    def __init__(self, cfg, seed, vehicle, frame) -> None:
        super().__init__(cfg, seed, vehicle)
        self.frame = frame

    def measure(self, tr: Truth):
        c = self.cfg
        if tr.depth > c.max_depth_m:
            return None  # antenna under water: a GPS says nothing at all
        m = gps_fix_t()
        m.utime, m.vehicle, m.fix_type = utime(tr.t), self.vehicle, gps_fix_t.FIX_3D
        m.north_m = tr.eta[0] + c.bias + self.gauss(c.noise)
        m.east_m = tr.eta[1] + c.bias + self.gauss(c.noise)
        m.latitude_deg, m.longitude_deg = self.frame.to_latlon(m.north_m, m.east_m)
        m.hdop, m.horizontal_sigma_m, m.satellites = c.hdop, c.noise, c.satellites
        # what a receiver tells besides: the model has a plain GPS fix and
        # nothing else (simulated time is not UTC: no utc_utime)
        m.quality, m.utc_utime = gps_fix_t.QUALITY_GPS, -1
        m.altitude_m = m.speed_mps = m.course_deg = m.pdop = m.vdop = math.nan
        return m
