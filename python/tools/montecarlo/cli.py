#!/usr/bin/env python3
"""Monte Carlo: one scenario over many seeds, in parallel worlds that cannot
hear each other, summarised as mean and 95 % interval (docs/tools.md).

    auv-montecarlo SCENARIO.yaml --seeds 20 [--first-seed 1] [--jobs 2] [--out DIR]
    auv-montecarlo SCENARIO.yaml --seeds 200 --dask tcp://scheduler:8786
    auv-montecarlo SCENARIO.yaml --seeds 4 --dask-local 2

The seed (the scenario's `seed`: target field, currents, every sensor's
noise) is the only thing that changes between runs. Each run is the
launcher and the report tool in a network namespace of its own
(tests/isolated_net.sh; without namespaces, on a port of its own), so any
number run side by side. On one machine the runs are local processes
(--jobs at once); --dask hands them to a Dask distributed cluster, whose
workers must have this repository, built, at the same path (--dask-local N
starts a LocalCluster of N worker processes here, as the tests do).

Writes into --out: seed_<k>/ (each run's folder and report), runs.json,
summary.json, summary.txt and montecarlo.png/.svg. Exit status 0 when every
run reported, 1 when some did not, 2 on bad usage.
"""

from __future__ import annotations

import argparse
import json
import os
import socket
import subprocess
import sys
import time
from concurrent.futures import Executor, ThreadPoolExecutor
from pathlib import Path

from auvlcm.paths import ROOT, build_dir
from tools.montecarlo.summary import plot, summarize, summary_text

BASE_PORT = 7900  # without namespaces, run k listens on BASE_PORT + k


def run_one(spec: dict) -> dict:
    """One seed: launch, report, figures. Runs on whichever machine executes it."""
    root, out, seed = Path(spec["root"]), Path(spec["out"]), spec["seed"]
    from tools.montecarlo.summary import metrics_of

    out.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ)
    env.pop("AUV_IN_ISOLATED_NET", None)  # a namespace of its own even inside an isolated parent
    env["PYTHONPATH"] = str(Path(spec["build"]) / "gen" / "python")  # that build's message types
    py = spec["python"] if spec.get("python") and Path(spec["python"]).exists() else sys.executable
    url = f"udpm://239.255.76.67:{BASE_PORT + spec['index']}?ttl=0"
    launch = [
        py,
        "-m",
        "tools.launch",
        spec["scenario"],
        "--seed",
        str(seed),
        "--out",
        str(out / "run"),
        "--lcm-url",
        url,
        "--build",
        spec["build"],
        "--progress",
        "0",
    ]
    result = {"seed": seed, "host": socket.gethostname(), "out": str(out)}
    wall0 = time.monotonic()
    with open(out / "launch.out", "w") as f:
        rc = subprocess.call(
            [str(root / "tests/isolated_net.sh"), *launch],
            stdout=f,
            stderr=subprocess.STDOUT,
            env=env,
            timeout=spec.get("timeout"),
        )
    result["launch_exit"] = rc
    log = out / "run" / "run.lcmlog"
    if not log.exists():
        result["error"] = f"launcher exit {rc}, no log (see {out / 'launch.out'})"
        return result
    with open(out / "report.out", "w") as f:
        rrc = subprocess.call(
            [py, "-m", "tools.report", str(log), "--out", str(out), "--no-plots"],
            stdout=f,
            stderr=subprocess.STDOUT,
            env=env,
        )
    result["wall_s"] = time.monotonic() - wall0
    if rrc != 0:
        result["error"] = f"report exit {rrc} (see {out / 'report.out'})"
        return result
    rep = json.loads((out / "report.json").read_text())
    result["metrics"] = metrics_of(rep)
    return result


def _executor(args) -> tuple[Executor, object]:
    """Local threads that each wait on a run's processes, or Dask's executor."""
    if not (args.dask or args.dask_local):
        return ThreadPoolExecutor(max_workers=args.jobs), None
    from distributed import Client, LocalCluster

    if args.dask_local:
        import dask

        # a worker waits on its run's processes, which keep the machine's cores busy: one
        # starved of the CPU for a while is slow, not dead (the default 5 min would drop it
        # and lose its run on a loaded machine)
        dask.config.set({"distributed.scheduler.worker-ttl": "30 minutes"})
        cluster = LocalCluster(n_workers=args.dask_local, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(cluster)
        return client.get_executor(pure=False), (client, cluster)
    client = Client(args.dask)
    return client.get_executor(pure=False), (client,)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenario", type=Path)
    ap.add_argument("--seeds", type=int, default=10, help="number of runs (default 10)")
    ap.add_argument("--first-seed", type=int, default=1)
    ap.add_argument(
        "--jobs",
        type=int,
        default=max(1, (os.cpu_count() or 2) // 2),
        help="local runs at once (default: half the cores; each run is several processes)",
    )
    ap.add_argument("--dask", metavar="ADDRESS", help="a Dask distributed scheduler to run the seeds on")
    ap.add_argument("--dask-local", type=int, metavar="N", help="a local Dask cluster of N worker processes")
    ap.add_argument("--out", type=Path, help="default build/montecarlo/<scenario name>")
    ap.add_argument("--build", type=Path, default=build_dir())
    ap.add_argument("--timeout", type=float, help="wall seconds for one run's launcher")
    ap.add_argument("--no-plot", action="store_true")
    args = ap.parse_args(argv)
    if args.seeds < 1 or args.jobs < 1 or (args.dask_local is not None and args.dask_local < 1):
        ap.error("--seeds, --jobs and --dask-local must be at least 1")
    if args.dask and args.dask_local:
        ap.error("--dask and --dask-local exclude each other")
    if not args.scenario.is_file():
        print(f"montecarlo: {args.scenario}: no such scenario", file=sys.stderr)
        return 2
    out = (args.out or ROOT / "build" / "montecarlo" / args.scenario.stem).resolve()
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        print(f"montecarlo: --out {out}: {exc.strerror or exc}", file=sys.stderr)
        return 2
    build = args.build if args.build.is_absolute() else ROOT / args.build
    specs = [
        {
            "root": str(ROOT),
            "build": str(build),
            "scenario": str(args.scenario.resolve()),
            "seed": s,
            "index": i,
            "out": str(out / f"seed_{s}"),
            "timeout": args.timeout,
            "python": sys.executable,
        }
        for i, s in enumerate(range(args.first_seed, args.first_seed + args.seeds))
    ]
    where = (
        f"Dask scheduler {args.dask}"
        if args.dask
        else f"a local Dask cluster of {args.dask_local}"
        if args.dask_local
        else f"{args.jobs} local job(s)"
    )
    print(f"montecarlo: {args.scenario.name}: {len(specs)} seeds on {where}; out {out}", flush=True)
    try:
        executor, held = _executor(args)
    except (OSError, ValueError, TimeoutError) as exc:
        print(f"montecarlo: cannot reach the executor: {exc}", file=sys.stderr)
        return 2
    runs: list[dict] = []
    try:
        with executor:
            futures = [executor.submit(run_one, sp) for sp in specs]
            for sp, fut in zip(specs, futures):
                try:
                    r = fut.result()
                except Exception as exc:  # a run that broke is a failed run, not a failed study
                    r = {"seed": sp["seed"], "error": f"{type(exc).__name__}: {exc}"}
                runs.append(r)
                m = r.get("metrics")
                print(
                    f"  seed {r['seed']}: "
                    + (f"{m['outcome']}, {r['wall_s']:.0f} s wall" if m else f"failed: {r.get('error')}"),
                    flush=True,
                )
    except KeyboardInterrupt:
        print("montecarlo: interrupted", file=sys.stderr)
        return 130
    finally:
        # the client first, its futures released, then the cluster: a cluster
        # closed under a live client loses the results it still holds, and its
        # scheduler warns of "lost" tasks at the end of a run that went well
        futures = []
        for h in held or ():
            h.close()
    s = summarize(runs)
    (out / "runs.json").write_text(json.dumps(runs, indent=1))
    (out / "summary.json").write_text(json.dumps(s, indent=1))
    text = summary_text(s)
    (out / "summary.txt").write_text(text)
    print(text, end="")
    if not args.no_plot:
        for p in plot(runs, s, out):
            print(f"plot      {p}")
    return 0 if s["reported"] == s["runs"] else 1


if __name__ == "__main__":
    sys.exit(main())
