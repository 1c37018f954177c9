"""auv-montecarlo: a short survey over two seeds on a local Dask cluster (two
worker processes), each run in its own network namespace, summarised as
mean and 95 % interval with a plot; the statistics on their own; usage."""

from __future__ import annotations

import json
import math
import subprocess
import sys

import lcm
import pytest
from conftest import BUILD, ROOT

from auv import ground_truth_t
from tools.montecarlo.summary import interval, metrics_of, summarize, summary_text

MC = [sys.executable, "-m", "tools.montecarlo"]
# One vehicle, two short lines over part of the demo's target field: a few minutes of sim time.
PLAN = [
    "--polygon",
    "150,120; 190,120; 190,150; 150,150",
    "--vehicles",
    "1",
    "--heading",
    "0",
    "--range",
    "40",
    "--nadir-gap",
    "8",
    "--overlap",
    "0.1",
    "--world",
    str(ROOT / "missions/scenarios/mcm_world.yaml"),
    "--sim-config",
    str(ROOT / "missions/sim/remus100_mcm.yaml"),
    "--fix-every-min",
    "60",
]


def test_interval_is_the_t_interval_of_the_mean_within_the_figures_range():
    s = interval([1.0, 2.0, 3.0, 4.0])
    assert s["mean"] == 2.5 and s["min"] == 1.0 and s["max"] == 4.0
    half = 3.182 * (1.6666666666666667**0.5) / 2  # t(0.975, 3) * sd / sqrt(n)
    assert s["lo"] == pytest.approx(2.5 - half) and s["hi"] == pytest.approx(2.5 + half)
    assert not s["clipped"]
    # a count: never below zero (the user's study: false alarms [-25.3, 38.3])
    c = interval([0.0, 1.0, 12.0], (0.0, math.inf))
    assert c["lo"] == 0.0 and c["hi"] > 12.0 and c["clipped"], c
    # a fraction: never over one
    f = interval([0.9, 1.0, 1.0, 1.0], (0.0, 1.0))
    assert f["hi"] == 1.0 and 0.8 < f["lo"] < 0.95 and f["clipped"], f
    # two runs: no interval, it says so (a t-interval on 2 runs is 12.7 standard errors wide)
    two = interval([10.0, 50.0], (0.0, math.inf))
    assert two["lo"] is None and two["hi"] is None and "too small" in two["too_few"], two
    assert (two["mean"], two["min"], two["max"]) == (30.0, 10.0, 50.0)
    runs = [
        {
            "seed": 1,
            "metrics": {
                "outcome": "done",
                "coverage": 0.9,
                "pd": None,
                "false_alarms": 2,
                "nav_error_rms_m": 1.0,
                "mission_time_s": 100.0,
            },
        },
        {"seed": 2, "error": "launcher exit 5"},
    ]
    s = summarize(runs)
    assert s["reported"] == 1 and s["failed_runs"] == {"2": "launcher exit 5"} and "pd" not in s["metrics"]
    assert not s["team"] and "team:" not in summary_text(s)  # a survey has no team figures


def test_a_team_study_carries_the_teams_figures():
    """From auv-report's team section: identified, their fraction, false
    identifications, detection to identification; in the JSON and the text."""

    def rep(identified: int, false_ids: int, latency: float | None) -> dict:
        team = {"mine_like_targets": 4, "mine_like_identified": identified, "false_identifications": [{}] * false_ids}
        team["detect_to_identify_s"] = {"mean": latency} if latency is not None else None
        return {"duration_s": 600.0, "outcome": "done", "team": team}

    runs = [
        {"seed": k, "metrics": metrics_of(rep(i, f, lat))}
        for k, (i, f, lat) in enumerate([(4, 0, 120.0), (3, 1, 180.0), (4, 0, None)])
    ]
    s = summarize(runs)
    assert s["team"]
    m = s["metrics"]
    assert m["mine_like_identified"]["mean"] == pytest.approx(11 / 3) and m["mine_like_identified"]["n"] == 3
    assert m["identified_fraction"]["hi"] <= 1.0 and m["identified_fraction"]["mean"] == pytest.approx(11 / 12)
    assert m["false_identifications"]["lo"] == 0.0 and m["false_identifications"]["clipped"]
    assert m["detect_to_identify_s"]["n"] == 2 and m["detect_to_identify_s"]["lo"] is None  # one run had none
    text = summary_text(s)
    assert "team: mine-like identified" in text and "team: false identifications" in text, text
    assert "detection to identification" in text and "too small for an interval" in text, text


@pytest.mark.parametrize(
    "args, message",
    [
        (["--seeds", "0"], "must be at least 1"),
        (["--dask", "tcp://x:1", "--dask-local", "2"], "exclude each other"),
    ],
)
def test_usage_errors(tmp_path, args, message, child_env):
    sc = tmp_path / "s.yaml"
    sc.write_text("vehicles: []\n")
    run = subprocess.run(MC + [sc, *args, "--out", tmp_path / "o"], capture_output=True, text=True, env=child_env)
    assert run.returncode == 2 and message in run.stderr and "Traceback" not in run.stderr
    run = subprocess.run(MC + [tmp_path / "missing.yaml"], capture_output=True, text=True, env=child_env)
    assert run.returncode == 2 and "no such scenario" in run.stderr


def _truth_and_targets(log):
    times, targets = [], None
    for ev in lcm.EventLog(str(log), "r"):
        if ev.channel == "AUV1.TRUTH":
            times.append(ground_truth_t.decode(ev.data).utime)
        elif ev.channel == "SIM.TARGETS" and targets is None:
            targets = ev.data
    return times, targets


def test_two_seeds_on_a_local_dask_cluster(tmp_path, child_env):
    plan = subprocess.run(
        [
            sys.executable,
            "-m",
            "tools.plan.plan_survey",
            *PLAN,
            "--out",
            tmp_path / "sc",
            "--name",
            "mc",
            "--build",
            BUILD,
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert plan.returncode == 0, plan.stderr
    out = tmp_path / "mc"
    run = subprocess.run(
        MC
        + [
            tmp_path / "sc" / "mc.yaml",
            "--seeds",
            "2",
            "--first-seed",
            "3",
            "--dask-local",
            "2",
            "--out",
            out,
            "--build",
            BUILD,
            "--timeout",
            "500",
        ],
        capture_output=True,
        text=True,
        timeout=900,
        env=child_env,
    )
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    s = json.loads((out / "summary.json").read_text())
    assert s["runs"] == s["reported"] == 2 and s["outcomes"] == {"done": 2}, s
    for key in ("coverage", "nav_error_rms_m", "mission_time_s", "false_alarms"):
        m = s["metrics"][key]
        assert m["n"] == 2 and m["min"] <= m["mean"] <= m["max"] and m["lo"] is None, (key, m)
    assert "too small for an interval" in run.stdout and (out / "montecarlo.png").stat().st_size > 1000
    # a clean end: no warning from Dask as its cluster closes (lost tasks, a closed stream)
    # (a late heartbeat on a loaded machine is the machine's, not the end's: not counted)
    noise = [
        ln
        for ln in run.stderr.splitlines()
        if ("WARNING" in ln or "Traceback" in ln or "lost" in ln.lower()) and "heartbeat" not in ln.lower()
    ]
    assert not noise, run.stderr[-3000:]
    runs = json.loads((out / "runs.json").read_text())
    assert sorted(r["seed"] for r in runs) == [3, 4]
    worlds = []
    for seed in (3, 4):
        times, targets = _truth_and_targets(out / f"seed_{seed}" / "run" / "run.lcmlog")
        # one simulator per world: a second world's AUV1 would interleave its own times
        assert len(times) > 100 and all(b > a for a, b in zip(times, times[1:])), seed
        worlds.append(targets)
    assert worlds[0] is not None and worlds[0] != worlds[1]  # the seed changed the target field


def test_local_jobs_report_runs_that_fail(tmp_path, child_env):
    """The local path (--jobs): a scenario whose plan does not load makes every
    run fail at once; the study still ends, names each failed seed, exits 1."""
    bad = tmp_path / "bad.chasm"
    bad.write_text('mission "x"\nstart nowhere\n')
    sc = tmp_path / "s.yaml"
    sc.write_text(f"""name: bad
time: {{mode: lockstep, limit: 10}}
vehicles:
  - id: AUV1
    sim: {{config: {ROOT / "missions/sim/remus100.yaml"}}}
    managers:
      - {{name: NAVIGATOR, plan: {bad}, bind: {ROOT / "missions/bindings/navigator.bind"}}}
""")
    run = subprocess.run(
        MC + [sc, "--seeds", "2", "--jobs", "2", "--out", tmp_path / "o", "--build", BUILD, "--no-plot"],
        capture_output=True,
        text=True,
        timeout=300,
        env=child_env,
    )
    assert run.returncode == 1, run.stdout + run.stderr
    s = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert s["runs"] == 2 and s["reported"] == 0 and set(s["failed_runs"]) == {"1", "2"}
    assert all("launcher exit 2" in e for e in s["failed_runs"].values()), s
    assert "seed 1: no report" in run.stdout and "Traceback" not in run.stderr
