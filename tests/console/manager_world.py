"""A real chasm-manager (tests/managers/dive.chasm as AUV1 NAVIGATOR) on a
clock the test drives from a thread: SIM.CLOCK and AUV1.NAV at 20 Hz of
mission time, paced at wall time so the manager keeps up."""

from __future__ import annotations

import signal
import subprocess
import threading

import lcm
from conftest import ROOT, manager_cmd
from lcm_proc import stop

from auv import nav_solution_t, sim_clock_t

HERE = ROOT / "tests" / "managers"


class ManagerWorld:
    def __init__(self, url: str, env: dict, sanitized: bool = False, extra: tuple = ()) -> None:
        self.lc = lcm.LCM(url)
        self.utime = 0
        self._stop = threading.Event()
        cmd = manager_cmd(HERE / "dive.chasm", HERE / "vehicle.bind", url, *extra, sanitized=sanitized)
        self.mgr = subprocess.Popen(cmd, env=env, stderr=subprocess.PIPE, text=True)
        self.thread = threading.Thread(target=self._tick, daemon=True)
        self.thread.start()

    def _tick(self) -> None:
        while not self._stop.wait(0.05):
            self.utime += 50_000
            nav = nav_solution_t()
            nav.utime, nav.vehicle, nav.depth_m, nav.north_m, nav.east_m = self.utime, "AUV1", 0.0, 10.0, 5.0
            self.lc.publish("AUV1.NAV", nav.encode())
            clock = sim_clock_t()
            clock.utime, clock.server_id, clock.step_us = self.utime, "test", 50_000
            self.lc.publish("SIM.CLOCK", clock.encode())

    def close(self) -> int:
        self._stop.set()
        self.thread.join()
        return stop(self.mgr, signal.SIGTERM)
