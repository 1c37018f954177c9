"""A vehicle flown from its backseat by auv-launch (docs/frontseat.md, "The team in
backseat mode"): missions/frontseat/backseat_line.yaml, the simulator's Iver3
frontseat on a pty, auv-frontseat started by the launcher where the PILOT would
stand, the NAVIGATOR's two-leg line through it.

- What the launcher refuses before anything starts, at file:line:col: a lockstep
  world (the launcher's clock, or the simulators' lockstep clock), a manager that
  writes the actuators (a PILOT), `nav: ekf`, auv-frontseat's limits on a vehicle
  without a frontseat.
- Control taken away mid-line and given back: the emulator's operator takes the
  vehicle (mode M, `manual_at_s` for `manual_for_s`) in the middle of the line and
  gives it back. frontseat_status_t shows control lost (MANUAL) and granted again;
  auv-frontseat kept asking meanwhile and the frontseat ignored the requests (the
  vehicle flew the operator's heading, not the line's); after the give-back the
  vehicle is back on its line (the truth's cross-track distance under XTRACK_M
  within BACK_WITHIN_S and under it to the line's end), and the navigator's leg
  advances to the second leg and the mission ends done.
"""

from __future__ import annotations

import math
import subprocess
import sys
import time
from pathlib import Path

import yaml
from conftest import ROOT

from auv import frontseat_status_t
from auvlcm.log import read_events

SCENARIO = ROOT / "missions" / "frontseat" / "backseat_line.yaml"
LAUNCH = [sys.executable, "-m", "tools.launch"]
# the operator's window: in the middle of the line (A (0, 0) to B (0, 120), east, at
# 1.5 m/s; the vehicle is on it from about 40 s, after its dive on its own mission and
# its run onto the line), long enough to turn to the operator's heading (at the pilot's
# 6 deg/s) and leave the line
MANUAL_AT_S, MANUAL_FOR_S = 45.0, 15.0
OWN_HEADING_DEG = 45.0  # the frontseat's own mission: what the operator flies
LINE_END_EAST = 120.0
XTRACK_M = 2.0  # back on the line: the ILOS (10 m lookahead) intercepts at up to 60 deg, turns at 6 deg/s
BACK_WITHIN_S = 40.0  # measured about 30 s from 12 m off (it runs on to 18 m while it turns back)
WARP = 6.0


def scenario(tmp_path: Path, frontseat: dict | None = None, **changes) -> tuple[Path, dict]:
    """backseat_line.yaml with its paths absolute, the frontseat's keys and the
    given top-level or vehicle changes (`vehicle=`) applied; written into tmp_path."""
    doc = yaml.safe_load(SCENARIO.read_text())
    base = SCENARIO.parent
    v = doc["vehicles"][0]
    v["sim"]["config"] = str((base / v["sim"]["config"]).resolve())
    for m in v["managers"]:
        m["plan"], m["bind"] = str((base / m["plan"]).resolve()), str((base / m["bind"]).resolve())
    v["sim"]["frontseat"].update(frontseat or {})
    v.update(changes.pop("vehicle", {}))
    doc.update(changes)
    path = tmp_path / "backseat_line.yaml"
    path.write_text(yaml.safe_dump(doc, sort_keys=False))
    return path, doc


def launch(path: Path, out: Path, url: str, env: dict, timeout: float = 120) -> subprocess.CompletedProcess:
    return subprocess.run(
        LAUNCH + [str(path), "--out", str(out), "--lcm-url", url, "--progress", "0"],
        env=env,
        capture_output=True,
        text=True,
        timeout=timeout,
    )


def test_the_launcher_refuses_what_a_backseat_cannot_be(tmp_path, lcm_url, child_env):
    pilot = {
        "name": "PILOT",
        "plan": str(ROOT / "missions" / "pilot" / "pilot.chasm"),
        "bind": str(ROOT / "missions" / "bindings" / "pilot.bind"),
        "rate": 20,
    }
    path, doc = scenario(tmp_path, time={"mode": "scaled", "warp": 4, "limit": 100})
    v = doc["vehicles"][0]
    v["managers"].insert(0, pilot)
    v["nav"] = "ekf"
    plain = {
        "id": "AUV2",
        "sim": {"config": v["sim"]["config"], "initial": {"east_m": 50.0}},
        "backseat": {"max_depth": 20},
        "managers": [{**v["managers"][1], "bind": str(ROOT / "missions" / "bindings" / "navigator.bind")}],
    }
    doc["vehicles"].append(plain)
    path.write_text(yaml.safe_dump(doc, sort_keys=False))
    run = launch(path, tmp_path / "out", lcm_url, child_env)
    err = run.stderr
    assert run.returncode == 2, run.stdout + err
    assert "launcher's clock is lockstep in every mode" in err, err
    assert "AUV1.PILOT: writes AUV1.ACTUATORS (pilot.bind)" in err, err
    assert "AUV1.nav: ekf" in err and "the frontseat navigates" in err, err
    assert "AUV2.backseat: auv-frontseat's limits, but" in err, err
    assert f"{path}:" in err and "launch: " in err  # file:line:col of the scenario
    assert not (tmp_path / "out" / "run.lcmlog").exists()

    # the simulators' own lockstep clock: refused as well, at the frontseat's line
    path, doc = scenario(tmp_path, vehicle={"sim": {**doc["vehicles"][0]["sim"], "simulation": {"clock": "lockstep"}}})
    run = launch(path, tmp_path / "out2", lcm_url, child_env)
    assert run.returncode == 2 and "its simulator's clock is lockstep" in run.stderr, run.stdout + run.stderr
    line = next(i for i, t in enumerate(path.read_text().splitlines(), 1) if t.strip().startswith("frontseat:"))
    assert f"{path}:{line + 1}:" in run.stderr, run.stderr  # the section's first key


def angle_diff(a: float, b: float) -> float:
    return abs((a - b + math.pi) % (2 * math.pi) - math.pi)


def test_control_taken_away_mid_line_and_given_back(tmp_path, lcm_url, child_env):
    path, doc = scenario(
        tmp_path,
        frontseat={"manual_at_s": MANUAL_AT_S, "manual_for_s": MANUAL_FOR_S},
        time={"mode": "scaled", "warp": WARP, "source": "simulators", "limit": 300},
    )
    doc["vehicles"][0]["sim"]["simulation"]["warp"] = WARP
    path.write_text(yaml.safe_dump(doc, sort_keys=False))
    out = tmp_path / "run"
    wall0 = time.monotonic()
    run = launch(path, out, lcm_url, child_env)
    wall = time.monotonic() - wall0
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]

    truth, status, legs = [], [], []
    for ev in read_events(out / "run.lcmlog"):
        if ev.msg is None:
            continue
        if ev.channel == "AUV1.TRUTH":
            truth.append((ev.msg.utime / 1e6, *ev.msg.eta))
        elif ev.channel == "AUV1.FRONTSEAT":
            status.append(ev.msg)
        elif ev.channel == "AUV1.CHASM.NAVIGATOR" and ev.msg.path_len:
            leaf = "/".join(ev.msg.active_path)
            if not legs or legs[-1][1] != leaf:
                legs.append((ev.msg.utime / 1e6, leaf))
    assert truth and status and legs

    # control lost to the operator (MANUAL, mode M) and granted again; auv-frontseat kept asking
    manual = [s for s in status if s.state == frontseat_status_t.STATE_MANUAL]
    assert manual and all(s.mode == "M" and not s.has_control for s in manual), manual[:1]
    assert any(s.requesting for s in manual), "auv-frontseat stopped asking while manual"
    t_lost = min(s.utime for s in manual) / 1e6
    t_back = min(s.utime / 1e6 for s in status if s.has_control and s.utime / 1e6 > t_lost)
    assert (
        MANUAL_AT_S <= t_lost < MANUAL_AT_S + 1.0 and MANUAL_AT_S + MANUAL_FOR_S <= t_back < t_lost + MANUAL_FOR_S + 2
    )
    final = status[-1]
    assert final.control_granted >= 2 and final.control_lost >= 1, final

    # while manual the requests were ignored: the vehicle flew the operator's heading, off the line
    late = [r for r in truth if t_lost + 10.0 <= r[0] <= t_back - 0.5]
    assert late and all(angle_diff(r[6], math.radians(OWN_HEADING_DEG)) < math.radians(10) for r in late), late[-1:]
    off = max(abs(r[1]) for r in truth if t_lost <= r[0] <= t_back)
    assert off > 5.0, off

    # the navigator's leg advances past the line's end, and the mission ends done
    leaves = [leaf for _, leaf in legs]
    assert "route/line" in leaves and "route/leg2" in leaves and "route/recover" in leaves, leaves
    t_leg2 = next(t for t, leaf in legs if leaf == "route/leg2")
    east_then = min(truth, key=lambda r: abs(r[0] - t_leg2))[2]
    assert t_leg2 > t_back and east_then >= LINE_END_EAST - 2.0, (t_leg2, east_then)

    # back on the line within BACK_WITHIN_S, and on it to the line's end (the second leg's start)
    line = [r for r in truth if t_back <= r[0] < t_leg2]
    on = next((r[0] for r in line if abs(r[1]) < XTRACK_M), None)
    assert on is not None and on - t_back <= BACK_WITHIN_S, (on, t_back, off)
    worst = max(abs(r[1]) for r in line if r[0] >= on + 5.0)
    assert worst < XTRACK_M, worst
    assert max(r[2] for r in line) >= LINE_END_EAST - 2.0  # along the line to its end
    assert "AUV1: done" in run.stdout, run.stdout[-2000:]
    print(
        f"control lost at {t_lost:.1f} s, back at {t_back:.1f} s, {off:.1f} m off the line; on it again "
        f"{on - t_back:.1f} s later, then within {worst:.2f} m; leg 2 at {t_leg2:.1f} s; {wall:.1f} s wall"
    )
