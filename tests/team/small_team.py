"""A small team scenario for the full-stack team tests: the planner's team
plans (auv-plan-survey --team N --ri 1) over a corner of the committed MCM
world, short enough to fly in a few minutes of sim time, with the variants a
test needs (modem settings, plan parameters, start positions, planned faults)
written beside it. Every run is the real launcher over real LCM, lockstep."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import yaml
from conftest import BUILD

from tools.demo import TEAM_PLAN_ARGS

# 90 m of line north, 110 m east: four line legs per search vehicle
POLYGON = "20,20; 70,20; 70,130; 20,130"


def plan(out: Path, search: int = 2, ri: int = 1, polygon: str = POLYGON) -> Path:
    """The planner's scenario for `search` search vehicles and `ri` RI vehicles."""
    run = subprocess.run(
        [
            sys.executable,
            "-m",
            "tools.plan.plan_survey",
            "--polygon",
            polygon,
            "--team",
            str(search),
            "--ri",
            str(ri),
            *TEAM_PLAN_ARGS,  # the committed team's settings
            "--out",
            out,
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 0, run.stdout + run.stderr
    return out / f"{out.name}.yaml"


def variant(
    base: Path,
    out: Path,
    *,
    modem: dict | None = None,
    params: dict[str, dict] | None = None,
    initial: dict[str, dict] | None = None,
    faults: list | None = None,
    limit_s: float | None = None,
) -> Path:
    """A copy of scenario `base` as out (paths made absolute): `modem` merged
    into every simulator's modem section, `params[vid]` given to the vehicle's
    NAVIGATOR plan (-D), `initial[vid]` its start, `faults` the planned faults."""
    sc = yaml.safe_load(base.read_text())
    for v in sc["vehicles"]:
        v["sim"]["config"] = str((base.parent / v["sim"]["config"]).resolve())
        if modem:
            v["sim"]["modem"] = dict(modem)
        if initial and v["id"] in initial:
            v["sim"]["initial"] = {**v["sim"].get("initial", {}), **initial[v["id"]]}
        for m in v["managers"]:
            m["plan"] = str((base.parent / m["plan"]).resolve())
            m["bind"] = str((base.parent / m["bind"]).resolve())
            if m["name"] == "NAVIGATOR" and params and v["id"] in params:
                m["params"] = {k: str(x) for k, x in params[v["id"]].items()}
    if "survey" in sc:
        sc["survey"] = str((base.parent / sc["survey"]).resolve())
    if faults:
        sc["faults"] = faults
    if limit_s is not None:
        sc["time"]["limit"] = limit_s
    out.write_text(yaml.safe_dump(sc, sort_keys=False))
    return out


def fly(scenario: Path, run_dir: Path, lcm_url: str, env: dict, expect_rc: int | None = 0) -> str:
    """Launch the scenario to its end; its stdout (expect_rc None: any exit status)."""
    p = subprocess.run(
        [
            sys.executable,
            "-m",
            "tools.launch",
            scenario,
            "--out",
            run_dir,
            "--lcm-url",
            lcm_url,
            "--build",
            BUILD,
            "--progress",
            "0",
        ],
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert expect_rc is None or p.returncode == expect_rc, p.stdout[-3000:] + p.stderr[-3000:]
    return p.stdout


def report(run_dir: Path, out: Path, env: dict) -> dict:
    """auv-report's JSON of the run (no plots)."""
    p = subprocess.run(
        [sys.executable, "-m", "tools.report", run_dir / "run.lcmlog", "--out", out, "--no-plots"],
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert p.returncode == 0, p.stdout[-2000:] + p.stderr[-2000:]
    return json.loads((out / "report.json").read_text())


def messages(log: Path, suffix: str) -> list:
    """(channel, decoded message) of every message on a channel ending with suffix."""
    from auvlcm.log import read_events

    return [(ev.channel, ev.msg) for ev in read_events(log) if ev.channel.endswith(suffix) and ev.msg is not None]


def team_events(log: Path) -> list[tuple[float, str, str, str, int, str]]:
    """(sim s, vehicle, kind name, origin, number, text) of every TEAM_EVENT."""
    from auv import team_event_t

    names = {getattr(team_event_t, k): k for k in dir(team_event_t) if k.isupper()}
    return [
        (m.utime / 1e6, m.vehicle, names.get(m.kind, str(m.kind)), m.origin, m.number, m.text)
        for _, m in messages(log, ".TEAM_EVENT")
        if isinstance(m, team_event_t)
    ]
