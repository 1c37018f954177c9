"""`auv-hil-vc`: one vehicle computer at the wire (docs/hil.md).

Starts, in the vehicle computer's own LCM world: its recorder, the time-link
driver (SIM.CLOCK from the simulator's time sentences), a driver per device
link, auv-nav and the vehicle's managers, every one on `--clock sim`; watches
the end manager (tools/launch/mission_watch.py) and stops everything, recorder
last, when the mission ends, at the scenario's time limit, on SIGINT/SIGTERM or
when a process dies. Writes outcome.json beside its log and exits with the
launcher's codes (tools/launch/launcher.py EXIT).

The simulator is not in this world: nothing here reads or writes its LCM.
"""

from __future__ import annotations

import argparse
import json
import signal
import sys
import time
from pathlib import Path

from auvlcm import programs
from auvlcm.chanfilter import FilteredLcm
from auvlcm.paths import ROOT
from auvlcm.url import check_local, with_receive_buffer
from confcheck import ConfigError
from tools.launch.annotate import Annotator
from tools.launch.launcher import EXIT, manager_cmd
from tools.launch.mission_watch import MissionWatch
from tools.launch.procs import TIER_FILTER, TIER_MANAGER, TIER_RECORDER, TIER_SIMULATOR, Child, stop_together
from tools.scenario.scenario_file import Scenario, load_scenario

STARTUP_TIMEOUT_S = 60.0


def driver_cmds(build: Path, vid: str, url: str, links: dict, flags: dict[str, list[str]]) -> list[tuple[str, list]]:
    """(name, command) of every driver: links is {device: {"tcp": ..} or {"port": .., "baud": ..}}."""
    out = []
    for dev, where in links.items():
        program = "payload" if dev.startswith("payload") else dev
        clock = "system" if dev == "timesync" else "sim"  # the time link is the clock
        cmd = programs.device_driver(build, program, vehicle=vid, lcm_url=url, clock=clock, raw=False, **where)
        out.append((f"{vid}.{dev}", cmd + list(flags.get(dev, []))))
    return out


class VehicleComputer:
    def __init__(self, sc: Scenario, vid: str, a: argparse.Namespace) -> None:
        self.sc, self.vid, self.a = sc, vid, a
        self.v = next(v for v in sc.vehicles if v.id == vid)
        self.url = with_receive_buffer(a.url)
        self.children: list[Child] = []
        self.lc = FilteredLcm(self.url)
        mine = Scenario(**{**sc.__dict__, "vehicles": [self.v]})
        self.watch = MissionWatch(self.lc, mine)
        self.watch.expected.discard(f"{vid}.sim")  # the simulator is not in this world
        self.notes = Annotator(self.lc, f"hil-vc@{vid}", ROOT)
        self.out: Path = a.out
        self.reason = ""

    def start(self, name: str, cmd: list, tier: int) -> None:
        c = Child(name, [str(x) for x in cmd], self.out / f"{name}.out", tier=tier)
        c.start()
        self.children.append(c)

    def start_all(self) -> None:
        a, vid = self.a, self.vid
        build = a.build
        log = self.out / f"{vid}.lcmlog"
        self.start("recorder", programs.auv_recorder(build, lcm_url=self.url, log=log), TIER_RECORDER)
        deadline = time.monotonic() + 20
        while not (log.exists() and log.stat().st_size > 0) and time.monotonic() < deadline:
            time.sleep(0.01)
        links = json.loads(a.links.read_text())
        for name, cmd in driver_cmds(build, vid, self.url, links["drivers"], links.get("flags", {})):
            self.start(name, cmd, TIER_SIMULATOR)  # the devices' side: stopped after the software
        nav = programs.auv_nav(build, config=a.nav_config, vehicle=vid, lcm_url=self.url, rate_hz=self.v.nav.rate_hz)
        self.start(f"{vid}.NAV", nav, TIER_FILTER)
        for m in self.v.managers:
            cmd = manager_cmd(build, self.url, vid, m, self.sc.key_file)
            self.start(f"{vid}.{m.name}", cmd, TIER_MANAGER)
        for m in self.v.managers:
            self.notes.plan(m.plan, vid)

    def dead(self) -> Child | None:
        return next((c for c in self.children if not c.stopping and c.poll() is not None), None)

    def run(self, stop) -> str:
        deadline = time.monotonic() + STARTUP_TIMEOUT_S
        while not self.watch.all_ready():
            if stop():
                return "interrupted"
            if self.dead() or time.monotonic() > deadline:
                self.reason = f"not ready: {', '.join(self.watch.not_ready())}"
                return "died"
            self.watch.handle(0.1)
        print(f"hil-vc: {self.vid}: every process reports; flying", flush=True)
        next_progress = time.monotonic() + 10
        while True:
            if stop():
                return "interrupted"
            d = self.dead()
            if d is not None:
                self.reason = f"{d.name} exited with status {d.poll()}: {d.tail()}"
                return "died"
            self.watch.handle(0.1)
            outcome = self.watch.outcome()
            if outcome:
                return outcome
            if self.watch.sim_time_us / 1e6 >= self.sc.time.limit_s:
                self.reason = f"mission time limit {self.sc.time.limit_s:g} s reached"
                return "time limit"
            if time.monotonic() >= next_progress:
                next_progress += 10
                print(
                    f"hil-vc: t={self.watch.sim_time_us / 1e6:8.1f} s  {'  '.join(self.watch.progress())}", flush=True
                )

    def stop(self, result: str) -> dict:
        end_us = self.watch.sim_time_us
        # not `mission end`: that is the whole run's (auv-hil-wire writes it), and the report cuts there
        self.notes.event("computer end", json.dumps({"sim_time_s": end_us / 1e6}), vehicle=self.vid, utime=end_us)
        codes = stop_together(self.children)
        summary = {
            "vehicle": self.vid,
            "outcome": result,
            "exit_code": EXIT[result],
            "reason": self.reason,
            "sim_time_s": end_us / 1e6,
            "vehicles": self.watch.vehicle_summary(),
            "exits": codes,
            "log": str(self.out / f"{self.vid}.lcmlog"),
        }
        (self.out / "outcome.json").write_text(json.dumps(summary, indent=1))
        return summary


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="auv-hil-vc", description="One vehicle computer at the wire (docs/hil.md).")
    ap.add_argument("scenario", type=Path)
    ap.add_argument("--vehicle", required=True)
    ap.add_argument(
        "--links", type=Path, required=True, help="JSON: the drivers' ports and flags (auv-hil-wire writes it)"
    )
    ap.add_argument("--nav-config", type=Path, required=True)
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--build", type=Path, default=ROOT / "build")
    programs.add_lcm_url_argument(ap, "this vehicle computer's LCM world", required=True)
    a = ap.parse_args(argv)
    try:
        a.url = check_local(a.url)
    except ValueError as exc:
        ap.error(str(exc))
    try:
        sc = load_scenario(a.scenario)
    except ConfigError as exc:
        print("\n".join(exc.errors), file=sys.stderr)
        return 2
    if a.vehicle not in {v.id for v in sc.vehicles}:
        ap.error(f"{a.scenario}: no vehicle {a.vehicle}")
    a.out.mkdir(parents=True, exist_ok=True)
    stopping = {"now": False}

    def on_signal(*_):
        stopping["now"] = True

    signal.signal(signal.SIGINT, on_signal)
    signal.signal(signal.SIGTERM, on_signal)
    vc = VehicleComputer(sc, a.vehicle, a)
    result = "died"
    try:
        vc.start_all()
        result = vc.run(lambda: stopping["now"])
    finally:
        s = vc.stop(result)
    print(f"hil-vc: {a.vehicle}: {s['outcome']} at t={s['sim_time_s']:.1f} s {s['reason']}", flush=True)
    return s["exit_code"]


if __name__ == "__main__":
    sys.exit(main())
