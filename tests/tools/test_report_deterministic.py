"""Two runs, one report: the same scenario flown twice over real LCM gives the
same report.json, byte for byte, once the wall-clock and path entries are
left out (the log's path, the plots' paths). The record and every figure end
at the mission's end (docs/scenarios.md, "End"): the world is stepped up to a
defined step and no further, the launcher marks that step in the log, the
recorder records nothing of the world after the mark, and the report cuts
every series there. What happens while the processes stop (the order they go
in, how long it takes) is not in the report.

Two small worlds, as the launcher steps them: its own clock, and the
simulators' multi-HIL lockstep (the demo's kind, where the launcher takes part
to hold the world at the end). Two vehicles on the test plugin's plan (it ends
after a count of cycles), one on the onboard filter (auv-nav) for a
navigation error, the other ending later.
"""

from __future__ import annotations

import json
import subprocess
import sys

import pytest
import yaml
from conftest import BUILD
from test_launch import launch, vehicle, write_scenario

from auvlcm.log import read_events

WALL = ("log", "plots")  # the log's path, the plots' paths


def scenario(tmp_path, world: str):
    ekf = vehicle("AUV1", cycles=40)
    ekf["nav"] = "ekf"
    vehicles = [ekf, vehicle("AUV2", east=40.0, cycles=70)]
    path = write_scenario(tmp_path, vehicles, limit=60)
    if world == "simulators":
        sc = yaml.safe_load(path.read_text())
        sc["time"]["source"] = "simulators"
        for v in sc["vehicles"]:
            v["sim"]["simulation"] = {"clock": "lockstep"}
            # 2 simulators, 4 managers, a filter and the recorder (each named by the launcher, itself too)
            v["sim"]["multihil"] = {"enabled": True, "lockstep_participants": 8}
        path.write_text(yaml.safe_dump(sc, sort_keys=False))
    return path


def report(log, out, env) -> dict:
    cmd = [sys.executable, "-m", "tools.report", str(log), "--out", str(out), "--no-plots"]
    run = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    return json.loads((out / "report.json").read_text())


@pytest.mark.parametrize("world", ["launcher", "simulators"])
def test_two_runs_give_the_same_report(tmp_path, lcm_url, child_env, world):
    path = scenario(tmp_path, world)
    reports, logs = [], []
    for name in ("a", "b"):
        run = launch(path, tmp_path / name, lcm_url, child_env, "--build", str(BUILD))
        assert run.returncode == 0, run.stdout + run.stderr
        assert "0 dropped, 0 missed" in run.stdout, run.stdout
        log = tmp_path / name / "run.lcmlog"
        logs.append(log)
        reports.append(report(log, tmp_path / name / "report", child_env))
    a, b = ({k: v for k, v in r.items() if k not in WALL} for r in reports)
    assert a["log_events"] == b["log_events"], (a["log_events"], b["log_events"])
    assert a["outcome"] == "done" and a["end_from"] == "mark", a
    assert a["navigation_error"]["AUV1"]["samples"] > 20, a["navigation_error"]
    assert a["record"]["AUV2"]["samples"] > 60 and a["record"]["AUV2"]["missing"] == 0, a["record"]
    # after the mark only the launcher's notes of the stop: an exit each (2 x (simulator,
    # 2 managers), a filter) and the summary
    assert a["log_events_after_end"] == 8, a["log_events_after_end"]
    assert {k: v for k, v in a.items() if a[k] != b.get(k)} == {k: v for k, v in b.items() if b[k] != a.get(k)}
    assert json.dumps(a, indent=1) == json.dumps(b, indent=1)
    # the mark is stamped with the step the world ended at: no clock after it in the record
    for log in logs:
        end, last_clock, notes = None, 0, set()
        for ev in read_events(log):
            if ev.channel == "SIM.ANNOTATION":
                notes.add(ev.msg.name)
            if ev.channel == "SIM.ANNOTATION" and ev.msg.name == "mission end":
                end = ev.msg.utime
            elif ev.channel == "SIM.CLOCK":
                assert end is None, "a clock recorded after the mission's end"
                last_clock = max(last_clock, ev.msg.utime)
        assert end is not None and end == last_clock, (end, last_clock)
        # the launcher's first note, sent once the recorder's file exists (which it
        # once created before it listened: a run then had one event less)
        assert "logger" in notes, sorted(notes)
