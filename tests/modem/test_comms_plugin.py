"""Plugin comms through the chasm tool (no LCM): peer_report numbers each
report, freezes its values between runs, keeps counting across re-entry and
labels it; peer_within compares positions; schema errors at load."""

from __future__ import annotations

import re
import subprocess

import pytest

NAV = """use comms
input nav.north_m : double m
input nav.east_m : double m
input nav.depth_m : double m
input nav.heading_rad : double rad
input nav.speed_over_ground_mps : double m/s
"""
REPORT = """output report.north_m : double m
output report.east_m : double m
output report.depth_m : double m
output report.heading_rad : double rad
output report.speed_mps : double m/s
output report.seq : int
output report.active_state : string
"""
INPUTS = """0 s nav.north_m = 1 m
0 s nav.east_m = 2 m
0 s nav.depth_m = 3 m
0 s nav.heading_rad = 90 deg
0 s nav.speed_over_ground_mps = 1.5 m/s
3 s nav.north_m = 7 m
"""
LINE = re.compile(r"^\s*([\d.]+) s\s+(\S+)\s.*?((?:report\.\w+=\S+\s*)+)$")


def chasm(variant_dir, tmp_path, plan: str, inputs: str, *args):
    (tmp_path / "p.chasm").write_text(plan)
    (tmp_path / "in.txt").write_text(inputs)
    return subprocess.run(
        [
            variant_dir / "bin" / "chasm",
            "run",
            "-P",
            variant_dir / "plugins",
            tmp_path / "p.chasm",
            "--inputs",
            tmp_path / "in.txt",
            *args,
        ],
        capture_output=True,
        text=True,
        timeout=60,
    )


def trace(res) -> list[tuple[float, str, dict]]:
    rows = []
    for line in res.stdout.splitlines():
        m = LINE.match(line)
        if m:
            vals = dict(kv.split("=", 1) for kv in m.group(3).split())
            rows.append((float(m.group(1)), m.group(2), vals))
    return rows


def test_reports_are_numbered_frozen_between_runs_and_count_across_reentry(variant_dir, tmp_path):
    plan = (
        NAV
        + REPORT
        + """
state a {
    do peer_report(out_label = report.active_state) every 2 s
    when elapsed > 5 s -> b
}
state b {
    when elapsed > 1 s -> a
}
"""
    )
    watch = [
        a for v in ("seq", "north_m", "heading_rad", "speed_mps", "active_state") for a in ("--watch", f"report.{v}")
    ]
    res = chasm(variant_dir, tmp_path, plan, INPUTS, "--until", "9", "--dt", "0.5", "--trace", *watch)
    assert res.returncode == 0, res.stderr
    rows = {t: (leaf, v) for t, leaf, v in trace(res)}
    seq = {t: int(v["report.seq"]) for t, (_, v) in rows.items()}
    # runs at the first cycle after entry, then every 2 s from entry; b pauses it
    assert [seq[t] for t in (0.0, 0.5, 1.5, 2.0, 3.5, 4.0, 6.5, 7.5, 9.0)] == [0, 1, 1, 2, 2, 3, 3, 4, 5]
    north = {t: float(v["report.north_m"]) for t, (_, v) in rows.items()}
    assert north[3.5] == 1.0 and north[4.0] == 7.0  # nav changed at 3 s; report at 4 s
    assert rows[2.0][1]["report.heading_rad"] == "1.5708" and rows[2.0][1]["report.speed_mps"] == "1.5"
    assert rows[2.0][1]["report.active_state"] == '"a"'  # default label: the behavior's state


def test_label_comes_from_a_plan_variable(variant_dir, tmp_path):
    plan = (
        NAV
        + REPORT
        + """var phase : string = "idle"
state mission {
    do peer_report(label = phase, out_label = report.active_state) every 1 s
    state one {
        do set phase = "survey" on entry
    }
}
"""
    )
    res = chasm(variant_dir, tmp_path, plan, INPUTS, "--until", "3", "--trace", "--watch", "report.active_state")
    assert res.returncode == 0, res.stderr
    assert trace(res)[-1][2]["report.active_state"] == '"survey"'


@pytest.mark.parametrize("peer_north, expected", [(230.0, "met"), (270.0, "apart")])
def test_peer_within_is_horizontal_distance(variant_dir, tmp_path, peer_north, expected):
    plan = """use comms
input nav.north_m : double m
input nav.east_m : double m
input peer.north_m : double m
input peer.east_m : double m
test close : peer_within(peer_north = peer.north_m, peer_east = peer.east_m, radius = 50 m)
state waiting {
    when close -> met
    when elapsed > 5 s -> apart
}
state met { }
state apart { }
"""
    inputs = (
        f"0 s nav.north_m = 200 m\n0 s nav.east_m = 0 m\n1 s peer.north_m = {peer_north} m\n1 s peer.east_m = 40 m\n"
    )
    res = chasm(variant_dir, tmp_path, plan, inputs, "--until", "8", "--expect", expected)
    assert res.returncode == 0, res.stdout + res.stderr  # 230 m: 50 m away; 270 m: 80.6 m


def test_schema_errors_are_load_errors(variant_dir, tmp_path):
    plan = """use comms
input nav.north_m : double m
input nav.east_m : double m
test close : peer_within(radius = 50 m)
state a { when close -> a }
"""
    res = chasm(variant_dir, tmp_path, plan, "0 s nav.north_m = 0 m\n")
    assert res.returncode == 1
    assert "'peer_within' needs parameter 'peer_north'" in res.stderr
    res = chasm(variant_dir, tmp_path, NAV + "state a { do peer_report() every 1 s }\n", "")
    assert res.returncode == 1 and "report.north_m" in res.stderr and "declare it or bind" in res.stderr
