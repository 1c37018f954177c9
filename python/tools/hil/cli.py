"""`auv-hil-wire`: a scenario flown with hardware in the loop at the wire (docs/hil.md).

The simulators share one world (multi-HIL, scaled time: the elected server's
clock) in the simulator's LCM world, and speak to each vehicle only through its
device links (sim.devices: every sensor, the fins, the modem, the time link and
the payload link at the wire, `publish_lcm: false`). Each vehicle computer
(`auv-hil-vc`: drivers, auv-nav, managers, its recorder) runs in a world of its
own: another LCM port on one machine, or its own network namespace (`--exec-vc`
gives the command prefix that runs a program there).

At the end every world's log is merged into run.lcmlog (by receive time), so
`auv-report` reads one run; summary.json has each vehicle's outcome.
"""

from __future__ import annotations

import argparse
import json
import shlex
import signal
import sys
import time
from pathlib import Path

import yaml

from auvlcm import programs
from auvlcm.paths import ROOT
from auvlcm.url import check_local, default_url
from confcheck import ConfigError
from confcheck.reader import dump_yaml
from tools.hil.links import Link, plan_links, wired_config
from tools.hil.merge import merge_logs
from tools.hil.notes import end_notes, start_notes
from tools.launch.procs import Child, stop_together
from tools.launch.simconfig import write_configs
from tools.scenario.scenario_file import Scenario, load_scenario

FINS_TABLE = ROOT / "missions" / "hil" / "remus100_fins.table"  # one file for auv-servo and the simulator
VC_PORT0 = 7767  # one machine: vehicle computer i's LCM world is udpm on port VC_PORT0 + i


def devices_of(cfg: dict) -> list[str]:
    """The links this simulator configuration can serve: every device it has."""
    sensors = cfg.get("sensors") or {}
    out = ["timesync", "gps", "ahrs", "depth", "dvl", "servo"]
    out = [d for d in out if d in ("timesync", "servo") or (sensors.get(d) or {}).get("enabled", True)]
    if cfg.get("modem"):
        out.append("modem")
    if cfg.get("sonar"):
        out.append("payload")
    if cfg.get("identify"):
        out.append("payload_looks")
    return out


def modem_addresses(sc: Scenario) -> dict[str, int]:
    """The team's modem addresses: the scenario's vehicles in order, from 1."""
    return {v.id: i + 1 for i, v in enumerate(sc.vehicles)}


def driver_flags(sc: Scenario, cfg: dict, links: list[Link]) -> dict[str, list[str]]:
    """Each driver's own flags, from the simulator's configuration (the same
    vehicle: the world's origin, the modem's address table, the fins' table)."""
    from sim.config import loads

    loaded = loads(dump_yaml(cfg), Path("wired.sim.yaml"))
    env = loaded.env
    flags: dict[str, list[str]] = {"gps": programs.gps_origin_flags(env.origin_latitude_deg, env.origin_longitude_deg)}
    flags["modem"] = programs.modem_flags(modem_addresses(sc))
    flags["servo"] = programs.servo_table_flags(FINS_TABLE)
    return {d.device: flags.get(d.device, []) for d in links}


def prepare(sc: Scenario, a: argparse.Namespace) -> dict[str, dict]:
    """Write each vehicle's wired simulator configuration, nav config and links file."""
    from sim.config import load
    from tools.nav.navconf import nav_config_text

    paths, errors = write_configs(sc, sc.vehicles, a.out)
    if errors:
        raise ConfigError(errors)
    plan = {}
    n = len(sc.vehicles)
    for i, v in enumerate(sc.vehicles):
        cfg = yaml.safe_load(paths[v.id].read_text())
        pty_dir = (a.out / "pty" / v.id) if a.transport == "pty" else None
        if pty_dir is not None:
            pty_dir.mkdir(parents=True, exist_ok=True)
        links = plan_links(devices_of(cfg), i, a.base_port, pty_dir)
        table = ",".join(f"{vid}={addr}" for vid, addr in modem_addresses(sc).items())
        extra = {
            "ahrs": {"sentences": ["VNYMR"]},  # the one that carries the body rates auv-nav needs
            "servo": {"table": str(FINS_TABLE)},
            "modem": {"table": table},
        }
        cfg = wired_config(cfg, links, extra)
        # every physics step of 50 Hz: a manager cycles at most once per clock message
        cfg["time_link"] = {**cfg.get("time_link", {}), "rate_hz": 50}
        cfg["simulation"] = {**cfg.get("simulation", {}), "clock": "scaled", "warp": a.warp}
        cfg["multihil"] = {"enabled": True, "priority": 10 * (n - i)}
        path = a.out / f"{v.id}.wired.sim.yaml"
        path.write_text(f"# {v.id} at the wire (auv-hil-wire)\n" + dump_yaml(cfg))
        nav = a.out / f"{v.id}.nav"
        nav.write_text(nav_config_text(load(path)))
        drivers = {d.device: d.driver_port(a.sim_host) for d in links}
        linkfile = a.out / f"{v.id}.links.json"
        linkfile.write_text(json.dumps({"drivers": drivers, "flags": driver_flags(sc, cfg, links)}, indent=1))
        plan[v.id] = {"sim": path, "nav": nav, "links": linkfile}
    return plan


def parse_exec(items: list[str]) -> dict[str, list[str]]:
    out = {}
    for it in items:
        vid, _, prefix = it.partition("=")
        out[vid] = shlex.split(prefix)
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="auv-hil-wire", description=__doc__.split("\n\n")[0])
    ap.add_argument("scenario", type=Path)
    ap.add_argument("--out", type=Path, default=ROOT / "build" / "hil-wire")
    ap.add_argument("--transport", choices=("pty", "tcp"), default="pty")
    ap.add_argument("--warp", type=float, default=2.0, help="sim seconds per wall second (default 2)")
    ap.add_argument("--sim-host", default="127.0.0.1", help="TCP: the simulators' address as the vehicles see it")
    ap.add_argument("--base-port", type=int, default=4100, help="TCP: the first link's port")
    ap.add_argument("--exec-sim", default="", help="command prefix that runs a program on the simulator PC")
    ap.add_argument("--exec-vc", action="append", default=[], metavar="VID=PREFIX", help="... on VID's computer")
    ap.add_argument(
        "--vc-lcm-url", default="", help="every vehicle computer's LCM URL (with --exec-vc: each in its own namespace)"
    )
    ap.add_argument("--build", type=Path, default=ROOT / "build")
    programs.add_lcm_url_argument(ap, "the simulators' LCM world", default=default_url())
    a = ap.parse_args(argv)
    if a.warp <= 0:
        ap.error("--warp must be positive")
    try:
        sc = load_scenario(a.scenario)
        a.out.mkdir(parents=True, exist_ok=True)
        plan = prepare(sc, a)
        sim_url = check_local(a.url)
    except ConfigError as exc:
        print("\n".join(exc.errors), file=sys.stderr)
        print(f"auv-hil-wire: {a.scenario}: {len(exc.errors)} error(s)", file=sys.stderr)
        return 2
    except (OSError, ValueError) as exc:
        print(f"auv-hil-wire: {exc}", file=sys.stderr)
        return 2
    vc_exec, sim_exec = parse_exec(a.exec_vc), shlex.split(a.exec_sim)
    stopping = {"now": False}
    signal.signal(signal.SIGINT, lambda *_: stopping.update(now=True))
    signal.signal(signal.SIGTERM, lambda *_: stopping.update(now=True))
    sims: list[Child] = []
    vcs: dict[str, Child] = {}
    log = a.out / "sim.lcmlog"
    rec = Child(
        "sim.recorder",
        [*sim_exec, *programs.auv_recorder(a.build, lcm_url=sim_url, log=log)],
        a.out / "sim.recorder.out",
    )
    rec.start()
    wall0 = time.monotonic()
    try:
        for i, v in enumerate(sc.vehicles):
            url = a.vc_lcm_url or f"udpm://239.255.76.67:{VC_PORT0 + i}?ttl=0"
            cmd = [sys.executable, "-m", "tools.hil.vc", str(sc.path), "--vehicle", v.id, "--lcm-url", url]
            cmd += ["--links", plan[v.id]["links"], "--nav-config", plan[v.id]["nav"], "--out", a.out / v.id]
            cmd += ["--build", a.build]
            vcs[v.id] = Child(f"{v.id}.vc", [*vc_exec.get(v.id, []), *map(str, cmd)], a.out / f"{v.id}.vc.out")
            vcs[v.id].start()
        for v in sc.vehicles:  # the best priority first: it serves the world
            cmd = programs.simulator(plan[v.id]["sim"], lcm_url=sim_url)
            sims.append(Child(f"{v.id}.sim", [*sim_exec, *cmd], a.out / f"{v.id}.sim.out"))
            sims[-1].start()
            time.sleep(0.5)
        print(f"auv-hil-wire: {len(vcs)} vehicle computers, {len(sims)} simulators at x{a.warp:g}", flush=True)
        while not stopping["now"] and any(c.poll() is None for c in vcs.values()):
            dead = next((s for s in sims if s.poll() is not None), None)
            if dead is not None:
                print(f"auv-hil-wire: {dead.name} exited ({dead.poll()}): {dead.tail()}", flush=True)
                break
            time.sleep(0.2)
    finally:
        codes = stop_together(list(vcs.values()) + sims + [rec])
    outcomes = {}
    for v in sc.vehicles:
        f = a.out / v.id / "outcome.json"
        outcomes[v.id] = json.loads(f.read_text()) if f.exists() else {"outcome": "died", "exit_code": 5}
    worst = max(outcomes.values(), key=lambda o: o["exit_code"])
    end_us = round(max(o.get("sim_time_s", 0.0) for o in outcomes.values()) * 1e6)
    summary = {
        "scenario": sc.name,
        "host": None,
        "mode": f"hil-wire ({a.transport}, x{a.warp:g})",
        "outcome": worst["outcome"],
        "exit_code": worst["exit_code"],
        "reason": "; ".join(f"{vid} {o.get('reason')}" for vid, o in outcomes.items() if o.get("reason")),
        "sim_time_s": end_us / 1e6,
        "wall_s": round(time.monotonic() - wall0, 1),
        "vehicles": {vid: o.get("vehicles", {}).get(vid, {"outcome": o["outcome"]}) for vid, o in outcomes.items()},
        "exits": codes,
        "log": str(a.out / "run.lcmlog"),
    }
    files = {vid: {"sim": p["sim"], "nav": p["nav"]} for vid, p in plan.items()}
    merge_logs(
        [log, *(a.out / v.id / f"{v.id}.lcmlog" for v in sc.vehicles)],
        a.out / "run.lcmlog",
        head=start_notes(sc, files),
        tail=end_notes(end_us, summary),
    )
    (a.out / "summary.json").write_text(json.dumps(summary, indent=1))
    for vid, o in outcomes.items():
        print(f"auv-hil-wire: {vid}: {o['outcome']} at t={o.get('sim_time_s', 0):.1f} s {o.get('reason', '')}")
    print(f"auv-hil-wire: results in {a.out}/ (summary.json, run.lcmlog; each vehicle computer's in its folder)")
    return worst["exit_code"]


if __name__ == "__main__":
    sys.exit(main())
