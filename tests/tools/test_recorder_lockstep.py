"""auv-recorder in a real lockstep world (python/sim/multihil: the
environment server steps time when every participant reported): while the
recorder is stopped, time does not advance; afterwards its log holds every
clock step and every TRUTH sample, none missing."""

from __future__ import annotations

import os
import signal
import subprocess
import time

import lcm

from auv import ground_truth_t, sim_clock_t
from tools.launch.world import VehicleSpec, World


def _clock_us(lst: list) -> int:
    return lst[-1] if lst else -1


def test_time_waits_for_a_stopped_recorder(tmp_path, lcm_url, child_env, build_dir):
    world = World(tmp_path / "w", lcm_url, build_dir, child_env)
    log, stats = tmp_path / "rec.lcmlog", tmp_path / "rec.json"
    lc = lcm.LCM(lcm_url)
    clocks: list[int] = []
    lc.subscribe("SIM.CLOCK", lambda _c, d: clocks.append(sim_clock_t.decode(d).utime))

    def pump(seconds: float, until=lambda: False) -> bool:
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline and not until():
            lc.handle_timeout(20)
        return until()

    rec = subprocess.Popen(
        [str(build_dir / "bin" / "auv-recorder"), "--lcm-url", lcm_url, "-f", str(log), "--stats", str(stats)],
        env=child_env,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
    )
    spec = VehicleSpec("AUV1")
    try:
        world.managers(spec)
        # three participants: the simulator, its NAVIGATOR and the recorder
        world.simulator(spec, "lockstep", {"lockstep_participants": 3, "step_s": 0.1, "lockstep_timeout_s": 60})
        assert pump(120, lambda: _clock_us(clocks) >= 3_000_000), {n: world.output(n)[-400:] for n in world.procs}
        os.kill(rec.pid, signal.SIGSTOP)
        pump(1.0)  # the step in flight when it stopped may still end
        held = _clock_us(clocks)
        pump(2.0)
        assert _clock_us(clocks) == held, "time went on without the recorder"
        os.kill(rec.pid, signal.SIGCONT)
        assert pump(60, lambda: _clock_us(clocks) >= held + 2_000_000), "time did not resume"
    finally:
        os.kill(rec.pid, signal.SIGCONT)
        world.stop()
        rec.send_signal(signal.SIGINT)
        out = rec.communicate(timeout=30)[0]
    assert rec.returncode == 0, out
    assert "dropped 0" in out and "missed 0" in out, out
    steps, truth = [], []
    for ev in lcm.EventLog(str(log), "r"):
        if ev.channel == "SIM.CLOCK":
            steps.append(sim_clock_t.decode(ev.data).utime)
        elif ev.channel == "AUV1.TRUTH":
            truth.append(ground_truth_t.decode(ev.data).utime)
    run = sorted(set(s for s in steps if s > 0))
    assert run and all(b - a == 100_000 for a, b in zip(run, run[1:])), "a clock step is missing from the log"
    dt = [b - a for a, b in zip(truth, truth[1:])]
    assert len(truth) > 30 and max(dt) <= 1.5 * sorted(dt)[len(dt) // 2], "a TRUTH sample is missing"
