"""Logs as numpy arrays and the lcmlog CLI, on logs written through lcm.EventLog
with fully random messages of every project type."""

from __future__ import annotations

import csv
import random
import subprocess
import sys

import lcm
import numpy as np
import pytest
from lcm_samples import random_message

from auv import chasm_status_t, depth_t, nav_solution_t, target_field_t
from auvlcm.arrays import load_log
from auvlcm.types import all_types

LCMLOG = [sys.executable, "-m", "tools.logs.lcmlog"]


def _leaves(msg, prefix=""):
    """Every fixed-size numeric/string leaf of a message, walked independently of
    auvlcm.arrays: by recursion over the Python values themselves."""
    cls = type(msg)
    for name, dims in zip(cls.__slots__, cls.__dimensions__):
        if dims and any(isinstance(d, str) for d in dims):
            continue
        yield from _value_leaves(getattr(msg, name), prefix + name)


def _value_leaves(v, path):
    if isinstance(v, (list, tuple, bytes)):
        for i, x in enumerate(v):
            yield from _value_leaves(x, f"{path}[{i}]")
    elif hasattr(v, "__slots__"):
        yield from _leaves(v, path + ".")
    else:
        yield path, v


def write_log(path, events):
    log = lcm.EventLog(str(path), "w", overwrite=True)
    for i, (channel, data) in enumerate(events):
        log.write_event(1000 * i, channel, data)
    log.close()


@pytest.fixture
def every_type_log(tmp_path):
    rng = random.Random(7)
    msgs = {f"T.{cls.__name__.upper()}": [random_message(cls, rng) for _ in range(5)] for cls in all_types()}
    events = [(ch, m.encode()) for i in range(5) for ch, ms in msgs.items() for m in ms[i : i + 1]]
    path = tmp_path / "all.lcmlog"
    write_log(path, events)
    return path, msgs


def test_every_field_of_every_type_becomes_a_column(every_type_log):
    path, msgs = every_type_log
    log = load_log(path)
    assert log.stats.undecodable == 0 and set(log.channels) == set(msgs)
    for ch, ms in msgs.items():
        arr = log[ch]
        assert len(arr) == len(ms)
        expected = [dict(_leaves(m)) for m in ms]
        assert set(arr.columns) == set(expected[0]), ch
        for name, col in arr.columns.items():
            want = [e[name] for e in expected]
            if col.dtype == object:
                assert list(col) == want
            else:
                np.testing.assert_array_equal(col, np.array(want, dtype=col.dtype), err_msg=f"{ch} {name}")
        cls = type(ms[0])
        for name, dims in zip(cls.__slots__, cls.__dimensions__):
            if dims and any(isinstance(d, str) for d in dims):
                enc = lambda xs: [x.encode() if hasattr(x, "encode") else x for x in xs]  # noqa: E731
                assert [enc(r) for r in arr.ragged[name]] == [enc(getattr(m, name)) for m in ms]


def test_nested_arrays_are_named_like_c_and_time_is_sim_time(tmp_path):
    nav = nav_solution_t()
    nav.utime = 2_500_000
    nav.position_cov_m2 = [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0], [7.0, 8.0, 9.0]]
    write_log(tmp_path / "n.lcmlog", [("AUV1.NAV", nav.encode())])
    arr = load_log(tmp_path / "n.lcmlog")["AUV1.NAV"]
    assert arr["position_cov_m2[0][1]"][0] == 2.0 and arr["position_cov_m2[2][0]"][0] == 7.0
    assert arr.t[0] == 2.5
    with pytest.raises(KeyError, match="no column 'north'"):
        arr["north"]


def test_undecodable_and_foreign_events_are_counted_and_dropped(tmp_path):
    good = depth_t()
    good.depth_m = 4.0
    data = good.encode()
    write_log(
        tmp_path / "bad.lcmlog",
        [
            ("AUV1.DEPTH", data),
            ("AUV1.DEPTH", data[:-3]),
            ("AUV1.DEPTH", b"\x00" * 12),
            ("AUV1.DEPTH", nav_solution_t().encode()),
            ("AUV1.DEPTH", data + b"x"),
            ("AUV1.DEPTH", data),
        ],
    )
    log = load_log(tmp_path / "bad.lcmlog")
    assert len(log["AUV1.DEPTH"]) == 2 and list(log["AUV1.DEPTH"]["depth_m"]) == [4.0, 4.0]
    assert log.undecodable["AUV1.DEPTH"] == 3 and log.type_conflicts["AUV1.DEPTH"] == 1
    run = subprocess.run(LCMLOG + ["summary", str(tmp_path / "bad.lcmlog")], capture_output=True, text=True, timeout=60)
    assert run.returncode == 1, run.stderr
    assert "3 undecodable event(s) on AUV1.DEPTH" in run.stderr
    assert "1 event(s) of another type on AUV1.DEPTH" in run.stderr


def test_csv_export_round_trips_values(tmp_path, every_type_log):
    path, msgs = every_type_log
    ch = "T.NAV_SOLUTION_T"
    out = tmp_path / "nav.csv"
    run = subprocess.run(LCMLOG + ["csv", str(path), ch, str(out)], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, run.stderr
    rows = list(csv.DictReader(open(out)))
    assert len(rows) == 5
    for row, m in zip(rows, msgs[ch]):
        assert float(row["position_cov_m2[1][2]"]) == m.position_cov_m2[1][2]
        assert int(row["utime"]) == m.utime and row["vehicle"] == m.vehicle


def test_csv_all_and_ragged_columns(tmp_path):
    st = chasm_status_t()
    st.utime, st.vehicle, st.manager = 1_000_000, "AUV1", "NAVIGATOR"
    st.path_len, st.active_path, st.time_in_state_s = 2, ["mission", "line1"], [3.0, 1.5]
    tf = target_field_t()
    write_log(tmp_path / "s.lcmlog", [("AUV1.CHASM.NAVIGATOR", st.encode()), ("SIM.TARGETS", tf.encode())])
    outdir = tmp_path / "csv"
    run = subprocess.run(
        LCMLOG + ["csv", str(tmp_path / "s.lcmlog"), "--all", str(outdir)], capture_output=True, text=True, timeout=60
    )
    assert run.returncode == 0, run.stderr
    row = next(csv.DictReader(open(outdir / "AUV1.CHASM.NAVIGATOR.csv")))
    assert row["active_path"] == "mission;line1" and row["time_in_state_s"] == "3.0;1.5"
    assert (outdir / "SIM.TARGETS.csv").exists()


def test_npz_and_states(tmp_path):
    events = []
    for i, (path, run) in enumerate([(["a"], 1), (["a"], 1), (["b", "c"], 1), (["b", "c"], 3)]):
        st = chasm_status_t()
        st.utime, st.run_state, st.path_len, st.active_path = i * 1_000_000, run, len(path), path
        st.time_in_state_s = [0.0] * len(path)
        st.last_condition = f"cond{i}"
        events.append(("AUV2.CHASM.NAVIGATOR", st.encode()))
    write_log(tmp_path / "st.lcmlog", events)
    run = subprocess.run(LCMLOG + ["states", str(tmp_path / "st.lcmlog")], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, run.stderr
    lines = [ln.split() for ln in run.stdout.splitlines()[1:]]
    assert [(ln[0], ln[5], ln[6]) for ln in lines] == [
        ("0.00", "running", "a"),
        ("2.00", "running", "b/c"),
        ("3.00", "done", "b/c"),
    ]
    run = subprocess.run(
        LCMLOG + ["npz", str(tmp_path / "st.lcmlog"), str(tmp_path / "o.npz")],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert run.returncode == 0, run.stderr
    z = np.load(tmp_path / "o.npz")
    assert list(z["AUV2.CHASM.NAVIGATOR/run_state"]) == [1, 1, 1, 3]


def test_cli_bad_usage(tmp_path):
    run = subprocess.run(
        LCMLOG + ["summary", str(tmp_path / "missing.lcmlog")], capture_output=True, text=True, timeout=60
    )
    assert run.returncode == 2 and "no such log file" in run.stderr
