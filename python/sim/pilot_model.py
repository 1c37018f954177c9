"""The pilot's control law in Python, with its gains read from the plan.

The vehicle's pilot is a CHASM manager running missions/pilot/pilot.chasm
with the pilot plugin (c/plugins/pilot). The validation report and quick
tests fly the physics in-process, with no LCM and no clock, and need the same
controller: this module is the plugin's cascade written again (heading:
turn-rate-limited PD on yaw rate with a zoned integrator; depth -> pitch ->
stern plane; speed: feed-forward + PI), but its gains are never written
here: `PilotGains.from_plan()` reads the `param` lines of the plan, the one
place they are set. tests/missions fly the real manager on the same plant.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, fields
from pathlib import Path

PLAN = Path(__file__).resolve().parents[2] / "missions" / "pilot" / "pilot.chasm"
_UNITS = {
    "": 1.0,
    "rad": 1.0,
    "deg": math.pi / 180.0,
    "deg/s": math.pi / 180.0,
    "rad/s": 1.0,
    "s": 1.0,
    "m": 1.0,
    "m/s": 1.0,
}
_PARAM = re.compile(r"^param\s+(\w+)\s*=\s*([-+0-9.eE]+)\s*([a-z/]*)")


@dataclass
class PilotGains:
    """Every number the pilot plan sets (SI units); from_plan() fills them."""

    heading_kp: float
    heading_kd: float
    heading_ki: float
    max_turn_rate: float
    max_rudder: float
    rudder_slew: float
    heading_i_limit: float
    heading_i_zone: float
    depth_kp: float
    depth_ki: float
    depth_kd: float
    depth_rate_tau: float
    max_pitch: float
    pitch_slew: float
    pitch_kp: float
    pitch_ki: float
    pitch_kd: float
    max_plane: float
    plane_slew: float
    plane_i_limit: float
    rpm_per_mps: float
    speed_kp: float
    speed_ki: float
    speed_i_limit: float
    max_rpm: float
    rpm_slew: float

    @classmethod
    def from_plan(cls, path: Path = PLAN) -> "PilotGains":
        values: dict[str, float] = {}
        for line in path.read_text().splitlines():
            m = _PARAM.match(line.strip())
            if m and m.group(3) in _UNITS:
                values[m.group(1)] = float(m.group(2)) * _UNITS[m.group(3)]
        missing = [f.name for f in fields(cls) if f.name not in values]
        if missing:
            raise ValueError(f"{path}: the pilot plan sets no {', '.join(missing)}")
        return cls(**{f.name: values[f.name] for f in fields(cls)})


def _clamp(x: float, lo: float, hi: float) -> float:
    return lo if x < lo else hi if x > hi else x


class Pid:
    """pu_pid: clamped, slew-limited PID with conditional integration."""

    def __init__(self, kp, ki, kd, lim, slew, i_limit, i_zone=0.0, lo=None) -> None:
        self.kp, self.ki, self.kd, self.slew, self.i_zone = kp, ki, kd, slew, i_zone
        self.lo, self.hi = (-lim if lo is None else lo), lim
        self.i_limit = i_limit if i_limit > 0.0 else max(abs(self.lo), abs(self.hi))
        self.integral = 0.0
        self.output: float | None = None

    def step(self, e: float, de: float, ff: float, dt: float, ki: float | None = None) -> float:
        ki = self.ki if ki is None else ki
        step_i = 0.0 if self.i_zone > 0.0 and abs(e) > self.i_zone else ki * e * dt
        i_new = _clamp(self.integral + step_i, -self.i_limit, self.i_limit)
        unlimited = ff + self.kp * e + i_new + self.kd * de
        u = _clamp(unlimited, self.lo, self.hi)
        if self.output is not None and self.slew > 0.0:
            u = _clamp(u, self.output - self.slew * dt, self.output + self.slew * dt)
        limited = abs(u - unlimited) > 1e-12 * (1.0 + abs(unlimited))
        if limited and ((unlimited > u and step_i > 0.0) or (unlimited < u and step_i < 0.0)):
            i_new = self.integral
        self.integral = i_new
        self.output = u
        return u


def wrap_pi(a: float) -> float:
    return (a + math.pi) % (2.0 * math.pi) - math.pi


class PilotModel:
    """Heading, depth (or pitch) and speed (or rpm) control, one call per cycle."""

    def __init__(self, g: PilotGains | None = None, dt: float = 0.05) -> None:
        self.g = g = g or PilotGains.from_plan()
        self.dt = dt
        self.heading = Pid(
            g.heading_kp, g.heading_ki, g.heading_kd, g.max_rudder, g.rudder_slew, g.heading_i_limit, g.heading_i_zone
        )
        self.depth = Pid(g.depth_kp, g.depth_ki, g.depth_kd, g.max_pitch, g.pitch_slew, g.max_pitch)
        self.pitch = Pid(g.pitch_kp, g.pitch_ki, g.pitch_kd, g.max_plane, g.plane_slew, g.plane_i_limit)
        self.speed = Pid(g.speed_kp, g.speed_ki, 0.0, g.max_rpm, g.rpm_slew, g.speed_i_limit, lo=0.0)
        self._rate = None
        self._last_depth = None

    def start(self, pitch: float, plane: float = 0.0, rpm: float = 0.0) -> None:
        """Take over without a jump, as the behaviors' start() does."""
        self.depth.output, self.pitch.output, self.speed.output = pitch, -plane, rpm

    def rudder(self, heading_cmd: float, heading: float, r: float) -> float:
        g = self.g
        e = wrap_pi(heading_cmd - heading)
        lim = g.heading_kd * g.max_turn_rate / g.heading_kp if g.heading_kp > 0.0 else abs(e)
        e_lim = _clamp(e, -lim, lim)
        return self.heading.step(e_lim, -r, 0.0, self.dt, None if e_lim == e else 0.0)

    def stern_for_pitch(self, pitch_cmd: float, pitch: float, q: float) -> float:
        return -self.pitch.step(pitch_cmd - pitch, -q, 0.0, self.dt)

    def stern_for_depth(self, target: float, depth: float, pitch: float, q: float) -> float:
        dt = self.dt
        if self._last_depth is not None:
            raw = (depth - self._last_depth) / dt
            tau = self.g.depth_rate_tau
            self._rate = (
                raw
                if self._rate is None or tau <= 0.0
                else self._rate + (1.0 - math.exp(-dt / tau)) * (raw - self._rate)
            )
        self._last_depth = depth
        pitch_cmd = self.depth.step(depth - target, self._rate or 0.0, 0.0, dt)
        return self.stern_for_pitch(pitch_cmd, pitch, q)

    def prop(self, speed_cmd: float, u: float, through_water: bool = False) -> float:
        """rpm for speed_cmd; through the water: the rpm law alone (setpoint_t)."""
        if through_water:
            self.speed.integral = 0.0
            return (
                self.speed.step(0.0, 0.0, self.g.rpm_per_mps * max(speed_cmd, 0.0), self.dt, 0.0)
                if speed_cmd > 0.0
                else self.speed.step(0.0, 0.0, 0.0, self.dt, 0.0)
            )
        if not speed_cmd > 0.0:
            self.speed.integral = 0.0
            return self.speed.step(0.0, 0.0, 0.0, self.dt, 0.0)
        return self.speed.step(speed_cmd - u, 0.0, self.g.rpm_per_mps * speed_cmd, self.dt)
