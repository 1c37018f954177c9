"""Simulator benchmark: physics steps per second and real-time factor.

Prints figures, asserts nothing. Three measurements in one run, so their
ratios are meaningful on whatever machine runs them:
  1. the bare RK4 integrator (Dynamics.step, inputs fixed)       = baseline
  2. the full vehicle model (actuators + environment + RK4 + seabed)
  3. the full model with every sensor sampled and encoded (no network)
  4. the HIL loop publishing everything over LCM (ttl=0), as fast as it can
Run: tests/isolated_net.sh .venv/bin/python bench/sim_bench.py
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "python")]
import auvlcm  # noqa: E402,F401

from sim.config import load  # noqa: E402
from sim.dynamics import Dynamics  # noqa: E402
from sim.hil import build_model, build_sensors  # noqa: E402
from sim.vehicle import REMUS100  # noqa: E402

CONFIG = ROOT / "missions" / "sim" / "remus100.yaml"
SIM_SECONDS = 120.0


def rate(fn, steps: int) -> float:
    t0 = time.perf_counter()
    fn(steps)
    return steps / (time.perf_counter() - t0)


def bare(steps: int) -> None:
    d = Dynamics(REMUS100, 0.02)
    d.set_state([0, 0, 10, 0, 0, 0], [1.5, 0, 0, 0, 0, 0])
    d.thrust = 3.86
    for _ in range(steps):
        d.step()


def model_only(steps: int) -> None:
    m = build_model(load(CONFIG))
    for _ in range(steps):
        m.step()


def with_sensors(steps: int) -> None:
    cfg = load(CONFIG)
    m = build_model(cfg)
    sensors = build_sensors(cfg, m)
    tr = m.truth()
    for _ in range(steps):
        m.step()
        m.truth(tr)
        for s in sensors:
            msg = s.poll(tr)
            if msg is not None:
                msg.encode()


def hil(seconds: float) -> tuple[float, int]:
    import contextlib
    import io

    from sim.hil import Simulator
    cfg = load(CONFIG)
    cfg.sim.duration_s = seconds
    cfg.sim.lcm_url = "udpm://239.255.76.67:7799?ttl=0"
    sim = Simulator(cfg, fast=True)
    t0 = time.perf_counter()
    with contextlib.redirect_stdout(io.StringIO()):
        sim.run()
    wall = time.perf_counter() - t0
    return seconds / wall, sim.published


def main() -> None:
    dt = 0.02
    n = int(SIM_SECONDS / dt)
    base = rate(bare, n)
    full = rate(model_only, n)
    sens = rate(with_sensors, n)
    print(f"sim_bench: REMUS 100, RK4 at {1 / dt:.0f} Hz, {SIM_SECONDS:.0f} s of sim time per case")
    print(f"  bare integrator (baseline)    {base:9.0f} steps/s   {base * dt:7.1f}x real time")
    print(f"  vehicle model                 {full:9.0f} steps/s   {full * dt:7.1f}x real time"
          f"   {full / base:.2f} of baseline")
    print(f"  model + all sensors (encoded) {sens:9.0f} steps/s   {sens * dt:7.1f}x real time"
          f"   {sens / base:.2f} of baseline")
    try:
        rtf, published = hil(SIM_SECONDS)
        print(f"  HIL loop over LCM, all output {rtf * 50:9.0f} steps/s   {rtf:7.1f}x real time"
              f"   {rtf / (base * dt):.2f} of baseline, {published / SIM_SECONDS:.0f} msgs per sim s")
    except Exception as exc:  # no multicast route: say so, still print the rest
        print(f"  HIL loop over LCM: skipped ({exc}); run under tests/isolated_net.sh")


if __name__ == "__main__":
    main()
