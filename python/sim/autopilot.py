"""A minimal stateless heading / depth / pitch controller for scripting survey logs.

Not the project's pilot. The pilot is a CHASM manager (c/plugins/pilot,
missions/pilot/pilot.chasm), and whatever flies a vehicle in-process in
its place (the validation report, tests) flies its own C loops through
sim.pilot. This PD is a deliberately different controller with one user,
tools/nav/survey_pilot.py, which makes the navigation test logs
(tools/nav/survey_log.py), and it stays for these reasons:

- survey_pilot asks for what the pilot would refuse: 20 deg bow-up to
  surface, where the plan clamps pitch commands to its max_pitch (15 deg),
  then runs awash on the surface for GPS fixes.
- survey_pilot switches between the depth and pitch loops from one call
  to the next, and calls at whatever rate its NAV arrives. This PD has no
  state, so it copes. The pilot's loops integrate and slew, and would need
  restarting on every switch and the time between calls.
- The navigation tests and bench (tests/nav, bench/nav_bench.py) are
  measured on the trajectories it flies. Changing the controller would
  re-baseline those figures, which is a change of its own.

It holds heading well; with no integrator it leaves the positively buoyant
REMUS some way shallow of a depth target. Positive rudder turns the bow to
starboard; positive stern plane pitches the bow down (actuators_t).
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
