"""Why a mission ended: the launcher's summary, outcome.json and the report
name the test that fired (`too_deep`), or the abort condition's text when no
named test is in it, not just "aborted ... emergency"."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import yaml
from conftest import ROOT

HERE = Path(__file__).resolve().parent / "scenarios"
LAUNCH = [sys.executable, "-m", "tools.launch"]
REPORT = [sys.executable, "-m", "tools.report"]
SIM = str(ROOT / "missions" / "sim" / "remus100_multihil.yaml")
BIND = str(ROOT / "missions" / "bindings" / "direct_actuators.bind")


def test_the_summary_outcome_and_report_name_what_fired(tmp_path, lcm_url, child_env):
    plan = (HERE / "mission.chasm").read_text()
    plan = plan.replace(
        "test must_fail : failing == true", "test must_fail : failing == true\ntest too_deep : nav.depth_m > -1 m"
    )
    plan = plan.replace(
        "abort when nav_stale or elapsed > $abort_at -> emergency", "abort when nav_stale or too_deep -> emergency"
    )
    (tmp_path / "deep.chasm").write_text(plan)

    def veh(vid, plan_path, **params):
        return {
            "id": vid,
            "sim": {"config": SIM, "initial": {"east_m": 40.0 * int(vid[-1])}},
            "managers": [
                {
                    "name": "NAVIGATOR",
                    "plan": str(plan_path),
                    "bind": BIND,
                    "rate": 10,
                    "params": {"cycles": 100000, **params},
                }
            ],
        }

    sc = {
        "name": "cause",
        "seed": 1,
        "time": {"mode": "lockstep", "limit": 30, "wall_limit": 120},
        "vehicles": [veh("AUV1", tmp_path / "deep.chasm"), veh("AUV2", HERE / "mission.chasm", abort_at="2 s")],
    }
    path = tmp_path / "cause.yaml"
    path.write_text(yaml.safe_dump(sc, sort_keys=False))
    run = subprocess.run(
        LAUNCH + [str(path), "--out", str(tmp_path / "run"), "--lcm-url", lcm_url, "--progress", "0"],
        env=child_env,
        capture_output=True,
        text=True,
        timeout=180,
    )
    assert run.returncode == 3, run.stdout + run.stderr
    assert "launch: aborted at" in run.stdout and "AUV1 too_deep" in run.stdout, run.stdout
    assert "AUV1: aborted (too_deep at t=" in run.stdout
    assert "AUV2: aborted (nav_stale or elapsed > 2 s at t=" in run.stdout, run.stdout

    out = json.loads((tmp_path / "run" / "outcome.json").read_text())
    a1, a2 = out["vehicles"]["AUV1"], out["vehicles"]["AUV2"]
    assert a1["cause"] == "too_deep" and a1["abort_condition"] == "nav_stale or too_deep"
    assert a1["abort_at_s"] < 1.0
    assert a2["cause"] == "nav_stale or elapsed > 2 s" and abs(a2["abort_at_s"] - 2.0) < 0.25
    assert out["reason"] == "AUV1 too_deep; AUV2 nav_stale or elapsed > 2 s"

    rep = subprocess.run(
        REPORT + [str(tmp_path / "run" / "run.lcmlog"), "--out", str(tmp_path / "rep")],
        env=child_env,
        capture_output=True,
        text=True,
        timeout=180,
    )
    assert rep.returncode == 0, rep.stdout + rep.stderr
    text = (tmp_path / "rep" / "report.txt").read_text()
    assert "AUV1: aborted (cause: too_deep)" in text and "outcome   aborted (AUV1 too_deep;" in text
    assert json.loads((tmp_path / "rep" / "report.json").read_text())["vehicle_causes"]["AUV1"] == "too_deep"
    assert (tmp_path / "rep" / "states.png").stat().st_size > 5000  # aborts marked with their cause
