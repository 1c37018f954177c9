"""Manager benchmark: latency from an input message to the resulting output
message, and the CPU a manager uses, over udpm (ttl=0) on this host.

The manager is build/bin/chasm-manager running the PILOT plan
(missions/pilot/pilot.chasm) in rpm mode, where rpm_control copies
setpoint.prop_rpm to actuators.prop_rpm: each SETPOINT carries a new rpm, and
its ACTUATORS answer is the first one that carries it back. Prints figures,
asserts nothing. Measurements, in one run:

  1. baseline: a Python process echoing raw LCM messages (the same client,
     the same sockets, no CHASM): the floor any manager latency sits on
  2. the manager on a driven clock: SETPOINT, NAV, then SIM.CLOCK; the cycle
     runs when the tick arrives, so this is the manager's own latency
  3. the manager on the system clock at 10 Hz and 100 Hz with NAV at 20 Hz
     and SETPOINT at 10 Hz (at random phases): latency, which now includes
     waiting for the next cycle (half a period on average), and CPU use from
     /proc (schedstat)

Run: tests/isolated_net.sh .venv/bin/python bench/manager_bench.py
"""

from __future__ import annotations

import argparse
import os
import random
import signal
import statistics
import subprocess
import sys
import time
from pathlib import Path

import lcm

from auv import actuators_t, chasm_status_t, nav_solution_t, setpoint_t, sim_clock_t
from auvlcm import programs

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
from lcm_proc import wait_for_line  # noqa: E402

BUILD = Path(os.environ.get("AUV_BUILD", ROOT / "build"))
BUILD = BUILD if BUILD.is_absolute() else ROOT / BUILD
URL = "udpm://239.255.76.67:7691?ttl=0"


def echo(url: str) -> int:
    """The baseline's other end: republish every BENCH.PING as BENCH.PONG."""
    lc = lcm.LCM(url)
    lc.subscribe("BENCH.PING", lambda _c, data: lc.publish("BENCH.PONG", data))
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(0))
    print("echo: ready", flush=True)
    while True:
        lc.handle_timeout(1000)


class Client:
    """Publishes inputs and times the answers."""

    def __init__(self, url: str) -> None:
        self.lc = lcm.LCM(url)
        self.rpm_seen: dict[float, int] = {}  # rpm value -> first arrival [ns]
        self.pong: dict[bytes, int] = {}
        self.costs: list[float] = []
        self.lc.subscribe("AUV1.ACTUATORS", self._on_act)
        self.lc.subscribe("BENCH.PONG", lambda _c, d: self.pong.setdefault(d, time.perf_counter_ns()))
        self.lc.subscribe("AUV1.CHASM.PILOT", self._on_status)

    def _on_act(self, _c, data) -> None:
        m = actuators_t.decode(data)
        self.rpm_seen.setdefault(round(m.prop_rpm, 3), time.perf_counter_ns())

    def _on_status(self, _c, data) -> None:
        m = chasm_status_t.decode(data)
        if m.run_state == chasm_status_t.RUN_RUNNING:
            self.costs.append(m.cycle_cost_us)

    def pump_until(self, done, timeout_s: float) -> bool:
        end = time.monotonic() + timeout_s
        while not done() and time.monotonic() < end:
            self.lc.handle_timeout(5)
        return done()

    def setpoint(self, utime: int, rpm: float) -> None:
        m = setpoint_t()
        m.utime, m.vehicle = utime, "BENCH"
        m.vertical_mode, m.depth_m = setpoint_t.VERTICAL_DEPTH, 10.0
        m.speed_mode, m.prop_rpm = setpoint_t.SPEED_RPM, rpm
        self.lc.publish("AUV1.SETPOINT", m.encode())

    def nav(self, utime: int) -> None:
        m = nav_solution_t()
        m.utime, m.vehicle, m.depth_m, m.u_mps = utime, "BENCH", 10.0, 1.5
        self.lc.publish("AUV1.NAV", m.encode())

    def clock(self, utime: int) -> None:
        m = sim_clock_t()
        m.utime, m.server_id, m.step_us = utime, "bench", 50_000
        self.lc.publish("SIM.CLOCK", m.encode())


def rpm_value(k: int) -> float:
    """Distinct from the last 199, never 0 (what `idle` sends), and within
    rpm_control's slew (500 rpm/s) of the one before: each is copied at once."""
    return round(0.01 + (k % 199) * 0.01, 3)


def start(cmd: list[str], ready: str) -> subprocess.Popen:
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        wait_for_line(p, ready, timeout=20)  # tests/lcm_proc.py: select() on a text pipe misses buffered lines
    except AssertionError as e:
        p.kill()
        raise SystemExit(f"manager_bench: {cmd[0]} did not start: {e}") from None
    return p


def stop(p: subprocess.Popen) -> None:
    p.send_signal(signal.SIGTERM)
    try:
        p.wait(10)
    except subprocess.TimeoutExpired:
        p.kill()
        p.wait()


def manager(url: str, clock: str, rate: float) -> subprocess.Popen:
    return start(
        programs.chasm_manager(
            BUILD,
            plan=ROOT / "missions" / "pilot" / "pilot.chasm",
            bind=ROOT / "missions" / "bindings" / "pilot.bind",
            vehicle="AUV1",
            name="PILOT",
            lcm_url=url,
            rate_hz=rate,
            clock=clock,
            plugin_path=[BUILD / "plugins"],
        ),
        "PILOT: running",
    )


def cpu_ns(pid: int) -> int:
    """CPU time of a process so far: schedstat (ns) where there is one, else stat (ticks)."""
    try:
        return int(Path(f"/proc/{pid}/schedstat").read_text().split()[0])
    except (OSError, ValueError, IndexError):
        f = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
        return (int(f[11]) + int(f[12])) * 1_000_000_000 // os.sysconf("SC_CLK_TCK")


def figures(name: str, lat_ns: list[int], extra: str = "") -> None:
    us = sorted(x / 1000 for x in lat_ns)
    p99 = us[min(len(us) - 1, int(0.99 * len(us)))]
    print(f"  {name:44} median {statistics.median(us):8.1f} us   p99 {p99:8.1f} us   n={len(us)}{extra}")


def bench_echo(c: Client, url: str, n: int) -> None:
    p = start([sys.executable, __file__, "--echo", url], "echo: ready")
    lat = []
    try:
        for k in range(n):
            key = k.to_bytes(8, "little")
            t0 = time.perf_counter_ns()
            c.lc.publish("BENCH.PING", key)
            if c.pump_until(lambda: key in c.pong, 5.0):
                lat.append(c.pong[key] - t0)
    finally:
        stop(p)
    figures("baseline: Python LCM echo (round trip)", lat)


def bench_driven(c: Client, url: str, n: int) -> None:
    p = manager(url, "sim", 20)
    lat, utime, k, warm = [], 1_000_000, 0, 0
    try:
        while len(lat) < n and k < 2 * n + 100:
            utime += 50_000
            rpm = rpm_value(k)
            k += 1
            c.rpm_seen.pop(rpm, None)
            t0 = time.perf_counter_ns()
            c.setpoint(utime, rpm)
            c.nav(utime)
            c.clock(utime)
            # the plan starts, and leaves `idle`, in the first few cycles
            if c.pump_until(lambda: rpm in c.rpm_seen, 5.0 if warm >= 5 else 0.2):
                warm += 1
                if warm > 5:
                    lat.append(c.rpm_seen[rpm] - t0)
    finally:
        stop(p)
    cost = statistics.median(c.costs) if c.costs else float("nan")
    figures("manager, driven clock (SETPOINT -> ACTUATORS)", lat, f"   step CPU median {cost:.1f} us")


def bench_system(c: Client, url: str, rate: float, seconds: float) -> None:
    p = manager(url, "system", rate)
    lat, sent = [], {}
    k, rng = 1, random.Random(7)
    next_nav = next_sp = time.monotonic()
    try:
        c.pump_until(lambda: False, 0.5)  # let it subscribe
        cpu0, wall0 = cpu_ns(p.pid), time.monotonic()
        while time.monotonic() - wall0 < seconds:
            now = time.monotonic()
            utime = int(time.time() * 1e6)
            if now >= next_nav:
                c.nav(utime)
                next_nav += 1 / 20
            if now >= next_sp:
                rpm = rpm_value(k)
                c.rpm_seen.pop(rpm, None)
                sent[rpm] = time.perf_counter_ns()
                c.setpoint(utime, rpm)
                # 10 Hz on average, at a random phase to the manager's cycle,
                # so the wait for the next cycle is sampled, not one offset
                next_sp = now + rng.uniform(0.05, 0.15)
                k += 1
            c.lc.handle_timeout(2)
            for rpm in [r for r in sent if r in c.rpm_seen]:
                lat.append(c.rpm_seen[rpm] - sent.pop(rpm))
        cpu = (cpu_ns(p.pid) - cpu0) / 1e9
        wall = time.monotonic() - wall0
    finally:
        stop(p)
    figures(
        f"manager, system clock {rate:5.0f} Hz",
        lat[5:],
        f"   CPU {100 * cpu / wall:5.2f} % of a core ({1e6 * cpu / (wall * rate):.0f} us per cycle)",
    )


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    programs.add_lcm_url_argument(ap, "LCM URL", default=URL)
    ap.add_argument("-n", type=int, default=2000, help="round trips per latency measurement")
    ap.add_argument("--seconds", type=float, default=15.0, help="length of each system-clock run")
    ap.add_argument("--echo", metavar="URL", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.echo:
        return echo(args.echo)
    if not (BUILD / "bin" / "chasm-manager").exists():
        print(f"{BUILD / 'bin' / 'chasm-manager'} is not built: run `make build`", file=sys.stderr)
        return 1
    c = Client(args.url)
    print(
        f"manager_bench: chasm-manager + missions/pilot/pilot.chasm over {args.url}, "
        f"{os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.2f}"
    )
    bench_echo(c, args.url, args.n)
    bench_driven(c, args.url, args.n)
    for rate in (10.0, 100.0):
        bench_system(c, args.url, rate, args.seconds)
    return 0


if __name__ == "__main__":
    sys.exit(main())
