"""Closed-loop mission runs for tests/missions: the simulator (scaled time)
plus the PILOT and NAVIGATOR managers on its clock, all over real LCM on the
test's private URL, with the ground truth and the navigator's state timeline
recorded in memory as they arrive."""

from __future__ import annotations

import signal
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import lcm
import yaml

from auv import chasm_status_t, ground_truth_t, nav_solution_t
from auvlcm.rx import Receiver
from conftest import BUILD, ROOT
from lcm_proc import stop

MISSIONS = ROOT / "missions"
SIM_CONFIG = MISSIONS / "sim" / "remus100.yaml"


@dataclass
class Truth:
    t: float
    n: float
    e: float
    depth: float
    heading: float


@dataclass
class Record:
    truth: list[Truth] = field(default_factory=list)
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


def sim_config(tmp: Path, **overrides) -> Path:
    """The example vehicle with the clock published at the pilot's rate and
    any `section.key` overrides (e.g. initial={'north_m': -50})."""
    cfg = yaml.safe_load(SIM_CONFIG.read_text())
    cfg["simulation"]["clock_rate_hz"] = 20
    for section, values in overrides.items():
        cfg.setdefault(section, {}).update(values)
    path = tmp / "sim.yaml"
    path.write_text(yaml.safe_dump(cfg))
    return path


class Mission:
    """One vehicle flying one navigator plan. Use as a context manager."""

    def __init__(self, tmp: Path, url: str, env: dict, plan: Path, params: dict[str, str] | None = None,
                 warp: float = 20.0, nav_cut_s: float | None = None, sim: dict | None = None) -> None:
        self.tmp, self.url, self.env, self.warp = tmp, url, env, warp
        self.plan, self.params, self.nav_cut_s = plan, params or {}, nav_cut_s
        self.sim_cfg = sim_config(tmp, **(sim or {}))
        self.lc = lcm.LCM(url)
        self.rx = Receiver(self.lc)
        self.rec = Record()
        self.procs: dict[str, subprocess.Popen] = {}
        self.rx.subscribe("AUV1.TRUTH", ground_truth_t, self._on_truth, 1000)
        self.rx.subscribe("AUV1.CHASM.NAVIGATOR", chasm_status_t, self._on_status, 1000)
        bind = MISSIONS / "bindings" / "navigator.bind"
        if nav_cut_s is not None:
            # The navigator's navigation comes through this process, which stops
            # forwarding it at nav_cut_s; the pilot keeps its own feed.
            bind = tmp / "navigator_relay.bind"
            bind.write_text((MISSIONS / "bindings" / "navigator.bind").read_text()
                            .replace("${VEHICLE}.NAV ", "${VEHICLE}.NAV_RELAY "))
            self.lc.subscribe("AUV1.NAV", self._relay).set_queue_capacity(1000)
        self.bind = bind

    def _on_truth(self, channel: str, m: ground_truth_t) -> None:
        self.rec.truth.append(Truth(m.utime / 1e6, m.eta[0], m.eta[1], m.eta[2], m.eta[5]))

    def _on_status(self, channel: str, m: chasm_status_t) -> None:
        self.rec.run_state = m.run_state
        path = "/".join(m.active_path)
        if m.path_len and (not self.rec.states or self.rec.states[-1][1] != path):
            self.rec.states.append((m.utime / 1e6, path, m.last_condition))

    def _relay(self, channel: str, data: bytes) -> None:
        if nav_solution_t.decode(data).utime / 1e6 < self.nav_cut_s:
            self.lc.publish("AUV1.NAV_RELAY", data)

    def _start(self, name: str, cmd: list) -> None:
        out = open(self.tmp / f"{name}.out", "w")
        self.procs[name] = subprocess.Popen([str(c) for c in cmd], stdout=out, stderr=subprocess.STDOUT,
                                            env=self.env)

    def __enter__(self) -> "Mission":
        manager = BUILD / "bin" / "chasm-manager"
        common = ["--vehicle", "AUV1", "--clock", "sim", "--url", self.url, "--plugin-path", BUILD / "plugins"]
        self._start("pilot", [manager, "--plan", MISSIONS / "pilot" / "pilot.chasm", "--bind",
                              MISSIONS / "bindings" / "pilot.bind", "--name", "PILOT", "--rate", "20", *common])
        defines = [a for k, v in self.params.items() for a in ("-D", f"{k}={v}")]
        self._start("navigator", [manager, "--plan", self.plan, "--bind", self.bind, "--name", "NAVIGATOR",
                                  "--rate", "10", *common, *defines])
        return self

    def fly(self, until: Callable[[Record], bool], max_sim_s: float) -> Record:
        """Runs the simulator until `until(record)` holds or max_sim_s of sim time."""
        self._start("sim", [sys.executable, ROOT / "python" / "sim", self.sim_cfg, "--clock", "scaled",
                            "--warp", self.warp, "--duration", max_sim_s, "--lcm-url", self.url])
        deadline = time.monotonic() + 3 * max_sim_s / self.warp + 60
        while time.monotonic() < deadline and self.procs["sim"].poll() is None and not until(self.rec):
            self.lc.handle_timeout(50)
        for name in ("navigator", "pilot"):
            assert self.procs[name].poll() is None, f"{name} died:\n{self.output(name)}"
        return self.rec

    def output(self, name: str) -> str:
        path = self.tmp / f"{name}.out"
        return path.read_text()[-3000:] if path.exists() else ""

    def __exit__(self, *exc) -> None:
        for proc in self.procs.values():
            stop(proc, signal.SIGINT)
