#!/usr/bin/env python3
"""auv-launch: start and supervise a whole scenario with one command (docs/scenarios.md).

    auv-launch SCENARIO.yaml [--host NAME] [--out DIR] [--lcm-url URL]

Order: the recorder (auv-recorder, or lcm-logger if chosen), the files the run uses annotated into the log, the
simulators, the onboard navigation filters (vehicles with `nav: ekf`) and the
auv-frontseat of each vehicle flown from its backseat (a `frontseat:` in its
simulator configuration: tools/launch/backseat.py), the managers; then the
global clock starts. The mission ends when
every vehicle's navigator is done, aborted or failed, or at the time limit;
Ctrl-C, SIGTERM or any process dying ends it too. In a lockstep world the end
is a step, marked in the log (`mission end`) before anything stops
(tools/launch/launcher.py); everything is then stopped a kind at a time, the
recorder last.

A scenario's planned faults (`faults:`, tools/scenario/faults.py) are applied
at their sim time: a lost vehicle's processes are killed and it counts as
over ("lost"), not as a death.

Exit status: 0 every vehicle done (or lost by a planned fault); 3 a vehicle aborted; 4 a vehicle failed;
5 a process died; 6 time limit; 2 bad scenario or usage; 130 interrupted.
"""

from __future__ import annotations

import argparse
import json
import signal
import sys
from pathlib import Path

from auvlcm import auth, programs
from auvlcm.paths import ROOT, build_dir
from auvlcm.url import check_local, default_url
from confcheck import ConfigError
from sim import clock_modes
from tools.launch.backseat import frontseat_ports
from tools.launch.launcher import EXIT, Launcher, check_plans, nav_configs
from tools.launch.procs import children_batch
from tools.launch.recorder_cmd import recorder_takes_part
from tools.launch.sched_policy import CHOICES as SCHED_CHOICES
from tools.launch.sched_policy import batch_available, wants_batch
from tools.launch.simconfig import write_configs
from tools.scenario.scenario_file import RECORDERS, TIME_MODES, Scenario, load_scenario


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenario", type=Path)
    ap.add_argument("--host", help="start only this host's part of the scenario")
    ap.add_argument("--out", type=Path, help="run folder (default build/runs/<scenario name>)")
    programs.add_lcm_url_argument(ap, "LCM URL (default: the scenario's, else $LCM_DEFAULT_URL or the project's)")
    ap.add_argument("--build", type=Path, default=build_dir())
    ap.add_argument("--warp", type=float, help="override time.warp")
    ap.add_argument(
        "--time",
        type=clock_modes.argument,
        metavar="{" + ",".join(TIME_MODES) + "}",
        help="override time.mode: the pace of the lockstep clock (lockstep: as fast as the "
        "slowest process; scaled: at most warp x; realtime)",
    )
    ap.add_argument("--seed", type=int, help="override the scenario's seed (tools/montecarlo/cli.py)")
    ap.add_argument(
        "--sched",
        choices=SCHED_CHOICES,
        default="auto",
        help="CPU scheduling of the processes the launcher starts: batch (no preemption on "
        "wake-up: throughput), normal, or auto (batch for time lockstep, normal when paced)",
    )
    ap.add_argument("--progress", type=float, default=5.0, help="wall seconds between progress lines (0: none)")
    ap.add_argument(
        "--recorder",
        choices=RECORDERS,
        help="what records the log (default: the scenario's logging.recorder, auv-recorder)",
    )
    ap.add_argument(
        "--netns", action="store_true", help="running in a network namespace made for this run: allows ttl=1 URLs"
    )
    ap.add_argument(
        "--agents",
        action="store_true",
        help="run every host's part through its host agent (docs/hosts.md); this process keeps the clock and the watch",
    )
    ap.add_argument("--restart", action="append", default=[], metavar="RULE", help="with --agents: restart rule")
    ap.add_argument("--deadman", type=float, default=10.0, help="with --agents: the agents' dead-man time [s]")
    ap.add_argument("--agent-timeout", type=float, default=30.0, help="with --agents: seconds to wait for answers")
    args = ap.parse_args(argv)
    if args.warp is not None and not 0 < args.warp < float("inf"):
        ap.error(f"--warp must be a number > 0, got {args.warp}")
    if not 0 <= args.progress < float("inf"):
        ap.error(f"--progress must be a number >= 0, got {args.progress}")
    try:
        sc = load_scenario(args.scenario)
        if args.host is not None and args.host not in sc.hosts:
            raise ConfigError([f"{sc.path}: hosts: --host {args.host} is not one of: {', '.join(sc.hosts)}"])
        if args.agents:
            from tools.hosts.agentctl import parse_rule

            if args.host is not None:
                raise ValueError("--agents runs every host's part: leave out --host")
            [parse_rule(r) for r in args.restart]
            if not 0 <= args.deadman < float("inf"):
                raise ValueError(f"--deadman {args.deadman}: expected seconds >= 0")
            if sc.faults:
                # the agents run the processes: a lost vehicle's would fly on
                raise ValueError(
                    f"{sc.faults[0].where}: faults: not applied by host agents yet; "
                    "run this scenario without --agents (or per host with --host)"
                )
        url = check_local(args.url or sc.lcm_url or default_url(), inside_netns=args.netns)
    except ConfigError as exc:
        print("\n".join(exc.errors), file=sys.stderr)
        print(f"launch: {args.scenario}: {len(exc.errors)} error(s)", file=sys.stderr)
        return 2
    except ValueError as exc:
        print(f"launch: {exc}", file=sys.stderr)
        return 2
    if args.seed is not None:
        sc.seed = args.seed
    if args.time is not None:
        sc.time.mode = args.time
    args.out = (args.out or ROOT / "build" / "runs" / sc.name).resolve()
    args.out.mkdir(parents=True, exist_ok=True)
    mine = sc.vehicles_on(args.host)
    if args.agents and args.recorder and args.recorder != sc.log_recorder:
        print(
            f"launch: --recorder {args.recorder}: with --agents the log host's agent records, with the "
            f"scenario's logging.recorder ({sc.log_recorder}): set it there",
            file=sys.stderr,
        )
        return 2
    # the recorder takes part in a lockstep world, whichever host records
    records = recorder_takes_part(sc, args.recorder or sc.log_recorder)
    sim_configs, errors = write_configs(sc, sc.vehicles, args.out, records)
    navs, nav_errors = nav_configs(Scenario(**{**sc.__dict__, "vehicles": mine}), sim_configs, args.out, args.build)
    errors += nav_errors
    frontseats, fs_errors = frontseat_ports(sc, sim_configs)
    errors += fs_errors
    errors += check_plans(Scenario(**{**sc.__dict__, "vehicles": mine}), args.build)
    if errors:
        print("\n".join(errors), file=sys.stderr)
        print(f"launch: {args.scenario}: {len(errors)} error(s)", file=sys.stderr)
        return 2

    ring = auth.ring_for(sc.key_file, "launch")  # checked with the scenario; None: said once
    flag = {"stop": False}
    for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
        signal.signal(sig, lambda *_: flag.update(stop=True))
    if args.agents:
        from tools.hosts.agent_launch import run_on_agents

        args.stop_flag = flag
        result, run = run_on_agents(sc, args, url, sim_configs, navs, ring)
        return _finish(run, args, result)
    batch = wants_batch(sc.time.mode, args.sched)
    why_not = batch_available() if batch else None
    if why_not:
        print(f"launch: {why_not}", file=sys.stderr)
        batch = False
    children_batch(batch)  # every process started from here on
    run = Launcher(sc, args, url, sim_configs, navs, frontseats=frontseats)
    print(
        f"launch: {sc.name}: {len(mine)} vehicle(s){f' on host {args.host}' if args.host else ''}, "
        f"time {sc.time.mode}{'' if sc.time.mode != 'scaled' else f' x{args.warp or sc.time.warp:g}'}, "
        f"{'SCHED_BATCH' if batch else 'default'} scheduling, over {url}; run folder {args.out}",
        flush=True,
    )
    result = "died"
    try:
        run.start_all()
        result = run.wait_ready(lambda: flag["stop"]) or run.supervise(lambda: flag["stop"])
    except RuntimeError as exc:
        run.stop_reason = str(exc)
    finally:
        run.stop_all(result)
    return _finish(run, args, result)


def _finish(run: Launcher, args, result: str) -> int:
    s = run.summary(result)
    counts = run.recorder_counts() if run.own_log and run.recorder == "auv-recorder" else None
    if counts is not None:
        s["recorder"] = counts
    (args.out / (f"outcome.{args.host}.json" if args.host else "outcome.json")).write_text(json.dumps(s, indent=2))
    print(f"launch: {result} at t={s['sim_time_s']:.1f} s" + (f": {s['reason']}" if s["reason"] else ""))
    for vid, v in s["vehicles"].items():
        at = v["lost_at_s"] if v.get("lost_at_s") is not None else v.get("abort_at_s")
        why = f" ({v['cause']}" + (f" at t={at:.1f} s" if at is not None else "") + ")" if v.get("cause") else ""
        print(f"  {vid}: {v['outcome'] or 'unfinished'}{why}  last state {v['path'] or '-'}  ({v['condition']})")
    drop = s["dropped"]
    if drop["decode_errors"] or drop["time"]:
        print(f"launch: dropped {drop['decode_errors']} undecodable message(s), {run.watch.time_drops.summary()}")
    if run.own_log:
        print(f"log: {run.log_path}")
        if counts is not None:
            print(
                f"record: {counts['written']} of {counts['received']} messages received written, "
                f"{counts['dropped']} dropped, {counts['missed']} missed (kernel socket drops)"
                + (f"; {counts['after_end']} after the mission's end left out" if counts.get("after_end") else "")
            )
    return EXIT[result]


if __name__ == "__main__":
    sys.exit(main())
