"""HIL at the wire against the message level: the cooperative MCM team flown both
ways (docs/hil.md), wall time and the report's figures side by side.

The full team: the committed team's plan (missions/scenarios/mcm_team: three search
vehicles and a reacquire-identify vehicle over the team's field), planned again with
every vehicle on the onboard filter (`--nav ekf`, which the wire needs: the vehicle
navigates on its drivers). The message level is the launcher's lockstep world, as
fast as the machine allows; the wire is `auv-hil-wire` on ptys at --warp, one LCM
world per vehicle computer. Prints figures, asserts nothing.
Run: tests/isolated_net.sh .venv/bin/python bench/hil_wire_bench.py [--quick] [--warp 8]
  --quick: the reduced team of tests/hil/test_hil_wire.py (one search vehicle and the RI)
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))
from tools.demo import TEAM_PLAN_ARGS  # noqa: E402

FULL = ("20,20; 220,20; 220,200; 20,200", 3)  # the committed team's polygon and search vehicles
QUICK = ("100,22; 140,22; 140,62; 100,62", 1)
URL = "udpm://239.255.76.67:7667?ttl=0"


def run(cmd: list, what: str) -> float:
    t0 = time.monotonic()
    p = subprocess.run([str(c) for c in cmd], capture_output=True, text=True)
    wall = time.monotonic() - t0
    if p.returncode not in (0, 3):  # 3: a vehicle aborted, still a run to report on
        print(f"{what} failed ({p.returncode}):\n{p.stdout[-2000:]}{p.stderr[-2000:]}")
        raise SystemExit(1)
    return wall


def figures(log: Path, out: Path) -> dict:
    run([sys.executable, "-m", "tools.report", log, "--out", out, "--no-plots"], "report")
    r = json.loads((out / "report.json").read_text())
    t = r.get("team", {})
    return {
        "outcome": r["outcome"],
        "sim_s": round(r["duration_s"], 1),
        "coverage": (r.get("coverage") or {}).get("fraction_once"),
        "detected": t.get("mine_like_detected"),
        "identified": t.get("mine_like_identified"),
        "nav_rms_m": {v: round(e["rms_m"], 2) for v, e in r["navigation_error"].items()},
    }


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--warp", type=float, default=8.0)
    a = ap.parse_args()
    polygon, search = QUICK if a.quick else FULL
    with tempfile.TemporaryDirectory(prefix="hilbench") as tmp:
        d = Path(tmp)
        plan = [sys.executable, "-m", "tools.plan.plan_survey", "--polygon", polygon, "--team", str(search)]
        run([*plan, "--ri", "1", *TEAM_PLAN_ARGS, "--nav", "ekf", "--out", d / "team"], "planning")
        sc = d / "team" / "team.yaml"
        wall_msg = run(
            [sys.executable, "-m", "tools.launch", sc, "--out", d / "msg", "--lcm-url", URL], "message level"
        )
        wire = [sys.executable, "-m", "tools.hil.cli", sc, "--out", d / "wire", "--warp", f"{a.warp:g}"]
        wall_wire = run([*wire, "--lcm-url", URL], "wire")
        fm, fw = (
            figures(d / "msg" / "run.lcmlog", d / "msg" / "rep"),
            figures(d / "wire" / "run.lcmlog", d / "wire" / "rep"),
        )
    print(f"team: {search} search + 1 RI, {'reduced' if a.quick else 'full'}; wire at x{a.warp:g} on ptys")
    print(f"{'':14s}{'message level':>22s}{'at the wire':>22s}")
    print(f"{'wall [s]':14s}{wall_msg:22.1f}{wall_wire:22.1f}   ratio {wall_wire / wall_msg:.2f}")
    for k in ("outcome", "sim_s", "coverage", "detected", "identified"):
        print(f"{k:14s}{str(fm[k]):>22s}{str(fw[k]):>22s}")
    for vid in fm["nav_rms_m"]:
        print(
            f"{'nav rms ' + vid + ' [m]':14s}{fm['nav_rms_m'][vid]:22.2f}{fw['nav_rms_m'].get(vid, float('nan')):22.2f}"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
