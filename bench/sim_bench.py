"""Simulator benchmark: physics steps per second and real-time factor.

Prints figures, asserts nothing. Every case runs in the same process, in
rounds (each case once per round), and keeps its best round: on a shared
machine the best of several short runs is the figure least disturbed by
other processes. The cases:
  1. the bare RK4 integrator (Dynamics.step, inputs fixed)        = baseline
     (the step is C, c/dynamics/: this is the cost of one call from Python
     with the inputs handed over; printed in microseconds a step too)
  2. the full vehicle model (actuators + environment + RK4 + seabed)
  3. the simulator's own loop with LCM replaced by a null sink, sensor
     messages as lcm-gen objects encoded by their encode() (the old path)
  4. the same loop as it runs: sensors packed straight into bytes where
     they can be (sim.wire): everything but the network
  5. over LCM (ttl=0), as fast as it can, the loop publishing each message
     itself (simulation.publish_thread: false, the path before the sender
     thread): the baseline of
  6. over LCM with the sender thread (the default).
  For 3-6, the wall-clock factor (also the median over the rounds), the
  factor from the loop thread's CPU time (time.thread_time) and from the
  whole process's (time.process_time: the sender thread and liblcm's
  receive thread included). On a machine shared with other work, wall time
  also counts the time the loop waited for a core.
Run: tests/isolated_net.sh .venv/bin/python bench/sim_bench.py [--rounds N] [--physics-only]
"""

from __future__ import annotations

import argparse
import contextlib
import io
import os
import statistics
import time
from pathlib import Path

from auvlcm.offline import OfflineLcm
from sim.config import load
from sim.dynamics import Dynamics
from sim.hil import Simulator, build_model
from sim.vehicle import REMUS100

ROOT = Path(__file__).resolve().parents[1]

CONFIG = ROOT / "missions" / "sim" / "remus100.yaml"
DT = 0.02
GOAL_X = 200.0


def bare(steps: int) -> None:
    d = Dynamics(REMUS100, DT)
    d.set_state([0, 0, 10, 0, 0, 0], [1.5, 0, 0, 0, 0, 0])
    d.thrust = 3.86
    for _ in range(steps):
        d.step()


def model_only(steps: int) -> None:
    m = build_model(load(CONFIG))
    for _ in range(steps):
        m.step()


class _LcmGenSimulator(Simulator):
    """The same loop with message objects and lcm-gen's encode() for every sensor."""

    def __init__(self, *args, **kwargs) -> None:
        super().__init__(*args, **kwargs)

        def lcmgen(sen):
            def poll(tr):
                msg = sen.poll(tr)
                return None if msg is None else msg.encode()

            return poll

        self._sensor_polls = [(sen.next_due, lcmgen(sen), ch) for sen, ch in self._sensor_channels]


def _run(sim: Simulator, seconds: float) -> dict:
    w0, c0, p0 = time.perf_counter(), time.thread_time(), time.process_time()
    with contextlib.redirect_stdout(io.StringIO()):
        sim.run()
    wall, cpu = time.perf_counter() - w0, time.thread_time() - c0
    proc = time.process_time() - p0
    out = {"wall_x": seconds / wall, "cpu_x": seconds / cpu, "proc_x": seconds / proc, "msgs": sim.published / seconds}
    # Let go of its LCM instance (see Simulator.close), or every earlier
    # round's liblcm receive thread would still be woken by each packet of
    # the later rounds.
    sim.close()
    return out


def _config(seconds: float):
    cfg = load(CONFIG)
    cfg.sim.duration_s = seconds
    cfg.sim.lcm_url = "udpm://239.255.76.67:7799?ttl=0"
    return cfg


def _offline(cls: type, seconds: float) -> dict:
    lc = OfflineLcm(keep=False)
    try:
        return _run(cls(_config(seconds), fast=True, lc=lc), seconds)
    finally:
        lc.close()


def loop_lcmgen(seconds: float) -> dict:
    return _offline(_LcmGenSimulator, seconds)


def loop_no_network(seconds: float) -> dict:
    return _offline(Simulator, seconds)


def hil(seconds: float) -> dict:
    return _run(Simulator(_config(seconds), fast=True), seconds)


def hil_in_loop(seconds: float) -> dict:
    cfg = _config(seconds)
    cfg.sim.publish_thread = False
    return _run(Simulator(cfg, fast=True), seconds)


def _cpu_times() -> list[int] | None:
    """The machine's CPU time counters (/proc/stat), None where there are none."""
    try:
        with open("/proc/stat") as f:
            return [int(v) for v in f.readline().split()[1:]]
    except (OSError, ValueError):
        return None


def _machine_line(before: list[int] | None, load: float) -> str:
    """What the figures were measured on: a busy machine, or a virtual machine
    whose host gave its time to others (steal), shows lower figures."""
    after = _cpu_times()
    line = f"machine: {os.cpu_count()} CPUs, load average {load:.2f} at the start"
    if before and after and len(after) > 7:
        d = [a - b for a, b in zip(after, before)]
        total = sum(d[:8]) or 1
        line += (
            f", during the run {100 * (total - d[3] - d[4]) / total:.0f} % busy, "
            f"{100 * d[7] / total:.0f} % stolen by the host"
        )
    return line


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--seconds", type=float, default=30.0, help="sim seconds per case per round")
    ap.add_argument("--physics-only", action="store_true", help="only the integrator and the vehicle model (1, 2)")
    args = ap.parse_args()
    n = int(args.seconds / DT)
    physics = [("bare integrator (baseline)", bare), ("vehicle model", model_only)]
    loops = [
        ("loop, no network, lcm-gen encode", loop_lcmgen),
        ("loop, no network (sensors+encode)", loop_no_network),
        ("HIL over LCM, loop publishes", hil_in_loop),
        ("HIL over LCM, all output", hil),
    ]
    if args.physics_only:
        loops = []
    best = {name: 0.0 for name, _ in physics}
    runs: dict[str, list[dict]] = {name: [] for name, _ in loops}
    errors: dict[str, str] = {}
    load, cpu0 = os.getloadavg()[0], _cpu_times()
    for _ in range(args.rounds):
        for name, fn in physics:
            t0 = time.perf_counter()
            fn(n)
            best[name] = max(best[name], n / (time.perf_counter() - t0))
        for name, fn in loops:
            if name in errors:
                continue
            try:
                runs[name].append(fn(args.seconds))
            except Exception as exc:  # no multicast route: say so, still print the rest
                errors[name] = str(exc)
    base = best["bare integrator (baseline)"]
    machine = _machine_line(cpu0, load)
    print(
        f"sim_bench: REMUS 100, RK4 at {1 / DT:.0f} Hz, default configuration "
        f"({CONFIG.relative_to(ROOT)}), best of {args.rounds} rounds of {args.seconds:.0f} sim s"
    )
    print(f"  {'case':44} {'steps/s':>8}  {'real time':>9}  {'of baseline':>11}")
    for name, _ in physics:
        r = best[name]
        print(f"  {name:44} {r:8.0f}  {r * DT:8.1f}x  {r / base:11.2f}   {1e6 / r:.2f} us a step")
    for name, _ in loops:
        if name in errors:
            print(f"  {name}: skipped ({errors[name]}); run under tests/isolated_net.sh")
            continue
        rs = runs[name]
        for kind, key in (("wall", "wall_x"), ("loop CPU", "cpu_x"), ("process CPU", "proc_x")):
            x = max(r[key] for r in rs)
            extra = ""
            if key == "wall_x":
                extra = f"   median {statistics.median(r[key] for r in rs):.0f}x, {rs[0]['msgs']:.0f} msgs per sim s"
            print(f"  {name + ' (' + kind + ')':44} {x / DT:8.0f}  {x:8.1f}x  {x / (base * DT):11.2f}{extra}")
    if "HIL over LCM, all output" in runs and "HIL over LCM, all output" not in errors:
        x = max(r["wall_x"] for r in runs["HIL over LCM, all output"])
        print(
            f"  goal >= {GOAL_X:.0f}x over LCM on wall time: {'met' if x >= GOAL_X else 'NOT met'} "
            f"({x:.0f}x, best round)"
        )
    print(f"  {machine}")


if __name__ == "__main__":
    main()
