"""The launcher's default fast time is deterministic (issue 14, item 1): the
same scenario twice gives the same messages, with the same contents, in the
same order, per channel, in the recorded log (only the receive stamps differ).
The second run is paced (`--time scaled`): the pace changes nothing else.

Two vehicles, one on the onboard filter (auv-nav), each with two managers, a
few seconds of sim time. Left out of the comparison, and why:
- SIM.ANNOTATION (the launcher's notes: process ids, wall times), <X>.HEALTH
  (CPU load), LCM_SELF_TEST;
- lockstep REGISTER and LEAVE (wall-paced registration, the asynchronous end);
- chasm_status_t.cycle_cost_us (the CPU time of a cycle);
- a repeat of the message just before it on its channel and writer: a lockstep
  clock or report sent again because no progress followed it for a while (a
  lost datagram, a slow step); it is the same message, counted once;
- messages stamped in or after the shorter run's last step (the end is
  asynchronous: the processes stop while it runs);
- sim_clock_t.warp: the pace, which the second run sets on purpose.
"""

from __future__ import annotations

from collections import defaultdict

import lcm
from test_launch import launch, vehicle, write_scenario

from auv import chasm_status_t, lockstep_t, sim_clock_t
from auvlcm.decode import decode_strict
from auvlcm.types import type_of

SKIP = ("SIM.ANNOTATION", "LCM_SELF_TEST")
REPEATED = ("SIM.CLOCK", "SIM.LOCKSTEP")


def messages(log) -> tuple[dict[str, list[bytes]], int]:
    per: dict[str, list] = defaultdict(list)
    last_clock = 0
    for ev in lcm.EventLog(str(log), "r"):
        ch = ev.channel
        if ch in SKIP or ch.endswith(".HEALTH"):
            continue
        m = decode_strict(type_of(ev.data), ev.data)
        if isinstance(m, sim_clock_t):
            last_clock = max(last_clock, m.utime)
            m.warp = 0.0  # the pace, which the second run changes on purpose
        if isinstance(m, lockstep_t) and m.kind != lockstep_t.KIND_STEP_DONE:
            continue
        if isinstance(m, chasm_status_t):
            m.cycle_cost_us = 0.0
        writer = getattr(m, "participant", "")
        per[f"{ch}/{writer}" if writer else ch].append((getattr(m, "utime", 0), m.encode()))
    return per, last_clock


def cut(per: dict, until_us: int) -> dict[str, list[bytes]]:
    out = {}
    for key, msgs in per.items():
        seq = []
        for utime, data in msgs:
            if utime > until_us:
                continue
            if key.split("/")[0] in REPEATED and seq and seq[-1] == data:
                continue
            seq.append(data)
        out[key] = seq
    return out


def test_fast_time_runs_twice_to_the_same_log(tmp_path, lcm_url, child_env):
    ekf = vehicle("AUV2", east=40.0, cycles=50)
    ekf["nav"] = "ekf"
    path = write_scenario(tmp_path, [vehicle("AUV1", cycles=40), ekf], limit=30)
    runs = []
    # the mode only paces the lockstep clock: fast, then scaled, give the same log
    for name, pace in (("a", []), ("b", ["--time", "scaled", "--warp", "40"])):
        run = launch(path, tmp_path / name, lcm_url, child_env, *pace)
        assert run.returncode == 0, run.stdout + run.stderr
        assert "0 dropped, 0 missed" in run.stdout, run.stdout
        runs.append(messages(tmp_path / name / "run.lcmlog"))
    until = min(last for _, last in runs) - 50_000  # the last step may be cut short by the end
    a, b = (cut(per, until) for per, _ in runs)
    assert until >= 4_000_000 and len(a["SIM.CLOCK"]) == until // 50_000 + 1  # every step, once
    for key in (
        "AUV1.TRUTH",
        "AUV2.NAV",
        "AUV1.CHASM.NAVIGATOR",
        "AUV2.ACTUATORS",
        "SIM.LOCKSTEP/AUV2.NAV",
        "SIM.LOCKSTEP/SIM.RECORDER",
        "SIM.LOCKSTEP/AUV1.sim",
    ):
        assert len(a.get(key, [])) > 20, (key, len(a.get(key, [])))
    assert len(a["AUV2.NAV_STATUS"]) >= 4  # once a second
    assert sorted(a) == sorted(b)
    for key in sorted(a):
        assert len(a[key]) == len(b[key]), f"{key}: {len(a[key])} vs {len(b[key])} messages"
        diff = next((i for i, (x, y) in enumerate(zip(a[key], b[key])) if x != y), None)
        assert diff is None, f"{key}: message {diff} differs"
