"""demo.py and auv-report: every flag and path ends in a result or a clear
error with exit status 2, never a traceback (issue 14: `demo.py --no-plots`
ended in one). The full run is tests/test_demo.py; here the paths around it."""

from __future__ import annotations

import json
import subprocess
import sys

import lcm
import pytest

from auv import ground_truth_t
from tools.demo import result_text, summary

DEMO = [sys.executable, "-m", "tools.demo"]
REPORT = [sys.executable, "-m", "tools.report"]


def _run(cmd, child_env, **kw):
    return subprocess.run([str(c) for c in cmd], capture_output=True, text=True, timeout=120, env=child_env, **kw)


@pytest.mark.parametrize(
    "args, message",
    [
        (["--vehicles", "2"], "--vehicles needs --polygon"),
        (["--polygon", "0,0; 100,0; 100,100", "--vehicles", "0"], "--vehicles must be at least 1"),
        (["--plan-only"], "--plan-only needs --polygon"),
        (["--polygon", "0,0; 1,x; 5,5", "--plan-only"], "not a number"),
        (["--polygon", "0,0; 100,0"], "at least 3 vertices"),
        (["--out", "/proc/no/such/dir"], "--out /proc/no/such/dir"),
        (["--bogus"], "unrecognized arguments"),
        (["--time", "warp"], "unknown clock mode 'warp': one of realtime, scaled, lockstep"),
        (["--time", "scaled", "--warp", "0"], "--warp must be a number > 0"),
    ],
)
def test_demo_usage_errors_are_clear(tmp_path, child_env, args, message):
    args = args if "--out" in args else args + ["--out", tmp_path / "d"]
    run = _run(DEMO + args, child_env)
    assert run.returncode == 2, run.stdout + run.stderr
    assert message in run.stderr and "Traceback" not in run.stderr


def _report(vehicles=("AUV1",), plots=None, coverage=True) -> dict:
    rep = {
        "outcome": "done",
        "vehicle_outcomes": {v: "done" for v in vehicles},
        "duration_s": 360.0,
        "navigation_error": {v: {"rms_m": 1.0, "max_m": 2.0} for v in vehicles},
        "record": {v: {"samples": 100, "missing": 0} for v in vehicles},
        "detection": {
            "mine_like_detected": 1,
            "mine_like_targets": 2,
            "pd": 0.5,
            "contacts": 3,
            "contacts_on_clutter": 1,
            "false_alarms": 1,
        },
    }
    if coverage:
        rep["coverage"] = {"survey_area_m2": 1e4, "fraction_once": 0.9, "fraction_twice": 0.5}
    if plots is not None:
        rep["plots"] = plots
    return rep


def test_demo_result_without_plots_and_without_a_survey(tmp_path):
    """--no-plots leaves no "plots" in the report (the old KeyError); a
    scenario without a survey has no coverage; neither breaks the summary."""
    text = result_text(_report(), tmp_path, tmp_path / "run.lcmlog", 12.0)
    assert "record    AUV1 0 of 100 truth samples lost" in text and "plot " not in text
    text = result_text(_report(plots=["a.png", "a.svg"], coverage=False), tmp_path, tmp_path / "x", 1.0)
    assert "plot      a.png" in text and "coverage" not in text
    assert "nav error -" in summary({**_report(), "navigation_error": {}, "record": {}})


@pytest.fixture
def small_log(tmp_path):
    path = tmp_path / "t.lcmlog"
    log = lcm.EventLog(str(path), "w", overwrite=True)
    for i in range(50):
        m = ground_truth_t()
        m.utime, m.vehicle = i * 100000, "AUV1"
        log.write_event(i * 1000, "AUV1.TRUTH", m.encode())
    log.close()
    return path


def test_report_without_plots_writes_the_report_and_no_plots(tmp_path, small_log, child_env):
    run = _run(REPORT + [small_log, "--out", tmp_path / "r", "--no-plots"], child_env)
    assert run.returncode == 0, run.stderr
    rep = json.loads((tmp_path / "r" / "report.json").read_text())
    assert "plots" not in rep and rep["record"]["AUV1"]["missing"] == 0
    assert not list((tmp_path / "r").glob("*.png"))


@pytest.mark.parametrize(
    "extra, message",
    [
        (["--survey", "/nonexistent/survey.json"], "No such file"),
        (["--survey", "LOG"], "--survey"),  # not JSON
        (["--survey", "EMPTY"], "not a survey description"),  # JSON, wrong shape
        (["--out", "LOG/x"], "Not a directory"),
        (["--radius", "0"], "must be > 0"),
    ],
)
def test_report_bad_paths_are_clear_errors(tmp_path, small_log, child_env, extra, message):
    empty = tmp_path / "empty.json"
    empty.write_text("{}")
    extra = [
        str(small_log) if a == "LOG" else str(empty) if a == "EMPTY" else a.replace("LOG", str(small_log))
        for a in extra
    ]
    run = _run(REPORT + [small_log, "--no-plots", *extra], child_env)
    assert run.returncode == 2, run.stdout + run.stderr
    assert message in run.stderr and "Traceback" not in run.stderr


def test_report_of_something_not_a_log_is_a_clear_error(tmp_path, child_env):
    junk = tmp_path / "junk.lcmlog"
    junk.write_bytes(b"not an lcm log at all\n" * 10)
    run = _run(REPORT + [junk], child_env)
    assert run.returncode == 2 and "not an LCM log" in run.stderr and "Traceback" not in run.stderr
    run = _run(REPORT + [tmp_path / "missing.lcmlog"], child_env)
    assert run.returncode == 2 and "no such log file" in run.stderr
