"""Closed-loop mission runs for tests/missions: the simulator plus the PILOT
and NAVIGATOR managers (--clock sim), all over real LCM on the test's private
URL, with the ground truth and the navigator's state timeline recorded in
memory as they arrive.

This process is the global clock (SIM.CLOCK, the simulator in stepped mode):
each 50 ms tick it waits until both managers have run their cycle at that
time. The default REMUS 100 doubles a yaw error in 0.7 s; in scaled time the
wall-clock latency between processes, multiplied by the warp, would be a
loop delay the heading control cannot live with, and a loaded machine would
change the flight. In lockstep a slow machine only makes the run slower."""

from __future__ import annotations

import signal
import subprocess
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import lcm
import yaml
from conftest import BUILD, ROOT
from lcm_proc import pump, stop

from auv import chasm_status_t, ground_truth_t, nav_solution_t, sim_clock_t
from auvlcm import programs
from auvlcm.rx import Receiver
from confcheck.checker import resolved

MISSIONS = ROOT / "missions"
SIM_CONFIG = MISSIONS / "sim" / "remus100.yaml"
TICK_US = 50_000  # the PILOT's 20 Hz
PERIODS_US = {"PILOT": 50_000, "NAVIGATOR": 100_000}  # --rate 20 and 10


@dataclass
class Pose:
    t: float
    n: float
    e: float
    depth: float
    heading: float
    altitude: float


@dataclass
class Record:
    truth: list[Pose] = field(default_factory=list)
    nav: list[Pose] = field(default_factory=list)  # what the vehicle believes (AUV1.NAV)
    # (sim time, active path "a/b", condition of the transition into it), one per change
    states: list[tuple[float, str, str]] = field(default_factory=list)
    run_state: int = -1

    def leaf(self) -> str:
        return self.states[-1][1] if self.states else ""

    def entered(self, path: str) -> tuple[float, str, str] | None:
        """The first time the navigator entered `path` (or a state below it)."""
        return next((s for s in self.states if s[1] == path or s[1].startswith(path + "/")), None)

    def state_at(self, t: float) -> str:
        current = ""
        for ts, path, _ in self.states:
            if ts > t:
                break
            current = path
        return current


def merge(into: dict, changes: dict) -> None:
    """Nested update; a None value removes the key."""
    for key, value in changes.items():
        if value is None:
            into.pop(key, None)
        elif isinstance(value, dict) and isinstance(into.get(key), dict):
            merge(into[key], value)
        else:
            into[key] = value


def sim_config(tmp: Path, **overrides) -> Path:
    """The example vehicle, stepped by SIM.CLOCK, with the truth published at
    every physics step (this process waits for it) and any `section: {key:
    value}` overrides merged in (e.g. initial={'north_m': -50}; None removes a key)."""
    cfg = resolved(SIM_CONFIG)  # with the base it extends
    cfg["simulation"].update(clock="lockstep", truth_rate_hz=cfg["simulation"].get("physics_rate_hz", 50))
    merge(cfg, overrides)
    path = tmp / "sim.yaml"
    path.write_text(yaml.safe_dump(cfg))
    return path


class Mission:
    """One vehicle flying one navigator plan. Use as a context manager."""

    def __init__(
        self,
        tmp: Path,
        url: str,
        env: dict,
        plan: Path,
        params: dict[str, str] | None = None,
        nav_cut_s: float | None = None,
        sim: dict | None = None,
    ) -> None:
        self.tmp, self.url, self.env = tmp, url, env
        self.plan, self.params, self.nav_cut_s = plan, params or {}, nav_cut_s
        self.sim_cfg = sim_config(tmp, **(sim or {}))
        self.lc = lcm.LCM(url)
        self.rx = Receiver(self.lc)
        self.rec = Record()
        self.procs: dict[str, subprocess.Popen] = {}
        self.rx.subscribe("AUV1.TRUTH", ground_truth_t, self._on_truth, 1000)
        self.rx.subscribe("AUV1.NAV", nav_solution_t, self._on_nav, 1000)
        self.rx.subscribe("AUV1.CHASM.NAVIGATOR", chasm_status_t, self._on_status, 1000)
        self.rx.subscribe("AUV1.CHASM.PILOT", chasm_status_t, self._on_pilot, 1000)
        self.cycled = {n: -(10**12) for n in PERIODS_US}  # utime of each manager's latest cycle
        self.utime = 0
        bind = MISSIONS / "bindings" / "navigator.bind"
        if nav_cut_s is not None:
            # The navigator's navigation comes through this process, which stops
            # forwarding it at nav_cut_s; the pilot keeps its own feed.
            bind = tmp / "navigator_relay.bind"
            bind.write_text(
                (MISSIONS / "bindings" / "navigator.bind")
                .read_text()
                .replace("${VEHICLE}.NAV ", "${VEHICLE}.NAV_RELAY ")
            )
            shared = "sensors.bind"  # what it includes, next to it
            (tmp / shared).write_text((MISSIONS / "bindings" / shared).read_text())
        self.bind = bind

    def _on_truth(self, channel: str, m: ground_truth_t) -> None:
        self.rec.truth.append(Pose(m.utime / 1e6, m.eta[0], m.eta[1], m.eta[2], m.eta[5], m.altitude_m))

    def _on_nav(self, channel: str, m: nav_solution_t) -> None:
        self.rec.nav.append(Pose(m.utime / 1e6, m.north_m, m.east_m, m.depth_m, m.heading_rad, m.altitude_m))
        if self.nav_cut_s is not None and m.utime / 1e6 < self.nav_cut_s:
            self.lc.publish("AUV1.NAV_RELAY", m.encode())

    def _on_pilot(self, channel: str, m: chasm_status_t) -> None:
        self.cycled["PILOT"] = max(self.cycled["PILOT"], m.utime)

    def _on_status(self, channel: str, m: chasm_status_t) -> None:
        self.cycled["NAVIGATOR"] = max(self.cycled["NAVIGATOR"], m.utime)
        self.rec.run_state = m.run_state
        path = "/".join(m.active_path)
        if m.path_len and (not self.rec.states or self.rec.states[-1][1] != path):
            self.rec.states.append((m.utime / 1e6, path, m.last_condition))

    def _start(self, name: str, cmd: list, ready: str) -> None:
        """Starts a process (output to a file) and waits for its `ready` line."""
        path = self.tmp / f"{name}.out"
        self.procs[name] = subprocess.Popen(
            [str(c) for c in cmd], stdout=open(path, "w"), stderr=subprocess.STDOUT, env=self.env
        )
        deadline = time.monotonic() + 30
        while ready not in path.read_text():
            assert self.procs[name].poll() is None, f"{name} exited:\n{self.output(name)}"
            assert time.monotonic() < deadline, f"{name} did not start:\n{self.output(name)}"
            time.sleep(0.05)

    def __enter__(self) -> "Mission":
        plugins = [BUILD / "plugins"]
        self._start(
            "pilot",
            programs.chasm_manager(
                BUILD,
                plan=MISSIONS / "pilot" / "pilot.chasm",
                bind=MISSIONS / "bindings" / "pilot.bind",
                vehicle="AUV1",
                name="PILOT",
                lcm_url=self.url,
                rate_hz=20,
                plugin_path=plugins,
            ),
            "PILOT: running",
        )
        self._start(
            "navigator",
            programs.chasm_manager(
                BUILD,
                plan=self.plan,
                bind=self.bind,
                vehicle="AUV1",
                name="NAVIGATOR",
                lcm_url=self.url,
                plugin_path=plugins,
                params=self.params,
            ),
            "NAVIGATOR: running",
        )
        self._start("sim", programs.simulator(self.sim_cfg, lcm_url=self.url), "running")
        return self

    def fly(self, until: Callable[[Record], bool], max_sim_s: float) -> Record:
        """Ticks the global clock until `until(record)` holds or max_sim_s of sim time."""
        clock = sim_clock_t()
        clock.server_id, clock.step_us = "test", TICK_US
        while self.utime < max_sim_s * 1e6 and not until(self.rec):
            self.utime += TICK_US
            clock.utime = self.utime
            self.lc.publish("SIM.CLOCK", clock.encode())
            if not pump(self.lc, self._cycled, timeout=20):
                for name, proc in self.procs.items():
                    assert proc.poll() is None, f"{name} died:\n{self.output(name)}"
                sim_t = self.rec.truth[-1].t if self.rec.truth else None
                raise AssertionError(
                    f"at t={self.utime / 1e6:.2f} s: managers' last cycles {self.cycled}, sim at {sim_t}, nav at {[p.t for p in self.rec.nav[-3:]]}"
                )
        return self.rec

    def _cycled(self) -> bool:
        """Whether the simulator has stepped to this tick (within half a
        physics step) and every manager has run the cycle due at it. A manager
        cycles one period after its last cycle (and at once when its plan
        starts), so one whose latest status is less than a period old is not
        due; its status for this tick may still be on its way, which is why
        this is evaluated afresh as messages arrive."""
        sim_there = bool(self.rec.truth) and self.rec.truth[-1].t * 1e6 >= self.utime - 11_000
        return sim_there and all(
            self.cycled[n] >= self.utime or self.cycled[n] + period > self.utime for n, period in PERIODS_US.items()
        )

    def output(self, name: str) -> str:
        path = self.tmp / f"{name}.out"
        return path.read_text()[-3000:] if path.exists() else ""

    def __exit__(self, *exc) -> None:
        for proc in self.procs.values():
            stop(proc, signal.SIGINT)
