"""A test that is the world's clock and the vehicle's pilot at once, over real LCM.

The simulator runs in stepped mode; the test publishes SIM.CLOCK one step at
a time and answers each step's NAV with an actuator command (sim.pilot: the
pilot plugin's C loops with the plan's gains) before the next step. The
loop is then exact whatever the CPU load: the published REMUS 100 is
open-loop unstable in yaw and pitch, and a late controller loses it.
"""

from __future__ import annotations

import lcm
from lcm_proc import pump

from auv import actuators_t, nav_solution_t, sim_clock_t
from auvlcm.rx import Receiver


class LockstepPilot:
    def __init__(
        self, lc: lcm.LCM, vehicle: str, depth_m: float, heading_rad: float = 0.0, rpm: float = 1500.0
    ) -> None:
        from sim.pilot import Pilot

        self.lc, self.vehicle = lc, vehicle
        self.depth, self.heading, self.rpm = depth_m, heading_rad, rpm
        self.ap = Pilot(dt=0.04)
        self.navs: list = []
        Receiver(lc).subscribe(f"{vehicle}.NAV", nav_solution_t, self._on_nav, queue_capacity=1000)

    def _on_nav(self, _channel: str, nav) -> None:
        self.navs.append(nav)
        cmd = actuators_t()
        cmd.utime, cmd.vehicle, cmd.seq, cmd.prop_rpm = nav.utime, self.vehicle, len(self.navs), self.rpm
        cmd.rudder_rad = self.ap.rudder(self.heading, nav.heading_rad, nav.r_radps)
        cmd.stern_plane_rad = self.ap.stern_for_depth(self.depth, nav.depth_m, nav.pitch_rad, nav.q_radps)
        self.lc.publish(f"{self.vehicle}.ACTUATORS", cmd.encode())

    def fly(self, seconds: float, step_us: int = 40_000) -> None:
        """Step the world from 0 to `seconds`; the INS must publish once per step."""
        self.ap.dt = step_us / 1e6
        clock = sim_clock_t()
        clock.server_id, clock.mode, clock.step_us = "test", sim_clock_t.MODE_LOCKSTEP, step_us
        for k in range(int(round(seconds * 1e6 / step_us)) + 1):
            clock.utime, clock.step = k * step_us, k
            self.lc.publish("SIM.CLOCK", clock.encode())
            assert pump(self.lc, lambda: self.navs and self.navs[-1].utime == clock.utime, timeout=20), (
                f"no NAV for t={clock.utime / 1e6:.2f}s"
            )
