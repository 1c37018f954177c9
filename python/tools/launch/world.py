"""Start a multi-HIL world on one machine: N vehicles, each a simulator with
its managers, in one environment, optionally recorded by lcm-logger.

Used by the tests, the benchmarks and `auv-multihil world`. Each vehicle gets
its own configuration (the base one with its vehicle id, start position and
priority) and one navigator manager flying missions/demo/depth_band.chasm
straight onto the actuators.

Why a second starter beside the launcher (launcher.py): here the simulators
keep the world's time themselves (the elected environment server's clock, with
failover when it dies, docs/multihil.md), which is what the multi-HIL tests
exercise; the launcher replaces that clock with its own lockstep clock. Both
build every command line with auvlcm.programs.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

from auvlcm import programs
from sim import clock_modes

ROOT = Path(__file__).resolve().parents[3]
BASE_CONFIG = ROOT / "missions" / "sim" / "remus100_multihil.yaml"
PLAN = ROOT / "missions" / "demo" / "depth_band.chasm"
BIND = ROOT / "missions" / "bindings" / "direct_actuators.bind"


@dataclass
class VehicleSpec:
    vehicle: str
    priority: int = 0
    east_m: float = 0.0
    clock_offset_us: float = 0.0
    clock_drift_ppm: float = 0.0
    managers: list[str] = field(default_factory=lambda: ["NAVIGATOR"])
    edits: list[tuple[str, str]] = field(default_factory=list)  # (old, new) in its config


def vehicle_config(out: Path, spec: VehicleSpec, multihil: dict, base: Path = BASE_CONFIG) -> Path:
    """The base configuration with this vehicle's id, start and multihil section."""
    text = base.read_text()
    assert "id: AUV1" in text and "multihil:" not in text, f"{base}: not a usable base"
    text = text.replace("id: AUV1", f"id: {spec.vehicle}")
    mh = {
        "priority": spec.priority,
        "clock_offset_us": spec.clock_offset_us,
        "clock_drift_ppm": spec.clock_drift_ppm,
        **multihil,
    }
    text += "\nmultihil:\n" + "".join(f"  {k}: {v}\n" for k, v in mh.items())
    text = text.replace("initial: {depth_m: 0.0}", f"initial: {{depth_m: 0.0, east_m: {spec.east_m}}}")
    for old, new in spec.edits:
        assert old in text, f"{base}: no {old!r} to edit"
        text = text.replace(old, new)
    path = out / f"{spec.vehicle}.yaml"
    path.write_text(text)
    return path


class World:
    def __init__(
        self, out: Path, url: str, build: Path = ROOT / "build", env: dict | None = None, python: str = sys.executable
    ) -> None:
        self.out, self.url, self.build, self.python = out, url, build, python
        self.env = dict(env or os.environ)
        self.env.setdefault("PYTHONPATH", str(build / "gen" / "python"))  # that build's message types
        self.procs: dict[str, subprocess.Popen] = {}
        out.mkdir(parents=True, exist_ok=True)

    def _start(self, name: str, cmd: list, prefix: list[str] | None = None) -> subprocess.Popen:
        p = subprocess.Popen(
            [*(prefix or []), *map(str, cmd)],
            stdout=open(self.out / f"{name}.out", "w"),
            stderr=subprocess.STDOUT,
            env=self.env,
            start_new_session=True,
        )
        self.procs[name] = p
        return p

    def logger(self, log: Path, prefix: list[str] | None = None) -> None:
        import lcm

        self._start("logger", programs.lcm_logger(Path(lcm.LCM_BIN_DIR).resolve(), lcm_url=self.url, log=log), prefix)
        time.sleep(0.3)

    def simulator(
        self,
        spec: VehicleSpec,
        clock: str,
        multihil: dict,
        warp: float = 1.0,
        duration: float = 0.0,
        prefix: list[str] | None = None,
        name: str | None = None,
    ) -> subprocess.Popen:
        cfg = vehicle_config(self.out, spec, {"enabled": "true", **multihil})
        cmd = programs.simulator(
            cfg,
            lcm_url=self.url,
            clock=clock,
            warp=warp if clock == "scaled" else None,
            duration=duration or None,
            python=self.python,
        )
        return self._start(name or f"{spec.vehicle}.sim", cmd, prefix)

    def managers(
        self,
        spec: VehicleSpec,
        prefix: list[str] | None = None,
        plan: Path = PLAN,
        bind: Path = BIND,
        extra: list[str] | None = None,
    ) -> None:
        for name in spec.managers:
            cmd = programs.chasm_manager(
                self.build, plan=plan, bind=bind, vehicle=spec.vehicle, name=name, lcm_url=self.url, extra=extra or ()
            )
            self._start(f"{spec.vehicle}.{name}", cmd, prefix)

    def kill(self, name: str) -> None:
        p = self.procs[name]
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGKILL)
            p.wait()

    def stop(self, timeout: float = 10.0) -> None:
        """SIGINT everything (logger last, so it records the ends), SIGKILL stragglers."""
        order = [n for n in self.procs if n != "logger"] + (["logger"] if "logger" in self.procs else [])
        for name in order:
            p = self.procs[name]
            if p.poll() is None:
                os.killpg(p.pid, signal.SIGINT)
            try:
                p.wait(timeout)
            except subprocess.TimeoutExpired:
                self.kill(name)

    def output(self, name: str) -> str:
        return (self.out / f"{name}.out").read_text()


def main(argv: list[str]) -> int:
    """`auv-multihil world`: N vehicles in one world on this machine."""
    import argparse

    from auvlcm.url import check_local, default_url

    ap = argparse.ArgumentParser(prog="auv-multihil world", description=main.__doc__)
    ap.add_argument("--vehicles", type=int, default=3)
    ap.add_argument("--clock", type=clock_modes.argument, metavar="{realtime,scaled,lockstep}", default="scaled")
    ap.add_argument("--warp", type=float, default=4.0)
    ap.add_argument("--duration", type=float, default=60.0, help="sim seconds per simulator")
    ap.add_argument("--out", type=Path, default=ROOT / "build" / "multihil")
    programs.add_lcm_url_argument(ap, "LCM URL (default $LCM_DEFAULT_URL or the project's)", default=default_url())
    a = ap.parse_args(argv)
    if a.vehicles < 1 or a.duration <= 0:
        ap.error("--vehicles and --duration must be positive")
    try:
        url = check_local(a.url)
    except ValueError as exc:
        ap.error(str(exc))
    world = World(a.out, url)
    log = a.out / "world.lcmlog"
    world.logger(log)
    specs = [VehicleSpec(f"AUV{i}", priority=a.vehicles - i, east_m=30.0 * (i - 1)) for i in range(1, a.vehicles + 1)]
    lockstep = {"lockstep_participants": 2 * a.vehicles} if a.clock == clock_modes.LOCKSTEP else {}
    print(f"world: {a.vehicles} vehicles, {a.clock} clock, {a.duration:g} sim s, on {url}")
    try:
        for s in specs:
            world.managers(s)
            world.simulator(s, a.clock, lockstep, warp=a.warp, duration=a.duration)
        for s in specs:
            world.procs[f"{s.vehicle}.sim"].wait()
    except KeyboardInterrupt:
        pass
    finally:
        world.stop()
    print(f"world: outputs in {a.out}/ (one .out per process), log {log}")
    return 0
