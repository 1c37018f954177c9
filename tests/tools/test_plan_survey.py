"""auv-plan-survey end to end: the plans it writes have the contract's shape
and match the geometry; they pass `chasm check` when the guidance and checks
plugins are built; the scenario loads; bad input exits 2."""

from __future__ import annotations

import json
import re
import shlex
import subprocess
import sys

import pytest
import yaml
from conftest import BUILD, ROOT

PLAN = [sys.executable, "-m", "tools.plan.plan_survey"]
POLY = "0,0; 500,-50; 600,300; 250,420; -20,300"


def run_planner(out, *extra):
    return subprocess.run(
        PLAN
        + [
            "--polygon",
            POLY,
            "--vehicles",
            "3",
            "--heading",
            "10",
            "--range",
            "40",
            "--nadir-gap",
            "4",
            "--overlap",
            "0.2",
            "--out",
            str(out),
            *extra,
        ],
        capture_output=True,
        text=True,
        timeout=60,
    )


def states_of(text):
    """State names and their bodies (a small structural reader, not the CHASM loader)."""
    names = re.findall(r"^\s*state\s+(\w+)\s*\{", text, re.M)
    return names


def test_plans_have_the_contract_shape_and_follow_the_geometry(tmp_path):
    run = run_planner(tmp_path / "s")
    assert run.returncode == 0, run.stderr
    survey = json.loads((tmp_path / "s" / "survey.json").read_text())
    for vid, v in survey["vehicles"].items():
        text = (tmp_path / "s" / f"{vid}.chasm").read_text()
        assert text.count("{") == text.count("}")
        names = states_of(text)
        assert len(names) == len(set(names))
        for target in re.findall(r"(?:->\s*(?:resume\s+(?:deep\s+)?)?|\bnext\s+)(\w+)", text):
            assert target in names, target
        # one state per leg, in order, each a track of that leg at survey altitude
        legs = re.findall(
            r"state (\w+) \{\n\s+do track\(from_north = (\S+) m, from_east = (\S+) m, "
            r"to_north = (\S+) m, to_east = (\S+) m, speed = \$speed\)\n"
            r"\s+do hold_altitude\(altitude = \$altitude\)\n\s+next (\w+)",
            text,
        )
        assert len(legs) == len(v["legs"])
        for (name, fn, fe, tn, te, nxt), leg, following in zip(legs, v["legs"], legs[1:] + [("recover",)]):
            assert name.startswith(leg["kind"])
            assert [float(fn), float(fe), float(tn), float(te)] == pytest.approx(leg["start"] + leg["end"], abs=0.051)
            assert nxt == following[0]
        assert re.search(
            r"^state gps_fix \{\n    do surface_fix\(timeout = \$fix_timeout\)\n"
            r"    when done -> resume deep survey.*\n    when failed -> resume deep survey",
            text,
            re.M,
        )
        assert "when fix_due -> gps_fix" in text and "test fix_due : elapsed > $fix_every" in text
        assert "start mission" in text and re.search(r'include "[./]*.*missions/common/safety.chasm"', text)
        for param in ("max_depth", "min_altitude", "nav_timeout", "mission_timeout", "area"):
            assert re.search(rf"^param {param} +=", text, re.M), param
        area = re.search(r'^param area += "([^"]+)"', text, re.M).group(1)
        assert len(area.split(";")) == len(survey["operating_area"])


def test_scenario_names_the_plans_and_starts(tmp_path):
    run = run_planner(tmp_path / "demo", "--name", "demo", "--fix-every-min", "10")
    assert run.returncode == 0, run.stderr
    sc = yaml.safe_load((tmp_path / "demo" / "demo.yaml").read_text())
    survey = json.loads((tmp_path / "demo" / "survey.json").read_text())
    assert [v["id"] for v in sc["vehicles"]] == ["AUV1", "AUV2", "AUV3"]
    for v in sc["vehicles"]:
        nav = next(m for m in v["managers"] if m["name"] == "NAVIGATOR")
        assert nav["plan"] == f"{v['id']}.chasm"
        assert [v["sim"]["initial"]["north_m"], v["sim"]["initial"]["east_m"]] == pytest.approx(
            survey["vehicles"][v["id"]]["start"], abs=0.051
        )
    assert "param fix_every    = 10 min" in (tmp_path / "demo" / "AUV2.chasm").read_text()
    # managers report twice a second of mission time and on every change, not every cycle
    assert {m["status_rate"] for v in sc["vehicles"] for m in v["managers"]} == {2.0}
    missing = [
        p
        for v in sc["vehicles"]
        for m in v["managers"]
        for p in (m["plan"], m["bind"])
        if not (tmp_path / "demo" / p).exists()
    ]
    assert not missing, f"the scenario names files that do not exist: {sorted(set(missing))}"
    from tools.scenario.scenario_file import load_scenario

    assert len(load_scenario(tmp_path / "demo" / "demo.yaml").vehicles) == 3


def test_plans_pass_chasm_check(tmp_path):
    needed = [
        BUILD / "plugins" / "chasm_guidance.so",
        ROOT / "missions" / "common" / "navigator_io.chasm",
        ROOT / "missions" / "common" / "safety.chasm",
    ]
    missing = [str(p) for p in needed if not p.exists()]
    assert not missing, f"chasm check needs the guidance plugin and the shared plan files: missing {missing}"
    assert run_planner(tmp_path / "s").returncode == 0
    plans = sorted((tmp_path / "s").glob("*.chasm"))
    check = subprocess.run(
        [str(BUILD / "bin" / "chasm"), "check", "-P", str(BUILD / "plugins"), *map(str, plans)],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert check.returncode == 0, check.stdout + check.stderr


@pytest.mark.parametrize(
    "args,msg",
    [
        (["--polygon", "0,0; 1,1", "--range", "40"], "at least 3 vertices"),
        (["--polygon", POLY, "--range", "40", "--overlap", "1.5"], "overlap"),
        (["--polygon", POLY, "--range", "40", "--vehicles", "2", "--ids", "A1"], "--ids names 1"),
        (["--polygon", POLY, "--range", "40", "--vehicles", "2", "--starts", "0,0"], "--starts gives 1"),
        (["--polygon", "@/nonexistent/poly.txt", "--range", "40"], "No such file"),
        (["--polygon", POLY, "--range", "40", "--status-rate", "-1"], "--status-rate -1: out of range"),
        (["--polygon", POLY, "--range", "40", "--status-rate", "nan"], "--status-rate nan: out of range"),
        (["--polygon", POLY, "--range", "40", "--backseat", "AUV1"], "--backseat: with --team only"),
    ],
)
def test_bad_input_exits_2(tmp_path, args, msg):
    run = subprocess.run(PLAN + args + ["--out", str(tmp_path / "x")], capture_output=True, text=True, timeout=60)
    assert run.returncode == 2 and msg in run.stderr, run.stderr


def test_the_committed_demo_scenario_is_what_the_planner_writes(tmp_path):
    """missions/scenarios/mcm_demo/ must not drift from the planner: regenerate it
    with the command recorded in its header and compare."""
    demo = ROOT / "missions" / "scenarios" / "mcm_demo"
    header = (demo / "mcm_demo.yaml").read_text().splitlines()[1]
    command = header.split("auv-plan-survey ", 1)[1]
    args = shlex.split(command)
    args[args.index("--out") + 1] = str(tmp_path / "mcm_demo")
    run = subprocess.run(PLAN + args, capture_output=True, text=True, timeout=60, cwd=ROOT)
    assert run.returncode == 0, run.stderr
    assert json.loads((tmp_path / "mcm_demo" / "survey.json").read_text()) == json.loads(
        (demo / "survey.json").read_text()
    )
    for plan in demo.glob("AUV*.chasm"):
        body = lambda p: p.read_text().split("start mission", 1)[1].rsplit("include", 1)[0]  # noqa: E731
        assert body(plan) == body(tmp_path / "mcm_demo" / plan.name), plan.name
