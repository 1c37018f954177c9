"""Multi-HIL benchmark: failover time, clock synchronisation error, lockstep rate.

Prints figures, asserts nothing. Cases:
  1. failover: three environment nodes (`auv-multihil node`, the
     EnvNode every simulator runs), the server SIGKILLed; time from the kill
     to the first SIM.CLOCK of the new server (goal < 1 s), the largest gap
     between consecutive SIM.CLOCK values a client sees, and the jump: how far
     the new server's first value is off the line the old one was on.
  2. clock sync on one host: a server and two clients with injected offsets
     (tens of ms) and drifts (+-100 ppm); error of each client's global
     estimate against the server's global time at the same instant, after
     10 s to converge (goal p99 < 200 us).
  3. the same through the link-impairment relay (python/tools/bridges/lcm_relay.py),
     2 ms +- 1 ms each way and 5 % loss (goal p99 < 1 ms).
  4. lockstep: 3 simulators, each with its navigator manager, 0.1 s steps;
     steps per second of wall time once running.
Run: tests/isolated_net.sh .venv/bin/python bench/multihil_bench.py [--quick]
"""

from __future__ import annotations

import argparse
import os
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import lcm

from auv import sim_clock_t
from sim.multihil.probe import load_probe, percentile, probe_errors
from tools.launch.world import VehicleSpec, World

ROOT = Path(__file__).resolve().parents[1]

ENV = {**os.environ, "PYTHONPATH": str(ROOT / "build" / "gen" / "python")}


class Clocks:
    """SIM.CLOCK as heard, with monotonic receive times, from a thread."""

    def __init__(self, url: str) -> None:
        self.lc = lcm.LCM(url)
        self.seen: list[tuple[float, int, str, int]] = []
        self.lc.subscribe("SIM.CLOCK", self._on).set_queue_capacity(100000)
        self.stop = False
        threading.Thread(target=self._run, daemon=True).start()

    def _on(self, _ch: str, data: bytes) -> None:
        m = sim_clock_t.decode(data)
        self.seen.append((time.monotonic(), m.utime, m.server_id, m.step))

    def _run(self) -> None:
        while not self.stop:
            self.lc.handle_timeout(20)


def node(out: Path, node_id: str, url: str, prio: int, *extra) -> subprocess.Popen:
    return subprocess.Popen(
        [
            sys.executable,
            "-m",
            "tools.launch.multihil_cli",
            "node",
            "--id",
            node_id,
            "--lcm-url",
            url,
            "--priority",
            str(prio),
            *map(str, extra),
        ],
        stdout=open(out / f"{node_id}.out", "w"),
        stderr=subprocess.STDOUT,
        env=ENV,
        start_new_session=True,
    )


def end(procs) -> None:
    for p in procs:
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGINT)
    for p in procs:
        try:
            p.wait(10)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)


def wait_for(pred, timeout: float) -> bool:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline and not pred():
        time.sleep(0.01)
    return pred()


def failover(out: Path, url: str, runs: int) -> None:
    times, gaps, jumps = [], [], []
    for r in range(runs):
        clocks = Clocks(url)
        a = node(out, f"A{r}-sim", url, 30)
        wait_for(lambda: clocks.seen, 20)
        procs = [a, node(out, f"B{r}-sim", url, 20), node(out, f"C{r}-sim", url, 10)]
        time.sleep(3.0)
        os.killpg(a.pid, signal.SIGKILL)
        killed = time.monotonic()
        ok = wait_for(lambda: clocks.seen[-1][2] != f"A{r}-sim", 10)
        time.sleep(0.5)
        end(procs)
        clocks.stop = True
        if not ok:
            print(f"  run {r}: no new server within 10 s")
            continue
        seen = clocks.seen
        k = next(i for i, c in enumerate(seen) if c[2] != f"A{r}-sim")
        times.append(seen[k][0] - killed)
        gaps.append((seen[k][1] - seen[k - 1][1]) / 1e6)
        jumps.append(abs(seen[k][1] - (seen[k - 1][1] + (seen[k][0] - seen[k - 1][0]) * 1e6)) / 1e3)
    print(f"failover ({len(times)} runs, failover timeout 0.5 s, heartbeats 10 Hz, realtime):")
    print(
        f"  server death -> new server's first SIM.CLOCK: mean {sum(times) / len(times):.3f} s, "
        f"max {max(times):.3f} s   (goal < 1 s)"
    )
    print(f"  largest SIM.CLOCK gap at clients: {max(gaps):.3f} s of global time")
    print(
        f"  jump off the global time line: mean {sum(jumps) / len(jumps):.2f} ms, "
        f"max {max(jumps):.2f} ms (one clock period: 100 ms)"
    )


def sync(out: Path, url: str, seconds: float, relay: bool) -> None:
    procs = []
    client_url = url
    if relay:
        port = int(url.split(":")[-1].split("?")[0])
        client_url = url.replace(str(port), str(port + 500))
        procs.append(
            subprocess.Popen(
                [
                    sys.executable,
                    "-m",
                    "tools.bridges.lcm_relay",
                    "--in",
                    url,
                    "--out",
                    client_url,
                    "--channel",
                    r"SIM\..*",
                    "--both",
                    "--delay-ms",
                    "2",
                    "--jitter-ms",
                    "1",
                    "--loss",
                    "0.05",
                ],
                stdout=open(out / "relay.out", "w"),
                stderr=subprocess.STDOUT,
                env=ENV,
                start_new_session=True,
            )
        )
    tag = "R" if relay else "L"
    procs.append(
        node(out, f"S{tag}-sim", url, 9, "--probe", out / f"s{tag}.probe", "--offset-us", 12000, "--drift-ppm", -30)
    )
    time.sleep(1.5)
    clients = [("1", 55000, 90), ("2", -38000, -110)]
    for name, off, drift in clients:
        procs.append(
            node(
                out,
                f"C{tag}{name}-sim",
                client_url,
                1,
                "--probe",
                out / f"c{tag}{name}.probe",
                "--offset-us",
                off,
                "--drift-ppm",
                drift,
            )
        )
    start = time.monotonic()
    time.sleep(seconds)
    end(procs)
    server = load_probe(out / f"s{tag}.probe")
    errs: list[float] = []
    for name, _, _ in clients:
        errs += probe_errors(server, load_probe(out / f"c{tag}{name}.probe"), after_us=(start + 10.0) * 1e6)
    a = [abs(e) for e in errs]
    where = "through the relay (2 ms +- 1 ms, 5 % loss)" if relay else "on one host"
    goal = "1 ms" if relay else "200 us"
    print(
        f"clock sync {where}: 2 clients, offsets 55/-38 ms, drifts +90/-110 ppm "
        f"(server -30 ppm), {len(a)} samples after 10 s:"
    )
    if a:
        print(
            f"  |error| p50 {percentile(a, 0.5):.0f} us, p99 {percentile(a, 0.99):.0f} us, "
            f"max {max(a):.0f} us   (goal p99 < {goal})"
        )


def lockstep(out: Path, url: str, seconds: float) -> None:
    clocks = Clocks(url)
    world = World(out / "lockstep", url, ROOT / "build", ENV)
    specs = [VehicleSpec(f"AUV{i}", east_m=30.0 * i) for i in (1, 2, 3)]
    try:
        for s in specs:
            world.managers(s)
            world.simulator(s, "stepped", {"lockstep_participants": 6, "step_s": 0.1})
        if not wait_for(lambda: len(clocks.seen) > 50, 60):
            print("lockstep: the world did not start")
            return
        t0, n0 = time.monotonic(), clocks.seen[-1][3]
        time.sleep(seconds)
        t1, n1 = time.monotonic(), clocks.seen[-1][3]
    finally:
        world.stop()
        clocks.stop = True
    rate = (n1 - n0) / (t1 - t0)
    print(
        f"lockstep: 3 simulators + 3 navigator managers (6 participants), 0.1 s steps, "
        f"50 Hz physics:\n  {rate:.1f} steps/s = {rate * 0.1:.1f}x real time"
    )


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="fewer runs, shorter windows")
    a = ap.parse_args()
    url = "udpm://239.255.76.67:7910?ttl=0"
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp)
        print(f"multihil_bench ({os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f} at start)")
        failover(out, url, 2 if a.quick else 5)
        sync(out, url, 16 if a.quick else 30, relay=False)
        sync(out, url, 16 if a.quick else 30, relay=True)
        lockstep(out, url, 5 if a.quick else 15)
    return 0


if __name__ == "__main__":
    sys.exit(main())
