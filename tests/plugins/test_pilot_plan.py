"""missions/pilot/pilot.chasm offline, with `chasm run` and scripted inputs:
it loads, each (vertical mode, speed mode) pair reaches its own state, and
the safety rules send it to `idle`. (The closed loop is in
test_pilot_closed_loop.py.)"""

from __future__ import annotations

import subprocess

import pytest
from conftest import ROOT, c_program

PLAN = ROOT / "missions" / "pilot" / "pilot.chasm"
NAV = {
    "nav.heading_rad": "0 rad",
    "nav.r_radps": "0 rad/s",
    "nav.depth_m": "10 m",
    "nav.altitude_m": "20 m",
    "nav.pitch_rad": "0 rad",
    "nav.q_radps": "0 rad/s",
    "nav.u_mps": "1.5 m/s",
}
SETPOINT = {
    "setpoint.heading_rad": "1 rad",
    "setpoint.depth_m": "12 m",
    "setpoint.altitude_m": "8 m",
    "setpoint.pitch_rad": "0.1 rad",
    "setpoint.speed_mps": "1.5 m/s",
    "setpoint.prop_rpm": "1200",
}


def inputs(vertical: int, speed: int, setpoint_until: float = 5.0, nav_until: float = 5.0, depth: str = "10 m") -> str:
    lines = []
    for i in range(11):
        t = i * 0.5
        if t <= nav_until:
            lines += [f"{t} s {k} = {v}" for k, v in {**NAV, "nav.depth_m": depth}.items()]
        if t <= setpoint_until:
            lines += [f"{t} s {k} = {v}" for k, v in SETPOINT.items()]
            lines += [f"{t} s setpoint.vertical_mode = {vertical}", f"{t} s setpoint.speed_mode = {speed}"]
    return "\n".join(lines) + "\n"


def run_plan(tmp_path, text: str, expect: str, *extra: str) -> subprocess.CompletedProcess:
    f = tmp_path / "in.txt"
    f.write_text(text)
    return subprocess.run(
        [
            str(c_program("bin/chasm")),
            "run",
            "-P",
            str(c_program("plugins")),
            str(PLAN),
            "--inputs",
            str(f),
            "--dt",
            "0.05",
            "--until",
            "5",
            "--expect",
            expect,
            *extra,
        ],
        capture_output=True,
        text=True,
        timeout=60,
    )


def test_the_pilot_plan_checks_clean():
    p = subprocess.run(
        [str(c_program("bin/chasm")), "check", "-P", str(c_program("plugins")), str(PLAN)],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert p.returncode == 0, p.stdout + p.stderr


@pytest.mark.parametrize(
    "vertical,speed,leaf",
    [
        (0, 0, "fly/mps/depth"),
        (1, 0, "fly/mps/altitude"),
        (2, 0, "fly/mps/pitch"),
        (0, 1, "fly/rpm/depth"),
        (1, 1, "fly/rpm/altitude"),
        (2, 1, "fly/rpm/pitch"),
    ],
)
def test_each_mode_pair_has_its_state(tmp_path, vertical, speed, leaf):
    p = run_plan(tmp_path, inputs(vertical, speed), leaf)
    assert p.returncode == 0, p.stdout + p.stderr


@pytest.mark.parametrize(
    "case,kw",
    [
        ("unknown vertical mode", dict(vertical=7, speed=0)),
        ("unknown speed mode", dict(vertical=0, speed=-1)),
        ("stale setpoint", dict(vertical=0, speed=0, setpoint_until=2.0)),
        ("stale navigation", dict(vertical=0, speed=0, nav_until=2.0)),
        ("deeper than max_depth", dict(vertical=0, speed=0, depth="101 m")),
    ],
)
def test_safety_rules_stop_the_vehicle(tmp_path, case, kw):
    p = run_plan(tmp_path, inputs(**kw), "idle")
    assert p.returncode == 0, f"{case}:\n{p.stdout}{p.stderr}"


def test_a_stale_setpoint_stops_one_cycle_after_the_timeout(tmp_path):
    p = run_plan(tmp_path, inputs(0, 0, setpoint_until=2.0), "idle")
    stopped = [line for line in p.stdout.splitlines() if "<- setpoint_stale or" in line]
    assert stopped and stopped[0].split()[0] == "3.050", p.stdout  # last setpoint at 2.0 s, age > 1 s
