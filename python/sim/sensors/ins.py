"""A black-box INS: ground truth plus the errors a real aided INS makes.

For vehicles whose navigation is a sealed unit, the simulator publishes its
output on <VEHICLE>.NAV (nav_solution_t, SOURCE_SIM_INS), or on the channel
`sensors.ins.channel` names (e.g. NAV_INS beside an onboard filter on NAV). The position error
grows like dead reckoning does: a heading error (constant bias plus a random
walk) turns along-track speed into cross-track drift, a velocity scale error
stretches along-track distance, and a position random walk covers the rest.
A GPS fix at the surface pulls the error back to the GPS's level.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from auv import nav_solution_t
from confcheck import setting
from sim.model import Truth
from sim.sensors.base import CHANNEL_HINT, CHANNEL_SUFFIX, Sensor, SensorConfig, utime, wrap_2pi, wrap_pi
from sim.wire import Encoder


@dataclass
class InsConfig(SensorConfig):
    rate_hz: float = setting(20.0, gt=0.0, unit="Hz")
    noise: float = setting(0.05, ge=0.0)  # white position noise [m]
    bias: float = math.radians(0.05)  # heading bias [rad]
    heading_noise: float = setting(math.radians(0.02), ge=0.0)  # [rad]
    heading_random_walk: float = setting(math.radians(0.002), ge=0.0)  # [rad/sqrt(s)]
    velocity_noise: float = setting(0.005, ge=0.0)  # [m/s]
    velocity_scale_error: float = 0.001  # [-], along-track
    position_random_walk: float = setting(0.005, ge=0.0)  # [m/sqrt(s)]
    attitude_noise: float = setting(math.radians(0.02), ge=0.0)  # roll, pitch [rad]
    gps_aiding: bool = True  # reset drift at the surface
    gps_sigma_m: float = setting(2.0, ge=0.0)  # position error after a surface fix
    surface_depth_m: float = 0.2
    dvl_max_altitude_m: float = setting(30.0, ge=0.0)  # bottom-lock aiding (status bits only)
    # <VEHICLE>.<channel> it publishes on; "off" publishes nothing (the onboard
    # filter then owns <VEHICLE>.NAV: one writer per channel)
    channel: str = setting("NAV", pattern=CHANNEL_SUFFIX, one_of=("off",), pattern_hint=CHANNEL_HINT)


class Ins(Sensor):
    name = "ins"
    topic = "NAV"  # the default of `channel`, which may move it
    config_class = InsConfig
    env_needs = ("waves", "bathymetry")  # its depth is a pressure gauge's; bottom lock
    uses = ("frame",)
    cfg: InsConfig

    def __init__(self, cfg, seed, vehicle, frame) -> None:
        super().__init__(cfg, seed, vehicle)
        self.topic = cfg.channel
        self.frame = frame
        self.err_n = 0.0
        self.err_e = 0.0
        self.head_walk = 0.0
        self.last_t: float | None = None
        self.pos_var = cfg.gps_sigma_m**2
        self.dist = 0.0  # distance travelled since the last fix [m]
        self.t_since_fix = 0.0
        self._pack = Encoder(nav_solution_t, vehicle=vehicle).pack

    def measure(self, tr: Truth):
        return nav_solution_t.decode(self.measure_encoded(tr))

    def measure_encoded(self, tr: Truth) -> bytes:
        """The nav_solution_t as bytes, packed from the values (20 Hz: no object)."""
        c = self.cfg
        gauss = self.gauss
        t = tr.t
        dt = 0.0 if self.last_t is None else t - self.last_t
        self.last_t = t
        eta, nu = tr.eta, tr.nu
        surfaced = eta[2] <= c.surface_depth_m
        vn, ve, _ = tr.velocity_ned()
        bias = c.bias
        if dt > 0.0:
            self.head_walk += gauss(c.heading_random_walk * math.sqrt(dt))
            he = bias + self.head_walk
            # the INS integrates its velocity rotated by its heading error and
            # scaled by its scale error; the difference from truth is
            # (R(he)(1+k) - I) v
            k = 1.0 + c.velocity_scale_error
            ch, sh = math.cos(he), math.sin(he)
            dn = (k * (ch * vn - sh * ve) - vn) * dt
            de = (k * (sh * vn + ch * ve) - ve) * dt
            rw = c.position_random_walk * math.sqrt(dt)
            self.err_n += dn + gauss(rw)
            self.err_e += de + gauss(rw)
            self.dist += math.hypot(vn, ve) * dt
            self.t_since_fix += dt
        status = nav_solution_t.STATUS_ALIGNED
        if surfaced and c.gps_aiding:
            self.err_n = gauss(c.gps_sigma_m)
            self.err_e = gauss(c.gps_sigma_m)
            self.dist = 0.0
            self.t_since_fix = 0.0
            status |= nav_solution_t.STATUS_GPS
        # the 1-sigma a real filter would claim: the fix's error plus the
        # dead-reckoning drift since (heading and scale errors grow with
        # distance, the random walk with time)
        frac2 = bias**2 + c.velocity_scale_error**2 + c.heading_random_walk**2 * self.t_since_fix
        self.pos_var = c.gps_sigma_m**2 + frac2 * self.dist**2 + c.position_random_walk**2 * self.t_since_fix
        noise = c.noise
        alt = tr.altitude_m
        if 0.0 < alt <= c.dvl_max_altitude_m:
            status |= nav_solution_t.STATUS_DVL_BOTTOM
            altitude = alt + gauss(noise)
        else:
            status |= nav_solution_t.STATUS_DVL_WATER
            altitude = -1.0
        north = eta[0] + self.err_n + gauss(noise)
        east = eta[1] + self.err_e + gauss(noise)
        # depth comes from a pressure sensor: it sees the waves' dynamic pressure
        depth = tr.pressure_depth + gauss(noise)
        lat, lon = self.frame.to_latlon(north, east)
        att = c.attitude_noise
        roll = wrap_pi(eta[3] + gauss(att))
        pitch = eta[4] + gauss(att)
        heading = wrap_2pi(eta[5] + bias + self.head_walk + gauss(c.heading_noise))
        vnoise = c.velocity_noise
        u = nu[0] + gauss(vnoise)
        v = nu[1] + gauss(vnoise)
        w = nu[2] + gauss(vnoise)
        pv = self.pos_var + noise**2
        dv = noise**2
        vv = vnoise**2
        av = att**2
        hv = c.heading_noise**2 + bias**2 + self.head_walk**2
        return self._pack(
            utime(t),
            nav_solution_t.SOURCE_SIM_INS,
            status,
            lat,
            lon,
            north,
            east,
            depth,
            altitude,
            roll,
            pitch,
            heading,
            u,
            v,
            w,
            nu[3],
            nu[4],
            nu[5],
            math.hypot(vn, ve),
            wrap_2pi(math.atan2(ve, vn) + bias + self.head_walk),
            pv,
            0.0,
            0.0,
            0.0,
            pv,
            0.0,
            0.0,
            0.0,
            dv,
            vv,
            0.0,
            0.0,
            0.0,
            vv,
            0.0,
            0.0,
            0.0,
            vv,
            av,
            0.0,
            0.0,
            0.0,
            av,
            0.0,
            0.0,
            0.0,
            hv,
        )
