"""`make demo`'s scenario, shortened: the simulator and a CHASM navigator close
the loop over real LCM, the logger records it, and the plan's transitions
happen for the reasons the plan gives."""

from __future__ import annotations

import subprocess
import sys

from auvlcm.log import LogStats, read_events
from conftest import BUILD, ROOT


def test_demo_runs_the_closed_loop_and_leaves_a_decodable_log(tmp_path, lcm_url, child_env):
    run = subprocess.run([sys.executable, ROOT / "python" / "tools" / "demo.py", "--out", tmp_path,
                          "--url", lcm_url, "--build", BUILD, "--duration", "120", "--warp", "25"],
                         env=child_env, capture_output=True, text=True, timeout=240)
    assert run.returncode == 0, run.stdout + run.stderr
    stats = LogStats()
    states, depths = [], []
    for ev in read_events(tmp_path / "depth_band.lcmlog", stats):
        if ev.channel == "AUV1.CHASM.NAVIGATOR" and ev.msg.path_len:
            path = "/".join(ev.msg.active_path)
            if not states or states[-1][0] != path:
                states.append((path, ev.msg.last_condition, ev.msg.utime))
        if ev.channel == "AUV1.TRUTH":
            depths.append((ev.msg.utime, ev.msg.eta[2]))
    assert stats.undecodable == 0 and stats.decoded > 5000
    names = [s[0] for s in states]
    assert names[:3] == ["transit/dive", "transit/climb", "transit/dive"], states
    assert states[1][1] == "too_deep" and states[2][1] == "too_shallow"
    assert names[-1] == "surface" and states[-1][1] == "elapsed > $duration"
    assert abs(states[-1][2] / 1e6 - 90.0) < 0.2  # the plan's 90 s, on the global clock
    at_surface_cmd = next(d for t, d in depths if t >= states[-1][2])
    assert max(d for _, d in depths) > 6.0          # it dove into the band
    assert depths[-1][1] < at_surface_cmd - 0.2       # and floats up once the prop stops
