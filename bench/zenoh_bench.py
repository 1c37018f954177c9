"""Sites joined by Zenoh: clock-sync error and failover across the bridge,
and a 6-vehicle world split between two sites (docs/zenoh.md).

Two sites on this machine: two LCM worlds on different ports (ttl=0: two
multicast domains that never meet), each with its auv-zenoh-bridge, joined
by TCP on 127.0.0.1 (site A's bridge listens, site B's connects). Prints
figures, asserts nothing. Cases:
  1. clock sync across the bridge: the server node at site A, two client
     nodes at site B with injected offsets and drifts; error of each
     client's global-time estimate against the server's, after 10 s.
  2. failover across sites: server at A (priority 30), next best at B (20),
     third at A (10); the server SIGKILLed; time from the kill to the new
     server's first SIM.CLOCK heard at site A, and which site took over.
  3. six vehicles, three per site, scaled x2 with navigators: one server,
     every client at both sites in its world, environment mismatches, and
     the bridges' counters.
Run: tests/isolated_net.sh .venv/bin/python bench/zenoh_bench.py [--quick]
"""

from __future__ import annotations

import argparse
import os
import re
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from multihil_bench import ENV, Clocks, end, node, wait_for

from sim.multihil.probe import load_probe, percentile, probe_errors
from tools.launch.world import VehicleSpec, World

ROOT = Path(__file__).resolve().parents[1]

URL_A = "udpm://239.255.76.67:7921?ttl=0"
URL_B = "udpm://239.255.76.67:7922?ttl=0"
EP = "tcp/127.0.0.1:17460"


def bridges(out: Path) -> list[subprocess.Popen]:
    cmd = [sys.executable, "-m", "tools.bridges.zenoh_bridge", "--realm", "bench", "--stats-period", "2"]
    return [
        subprocess.Popen(
            cmd + args,
            stdout=open(out / f"bridge.{name}.out", "w"),
            stderr=subprocess.STDOUT,
            env=ENV,
            start_new_session=True,
        )
        for name, args in (
            ("A", ["--site", "A", "--lcm-url", URL_A, "--listen", EP]),
            ("B", ["--site", "B", "--lcm-url", URL_B, "--connect", EP]),
        )
    ]


def sync(out: Path, seconds: float) -> None:
    procs = bridges(out)
    time.sleep(1.5)
    procs.append(node(out, "SZ-sim", URL_A, 9, "--probe", out / "sz.probe", "--offset-us", 12000, "--drift-ppm", -30))
    time.sleep(1.5)
    clients = [("1", 55000, 90), ("2", -38000, -110)]
    for name, off, drift in clients:
        procs.append(
            node(
                out,
                f"CZ{name}-sim",
                URL_B,
                1,
                "--probe",
                out / f"cz{name}.probe",
                "--offset-us",
                off,
                "--drift-ppm",
                drift,
            )
        )
    start = time.monotonic()
    time.sleep(seconds)
    end(procs)
    server = load_probe(out / "sz.probe")
    errs: list[float] = []
    for name, _, _ in clients:
        errs += probe_errors(server, load_probe(out / f"cz{name}.probe"), after_us=(start + 10.0) * 1e6)
    a = [abs(e) for e in errs]
    print(
        f"clock sync across the Zenoh bridge (server at site A, 2 clients at site B, offsets 55/-38 ms, "
        f"drifts +90/-110 ppm), {len(a)} samples after 10 s:"
    )
    if a:
        print(f"  |error| p50 {percentile(a, 0.5):.0f} us, p99 {percentile(a, 0.99):.0f} us, max {max(a):.0f} us")


def failover(out: Path, runs: int) -> None:
    times, takers = [], []
    for r in range(runs):
        procs = bridges(out)
        time.sleep(1.5)
        clocks = Clocks(URL_A)
        a = node(out, f"A{r}-sim", URL_A, 30)
        wait_for(lambda: clocks.seen, 20)
        procs += [a, node(out, f"B{r}-sim", URL_B, 20), node(out, f"C{r}-sim", URL_A, 10)]
        time.sleep(4.0)
        os.killpg(a.pid, signal.SIGKILL)
        killed = time.monotonic()
        ok = wait_for(lambda: clocks.seen[-1][2] != f"A{r}-sim", 10)
        time.sleep(0.5)
        end(procs)
        clocks.stop = True
        if not ok:
            print(f"  run {r}: no new server within 10 s")
            continue
        k = next(i for i, c in enumerate(clocks.seen) if c[2] != f"A{r}-sim")
        times.append(clocks.seen[k][0] - killed)
        takers.append(clocks.seen[k][2])
    if times:
        print(f"failover across sites ({len(times)} runs; server at A killed, next best at B):")
        print(
            f"  kill -> new server's first SIM.CLOCK at site A: mean {sum(times) / len(times):.3f} s, "
            f"max {max(times):.3f} s; new servers: {', '.join(takers)}"
        )


def six(out: Path, seconds: float) -> None:
    procs = bridges(out)
    time.sleep(1.5)
    worlds = {
        "A": World(out / "six.A", URL_A, ROOT / "build", ENV),
        "B": World(out / "six.B", URL_B, ROOT / "build", ENV),
    }
    specs = [
        (("A" if i <= 3 else "B"), VehicleSpec(f"AUV{i}", priority=60 - 10 * i, east_m=25.0 * i)) for i in range(1, 7)
    ]
    try:
        for site, s in specs:
            worlds[site].managers(s)
        for site, s in specs:
            worlds[site].simulator(s, "scaled", {}, warp=2.0)
            if s.vehicle == "AUV1":
                wait_for(lambda: "server for term 1" in worlds["A"].output("AUV1.sim"), 30)
        time.sleep(seconds)
        before_stop = {s.vehicle: worlds[site].output(f"{s.vehicle}.sim") for site, s in specs}
    finally:
        for w in worlds.values():
            w.stop()
        end(procs)
    joined, servers, mism = [], [], []
    for site, s in specs:
        text = worlds[site].output(f"{s.vehicle}.sim")
        servers += re.findall(r"(\S+): server for term (\d+)", before_stop[s.vehicle])
        joined += [f"{s.vehicle}@{site}"] if "client of AUV1-sim" in text or s.vehicle == "AUV1" else []
        mism += [int(m) for m in re.findall(r"(\d+) mismatches", text)]
    print(
        f"six vehicles, 3 per site, scaled x2, {seconds:.0f} s: servers before the stop {servers}; in AUV1-sim's world: "
        f"{len(joined)}/6; environment sample mismatches {sum(mism)}"
    )
    for name in ("A", "B"):
        lines = (out / f"bridge.{name}.out").read_text().strip().splitlines()
        print(f"  {lines[-1] if lines else 'bridge ' + name + ': no output'}")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp)
        print(f"zenoh_bench ({os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f} at start)")
        sync(out, 16 if a.quick else 30)
        failover(out, 2 if a.quick else 5)
        six(out, 10 if a.quick else 20)
    return 0


if __name__ == "__main__":
    sys.exit(main())
