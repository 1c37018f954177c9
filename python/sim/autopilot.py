"""A minimal heading / depth / pitch autopilot in the actuators_t sign convention.

Not the project's pilot (that is a CHASM manager, whose control law with the
plan's gains is sim.pilot_model, used by the validation): a stateless PD that
tools and tests call at any rate to script a vehicle (tools/nav/survey_pilot.py,
tests/sim/test_sim_sender.py). It holds heading well; with no integrator it
leaves the positively buoyant REMUS some way shallow of a depth target.
Positive rudder turns the bow to starboard; positive stern plane pitches the
bow down.
"""

from __future__ import annotations

import math
from dataclasses import dataclass


def _clamp(x: float, lim: float) -> float:
    return max(-lim, min(lim, x))


def wrap_pi(a: float) -> float:
    return (a + math.pi) % (2.0 * math.pi) - math.pi


@dataclass
class Autopilot:
    heading_kp: float = 2.0
    heading_kd: float = 1.0  # on yaw rate [s]
    depth_kp: float = 0.3  # [rad/m] depth error -> pitch command
    pitch_limit: float = 0.4  # [rad]
    pitch_kp: float = 2.0
    pitch_kd: float = 2.0
    fin_limit: float = math.radians(20.0)

    def rudder(self, heading_cmd: float, heading: float, r: float) -> float:
        e = wrap_pi(heading_cmd - heading)
        return _clamp(self.heading_kp * e - self.heading_kd * r, self.fin_limit)

    def stern_for_pitch(self, pitch_cmd: float, pitch: float, q: float) -> float:
        # nose below the command (pitch < cmd) needs bow up: negative plane
        return _clamp(-(self.pitch_kp * (pitch_cmd - pitch) - self.pitch_kd * q), self.fin_limit)

    def stern_for_depth(self, depth_cmd: float, depth: float, pitch: float, q: float) -> float:
        # too deep -> nose up (positive pitch command)
        pitch_cmd = _clamp(self.depth_kp * (depth - depth_cmd), self.pitch_limit)
        return self.stern_for_pitch(pitch_cmd, pitch, q)
