"""The launcher's default fast time is deterministic (issue 14, item 1): the
same scenario twice gives the same messages, with the same contents, in the
same order, per channel, in the recorded log (only the receive stamps differ;
what else is left out of the comparison, and why: tests/logcompare.py).
The second run is paced (`--time scaled`): the pace changes nothing else.

Two vehicles, one on the onboard filter (auv-nav), each with two managers, a
few seconds of sim time; a third is lost by a planned fault at 2 s, which the
launcher applies between two steps (tools/launch/fault_step.py): the same in both runs.
"""

from __future__ import annotations

import yaml
from logcompare import compare, cut, messages
from test_launch import launch, vehicle, write_scenario

from auv import chasm_status_t, ground_truth_t

LOST_AT = 2.0


def test_fast_time_runs_twice_to_the_same_log(tmp_path, lcm_url, child_env):
    ekf = vehicle("AUV2", east=40.0, cycles=50)
    ekf["nav"] = "ekf"
    for m in ekf["managers"]:  # a status twice a second and on every change (chasm-manager --status-rate)
        m["status_rate"] = 2
    path = write_scenario(tmp_path, [vehicle("AUV1", cycles=40), ekf, vehicle("AUV3", east=80.0)], limit=30)
    sc = yaml.safe_load(path.read_text())
    sc["faults"] = [{"at": LOST_AT, "vehicle": "AUV3", "do": "lose"}]
    path.write_text(yaml.safe_dump(sc, sort_keys=False))
    runs = []
    # the mode only paces the lockstep clock: fast, then scaled, give the same log
    for name, pace in (("a", []), ("b", ["--time", "scaled", "--warp", "40"])):
        run = launch(path, tmp_path / name, lcm_url, child_env, *pace)
        assert run.returncode == 0, run.stdout + run.stderr
        assert "0 dropped, 0 missed" in run.stdout, run.stdout
        # killed before the first step at or after its time: it did every step before
        assert f"AUV3 lost at t={LOST_AT:.1f} s" in run.stdout, run.stdout
        runs.append(messages(tmp_path / name / "run.lcmlog"))
        last = max(ground_truth_t.decode(d).utime for _, d in runs[-1][0]["AUV3.TRUTH"])
        assert (LOST_AT - 0.1) * 1e6 <= last < LOST_AT * 1e6, last  # TRUTH at 10 Hz
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
    # rate-limited statuses: which cycles publish depends on mission time and the
    # plan alone, so the two runs still agree (compare); at least one per 0.5 s
    rated = [chasm_status_t.decode(d).utime for d in a["AUV2.CHASM.NAVIGATOR"]]
    assert 8 <= len(rated) < 20 and all(y - x <= 500_000 for x, y in zip(rated, rated[1:])), rated
    compare(a, b)
