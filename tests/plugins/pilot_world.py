"""A lockstep world for closed-loop pilot tests: the simulator (stepped clock),
the PILOT manager and a scripted navigator, over real LCM.

This process is the global clock. Each tick it publishes the navigator's
setpoint and SIM.CLOCK, then waits until the PILOT has cycled at that time
(its status message, which follows its ACTUATORS in the same cycle) before
the next tick. The simulator advances only as SIM.CLOCK says, so a loaded
machine slows the run down but cannot change what happens in it.
"""

from __future__ import annotations

import math
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import lcm
import yaml
from lcm_proc import pump, stop, wait_for_line

from auv import actuators_t, chasm_status_t, ground_truth_t, pilot_status_t, setpoint_t, sim_clock_t
from auvlcm import programs
from auvlcm.rx import Receiver
from confcheck.checker import resolved

ROOT = Path(__file__).resolve().parents[2]
SIM_CONFIG = ROOT / "missions" / "sim" / "remus100.yaml"
PLAN = ROOT / "missions" / "pilot" / "pilot.chasm"
BIND = ROOT / "missions" / "bindings" / "pilot.bind"


@dataclass
class Setpoint:
    """What the scripted navigator asks for (SI units, setpoint_t modes)."""

    heading: float = 0.0
    vertical_mode: int = setpoint_t.VERTICAL_DEPTH
    depth: float = 0.0
    altitude: float = 0.0
    pitch: float = 0.0
    speed_mode: int = setpoint_t.SPEED_MPS
    speed: float = 0.0
    rpm: float = 0.0
    speed_reference: int = setpoint_t.SPEED_OVER_GROUND
    utime: int | None = None  # the stamp to send (None: the tick's time)


@dataclass
class Sample:
    """Ground truth at one tick, with the command the pilot sent."""

    t: float
    north: float
    east: float
    depth: float
    pitch: float
    heading: float
    u: float
    r: float
    altitude: float
    rudder: float = math.nan
    plane: float = math.nan
    rpm: float = math.nan


@dataclass
class World:
    """Simulator + PILOT, clocked from here. Use as a context manager."""

    tmp: Path
    url: str
    env: dict
    build: Path
    initial: dict = field(default_factory=dict)
    environment: dict = field(default_factory=dict)  # keys replaced in remus100.yaml's environment
    drop_waves: bool = False
    tick_s: float = 0.05  # the PILOT's 20 Hz
    manager_args: tuple = ()

    def __enter__(self) -> "World":
        self.lc = lcm.LCM(self.url)
        self.rx = Receiver(self.lc)
        self.truth: list = []
        self.status: list = []
        self.commands: list = []
        self.pilot_status: list = []
        self.rx.subscribe("AUV1.PILOT_STATUS", pilot_status_t, lambda c, m: self.pilot_status.append(m), 5000)
        self.rx.subscribe("AUV1.TRUTH", ground_truth_t, lambda c, m: self.truth.append(m), 5000)
        self.rx.subscribe("AUV1.CHASM.PILOT", chasm_status_t, lambda c, m: self.status.append(m), 5000)
        self.rx.subscribe("AUV1.ACTUATORS", actuators_t, lambda c, m: self.commands.append(m), 5000)
        self.procs: list[subprocess.Popen] = []
        self.utime = 0
        self.samples: list[Sample] = []
        mgr = programs.chasm_manager(
            self.build,
            plan=PLAN,
            bind=BIND,
            vehicle="AUV1",
            name="PILOT",
            lcm_url=self.url,
            rate_hz=round(1 / self.tick_s),
            plugin_path=[self.build / "plugins"],
            extra=self.manager_args,
        )
        self.pilot = self._start(mgr, "PILOT: running")
        self.sim = self._start([sys.executable, "-m", "sim", str(self._config())], "running")
        return self

    def __exit__(self, *exc) -> None:
        for p in reversed(self.procs):
            stop(p)

    def _start(self, cmd: list[str], ready: str) -> subprocess.Popen:
        p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=self.env)
        self.procs.append(p)
        wait_for_line(p, ready, timeout=30)
        return p

    def _config(self) -> Path:
        """remus100.yaml (the default table-coefficient vehicle) with the
        test's clock, start state and any environment change."""
        cfg = resolved(SIM_CONFIG)  # with the base it extends
        cfg["simulation"].update(
            clock="lockstep",
            lcm_url=self.url,
            truth_rate_hz=round(1 / self.tick_s),
            command_timeout_s=1.0,
            on_stale="hold",
        )
        cfg["initial"].update(self.initial)
        cfg["environment"].update(self.environment)
        if self.drop_waves:
            cfg["environment"].pop("waves", None)
        path = self.tmp / "sim.yaml"
        path.write_text(yaml.safe_dump(cfg))
        return path

    def run(self, until_s: float, script: Callable[[float], Setpoint | None]) -> None:
        """Tick until sim time until_s; script(t) gives the setpoint (None: send none)."""
        dt_us = round(self.tick_s * 1e6)
        while self.utime < until_s * 1e6:
            self.utime += dt_us
            sp = script(self.utime / 1e6)
            if sp is not None:
                self._publish_setpoint(sp)
            clock = sim_clock_t()
            clock.utime, clock.server_id, clock.step_us = self.utime, "test", dt_us
            self.lc.publish("SIM.CLOCK", clock.encode())
            ok = pump(self.lc, lambda: bool(self.status) and self.status[-1].utime >= self.utime, timeout=20)
            assert ok, f"the PILOT did not cycle at t={self.utime / 1e6:.2f} s"
            pump(self.lc, lambda: bool(self.truth) and self.truth[-1].utime >= self.utime - dt_us, timeout=5)
            self._sample()

    def _publish_setpoint(self, sp: Setpoint) -> None:
        m = setpoint_t()
        m.utime, m.vehicle = (self.utime if sp.utime is None else sp.utime), "AUV1"
        m.heading_rad, m.vertical_mode = sp.heading % (2 * math.pi), sp.vertical_mode
        m.depth_m, m.altitude_m, m.pitch_rad = sp.depth, sp.altitude, sp.pitch
        m.speed_mode, m.speed_mps, m.prop_rpm = sp.speed_mode, sp.speed, sp.rpm
        m.speed_reference = sp.speed_reference
        self.lc.publish("AUV1.SETPOINT", m.encode())

    def _sample(self) -> None:
        if not self.truth:
            return
        m = self.truth[-1]
        s = Sample(m.utime / 1e6, m.eta[0], m.eta[1], m.eta[2], m.eta[4], m.eta[5], m.nu[0], m.nu[5], m.altitude_m)
        if self.commands:
            c = self.commands[-1]
            s.rudder, s.plane, s.rpm = c.rudder_rad, c.stern_plane_rad, c.prop_rpm
        self.samples.append(s)

    def leaf(self) -> str:
        return "/".join(self.status[-1].active_path) if self.status else ""
