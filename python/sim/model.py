"""One simulated vehicle: actuators -> dynamics in the environment -> truth.

This is the physics only, with no LCM and no clock: the HIL loop, the
validation runs, the tests and the benchmark all drive this same object.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from sim.actuators import Actuators, Command
from sim.dynamics import Dynamics
from sim.environment import RHO_SEAWATER, Environment, G
from sim.geo import LocalFrame
from sim.vehicle import VehicleParams


@dataclass
class Truth:
    """A snapshot the sensors read: the true state and the world around it."""

    t: float = 0.0
    eta: tuple = (0.0,) * 6
    nu: tuple = (0.0,) * 6
    nu_dot: tuple = (0.0,) * 6
    current_ned: tuple = (0.0, 0.0, 0.0)
    water_depth_m: float = 0.0
    altitude_m: float = 0.0
    latitude_deg: float = 0.0
    longitude_deg: float = 0.0
    wave_pressure_pa: float = 0.0  # the waves' dynamic pressure at the vehicle

    @property
    def depth(self) -> float:
        return self.eta[2]

    @property
    def pressure_depth(self) -> float:
        """The depth a pressure gauge reads: the true depth plus the waves'
        dynamic pressure head (linear theory: the swell above, decayed)."""
        return self.eta[2] + self.wave_pressure_pa / (RHO_SEAWATER * G)

    def velocity_ned(self) -> tuple[float, float, float]:
        """Velocity over ground in NED [m/s]."""
        _, _, _, phi, th, psi = self.eta
        u, v, w = self.nu[0:3]
        cphi, sphi, cth, sth = math.cos(phi), math.sin(phi), math.cos(th), math.sin(th)
        cpsi, spsi = math.cos(psi), math.sin(psi)
        vn = cpsi * cth * u + (cpsi * sth * sphi - spsi * cphi) * v + (spsi * sphi + cpsi * cphi * sth) * w
        ve = spsi * cth * u + (cpsi * cphi + sphi * sth * spsi) * v + (sth * spsi * cphi - cpsi * sphi) * w
        vd = -sth * u + cth * sphi * v + cth * cphi * w
        return vn, ve, vd


class VehicleModel:
    def __init__(self, vp: VehicleParams, env: Environment, dt: float = 0.02) -> None:
        self.vp = vp
        self.env = env
        self.dt = dt
        self.dyn = Dynamics(vp, dt)
        self.act = Actuators(vp, dt)
        self.frame = LocalFrame(env.params.origin_latitude_deg, env.params.origin_longitude_deg)
        self.command = Command()
        self.steps = 0
        self.grounded_steps = 0

    @property
    def t(self) -> float:
        return self.dyn.t

    def replace_world(self, env: Environment) -> None:
        """Take another world (multi-HIL: the server's), its origin with it; in
        place, so the parts holding the environment or the frame follow."""
        self.env.replace_with(env)
        self.frame.re_origin(env.params.origin_latitude_deg, env.params.origin_longitude_deg)

    def set_pose(self, eta, nu=(0.0,) * 6, rpm: float = 0.0) -> None:
        self.dyn.set_state(eta, nu)
        self.act.rpm = rpm

    def step(self) -> None:
        """One physics step: actuators, the water at the vehicle, RK4."""
        d = self.dyn
        x = d.x
        # The water's velocity and acceleration are sampled once per step
        # (zero-order hold): they vary over metres and seconds, far slower
        # than one 20 ms step.
        d.current_ned, d.water_accel_ned = self.env.water(d.t, x[0], x[1], x[2])
        self.act.step(self.command)
        self.act.apply(d)
        d.step()
        # Seabed contact: the hull rests on the bottom instead of sinking
        # through it (a grounded vehicle is a scenario worth simulating).
        x = d.x
        floor = self.env.water_depth(x[0], x[1]) - self.vp.radius_m
        if x[2] > floor:
            x[2] = floor
            if x[8] > 0.0:
                x[8] = 0.0
            self.grounded_steps += 1
        self.steps += 1

    def truth(self, out: Truth | None = None) -> Truth:
        d = self.dyn
        x = d.x
        tr = out or Truth()
        tr.t = d.t
        tr.eta = tuple(x[0:6])
        tr.nu = tuple(x[6:12])
        tr.nu_dot = tuple(d.nu_dot)
        tr.current_ned = tuple(d.current_ned)
        tr.water_depth_m = self.env.water_depth(x[0], x[1])
        tr.altitude_m = tr.water_depth_m - x[2]
        tr.latitude_deg, tr.longitude_deg = self.frame.to_latlon(x[0], x[1])
        tr.wave_pressure_pa = self.env.wave_pressure(d.t, x[0], x[1], x[2]) if self.env.has_waves else 0.0
        return tr
