"""Actuators: fins with angle and slew limits, a propeller with a lag.

The pilot commands angles and rpm; what the hull feels is what the servos and
motor can deliver. Both are advanced once per physics step, before the
dynamics, and held over the step.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from sim.vehicle import VehicleParams


def _clamp(x: float, lo: float, hi: float) -> float:
    return lo if x < lo else hi if x > hi else x


@dataclass
class Command:
    rudder_rad: float = 0.0
    stern_plane_rad: float = 0.0
    prop_rpm: float = 0.0


class Actuators:
    def __init__(self, vp: VehicleParams, dt: float) -> None:
        self.dt = dt
        self.fin_max = vp.fin_max_rad
        self.fin_step = vp.fin_rate_radps * dt  # largest change per step
        self.rpm_max = vp.prop_max_rpm
        # exact discretisation of a first-order lag: no stiffness at any dt
        tc = vp.prop_time_constant_s
        self.alpha = 1.0 - math.exp(-dt / tc) if tc > 0.0 else 1.0
        n0 = vp.prop_nominal_rpm
        self.kt = vp.prop_nominal_thrust_n / (n0 * n0)
        self.kq = vp.prop_nominal_torque_nm / (n0 * n0)
        self.rudder_sign = vp.rudder_sign
        self.stern_sign = vp.stern_plane_sign
        self.rudder = 0.0
        self.stern = 0.0
        self.rpm = 0.0
        self.thrust = 0.0
        self.torque = 0.0

    def step(self, cmd: Command) -> None:
        fm, fs = self.fin_max, self.fin_step
        target = _clamp(cmd.rudder_rad, -fm, fm)
        self.rudder += _clamp(target - self.rudder, -fs, fs)
        target = _clamp(cmd.stern_plane_rad, -fm, fm)
        self.stern += _clamp(target - self.stern, -fs, fs)
        target = _clamp(cmd.prop_rpm, -self.rpm_max, self.rpm_max)
        self.rpm += self.alpha * (target - self.rpm)
        n = self.rpm
        self.thrust = self.kt * n * abs(n)
        self.torque = self.kq * n * abs(n)

    def apply(self, dyn) -> None:
        """Hand the delivered fin angles and prop forces to the dynamics."""
        dyn.rudder = self.rudder_sign * self.rudder
        dyn.stern = self.stern_sign * self.stern
        dyn.thrust = self.thrust
        dyn.torque = self.torque
