"""`make demo`: a 3-vehicle mine-countermeasure survey, end to end, in fast time.

The survey planner's scenario (missions/scenarios/mcm_demo, or a survey planned
here with --polygon/--vehicles) is run by the launcher: three simulated REMUS
100s with sidescan sonar over one seeded target field, each flown by a PILOT and
a NAVIGATOR (chasm-manager) on the launcher's global clock, everything logged.
The report tool then reads the log: outcome, coverage, detections against the
truth, navigation error, and the plots. This prints a short summary and where
the files are. Exit status: the launcher's when the mission did not end done,
else the report's.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PY = sys.executable
SCENARIO = ROOT / "missions" / "scenarios" / "mcm_demo" / "mcm_demo.yaml"
# What the committed scenario was planned with (its header); --polygon replans with these.
PLAN_ARGS = ["--heading", "80", "--range", "40", "--nadir-gap", "11.5", "--overlap", "0.1", "--fix-every-min", "30",
             "--depth-m", "4",
             "--world", str(ROOT / "missions/scenarios/mcm_world.yaml"), "--seed", "7",
             "--sim-config", str(ROOT / "missions/sim/remus100_mcm.yaml"), "--nav", "ekf"]


def run(cmd: list, what: str) -> int:
    print(f"demo: {what}", flush=True)
    return subprocess.call([str(c) for c in cmd])


def _pd(p: float | None) -> str:
    return "n/a" if p is None else f"{p:.2f}"


def summary(rep: dict) -> str:
    cov, det = rep["coverage"], rep["detection"]
    lines = [f"outcome   {rep['outcome']}: " + ", ".join(f"{v} {o}" for v, o in rep["vehicle_outcomes"].items()),
             f"duration  {rep['duration_s'] / 60:.1f} min of sim time",
             f"coverage  {cov['survey_area_m2'] / 1e6:.4f} km2: once {100 * cov['fraction_once']:.1f} %, "
             f"twice {100 * cov['fraction_twice']:.1f} %",
             f"detection {det['mine_like_detected']} of {det['mine_like_targets']} mine-like targets "
             f"(PD {_pd(det['pd'])}; in the covered area {det['mine_like_in_covered_area']}, "
             f"PD {_pd(det['pd_in_covered_area'])}); {det['contacts']} contacts, "
             f"{det['contacts_on_clutter']} on clutter, {det['false_alarms']} false alarms",
             "nav error " + ", ".join(f"{v} rms {e['rms_m']:.1f} m (max {e['max_m']:.1f})"
                                      for v, e in rep["navigation_error"].items()),
             "record    " + ", ".join(f"{v} {r['missing']} of {r['samples'] + r['missing']} truth samples lost"
                                      for v, r in rep["record"].items())]
    return "\n".join(lines)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", type=Path, default=ROOT / "build" / "demo")
    ap.add_argument("--polygon", help="plan this survey area instead (\"n,e; n,e; ...\" metres)")
    ap.add_argument("--vehicles", type=int, default=3, help="with --polygon")
    ap.add_argument("--url", help="LCM URL for the launcher (ttl=0)")
    ap.add_argument("--build", type=Path, help="build folder (default: the repository's)")
    ap.add_argument("--no-plots", action="store_true")
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    wall0 = time.monotonic()
    scenario = SCENARIO
    if args.polygon:
        plan_dir = args.out / "plan"
        rc = run([PY, ROOT / "python/tools/plan_survey.py", "--polygon", args.polygon, "--vehicles",
                  args.vehicles, *PLAN_ARGS, "--name", "mcm_demo", "--out", plan_dir], "planning the survey")
        if rc:
            return rc
        scenario = plan_dir / "mcm_demo.yaml"
    run_dir = args.out / "run"
    launch = [PY, ROOT / "python/tools/launch.py", scenario, "--out", run_dir, "--progress", "15"]
    launch += (["--url", args.url] if args.url else []) + (["--build", args.build] if args.build else [])
    launch_rc = run(launch, f"running {scenario.relative_to(ROOT) if scenario.is_relative_to(ROOT) else scenario}")
    log = run_dir / "run.lcmlog"
    if not log.exists():
        print(f"demo: the launcher left no log (exit {launch_rc})", file=sys.stderr)
        return launch_rc or 1
    report = [PY, ROOT / "python/tools/report.py", log, "--out", args.out] + (["--no-plots"] if args.no_plots else [])
    print("demo: writing the report", flush=True)
    rc = subprocess.call([str(c) for c in report], stdout=subprocess.DEVNULL)
    if rc:
        return rc
    rep = json.loads((args.out / "report.json").read_text())
    print(f"\n{summary(rep)}\nwall time {time.monotonic() - wall0:.0f} s\n")
    print(f"report    {args.out / 'report.txt'}  {args.out / 'report.json'}")
    for plot in rep["plots"]:
        if plot.endswith(".png"):
            print(f"plot      {plot}  (and .svg)")
    print(f"log       {log}   (replay: lcm-logplayer, watch: make spy)")
    return launch_rc


if __name__ == "__main__":
    sys.exit(main())
