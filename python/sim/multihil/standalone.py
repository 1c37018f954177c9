"""`auv-multihil node`: an environment node without a vehicle.

The same EnvNode a simulator runs, in a process of its own: it stands for a
simulator in election, failover and clock tests and benchmarks (cheap to
start many), serves a world on its own, or watches one. Its position stays
at the origin; in lockstep it is a participant that finishes each step at
once. --probe FILE writes "monotonic_us global_us role term" every 20 ms, so
a benchmark can compare clocks of processes on one machine.
"""

from __future__ import annotations

import argparse
import select
import signal
import sys
import time

import lcm

from auvlcm import programs
from auvlcm.url import check_local
from sim import clock_modes
from sim.environment import Environment, EnvParams
from sim.multihil.clock import LocalClock, mono_us
from sim.multihil.election import Timing
from sim.multihil.lockstep import Participation
from sim.multihil.node import EnvNode, NodeConfig


def parse(argv: list[str]) -> argparse.Namespace:
    ap = argparse.ArgumentParser(
        prog="auv-multihil node", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--id", required=True, help="client id, e.g. AUV1-sim")
    ap.add_argument("--vehicle", default="", help="vehicle id (default: the id up to '-')")
    ap.add_argument("--priority", type=int, default=0)
    programs.add_lcm_url_argument(ap, "LCM URL (ttl=0; ttl=1 only inside a test netns)", required=True)
    ap.add_argument("--mode", choices=clock_modes.MODES, default="realtime")
    ap.add_argument("--warp", type=float, default=1.0)
    ap.add_argument("--step", type=float, default=0.1, help="lockstep step [s]")
    ap.add_argument("--expect", type=int, default=0, help="lockstep participants before step 0")
    ap.add_argument("--offset-us", type=float, default=0.0, help="inject a local clock offset")
    ap.add_argument("--drift-ppm", type=float, default=0.0, help="inject a local clock drift")
    ap.add_argument("--join-window", type=float, default=1.0)
    ap.add_argument("--failover-timeout", type=float, default=0.5)
    ap.add_argument("--sync-hz", type=float, default=10.0)
    ap.add_argument("--needs", default="current,bathymetry", help="comma-separated variables")
    ap.add_argument("--duration", type=float, default=0.0, help="wall seconds (0: until stopped)")
    ap.add_argument("--probe", help="write clock probes to this file")
    return ap.parse_args(argv)


def main(argv: list[str]) -> int:
    a = parse(argv)
    try:
        url = check_local(a.url)
    except ValueError as exc:
        print(f"multihil: {exc}", file=sys.stderr)
        return 2
    lc = lcm.LCM(url)
    cfg = NodeConfig(
        a.id,
        a.vehicle or a.id.split("-")[0].upper(),
        a.priority,
        [v for v in a.needs.split(",") if v],
        1.0,
        a.mode,
        a.warp,
        step_s=a.step,
        lockstep_expect=a.expect,
        sync_hz=a.sync_hz,
        timing=Timing(join_window_s=a.join_window, failover_timeout_s=a.failover_timeout),
    )
    holder: list[EnvNode] = []

    def position() -> tuple[float, float, float, float] | None:
        g = holder[0].global_now_us()
        return None if g is None else (g / 1e6, 0.0, 0.0, 0.0)

    node = EnvNode(
        cfg,
        lc,
        Environment(EnvParams()),
        LocalClock(a.offset_us, a.drift_ppm),
        position=position,
        log=lambda s: print(s, flush=True),
    )
    holder.append(node)
    part = Participation(f"{cfg.vehicle}.sim", lambda m: lc.publish("SIM.LOCKSTEP", m.encode()))
    stop = []
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, lambda *_: stop.append(1))
    probe = open(a.probe, "w", buffering=1) if a.probe else None
    print(
        f"multihil: node {a.id} priority {a.priority} mode {a.mode} offset {a.offset_us:g} us "
        f"drift {a.drift_ppm:g} ppm",
        flush=True,
    )
    t_end = time.monotonic() + a.duration if a.duration > 0 else float("inf")
    next_probe = 0.0
    seen_clocks = 0
    fd = lc.fileno()
    while not stop and time.monotonic() < t_end:
        node.poll()
        if a.mode == "lockstep":
            part.poll()
            c = node.last_clock
            if c is not None and node.clock_messages != seen_clocks:
                seen_clocks = node.clock_messages  # each clock message, repeats included
                part.on_clock(c.step, c.utime)
                part.done()
        now = time.monotonic()
        if probe and now >= next_probe:
            next_probe = now + 0.02
            g = node.global_now_us()
            if g is not None:
                probe.write(f"{mono_us():.1f} {g:.1f} {node.role} {node.term}\n")
        ready, _, _ = select.select([fd], [], [], 0.005)
        while ready:
            lc.handle()
            ready, _, _ = select.select([fd], [], [], 0.0)
    if a.mode == "lockstep":
        part.leave()
    node.stop()
    print(
        f"multihil: node {a.id} stopped: role {node.role} term {node.term}, "
        f"{node.clock_messages} clock messages, {node.clock_regressions} regressions, "
        f"{node.samples_received} samples, {node.sample_mismatches} mismatches, "
        f"{node.rx.decode_errors} decode errors, {node.election.gaps} gaps, "
        f"{node.drops.summary()}",
        flush=True,
    )
    return 0
