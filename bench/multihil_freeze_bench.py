"""A frozen environment server resumes (issue 12, item 4): how often does global
time run backwards?

Two simulators (python/sim with multi-HIL, scaled time x2, the damped REMUS),
each with its navigator manager (as `auv-multihil world`), share one
world. Each try SIGSTOPs whichever simulator serves for --freeze
seconds (3 s: longer than the failover timeout, so the other takes over),
SIGCONTs it, and listens for a few seconds. Over the SIM.CLOCK stream as
heard it counts the tries in which a value went backwards, and those in which
a message of an older term followed one of a newer term. Prints figures,
asserts nothing.

Run: tests/isolated_net.sh .venv/bin/python bench/multihil_freeze_bench.py [--tries 10]
     [--python-root DIR]   (another checkout's python/, e.g. the code before the fix)
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
import tempfile
import threading
import time
from pathlib import Path

import lcm

from auv import sim_clock_t
from auvlcm import programs
from tools.launch.world import VehicleSpec, World

ROOT = Path(__file__).resolve().parents[1]


class Clocks:
    """SIM.CLOCK as heard, from a thread: (utime, term, server)."""

    def __init__(self, url: str) -> None:
        self.lc = lcm.LCM(url)
        self.seen: list[tuple[int, int, str]] = []
        self.lc.subscribe("SIM.CLOCK", self._on).set_queue_capacity(100000)
        self.stop = False
        threading.Thread(target=self._run, daemon=True).start()

    def _on(self, _ch: str, data: bytes) -> None:
        m = sim_clock_t.decode(data)
        self.seen.append((m.utime, m.term, m.server_id))

    def _run(self) -> None:
        while not self.stop:
            self.lc.handle_timeout(20)

    def wait(self, until, timeout: float) -> bool:
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if until():
                return True
            time.sleep(0.02)
        return until()


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tries", type=int, default=10)
    ap.add_argument("--freeze", type=float, default=3.0, help="wall seconds stopped")
    ap.add_argument("--python-root", type=Path, default=ROOT / "python")
    ap.add_argument("--no-managers", action="store_true", help="simulators only")
    programs.add_lcm_url_argument(ap, "LCM URL", default="udpm://239.255.76.67:7791?ttl=0")
    a = ap.parse_args()
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(a.python_root), str(ROOT / "build" / "gen" / "python")])}
    out = Path(tempfile.mkdtemp(prefix="freeze-bench-"))
    world = World(out, a.url, env=env)
    clocks = Clocks(a.url)
    sims = {}
    for vid, prio, east in (("AUV1", 2, 0.0), ("AUV2", 1, 30.0)):
        spec = VehicleSpec(vid, priority=prio, east_m=east)
        if not a.no_managers:
            world.managers(spec)
        sims[f"{vid}-sim"] = world.simulator(spec, "scaled", {}, warp=2.0)
    back_tries = old_term_tries = 0
    try:
        if not clocks.wait(lambda: len(clocks.seen) > 20, 60.0):
            print("no SIM.CLOCK within 60 s", file=sys.stderr)
            return 1
        time.sleep(2.0)  # the second simulator has joined
        for k in range(a.tries):
            utime, term, server = clocks.seen[-1]
            start = len(clocks.seen)
            os.killpg(sims[server].pid, signal.SIGSTOP)
            time.sleep(a.freeze)
            os.killpg(sims[server].pid, signal.SIGCONT)
            clocks.wait(lambda: any(t > term for _, t, _ in clocks.seen[start:]), 10.0)
            time.sleep(2.0)
            seg = clocks.seen[start - 1 :]
            back = sum(b[0] < x[0] for x, b in zip(seg, seg[1:]))
            old = sum(b[1] < x[1] for x, b in zip(seg, seg[1:]))
            worst = min((b[0] - x[0] for x, b in zip(seg, seg[1:])), default=0)
            back_tries += back > 0
            old_term_tries += old > 0
            print(
                f"try {k + 1}: froze {server} (term {term}); after: server "
                f"{clocks.seen[-1][2]} term {clocks.seen[-1][1]}; {back} backwards "
                f"(worst {worst / 1e6:+.3f} s), {old} old-term after new",
                flush=True,
            )
    finally:
        clocks.stop = True
        for p in sims.values():
            if p.poll() is None:
                os.killpg(p.pid, signal.SIGCONT)
        world.stop()
    print(
        f"{a.tries} tries, {a.freeze:g} s freezes, code {a.python_root}: time ran backwards "
        f"in {back_tries}, an old term followed a newer one in {old_term_tries}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
