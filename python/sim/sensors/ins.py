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

from sim.model import Truth
from sim.sensors.base import Sensor, SensorConfig, utime, wrap_2pi, wrap_pi


@dataclass
class InsConfig(SensorConfig):
    rate_hz: float = 20.0
    noise: float = 0.05                  # white position noise [m]
    bias: float = math.radians(0.05)     # heading bias [rad]
    heading_noise: float = math.radians(0.02)        # [rad]
    heading_random_walk: float = math.radians(0.002)  # [rad/sqrt(s)]
    velocity_noise: float = 0.005         # [m/s]
    velocity_scale_error: float = 0.001   # [-], along-track
    position_random_walk: float = 0.005   # [m/sqrt(s)]
    attitude_noise: float = math.radians(0.02)  # roll, pitch [rad]
    gps_aiding: bool = True               # reset drift at the surface
    gps_sigma_m: float = 2.0              # position error after a surface fix
    surface_depth_m: float = 0.2
    dvl_max_altitude_m: float = 30.0      # bottom-lock aiding (status bits only)
    # <VEHICLE>.<channel> it publishes on; "off" publishes nothing (the onboard
    # filter then owns <VEHICLE>.NAV: one writer per channel)
    channel: str = "NAV"


class Ins(Sensor):
    name = "ins"
    topic = "NAV"
    cfg: InsConfig

    def __init__(self, cfg, seed, vehicle, frame) -> None:
        super().__init__(cfg, seed, vehicle)
        self.topic = cfg.channel
        self.frame = frame
        self.err_n = 0.0
        self.err_e = 0.0
        self.head_walk = 0.0
        self.last_t: float | None = None
        self.pos_var = cfg.gps_sigma_m ** 2
        self.dist = 0.0          # distance travelled since the last fix [m]
        self.t_since_fix = 0.0

    def measure(self, tr: Truth):
        c = self.cfg
        dt = 0.0 if self.last_t is None else tr.t - self.last_t
        self.last_t = tr.t
        surfaced = tr.depth <= c.surface_depth_m
        vn, ve, _ = tr.velocity_ned()
        if dt > 0.0:
            self.head_walk += self.gauss(c.heading_random_walk * math.sqrt(dt))
            he = c.bias + self.head_walk
            # the INS integrates its velocity rotated by its heading error and
            # scaled by its scale error; the difference from truth is
            # (R(he)(1+k) - I) v
            k = 1.0 + c.velocity_scale_error
            ch, sh = math.cos(he), math.sin(he)
            dn = (k * (ch * vn - sh * ve) - vn) * dt
            de = (k * (sh * vn + ch * ve) - ve) * dt
            rw = c.position_random_walk * math.sqrt(dt)
            self.err_n += dn + self.gauss(rw)
            self.err_e += de + self.gauss(rw)
            self.dist += math.hypot(vn, ve) * dt
            self.t_since_fix += dt
        if surfaced and c.gps_aiding:
            self.err_n = self.gauss(c.gps_sigma_m)
            self.err_e = self.gauss(c.gps_sigma_m)
            self.dist = 0.0
            self.t_since_fix = 0.0
        # the 1-sigma a real filter would claim: the fix's error plus the
        # dead-reckoning drift since (heading and scale errors grow with
        # distance, the random walk with time)
        frac2 = c.bias ** 2 + c.velocity_scale_error ** 2 + c.heading_random_walk ** 2 * self.t_since_fix
        self.pos_var = (c.gps_sigma_m ** 2 + frac2 * self.dist ** 2
                        + c.position_random_walk ** 2 * self.t_since_fix)
        m = nav_solution_t()
        m.utime, m.vehicle, m.source = utime(tr.t), self.vehicle, nav_solution_t.SOURCE_SIM_INS
        status = nav_solution_t.STATUS_ALIGNED
        if surfaced and c.gps_aiding:
            status |= nav_solution_t.STATUS_GPS
        if 0.0 < tr.altitude_m <= c.dvl_max_altitude_m:
            status |= nav_solution_t.STATUS_DVL_BOTTOM
            m.altitude_m = tr.altitude_m + self.gauss(c.noise)
        else:
            status |= nav_solution_t.STATUS_DVL_WATER
            m.altitude_m = -1.0
        m.status = status
        m.north_m = tr.eta[0] + self.err_n + self.gauss(c.noise)
        m.east_m = tr.eta[1] + self.err_e + self.gauss(c.noise)
        m.depth_m = tr.eta[2] + self.gauss(c.noise)
        m.latitude_deg, m.longitude_deg = self.frame.to_latlon(m.north_m, m.east_m)
        m.roll_rad = wrap_pi(tr.eta[3] + self.gauss(c.attitude_noise))
        m.pitch_rad = tr.eta[4] + self.gauss(c.attitude_noise)
        m.heading_rad = wrap_2pi(tr.eta[5] + c.bias + self.head_walk + self.gauss(c.heading_noise))
        vnoise = c.velocity_noise
        m.u_mps = tr.nu[0] + self.gauss(vnoise)
        m.v_mps = tr.nu[1] + self.gauss(vnoise)
        m.w_mps = tr.nu[2] + self.gauss(vnoise)
        m.p_radps, m.q_radps, m.r_radps = tr.nu[3], tr.nu[4], tr.nu[5]
        m.speed_over_ground_mps = math.hypot(vn, ve)
        m.course_over_ground_rad = wrap_2pi(math.atan2(ve, vn) + c.bias + self.head_walk)
        pv = self.pos_var + c.noise ** 2
        m.position_cov_m2 = [[pv, 0.0, 0.0], [0.0, pv, 0.0], [0.0, 0.0, c.noise ** 2]]
        vv = vnoise ** 2
        m.velocity_cov_m2ps2 = [[vv, 0.0, 0.0], [0.0, vv, 0.0], [0.0, 0.0, vv]]
        av = c.attitude_noise ** 2
        hv = c.heading_noise ** 2 + c.bias ** 2 + self.head_walk ** 2
        m.attitude_cov_rad2 = [[av, 0.0, 0.0], [0.0, av, 0.0], [0.0, 0.0, hv]]
        return m
