"""A stepped world for modem tests: several simulator processes, one per
vehicle, on a private LCM URL, advanced by SIM.CLOCK from the test, one
physics step at a time. After each tick the test waits until every
simulator has published its truth for that step, so everything the
simulators published up to that step has arrived (one socket per process
keeps its order): a message seen after tick k was published at step <= k."""

from __future__ import annotations

import subprocess
import sys
import time
from collections import defaultdict
from pathlib import Path

import lcm
from lcm_proc import pump, stop, wait_for_line

from auv import chasm_status_t, ground_truth_t, modem_rx_t, modem_status_t, modem_tx_t, peer_report_t, sim_clock_t
from auvlcm.rx import Receiver

STEP_US = 20_000  # one physics step at 50 Hz
T0_US = 100_000_000  # the world starts at 100 s
# a simulator judges frames two lockstep clocks back (sim/modem/node.py): a
# frame that arrived at step k is delivered at step k + 2
LAG_CLOCKS = 2

SIM_CONFIG = """
vehicle: {{id: {vid}}}
simulation:
  clock: lockstep
  physics_rate_hz: 50
  truth_rate_hz: 50
  command_timeout_s: 100000
  lcm_url: "{url}"
initial: {{north_m: {north}, east_m: {east}, depth_m: {depth}}}
environment:
  seed: 5
  bathymetry: "flat:depth=300"
  sound_speed_mps: 1490.0
  sound_speed_gradient_per_m: 0.02
sensors:
  ins: {{rate_hz: 10}}
modem:
{modem}
"""


class World:
    def __init__(self, url: str, tmp_path: Path, env: dict) -> None:
        self.url, self.tmp, self.env = url, tmp_path, env
        self.lc = lcm.LCM(url)
        self.rx = Receiver(self.lc)
        self.procs: dict[str, subprocess.Popen] = {}
        self.sims: list[str] = []
        self.managers: dict[str, int] = {}  # status channel -> last status utime
        self.truth: dict[str, dict[int, tuple]] = defaultdict(dict)
        self.msgs: dict[str, list] = defaultdict(list)
        self.arrived_at: dict[str, list[tuple[int, object]]] = defaultdict(list)
        self.utime = T0_US - STEP_US
        self.tx_seq = 0

    # ------------------------------------------------------------ processes
    def add_sim(self, vid: str, north: float, east: float, depth: float, modem: dict | None = None) -> None:
        lines = "\n".join(f"  {k}: {v}" for k, v in (modem or {}).items()) or "  enabled: true"
        cfg = self.tmp / f"{vid}.yaml"
        cfg.write_text(SIM_CONFIG.format(vid=vid, url=self.url, north=north, east=east, depth=depth, modem=lines))
        self.rx.subscribe(f"{vid}.TRUTH", ground_truth_t, self._on_truth, queue_capacity=10000)
        self.watch(f"{vid}.MODEM_RX", modem_rx_t)
        self.watch(f"{vid}.MODEM_STATUS", modem_status_t)
        proc = subprocess.Popen(
            [sys.executable, "-m", "sim", str(cfg)],
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            env=self.env,
        )
        self.procs[vid] = proc
        self.sims.append(vid)
        wait_for_line(proc, "running", timeout=60)

    def add_process(self, name: str, proc: subprocess.Popen) -> None:
        self.procs[name] = proc

    def add_manager(self, vehicle: str, name: str, proc: subprocess.Popen, period_us: int = 100_000) -> None:
        """A manager taking part in the lockstep: ticks wait for each of its
        cycles (its status), so it never falls behind on a loaded machine."""
        self.procs[f"{vehicle}.{name}"] = proc
        self.period_us = period_us
        channel = f"{vehicle}.CHASM.{name}"
        self.watch(channel, chasm_status_t)
        self.managers[channel] = -1

    def wait_for_managers(self, timeout_s: float = 60.0) -> None:
        """Tick until every manager has run its first cycle (it subscribes late)."""
        deadline = time.monotonic() + timeout_s
        while not all(self.msgs[ch] for ch in self.managers):
            assert time.monotonic() < deadline, "a manager never ran a cycle"
            for proc in self.procs.values():
                assert proc.poll() is None, f"a process exited: {proc.args}"
            self.tick()
            pump(self.lc, lambda: all(self.msgs[ch] for ch in self.managers), timeout=0.05)

    def watch(self, channel: str, typ: type) -> None:
        def on_msg(ch, m):
            self.msgs[ch].append(m)
            self.arrived_at[ch].append((self.utime, m))

        self.rx.subscribe(channel, typ, on_msg, queue_capacity=10000)

    def close(self) -> dict[str, str]:
        """Stop every process (SIGINT); their outputs, failing on a bad exit."""
        outs, codes = {}, {}
        for name, proc in self.procs.items():
            codes[name] = stop(proc)
            outs[name] = proc.stdout.read() if proc.stdout else ""
        bad = {n: c for n, c in codes.items() if c != 0}
        assert not bad, f"processes exited badly: {bad}\n{outs}"
        return outs

    # ---------------------------------------------------------------- clock
    def _on_truth(self, _ch: str, m) -> None:
        self.truth[m.vehicle][m.utime] = tuple(m.eta[:3])

    def tick(self, n: int = 1) -> None:
        sims = self.sims
        for _ in range(n):
            self.utime += STEP_US
            c = sim_clock_t()
            c.utime, c.server_id, c.mode, c.step_us = self.utime, "test", sim_clock_t.MODE_LOCKSTEP, STEP_US
            self.lc.publish("SIM.CLOCK", c.encode())
            ok = pump(self.lc, lambda: all(self.utime in self.truth[v] for v in sims), timeout=20)
            assert ok, f"a simulator did not finish step {self.utime}"
            for ch in self.managers:
                msgs = self.msgs[ch]
                if msgs and self.utime >= msgs[-1].utime + self.period_us:
                    due = msgs[-1].utime + self.period_us
                    ok = pump(self.lc, lambda: msgs[-1].utime >= due, timeout=20)
                    assert ok, f"{ch} did not run its cycle at {due}"

    def run_for(self, seconds: float) -> None:
        self.tick(int(round(seconds * 1e6 / STEP_US)))

    # ---------------------------------------------------------------- modem
    def send(self, vid: str, n_bytes: int, dst: str = "", seq: int | None = None) -> modem_tx_t:
        """Offer a frame to vid's modem; it is taken at the current sim time."""
        self.tx_seq += 1
        m = modem_tx_t()
        m.utime, m.vehicle, m.dst_vehicle = self.utime, vid, dst
        m.seq = self.tx_seq if seq is None else seq
        m.kind, m.n_bytes, m.payload = modem_tx_t.KIND_RAW, n_bytes, bytes(i % 251 for i in range(n_bytes))
        self.lc.publish(f"{vid}.MODEM_TX", m.encode())
        return m

    def status(self, vid: str) -> modem_status_t:
        return self.msgs[f"{vid}.MODEM_STATUS"][-1]


def watch_peer(world: World, vid: str, other: str) -> str:
    ch = f"{vid}.PEER.{other}"
    world.watch(ch, peer_report_t)
    return ch
