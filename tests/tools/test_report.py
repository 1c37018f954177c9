"""Report and plots on a synthetic log written through lcm.EventLog with a known
geometry (expected figures worked out by hand below), and on a log from a real
launcher run."""

from __future__ import annotations

import bisect
import json
import math
import subprocess
import sys

import lcm
import pytest
from conftest import ROOT

from auv import (
    chasm_status_t,
    ground_truth_t,
    log_annotation_t,
    nav_solution_t,
    seabed_target_t,
    sidescan_contact_t,
    target_field_t,
)
from auvlcm.log import read_events

REPORT = [sys.executable, "-m", "tools.report"]
SURVEY = {
    "polygon": [[0, -60], [200, -60], [200, 90], [0, 90]],
    "area_m2": 200 * 150,
    "sonar": {"range_m": 40, "nadir_gap_m": 4},
    "operating_area": [[-100, -200], [300, -200], [300, 200]],
}


def synthetic_log(path, lost=()):
    """AUV1 flies north along east=0 (state line1), then south along east=50
    (state line2), at 10 m depth, 8 m altitude, 1 m/s, 10 Hz; its NAV is off by
    (3, 4) m throughout. Targets and contacts as in the test below. The TRUTH
    samples numbered in `lost` are left out, as a logger that dropped them."""
    log = lcm.EventLog(str(path), "w", overwrite=True)
    seq = [0]

    def put(ch, msg):
        log.write_event(seq[0], ch, msg.encode())
        seq[0] += 1

    a = log_annotation_t()
    a.kind, a.name, a.text = log_annotation_t.KIND_NOTE, "survey.json", json.dumps(SURVEY)
    put("SIM.ANNOTATION", a)
    end = log_annotation_t()
    end.kind, end.name = log_annotation_t.KIND_EVENT, "end"
    end.text = json.dumps({"outcome": "done", "reason": "", "vehicles": {"AUV1": {"outcome": "done"}}})
    tf = target_field_t()
    objs = [(100, 20, 0), (100, 2, 0), (150, -50, 0), (50, 30, 1)]
    tf.n_targets = len(objs)
    for i, (n, e, kind) in enumerate(objs):
        t = seabed_target_t()
        t.id, t.north_m, t.east_m, t.kind, t.depth_m = i, n, e, kind, 18
        tf.targets.append(t)
    put("SIM.TARGETS", tf)
    legs = [("line1", -20.0, 220.0, 0.0, 0.0), ("line2", 220.0, -20.0, 50.0, math.pi)]
    t_us = 0
    seq_truth = [0]
    for name, n_from, n_to, east, yaw in legs:
        steps = int(abs(n_to - n_from) * 10)
        for k in range(steps + 1):
            north = n_from + (n_to - n_from) * k / steps
            tr = ground_truth_t()
            tr.utime, tr.vehicle = t_us, "AUV1"
            tr.eta = [north, east, 10.0, 0.0, 0.0, yaw]
            tr.altitude_m, tr.water_depth_m = 8.0, 18.0
            if seq_truth[0] not in lost:
                put("AUV1.TRUTH", tr)
            seq_truth[0] += 1
            nav = nav_solution_t()
            nav.utime, nav.vehicle, nav.north_m, nav.east_m = t_us, "AUV1", north + 3.0, east + 4.0
            put("AUV1.NAV", nav)
            if k % 10 == 0:
                st = chasm_status_t()
                st.utime, st.vehicle, st.manager, st.run_state = t_us, "AUV1", "NAVIGATOR", 1
                st.active_path = ["mission", "survey", name]
                st.path_len, st.time_in_state_s = 3, [0.0] * 3
                put("AUV1.CHASM.NAVIGATOR", st)
            t_us += 100_000
    for n, e in ((101, 21), (50.5, 30), (180, -30)):
        c = sidescan_contact_t()
        c.utime, c.vehicle, c.north_m, c.east_m = t_us, "AUV1", n, e
        put("AUV1.CONTACTS", c)
    put("SIM.ANNOTATION", end)
    log.close()


def test_report_figures_on_a_known_geometry(tmp_path):
    synthetic_log(tmp_path / "s.lcmlog")
    run = subprocess.run(
        REPORT + [str(tmp_path / "s.lcmlog"), "--cell", "1", "--out", str(tmp_path / "r"), "--no-plots"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 0, run.stderr
    rep = json.loads((tmp_path / "r" / "report.json").read_text())
    assert rep["outcome"] == "done" and rep["vehicle_outcomes"] == {"AUV1": "done"}
    # Swaths inside the area (east -60..90): line1 sees -40..-4 and 4..40, line2 10..46 and 54..90,
    # over north 0..200. Once: 36 + 42 + 36 = 114 m wide; twice: 10..40, 30 m wide.
    cov = rep["coverage"]
    edge = 6 * 1 * 200  # at most a cell per swath edge, over the 200 m length
    assert abs(cov["covered_once_m2"] - 114 * 200) <= edge
    assert abs(cov["covered_twice_m2"] - 30 * 200) <= edge
    assert cov["raster_area_m2"] == pytest.approx(200 * 150, rel=0.01)
    d = rep["detection"]
    # mine-like at (100,20) seen by line1 and contacted; (100,2) in line1's nadir gap and 48 m
    # from line2: unseen; (150,-50) 50 m from line1: unseen. One contact on clutter, one far from all.
    assert d["mine_like_targets"] == 3 and d["mine_like_detected"] == 1 and d["pd"] == pytest.approx(1 / 3)
    assert d["mine_like_in_covered_area"] == 1 and d["pd_in_covered_area"] == 1.0
    assert (d["contacts"], d["contacts_on_clutter"], d["false_alarms"]) == (3, 1, 1)
    e = rep["navigation_error"]["AUV1"]
    assert e["mean_m"] == pytest.approx(5.0) and e["max_m"] == pytest.approx(5.0)
    text = (tmp_path / "r" / "report.txt").read_text()
    assert "PD 0.333" in text and "false alarms 1" in text


def test_report_counts_the_truth_samples_the_log_lost(tmp_path):
    for name, lost in (("whole", ()), ("lossy", (5, 300, 301, 302, 4000))):
        synthetic_log(tmp_path / f"{name}.lcmlog", lost=set(lost))
        run = subprocess.run(
            REPORT + [str(tmp_path / f"{name}.lcmlog"), "--out", str(tmp_path / name), "--no-plots"],
            capture_output=True,
            text=True,
            timeout=120,
        )
        assert run.returncode == 0, run.stderr
        r = json.loads((tmp_path / name / "report.json").read_text())["record"]["AUV1"]
        assert r["missing"] == len(lost) and r["interval_s"] == pytest.approx(0.1), r
        assert r["samples"] == 4802 - len(lost)
        assert f"{len(lost)} missing" in (tmp_path / name / "report.txt").read_text()


def test_plots_are_written_as_png_and_svg(tmp_path):
    synthetic_log(tmp_path / "s.lcmlog")
    run = subprocess.run(
        REPORT + [str(tmp_path / "s.lcmlog"), "--cell", "4", "--out", str(tmp_path / "r")],
        capture_output=True,
        text=True,
        timeout=180,
    )
    assert run.returncode == 0, run.stderr
    listed = set(json.loads((tmp_path / "r" / "report.json").read_text())["plots"])
    for name in ("tracks", "coverage", "contacts", "depth", "states"):
        for ext in ("png", "svg"):
            path = tmp_path / "r" / f"{name}.{ext}"
            assert str(path) in listed and path.stat().st_size > 1000
            head = path.read_bytes()[:200]
            assert head.startswith(b"\x89PNG") if ext == "png" else b"<svg" in path.read_bytes()[:2000]


def test_report_on_a_real_launcher_run(tmp_path, lcm_url, child_env):
    sc = ROOT / "tests" / "tools" / "scenarios" / "two_vehicles.yaml"
    run = subprocess.run(
        [
            sys.executable,
            "-m",
            "tools.launch",
            str(sc),
            "--out",
            str(tmp_path / "run"),
            "--lcm-url",
            lcm_url,
            "--progress",
            "0",
        ],
        env=child_env,
        capture_output=True,
        text=True,
        timeout=180,
    )
    assert run.returncode == 0, run.stdout + run.stderr
    rep_run = subprocess.run(
        REPORT + [str(tmp_path / "run" / "run.lcmlog")], env=child_env, capture_output=True, text=True, timeout=120
    )
    assert rep_run.returncode == 0, rep_run.stderr
    rep = json.loads((tmp_path / "run" / "report.json").read_text())
    assert rep["outcome"] == "done" and set(rep["vehicle_outcomes"]) == {"AUV1", "AUV2"}
    assert rep["undecodable_events"] == 0 and 14 < rep["duration_s"] < 17
    assert "coverage" not in rep and rep["detection"] is None
    truth = {"AUV1": [], "AUV2": []}  # independently: NAV against the truth interpolated in time
    navs = {"AUV1": [], "AUV2": []}
    for ev in read_events(tmp_path / "run" / "run.lcmlog"):
        if ev.channel.endswith(".TRUTH"):
            truth[ev.msg.vehicle].append((ev.msg.utime, ev.msg.eta[0], ev.msg.eta[1]))
        elif ev.channel.endswith(".NAV"):
            navs[ev.msg.vehicle].append((ev.msg.utime, ev.msg.north_m, ev.msg.east_m))
    for vid in ("AUV1", "AUV2"):
        times = [t for t, _, _ in truth[vid]]
        errs = []
        for t, n, e in navs[vid]:
            k = min(max(bisect.bisect_right(times, t), 1), len(times) - 1)
            (t0, n0, e0), (t1, n1, e1) = truth[vid][k - 1], truth[vid][k]
            w = min(max((t - t0) / (t1 - t0), 0.0), 1.0)
            errs.append(math.dist((n, e), (n0 + w * (n1 - n0), e0 + w * (e1 - e0))))
        got = rep["navigation_error"][vid]
        assert got["samples"] == len(errs) > 100
        assert got["max_m"] == pytest.approx(max(errs), abs=1e-6)
        assert got["mean_m"] == pytest.approx(sum(errs) / len(errs), abs=1e-6)
    assert (tmp_path / "run" / "tracks.png").exists() and (tmp_path / "run" / "states.svg").exists()


def test_report_bad_input(tmp_path):
    run = subprocess.run(REPORT + [str(tmp_path / "nope.lcmlog")], capture_output=True, text=True, timeout=60)
    assert run.returncode == 2 and "no such log file" in run.stderr
    log = lcm.EventLog(str(tmp_path / "empty.lcmlog"), "w", overwrite=True)
    log.close()
    run = subprocess.run(REPORT + [str(tmp_path / "empty.lcmlog")], capture_output=True, text=True, timeout=60)
    assert run.returncode == 2 and "no vehicle ground truth" in run.stderr


def test_vehicles_are_listed_in_number_order():
    from tools.report.run_data import vehicle_order

    ids = ["AUV10", "RI", "AUV2", "AUV1", "AUV16", "AUV3"]
    assert sorted(ids, key=vehicle_order) == ["AUV1", "AUV2", "AUV3", "AUV10", "AUV16", "RI"]
