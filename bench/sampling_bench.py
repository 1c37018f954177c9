"""Sampling benchmark: the adaptive front-sampling team against a lawnmower of equal
length in the same world (docs/sampling.md, "Graded against the truth"). Prints
figures, asserts nothing.

For each seed (the world's seed: the front's meander phase, every sensor's noise) it
flies missions/scenarios/sampling_team (zig-zags across the front, steered along it
by front_rule towards where the team's estimate is least certain) and
missions/scenarios/sampling_lawnmower (the same vehicles, estimators and link,
lawnmower lines across the expected front over the same area, for the same 6 min of
survey), grades both with the same area (north -100 to 700 m, east 150 to 550 m, at
5 m) and prints, per seed and as a mean with its 95 % interval over the seeds:

  - the team's map error at the end of each (rms of estimate minus truth, degC);
  - their ratio (the goal: adaptive / lawnmower <= 0.5);
  - when the adaptive team's error first reached the lawnmower's final error, over
    the lawnmower's survey time (the goal: < 0.5).

A lawnmower vehicle with no OK estimate counts the water's spread (it knows nothing).

Run: tests/isolated_net.sh .venv/bin/python bench/sampling_bench.py [--seeds 3] [--out DIR]
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

from tools.montecarlo.summary import interval
from tools.report.front_grade import sampling_section
from tools.report.run_data import load_run

ROOT = Path(__file__).resolve().parents[1]
SCENARIOS = {
    "adaptive": ROOT / "missions/scenarios/sampling_team/sampling_team.yaml",
    "lawnmower": ROOT / "missions/scenarios/sampling_lawnmower/sampling_lawnmower.yaml",
}
BOX = (-100.0, 700.0, 150.0, 550.0)  # the area both are graded over (north min, max, east min, max)


def fly(kind: str, seed: int, out: Path) -> dict:
    run_dir = out / f"{kind}-{seed}"
    cmd = [sys.executable, "-m", "tools.launch", str(SCENARIOS[kind]), "--out", str(run_dir), "--seed", str(seed)]
    cmd += ["--progress", "0"]
    rc = subprocess.call(cmd, stdout=subprocess.DEVNULL)
    if rc:
        raise SystemExit(f"sampling_bench: {kind} seed {seed}: the launcher exited {rc} (see {run_dir})")
    grade = sampling_section(load_run(run_dir / "run.lcmlog"), box=BOX)
    if grade is None:
        raise SystemExit(f"sampling_bench: {kind} seed {seed}: no front estimates in the log")
    return grade


def compare(a: dict, m: dict) -> dict:
    final_mow = m["team_map_rms_c"] if m["team_map_rms_c"] is not None else m["spread_c"]
    final_ada = a["team_map_rms_c"]
    # mission times (both start at 0): the lawnmower's error is final at its last estimate
    reach = next((t for t, c in zip(a["curve"]["t"], a["curve"]["team"]) if c <= final_mow), None)
    mow_t = m["curve"]["t"][-1] if m["curve"]["t"] else None
    return {
        "adaptive_c": final_ada,
        "lawnmower_c": final_mow,
        "ratio": final_ada / final_mow if final_mow else None,
        "reach_s": reach,
        "time_ratio": (reach / mow_t) if reach is not None and mow_t else None,
    }


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seeds", type=int, default=1, help="fly seeds 11, 12, ... (default 1 seed)")
    ap.add_argument("--out", type=Path, help="keep the runs here (default: a temporary folder)")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        out = args.out or Path(tmp)
        rows = []
        for seed in range(11, 11 + args.seeds):
            row = compare(fly("adaptive", seed, out), fly("lawnmower", seed, out))
            rows.append(row)
            reach = f"{row['reach_s']:.0f} s" if row["reach_s"] is not None else "never"
            print(
                f"seed {seed}: map error adaptive {row['adaptive_c']:.3f} degC, lawnmower {row['lawnmower_c']:.3f}"
                f" (ratio {row['ratio']:.2f}, goal <= 0.5); adaptive reached the lawnmower's final error at"
                f" {reach} ({row['time_ratio'] if row['time_ratio'] is None else round(row['time_ratio'], 2)} of"
                " its survey, goal < 0.5)",
                flush=True,
            )
        for key, label in (("adaptive_c", "adaptive map error [degC]"), ("lawnmower_c", "lawnmower map error [degC]")):
            show(label, interval([r[key] for r in rows], (0.0, float("inf"))))
        ratios = [r["ratio"] for r in rows if r["ratio"] is not None]
        if ratios:
            show("ratio adaptive / lawnmower", interval(ratios, (0.0, float("inf"))))
        times = [r["time_ratio"] for r in rows if r["time_ratio"] is not None]
        if times:
            show("time to the lawnmower's final error, / its survey", interval(times, (0.0, float("inf"))))
    return 0


def show(label: str, m: dict) -> None:
    span = f"95 % interval [{m['lo']:.3f}, {m['hi']:.3f}]" if m["lo"] is not None else m["too_few"]
    print(f"  {label:52s} mean {m['mean']:.3f}  {span}  (n {m['n']}, range {m['min']:.3f}..{m['max']:.3f})")


if __name__ == "__main__":
    sys.exit(main())
