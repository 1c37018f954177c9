"""A scenario with `radio:`: the launcher starts the radio model, the shore
gateway and the vehicle's gateway with the rest, and the vehicle's status
comes home over the radio into the log (SHORE.AUV1.RADIO_REPORT). Out of the
radio's range, `auvctl --shore abort` goes through the water: the shore
station's frame, heard by the vehicle's simulated modem, aborts its plan."""

from __future__ import annotations

import re
import subprocess
import sys
import time

import lcm
import yaml
from conftest import ROOT

from auv import radio_link_t, radio_report_t

SIM = str(ROOT / "missions" / "sim" / "remus100_multihil.yaml")
PLAN = str(ROOT / "tests" / "tools" / "scenarios" / "mission.chasm")
BIND = str(ROOT / "missions" / "bindings" / "direct_actuators.bind")


def _scenario(tmp_path, time_: dict, radio: dict, sim: dict) -> list[str]:
    sc = {
        "name": "radio_launch",
        "seed": 1,
        "time": time_,
        "radio": radio,
        "vehicles": [
            {
                "id": "AUV1",
                "sim": {"config": SIM, **sim},
                "managers": [
                    {"name": "NAVIGATOR", "plan": PLAN, "bind": BIND, "rate": 10, "params": {"cycles": 100000}}
                ],
            }
        ],
    }
    path = tmp_path / "radio.yaml"
    path.write_text(yaml.safe_dump(sc, sort_keys=False))
    return [sys.executable, "-m", "tools.launch", str(path), "--out", str(tmp_path / "run"), "--progress", "0"]


def test_the_launcher_starts_the_radio_and_the_status_comes_home(tmp_path, lcm_url, child_env):
    cmd = _scenario(
        tmp_path,
        {"mode": "lockstep", "limit": 8, "wall_limit": 120},
        {"report_period_s": 1.0, "acoustic": {"AUV1": 0}},
        {},
    )
    run = subprocess.run(cmd + ["--lcm-url", lcm_url], env=child_env, capture_output=True, text=True, timeout=180)
    assert run.returncode == 6, run.stdout + run.stderr  # the time limit: the plan runs on
    out = tmp_path / "run"
    assert "auv-radio AUV1: delivered 0" in (out / "AUV1.radio.out").read_text()
    steps = re.search(r"lockstep: (\d+) steps reported", (out / "radio.out").read_text())
    assert steps and int(steps[1]) >= 150, (out / "radio.out").read_text()  # the model took part: 8 s of 0.05 s
    assert "auv-radio-shore: frames dropped 0" in (out / "shore_gateway.out").read_text()
    reports, links = [], []
    for ev in lcm.EventLog(str(out / "run.lcmlog"), "r"):
        if ev.channel == "SHORE.AUV1.RADIO_REPORT":
            reports.append(radio_report_t.decode(ev.data))
        elif ev.channel == "AUV1.RADIO_LINK":
            links.append(radio_link_t.decode(ev.data))
    # at the surface, the hull bobs: the antenna (0.5 m) is clear of crests 0.1 m high above 0.4 m
    links = [m for m in links if m.depth_m < 1e8]  # not before the first truth
    assert len(links) > 5 and all(m.up == (m.depth_m < 0.4) for m in links), [(m.depth_m, m.up) for m in links]
    assert sum(m.up for m in links) > len(links) / 2
    assert len(reports) >= 4, len(reports)
    assert reports[-1].mission.startswith("RUNNING run") and reports[-1].vehicle == "AUV1", reports[-1].mission


def test_out_of_radio_range_an_abort_goes_through_the_water(tmp_path, lcm_url, child_env):
    cmd = _scenario(
        tmp_path,
        {"mode": "scaled", "warp": 10, "limit": 300, "wall_limit": 90},  # ends at the abort, seconds in
        {"shore_north_m": 500.0, "max_range_m": 100.0, "acoustic": {"AUV1": 0}},
        {"modem": {}},  # the vehicle's simulated modem hears the shore station's frame
    )
    launch = subprocess.Popen(cmd + ["--lcm-url", lcm_url], env=child_env, stdout=subprocess.PIPE, text=True)
    try:
        shore = tmp_path / "run" / "shore_gateway.out"
        deadline = time.monotonic() + 60
        while not (shore.exists() and "ready" in shore.read_text()):
            assert time.monotonic() < deadline and launch.poll() is None, "the shore gateway never came up"
            time.sleep(0.05)
        ctl = subprocess.run(
            [sys.executable, "-m", "tools.console.auvctl", "--lcm-url", lcm_url, "--timeout", "3", "--shore"]
            + ["abort", "AUV1"],
            env=child_env,
            capture_output=True,
            text=True,
            timeout=60,
        )
        out, _ = launch.communicate(timeout=120)
    finally:
        launch.kill()
    # no answer can come home (the radio is out of range), but the command went into the water
    assert ctl.returncode == 3 and "AUV1 abort (acoustic): in flight\n" in ctl.stdout, ctl.stdout + ctl.stderr
    assert launch.returncode == 3, out
    assert "AUV1: aborted (operator abort: shore, acoustic abort #" in out, out
    assert "acoustic commands 1" in (tmp_path / "run" / "AUV1.radio.out").read_text()
