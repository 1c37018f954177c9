#!/usr/bin/env python3
"""`make demo`: the cooperative mine-countermeasures team, end to end, in fast time.

Fast time is lockstep (docs/scenarios.md, "Time"): as fast as the slowest
process, and the same seed gives the same log, whatever the machine's load.

By default the committed team scenario (missions/scenarios/mcm_team): three
search vehicles with sidescan hand their mine-like contacts over the simulated
acoustic modem to a reacquire-identify vehicle, which identifies them
(docs/team.md). With --polygon the demo plans its own survey first: a plain
survey by --vehicles vehicles (missions/scenarios/mcm_demo's settings), or a
team of --team search vehicles and one RI vehicle (mcm_team's settings). The
launcher runs it (simulators, PILOT and NAVIGATOR managers, the recorder, on
one global clock); the report tool then reads the log: outcome, coverage,
detections against the truth, the team's hand-offs and link, navigation error,
and the plots. This prints a short summary and where the files are. Exit
status: the launcher's when the mission did not end done, else the report's.

`--mission sampling` runs the front-sampling team instead
(missions/scenarios/sampling_team, docs/sampling.md): three vehicles with CTDs
map an ocean front on board and share their fits over the acoustic modem; the
summary prints the grade of their estimates against the world's front.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path

from auvlcm import programs
from auvlcm.paths import ROOT
from sim import clock_modes

PY = sys.executable
SCENARIO = ROOT / "missions" / "scenarios" / "mcm_team" / "mcm_team.yaml"
SAMPLING_SCENARIO = ROOT / "missions" / "scenarios" / "sampling_team" / "sampling_team.yaml"
# What missions/scenarios/mcm_demo was planned with (its header); --polygon plans with these.
PLAN_ARGS = [
    "--heading",
    "80",
    "--range",
    "40",
    "--nadir-gap",
    "11.5",
    "--overlap",
    "0.1",
    "--fix-every-min",
    "30",
    "--depth-m",
    "4",
    "--world",
    str(ROOT / "missions/scenarios/mcm_world.yaml"),
    "--seed",
    "7",
    "--sim-config",
    str(ROOT / "missions/sim/remus100_mcm.yaml"),
    "--nav",
    "ekf",
]
# What missions/scenarios/mcm_team was planned with (its header); --polygon --team plans with these.
TEAM_PLAN_ARGS = [
    "--heading",
    "0",
    "--range",
    "40",
    "--nadir-gap",
    "9.5",
    "--overlap",
    "0.1",
    "--depth-m",
    "5",
    "--world",
    str(ROOT / "missions/scenarios/mcm_world.yaml"),
    "--seed",
    "7",
]


def run(cmd: list, what: str) -> int:
    print(f"demo: {what}", flush=True)
    return subprocess.call([str(c) for c in cmd])


def _pd(p: float | None) -> str:
    return "n/a" if p is None else f"{p:.2f}"


def summary(rep: dict) -> str:
    """The demo's summary; a scenario without a survey or targets has no coverage or detection line."""
    lines = [
        f"outcome   {rep['outcome']}: " + ", ".join(f"{v} {o}" for v, o in rep["vehicle_outcomes"].items()),
        f"duration  {rep['duration_s'] / 60:.1f} min of sim time",
    ]
    cov, det = rep.get("coverage"), rep.get("detection")
    if cov:
        lines.append(
            f"coverage  {cov['survey_area_m2'] / 1e6:.4f} km2: once {_pct(cov['fraction_once'])}, "
            f"twice {_pct(cov['fraction_twice'])}"
        )
    if det:
        lines.append(
            f"detection {det['mine_like_detected']} of {det['mine_like_targets']} mine-like targets "
            f"(PD {_pd(det['pd'])}"
            + (
                f"; in the covered area {det['mine_like_in_covered_area']}, PD {_pd(det['pd_in_covered_area'])}"
                if "pd_in_covered_area" in det
                else ""
            )
            + f"); {det['contacts']} contacts, {det['contacts_on_clutter']} on clutter, "
            f"{det['false_alarms']} false alarms"
        )
    team = rep.get("team")
    if team and team.get("mine_like_targets"):
        lat = team.get("detect_to_identify_s") or {}
        lines.append(
            f"team      {team['mine_like_identified']} of {team['mine_like_targets']} mine-like targets "
            f"identified ({team['mine_like_identified_as_mine']} as mine), "
            f"{len(team.get('false_identifications') or [])} false identifications, "
            f"{team['not_found']} not found"
            + (
                f"; detection to identification median {lat['median'] / 60:.1f} min, max {lat['max'] / 60:.1f} min"
                if lat.get("n")
                else ""
            )
        )
    if team:
        link = (team.get("link") or {}).get("per_vehicle", {})
        lines.append(
            "link      "
            + ", ".join(
                f"{v} {k['sent']} sent/{k['heard']} heard/{k['lost']} lost/{k['collided']} collided"
                for v, k in link.items()
            )
            or "-"
        )
        lines.append(f"takeovers {len(team.get('takeovers') or [])}")
    sampling = rep.get("sampling")
    if sampling:
        from tools.report.front_grade import sampling_text

        lines += sampling_text(sampling)
    lines += [
        "nav error "
        + (
            ", ".join(f"{v} rms {e['rms_m']:.1f} m (max {e['max_m']:.1f})" for v, e in rep["navigation_error"].items())
            or "-"
        ),
        "record    "
        + (
            ", ".join(
                f"{v} {r['missing']} of {r['samples'] + r['missing']} truth samples lost"
                for v, r in rep["record"].items()
            )
            or "-"
        ),
    ]
    return "\n".join(lines)


def result_text(rep: dict, out: Path, log: Path, wall_s: float) -> str:
    """What the demo prints at the end: the summary and where the files are."""
    lines = [
        "",
        summary(rep),
        f"wall time {wall_s:.0f} s",
        "",
        f"report    {out / 'report.txt'}  {out / 'report.json'}",
    ]
    lines += [f"plot      {p}  (and .svg)" for p in rep.get("plots", []) if p.endswith(".png")]  # none with --no-plots
    lines.append(f"log       {log}   (replay: lcm-logplayer, watch: make spy)")
    return "\n".join(lines)


def _pct(x: float | None) -> str:
    return "n/a" if x is None else f"{100 * x:.1f} %"


def main(argv: list[str] | None = None) -> int:
    try:
        return _main(argv)
    except KeyboardInterrupt:
        print("demo: interrupted", file=sys.stderr)
        return 130


def _main(argv: list[str] | None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", type=Path, default=ROOT / "build" / "demo")
    ap.add_argument(
        "--mission",
        choices=("mcm", "sampling"),
        default="mcm",
        help="mcm: the mine-countermeasures team (default); sampling: the front-sampling team",
    )
    ap.add_argument("--polygon", help='plan this survey area instead ("n,e; n,e; ..." metres)')
    ap.add_argument("--vehicles", type=int, help="with --polygon: a plain survey by this many vehicles (default 3)")
    ap.add_argument("--team", type=int, help="with --polygon: a team of this many search vehicles and one RI vehicle")
    programs.add_lcm_url_argument(ap, "LCM URL for the launcher (ttl=0)")
    ap.add_argument("--build", type=Path, help="build folder (default: the repository's)")
    ap.add_argument("--no-plots", action="store_true")
    ap.add_argument(
        "--time",
        type=clock_modes.argument,
        metavar="{" + ",".join(clock_modes.MODES) + "}",
        help="pace of the world's lockstep clock (default: the scenario's; lockstep: as fast "
        "as the slowest process; every mode gives the same result)",
    )
    ap.add_argument("--warp", type=float, help="with --time scaled: at most this many times real time")
    ap.add_argument(
        "--plan-only",
        action="store_true",
        help="with --polygon: plan the survey and check its plans with the plugins, then stop",
    )
    args = ap.parse_args(argv)
    if args.mission == "sampling" and args.polygon:
        ap.error("--polygon plans an MCM survey: not with --mission sampling")
    if args.plan_only and not args.polygon:
        ap.error("--plan-only needs --polygon")
    if args.vehicles is not None and not args.polygon:
        ap.error("--vehicles needs --polygon (the committed scenario has its own vehicles)")
    if args.vehicles is not None and args.vehicles < 1:
        ap.error("--vehicles must be at least 1")
    if args.team is not None and not args.polygon:
        ap.error("--team needs --polygon (the committed scenario has its own team)")
    if args.team is not None and args.vehicles is not None:
        ap.error("--team and --vehicles plan different surveys: give one")
    if args.team is not None and args.team < 1:
        ap.error("--team must be at least 1")
    if args.warp is not None and not 0 < args.warp < float("inf"):
        ap.error(f"--warp must be a number > 0, got {args.warp}")
    try:
        args.out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        print(f"demo: --out {args.out}: {exc.strerror or exc}", file=sys.stderr)
        return 2
    wall0 = time.monotonic()
    scenario = SAMPLING_SCENARIO if args.mission == "sampling" else SCENARIO
    if args.polygon:
        plan_dir = args.out / "plan"
        name = "mcm_team" if args.team else "mcm_demo"
        how = (
            ["--team", args.team, "--ri", "1", *TEAM_PLAN_ARGS]
            if args.team
            else ["--vehicles", args.vehicles or 3, *PLAN_ARGS]
        )
        rc = run(
            [PY, "-m", "tools.plan.plan_survey", "--polygon", args.polygon, *how, "--name", name, "--out", plan_dir]
            + (["--build", args.build] if args.build else []),
            "planning the survey",
        )
        if rc or args.plan_only:
            return rc
        scenario = plan_dir / f"{name}.yaml"
    run_dir = args.out / "run"
    launch = [PY, "-m", "tools.launch", scenario, "--out", run_dir, "--progress", "15"]
    launch += (["--lcm-url", args.url] if args.url else []) + (["--build", args.build] if args.build else [])
    launch += (["--time", args.time] if args.time else []) + (["--warp", args.warp] if args.warp else [])
    launch_rc = run(launch, f"running {scenario.relative_to(ROOT) if scenario.is_relative_to(ROOT) else scenario}")
    log = run_dir / "run.lcmlog"
    if not log.exists():
        print(f"demo: the launcher left no log (exit {launch_rc})", file=sys.stderr)
        return launch_rc or 1
    report = [PY, "-m", "tools.report", log, "--out", args.out] + (["--no-plots"] if args.no_plots else [])
    print("demo: writing the report", flush=True)
    rc = subprocess.call([str(c) for c in report], stdout=subprocess.DEVNULL)
    if rc:
        return rc
    rep = json.loads((args.out / "report.json").read_text())
    print(result_text(rep, args.out, log, time.monotonic() - wall0))
    return launch_rc


if __name__ == "__main__":
    sys.exit(main())
