"""Scaling benchmark: the full stack with 1, 2, 4, 8, 16 vehicles.

For each N, a survey of N equal shares (N x the area of one) is planned by
python/tools/plan/plan_survey.py with the demo's settings and flown by the
launcher in fast time: simulators, PILOT and NAVIGATOR managers, auv-nav,
the recorder, the launcher's clock. Prints per N: sim time, wall time,
real-time factor, vehicle-seconds per wall second, outcome, and the CPU
seconds of each kind of process (read from /proc while the run goes: the
simulator, managers, filter, recorder, clock = the launcher); with
--profile, where one simulator's time goes (py-spy, sampled for the run).
Also the CPU milliseconds per vehicle-second of sim time, per kind: the
figure that does not depend on what else the machine runs, and the ceiling it
puts on throughput (cores x 1000 / ms). Prints figures, asserts nothing (a
run that did not finish says so).

Run: tests/isolated_net.sh .venv/bin/python bench/scale_bench.py [--vehicles 1,2,4] [--all] [--profile]
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import subprocess
import sys
import time
from collections import Counter, defaultdict
from pathlib import Path

import yaml

from auvlcm import programs
from tools.demo import PLAN_ARGS

ROOT = Path(__file__).resolve().parents[1]

TICK = os.sysconf("SC_CLK_TCK")
# py-spy from requirements.txt (the venv's bin), else one on PATH
PYSPY = next((str(p) for p in [Path(sys.executable).parent / "py-spy"] if p.exists()), None) or shutil.which("py-spy")
KINDS = ("simulator", "managers", "filter", "recorder", "clock", "other")


def kind_of(cmd: str) -> str:
    if "python/sim" in cmd or "-m sim" in cmd:
        return "simulator"
    if "chasm-manager" in cmd:
        return "managers"
    if "auv-nav" in cmd:
        return "filter"
    if "auv-recorder" in cmd or "lcm-logger" in cmd:
        return "recorder"
    if "auv-launch" in cmd or "tools.launch" in cmd:
        return "clock"
    return "other"


def _stat(pid: int) -> tuple[int, int] | None:
    """(parent pid, utime + stime in ticks) of a process, or None if gone."""
    try:
        s = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return None
    f = s[s.rindex(")") + 2 :].split()
    return int(f[1]), int(f[11]) + int(f[12])


def descendants(root: int) -> dict[int, int]:
    """pid -> cpu ticks of root and everything below it."""
    stats = {}
    for d in os.listdir("/proc"):
        if d.isdigit() and (st := _stat(int(d))) is not None:
            stats[int(d)] = st
    children = defaultdict(list)
    for pid, (ppid, _) in stats.items():
        children[ppid].append(pid)
    out, todo = {}, [root]
    while todo:
        p = todo.pop()
        if p in stats:
            out[p] = stats[p][1]
            todo += children[p]
    return out


def cmdline(pid: int) -> str:
    try:
        return Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace")
    except OSError:
        return ""


def polygon(n: int, length: float, width: float) -> str:
    """n shares of length x width side by side: equal area each."""
    w = width * n
    return f"0,0; {length:g},0; {length:g},{w:g}; 0,{w:g}"


def profile_summary(raw: Path, top: int = 15) -> list[str]:
    """Self and inclusive shares of the sampled frames (py-spy raw: 'f1;f2;... count')."""
    self_n, incl, total = Counter(), Counter(), 0
    for line in raw.read_text().splitlines():
        stack, _, count = line.rpartition(" ")
        if not count.isdigit():
            continue
        frames = stack.split(";")
        c = int(count)
        total += c
        self_n[frames[-1]] += c
        for f in set(frames):
            incl[f] += c
    if not total:
        return ["  (no samples)"]
    lines = [f"  {total} samples; self time (top {top}):"]
    lines += [f"    {100 * c / total:5.1f} %  {f}" for f, c in self_n.most_common(top)]
    lines.append(f"  inclusive (top {top}):")
    lines += [f"    {100 * c / total:5.1f} %  {f}" for f, c in incl.most_common(top + 5)[5 : top + 5]]
    return lines


def as_baseline(scenario: Path) -> None:
    """The transport before the channel filter: every vehicle's simulator
    publishes from its sender thread (the default then); AUV_LCM_CHANFILTER=0
    in the run's environment does the rest."""
    doc = yaml.safe_load(scenario.read_text())
    for v in doc["vehicles"]:
        v["sim"].setdefault("simulation", {})["publish_thread"] = True
    scenario.write_text(yaml.safe_dump(doc, sort_keys=False))


BASELINES = {
    # before the channel filter (session 10): no filter, liblcm receiving, sender threads
    "transport": {"AUV_LCM_CHANFILTER": "0", "AUV_LCM_READER": "0"},
    # before the own sockets: filtered, but liblcm's thread receives (two wake-ups a message)
    "liblcm": {"AUV_LCM_READER": "0"},
    # before SCHED_BATCH (session 13): the default scheduling, wake-ups preempt (launch --sched normal)
    "sched": {},
}
BASELINE_LAUNCH_ARGS = {"sched": ["--sched", "normal"]}


def run_case(n: int, args, out: Path, baseline: str = "") -> dict:
    case = out / (f"v{n}-{baseline}" if baseline else f"v{n}")
    shutil.rmtree(case, ignore_errors=True)
    plan = subprocess.run(
        [
            sys.executable,
            "-m",
            "tools.plan.plan_survey",
            "--polygon",
            polygon(n, args.length, args.width),
            "--vehicles",
            str(n),
            *PLAN_ARGS,
            "--name",
            f"scale{n}",
            "--out",
            str(case / "plan"),
        ],
        capture_output=True,
        text=True,
    )
    if plan.returncode:
        return {"vehicles": n, "outcome": "plan failed", "error": plan.stderr.strip()}
    if baseline == "transport":
        as_baseline(case / "plan" / f"scale{n}.yaml")
    launch = [
        sys.executable,
        "-m",
        "tools.launch",
        str(case / "plan" / f"scale{n}.yaml"),
        "--out",
        str(case / "run"),
        "--progress",
        "0",
        *BASELINE_LAUNCH_ARGS.get(baseline, []),
    ] + (["--lcm-url", args.url] if args.url else [])
    env = dict(os.environ)
    env.update(BASELINES.get(baseline, {}))
    if args.cprofile:
        prof_dir = case / "cprofile"
        prof_dir.mkdir(parents=True, exist_ok=True)
        (prof_dir / "sitecustomize.py").write_text(SITECUSTOMIZE)
        env["SCALE_BENCH_PROFILE_DIR"] = str(prof_dir)
        env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(prof_dir), env.get("PYTHONPATH", "")]))
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    wall0 = time.monotonic()
    proc = subprocess.Popen(launch, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
    last: dict[int, int] = {}
    kinds: dict[int, str] = {}
    spy = None
    while proc.poll() is None:
        for pid, ticks in descendants(proc.pid).items():
            last[pid] = ticks
            if pid not in kinds:
                kinds[pid] = kind_of(cmdline(pid))
                if args.profile and spy is None and kinds[pid] == "simulator" and PYSPY:
                    spy = subprocess.Popen(
                        [
                            PYSPY,
                            "record",
                            "--pid",
                            str(pid),
                            "--format",
                            "raw",
                            "--rate",
                            "200",
                            "--nonblocking",
                            "-o",
                            str(case / "sim.pyspy.txt"),
                        ],
                        stdout=subprocess.DEVNULL,
                        stderr=subprocess.DEVNULL,
                    )
        time.sleep(0.25)
    wall = time.monotonic() - wall0
    text = proc.stdout.read()
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if spy is not None:
        spy.wait(30)
    cpu = Counter()
    for pid, ticks in last.items():
        cpu[kinds.get(pid, "other")] += ticks / TICK
    try:
        outcome = json.loads((case / "run" / "outcome.json").read_text())
    except (OSError, ValueError):
        outcome = {"outcome": "no outcome", "sim_time_s": 0.0}
    sim = outcome.get("sim_time_s", 0.0)
    res = {
        "vehicles": n,
        "baseline": baseline,
        "outcome": outcome.get("outcome"),
        "sim_time_s": sim,
        "wall_s": wall,
        "rtf": sim / wall if wall else 0.0,
        "vehicle_s_per_s": n * sim / wall if wall else 0.0,
        "cpu_s": {k: round(cpu[k], 2) for k in KINDS},
        "cpu_total_s": (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime),
        "processes": Counter(kinds.values()),
        "recorder": outcome.get("recorder"),
        "reason": outcome.get("reason", ""),
    }
    res["load_avg"] = os.getloadavg()[0]
    if outcome.get("outcome") != "done":
        res["tail"] = text.strip().splitlines()[-5:]
    prof = case / "sim.pyspy.txt"
    if prof.exists():
        res["profile"] = profile_summary(prof)
    if args.cprofile:
        res["profile"] = res.get("profile", []) + cprofile_summary(case / "cprofile")
    return res


# Loaded by every Python process of a --cprofile run (PYTHONPATH): a profile of the
# whole process (CPU time: waiting for a message costs nothing and is not
# shown), written at its normal exit. A `python -m sim` process is "sim".
SITECUSTOMIZE = """import os
_d = os.environ.get("SCALE_BENCH_PROFILE_DIR")
if _d:
    import atexit, cProfile, sys
    import time
    _p = cProfile.Profile(time.process_time)
    _p.enable()
    def _dump():
        _p.disable()
        arg0 = sys.argv[0] or "python"
        if os.path.basename(arg0) == "__main__.py":
            arg0 = os.path.dirname(arg0)
        name = os.path.basename(arg0).replace(".py", "")
        _p.dump_stats(os.path.join(_d, f"{name}.{os.getpid()}.prof"))
    atexit.register(_dump)
"""


def cprofile_summary(folder: Path, top: int = 8) -> list[str]:
    """The functions each kind of Python process spent most CPU time in (self time)."""
    import pstats

    lines = []
    for kind in ("sim", "launch"):
        files = sorted(folder.glob(f"{kind}.*.prof"))
        if not files:
            continue
        st = pstats.Stats(*map(str, files))
        total = max(st.total_tt, 1e-9)
        rows = sorted(st.stats.items(), key=lambda kv: -kv[1][2])[:top]
        lines.append(f"  cProfile {kind} ({len(files)} process(es), {total:.0f} s CPU in all), self time:")
        lines += [f"    {100 * tt / total:5.1f} %  {fn}:{line} {name}" for (fn, line, name), (_, _, tt, _, _) in rows]
    return lines or ["  (no cProfile output: did the processes exit normally?)"]


def report(r: dict, n: int, label: str) -> None:
    if "cpu_s" not in r:
        print(f"{n:>3}  {r['outcome']}: {r.get('error', '')}")
        return
    print(
        f"{n:>3} {r['sim_time_s']:7.0f} {r['wall_s']:7.1f} {r['rtf']:6.1f} {r['vehicle_s_per_s']:8.1f}         "
        + " ".join(f"{r['cpu_s'][k]:9.1f}" for k in KINDS)
        + f"   {r['outcome']}"
        + (f" ({r['reason']})" if r["outcome"] != "done" else "")
        + (f"   [{label}]" if label else ""),
        flush=True,
    )
    if r["sim_time_s"] > 0:
        # Load-independent: CPU per vehicle-second of sim, and the throughput that
        # would give if these cores did nothing else (a ceiling, not a measurement).
        per = {k: 1000 * r["cpu_s"][k] / (n * r["sim_time_s"]) for k in KINDS}
        total = sum(per.values())
        r["cpu_ms_per_vehicle_s"] = per
        print(
            f"    cpu per vehicle-second: {total:.1f} ms ("
            + ", ".join(f"{k} {v:.1f}" for k, v in per.items() if v)
            + f"); on {os.cpu_count()} idle "
            f"cores at most {os.cpu_count() * 1000 / total:.0f} vehicle-s/s",
            flush=True,
        )
    for line in r.get("profile", []):
        print(line)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--vehicles", default="1,2", help="comma-separated vehicle counts (default 1,2: quick)")
    ap.add_argument("--all", action="store_true", help="1, 2, 4, 8, 16")
    ap.add_argument("--length", type=float, default=150.0, help="each share's length [m] (north)")
    ap.add_argument("--width", type=float, default=60.0, help="each share's width [m] (east)")
    ap.add_argument("--profile", action="store_true", help="py-spy one simulator of each run")
    ap.add_argument(
        "--cprofile",
        action="store_true",
        help="cProfile every Python process of each run (the "
        "simulators, the launcher): where their CPU time goes, without py-spy",
    )
    ap.add_argument(
        "--baseline",
        nargs="?",
        const="transport",
        choices=sorted(BASELINES),
        help="also run each case as before: 'transport' (the default) before the channel filter "
        "and the own sockets (AUV_LCM_CHANFILTER=0, AUV_LCM_READER=0, simulators publishing from a "
        "sender thread), 'liblcm' before the own sockets only (AUV_LCM_READER=0), 'sched' with the "
        "default CPU scheduling instead of SCHED_BATCH (launch --sched normal); prints the ratios",
    )
    programs.add_lcm_url_argument(ap, "LCM URL for the launcher")
    ap.add_argument("--out", type=Path, default=ROOT / "build" / "bench" / "scale")
    args = ap.parse_args()
    try:
        counts = [1, 2, 4, 8, 16] if args.all else [int(x) for x in args.vehicles.split(",")]
    except ValueError:
        ap.error("--vehicles: comma-separated integers")
    args.out.mkdir(parents=True, exist_ok=True)
    print(
        f"scale_bench: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f} at start; "
        f"shares of {args.length:g} m x {args.width:g} m each"
    )
    if args.profile and not PYSPY:
        print("scale_bench: --profile: py-spy not found (pip install -r requirements.txt)")
    print(
        f"{'veh':>3} {'sim s':>7} {'wall s':>7} {'RTF':>6} {'veh-s/s':>8}  cpu s: "
        + " ".join(f"{k:>9}" for k in KINDS)
        + "   outcome"
    )
    results = []
    for n in counts:
        for baseline in ("", args.baseline) if args.baseline else ("",):
            r = run_case(n, args, args.out, baseline)
            results.append(r)
            report(r, n, f"baseline: {baseline}" if baseline else "")
        if args.baseline and all(x.get("cpu_ms_per_vehicle_s") for x in results[-2:]):
            now, before = results[-2], results[-1]
            cpu = [sum(x["cpu_ms_per_vehicle_s"].values()) for x in (now, before)]
            print(
                f"    {n} vehicles against the baseline: vehicle-s/s x"
                f"{now['vehicle_s_per_s'] / before['vehicle_s_per_s']:.2f}, "
                f"CPU per vehicle-second x{cpu[0] / cpu[1]:.2f}",
                flush=True,
            )
    (args.out / "scale.json").write_text(json.dumps(results, indent=1))
    print(f"scale_bench: {args.out / 'scale.json'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
