"""auv-plan-survey --team: the team scenario's plans (one roster, one lines string,
TDMA slots from the modem), bindings, configs and time; the committed mcm_team
scenario is what the planner writes; bad input exits 2; the committed plans load
with the built plugins (the team plugin included)."""

from __future__ import annotations

import json
import math
import re
import shlex
import subprocess
import sys

import pytest
import yaml
from conftest import ROOT

from tools.demo import TEAM_PLAN_ARGS

PLAN = [sys.executable, "-m", "tools.plan.plan_survey"]
POLY = "20,20; 220,20; 220,200; 20,200"
SCENARIO = ROOT / "missions" / "scenarios" / "mcm_team"


def run_team(out, *extra):
    return subprocess.run(
        PLAN
        + [
            "--polygon",
            POLY,
            "--team",
            "3",
            *TEAM_PLAN_ARGS[:10],  # the committed team's geometry and depth (not its world or seed)
            "--out",
            str(out),
            *extra,
        ],
        capture_output=True,
        text=True,
        timeout=120,
        cwd=ROOT,
    )


def param(text: str, name: str) -> str:
    m = re.search(rf"^param {name}\s*=\s*(.+?)\s*(#.*)?$", text, re.M)
    assert m, name
    return m.group(1)


def test_team_plans_share_roster_and_lines_and_get_one_slot_each(tmp_path):
    out = tmp_path / "t"
    run = run_team(out)
    assert run.returncode == 0, run.stderr
    survey = json.loads((out / "survey.json").read_text())
    team = survey["team"]
    assert team["roster"] == ["AUV1", "AUV2", "AUV3", "AUV4"] and team["ri"] == ["AUV4"]
    # the modem of remus100_team_search.yaml: 0.5 s + 32 B x 8 / 80 bps = 3.7 s
    assert team["frame_bytes"] == 32 and team["frame_s"] == pytest.approx(3.7)
    op = survey["operating_area"]
    diameter = max(math.dist(a, b) for a in op for b in op)
    assert team["slot_s"] == pytest.approx(math.ceil((3.7 + diameter / 1400 + 0.3) * 10 - 1e-9) / 10)
    texts = {vid: (out / f"{vid}.chasm").read_text() for vid in team["roster"]}
    for k, (vid, text) in enumerate(texts.items()):
        assert text.count("{") == text.count("}")
        assert "use team" in text and 'include "' in text and "team_safety.chasm" in text
        assert param(text, "team") == '"AUV1,AUV2,AUV3,AUV4"' and param(text, "me") == f'"{vid}"'
        assert param(text, "lines") == f'"{team["lines"]}"'
        assert param(text, "my_slot") == str(k) and param(text, "slots") == "4"
        assert param(text, "slot") == f"{team['slot_s']:g} s"
        assert "do team_link(" in text and "do team_status() every 20 s" in text
        assert ("do search_contacts(rx = contacts" in text) == (vid != "AUV4")
        assert ("do ri_reacquire(looks = looks" in text) == (vid == "AUV4")
    # the lines string: each search vehicle's survey lines in flying order, owner first
    parts = [p.split(":") for p in team["lines"].split("; ")]
    owners = [int(o) for o, _ in parts]
    assert owners == sorted(owners) and set(owners) == {0, 1, 2}
    for idx, vid in enumerate(["AUV1", "AUV2", "AUV3"]):
        legs = [leg for leg in survey["vehicles"][vid]["legs"] if leg["kind"] == "line"]
        mine = [seg for o, seg in parts if int(o) == idx]
        assert len(mine) == len(legs)
        for seg, leg in zip(mine, legs):
            a, b = seg.split()
            assert [float(x) for x in a.split(",")] == pytest.approx(leg["start"], abs=0.051)
            assert [float(x) for x in b.split(",")] == pytest.approx(leg["end"], abs=0.051)
    sc = yaml.safe_load((out / "t.yaml").read_text())
    assert sc["time"]["source"] == "simulators"
    for v in sc["vehicles"]:
        ri = v["id"] == "AUV4"
        assert v["sim"]["config"].endswith("remus100_ri.yaml" if ri else "remus100_team_search.yaml")
        assert v["sim"]["simulation"] == {"clock": "lockstep"}
        assert v["sim"]["multihil"] == {"enabled": True, "lockstep_participants": 12}
        nav = next(m for m in v["managers"] if m["name"] == "NAVIGATOR")
        assert nav["bind"].endswith("team_ri.bind" if ri else "team_search.bind")
    from tools.scenario.scenario_file import load_scenario

    loaded = load_scenario(out / "t.yaml")
    assert [v.id for v in loaded.vehicles] == team["roster"]  # the launcher's own checks accept it


def test_the_launchers_clock_and_no_ri(tmp_path):
    run = run_team(tmp_path / "f", "--time-source", "launcher", "--ri", "0")
    assert run.returncode == 0, run.stderr
    sc = yaml.safe_load((tmp_path / "f" / "f.yaml").read_text())
    assert sc["time"] == {"mode": "lockstep", "source": "launcher", "limit": sc["time"]["limit"]}
    assert [v["id"] for v in sc["vehicles"]] == ["AUV1", "AUV2", "AUV3"]
    assert "simulation" not in sc["vehicles"][0]["sim"]
    assert param((tmp_path / "f" / "AUV3.chasm").read_text(), "slots") == "3"


def test_the_onboard_filter_for_the_whole_team(tmp_path):
    """--nav ekf: every vehicle steers by auv-nav, which takes part in the lockstep
    world beside its simulator, pilot and navigator."""
    run = run_team(tmp_path / "e", "--nav", "ekf")
    assert run.returncode == 0, run.stderr
    sc = yaml.safe_load((tmp_path / "e" / "e.yaml").read_text())
    assert [v.get("nav") for v in sc["vehicles"]] == ["ekf"] * 4
    assert {v["sim"]["multihil"]["lockstep_participants"] for v in sc["vehicles"]} == {16}


def test_backseat_vehicles_get_a_frontseat_no_pilot_and_a_scaled_world(tmp_path):
    """--backseat (docs/frontseat.md, "The team in backseat mode"): the vehicles named get
    the simulator's frontseat, no PILOT, auv-frontseat's depth limit and a plan that
    surfaces by asking for 0 m; the whole world runs on the simulators' scaled clock."""
    run = run_team(tmp_path / "b", "--backseat", "AUV1,AUV4", "--warp", "3", "--nav", "ekf")
    assert run.returncode == 0, run.stderr
    assert "AUV1, AUV4 from the backseat, scaled clock x3" in run.stdout
    sc = yaml.safe_load((tmp_path / "b" / "b.yaml").read_text())
    assert sc["time"] == {"mode": "scaled", "warp": 3.0, "source": "simulators", "limit": sc["time"]["limit"]}
    by_id = {v["id"]: v for v in sc["vehicles"]}
    for vid, v in by_id.items():
        assert v["sim"]["simulation"] == {"clock": "scaled", "warp": 3.0}
        assert v["sim"]["multihil"]["enabled"] and "lockstep_participants" not in v["sim"]["multihil"]
        names = [m["name"] for m in v["managers"]]
        plan = (tmp_path / "b" / f"{vid}.chasm").read_text()
        if vid in ("AUV1", "AUV4"):
            fs = v["sim"]["frontseat"]
            assert names == ["NAVIGATOR"] and "nav" not in v and v["backseat"] == {"max_depth": 60.0}
            assert fs["wire"] == {"protocol": "iver3", "pty": f"{vid}.frontseat", "baud": 19200}
            assert fs["mission_depth_m"] == 5.0 and fs["mission_speed_mps"] == 1.5
            assert param(plan, "surface_speed") == "1.5 m/s" and "do surface(speed = $surface_speed)" in plan
            assert param(plan, "nav_timeout") == "15 s"  # NAV is the frontseat's: its silence is ridden out
        else:
            assert names == ["PILOT", "NAVIGATOR"] and v["nav"] == "ekf" and "frontseat" not in v["sim"]
            assert "surface_speed" not in plan and "do surface()" in plan and param(plan, "nav_timeout") == "5 s"
    # the server of the world: the first vehicle (the best priority)
    prios = [v["sim"]["multihil"]["priority"] for v in sc["vehicles"]]
    assert prios == sorted(prios, reverse=True) and len(set(prios)) == 4
    assert json.loads((tmp_path / "b" / "survey.json").read_text())["team"]["backseat"] == ["AUV1", "AUV4"]


@pytest.mark.parametrize(
    "extra,msg",
    [
        (["--backseat", "AUV9"], "--backseat AUV9: AUV9: not of the team AUV1,AUV2,AUV3,AUV4"),
        (["--backseat", "all", "--time-source", "launcher"], "cannot take part in the launcher's lockstep"),
        (["--backseat", "all", "--warp", "0"], "--warp 0"),
        (["--team", "0"], "1 to 14 search vehicles"),
        (["--team", "15"], "1 to 14 search vehicles"),
        (["--ri-start", "x"], "--ri-start"),
        (["--slot-guard", "-1"], "--slot-guard -1: out of range"),
        (["--silent", "nan"], "--silent nan: out of range"),
        (["--search-config", "missions/sim/remus100.yaml"], "no modem: section"),
        (["--ri-config", "/nonexistent.yaml"], "no such file"),
    ],
)
def test_bad_team_input_exits_2(tmp_path, extra, msg):
    run = run_team(tmp_path / "x", *extra)
    assert run.returncode == 2 and msg in run.stderr, run.stderr
    assert "Traceback" not in run.stderr


def test_mismatched_modems_are_refused(tmp_path):
    cfg = tmp_path / "ri.yaml"
    cfg.write_text(
        (ROOT / "missions" / "sim" / "remus100_ri.yaml").read_text().replace("bitrate_bps: 80", "bitrate_bps: 1300")
    )
    base = "remus100_base.yaml"  # the base it extends, next to it
    (tmp_path / base).write_text((ROOT / "missions" / "sim" / base).read_text())
    run = run_team(tmp_path / "x", "--ri-config", str(cfg))
    assert run.returncode == 2 and "one team, one modem profile" in run.stderr, run.stderr


def test_the_committed_team_scenario_is_what_the_planner_writes(tmp_path):
    header = (SCENARIO / "mcm_team.yaml").read_text().splitlines()[1]
    args = shlex.split(header.split("auv-plan-survey ", 1)[1])
    args[args.index("--out") + 1] = str(tmp_path / "mcm_team")
    run = subprocess.run(PLAN + args, capture_output=True, text=True, timeout=120, cwd=ROOT)
    assert run.returncode == 0, run.stderr
    assert json.loads((tmp_path / "mcm_team" / "survey.json").read_text()) == json.loads(
        (SCENARIO / "survey.json").read_text()
    )

    def plan_body(p):  # include paths are relative to the plan's folder
        return [ln for ln in p.read_text().splitlines() if not ln.startswith("include ")]

    plans = sorted(SCENARIO.glob("AUV*.chasm"))
    assert [p.name for p in plans] == ["AUV1.chasm", "AUV2.chasm", "AUV3.chasm", "AUV4.chasm"]
    for plan in plans:
        assert plan_body(plan) == plan_body(tmp_path / "mcm_team" / plan.name), plan.name

    def scenario(folder):  # file references resolved: the two folders differ
        sc = yaml.safe_load((folder / "mcm_team.yaml").read_text())
        for v in sc["vehicles"]:
            v["sim"]["config"] = str((folder / v["sim"]["config"]).resolve())
            for m in v["managers"]:
                m["plan"], m["bind"] = str((folder / m["plan"]).resolve()), str((folder / m["bind"]).resolve())
                m["plan"] = m["plan"].rsplit("/", 1)[1] if m["name"] == "NAVIGATOR" else m["plan"]
        return sc

    assert scenario(SCENARIO) == scenario(tmp_path / "mcm_team")


def chasm_check(plan):
    from conftest import BUILD, c_program

    return subprocess.run(
        [str(c_program("bin/chasm")), "check", "-P", str(BUILD / "plugins"), str(plan)],
        capture_output=True,
        text=True,
        timeout=60,
    )


def test_the_team_plans_load_with_the_team_plugin():
    for plan in sorted(SCENARIO.glob("AUV*.chasm")):
        run = chasm_check(plan)
        assert run.returncode == 0 and ": ok (" in run.stdout, run.stdout + run.stderr


def test_one_target_field_publisher_and_one_field_in_the_lockstep_team():
    """Stepped simulators in a multi-HIL world publish no SIM.TARGETS on `auto`: the
    launcher makes the first sonar vehicle the one publisher (as on its own clock); the
    RI vehicle's identify.targets build the same field as the search vehicles' sonar."""
    from confcheck.reader import dump_yaml
    from sim.config import loads
    from sim.sonar.publisher import build_field
    from tools.launch.simconfig import vehicle_config
    from tools.scenario.scenario_file import load_scenario

    sc = load_scenario(SCENARIO / "mcm_team.yaml")
    cfgs = {v.id: vehicle_config(sc, v, k) for k, v in enumerate(sc.vehicles)}
    assert [cfgs[v].get("sonar", {}).get("publish_targets") for v in ("AUV1", "AUV2", "AUV3", "AUV4")] == [
        "yes",
        "no",
        "no",
        None,
    ]
    sims = {vid: loads(dump_yaml(c), SCENARIO / f"{vid}.sim.yaml") for vid, c in cfgs.items()}
    search = build_field(sims["AUV1"])
    ri = build_field(sims["AUV4"], sims["AUV4"].identify.targets)
    assert len(search.targets) == 24
    assert [(t.north_m, t.east_m, t.kind) for t in ri.targets] == [
        (t.north_m, t.east_m, t.kind) for t in search.targets
    ]
