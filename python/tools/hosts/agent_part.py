"""One host's part of a scenario, as a host agent runs it (docs/hosts.md).

The same processes `auv-launch --host HOST` would start (simulators, onboard
filters, the auv-frontseat of a vehicle flown from its backseat, managers, with
the same command lines), plus the recorder the
scenario names (tools/launch/recorder_cmd.py) when it logs on this host; every check
the launcher makes comes first, and any failure refuses the whole part. What the agent does not run is the
launcher's clock and mission watch: `agentctl watch` runs those when the
scenario keeps time on the launcher (time.source: launcher).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from auvlcm.url import check_local
from confcheck import ConfigError
from tools.launch.backseat import frontseat_ports
from tools.launch.launcher import Launcher, check_plans, nav_configs
from tools.launch.procs import TIER_FILTER, TIER_MANAGER, TIER_RECORDER, TIER_SIMULATOR
from tools.launch.recorder_cmd import recorder_cmd, recorder_takes_part
from tools.launch.simconfig import write_configs
from tools.scenario.scenario_file import Scenario, load_scenario


@dataclass
class ProcSpec:
    name: str
    cmd: list[str]
    out: Path
    tier: int = TIER_RECORDER  # stop order (tools.launch.procs.TIER_*)


class _Commands(Launcher):
    """The launcher's command lines without its LCM, clock or children."""

    def __init__(self, sc: Scenario, url: str, sim_configs: dict, navs: dict, build: Path, frontseats: dict) -> None:
        self.sc, self.url, self.sim_configs, self.nav_configs, self.build = sc, url, sim_configs, navs, build
        self.frontseats = frontseats


class PartError(Exception):
    def __init__(self, errors: list[str]) -> None:
        super().__init__("\n".join(errors))
        self.errors = errors


def host_part(
    text: str,
    sent_path: str,
    host: str,
    run_dir: Path,
    url: str,
    build: Path,
    inside_netns: bool,
    key_file: Path | None = None,
) -> tuple[Scenario, list[ProcSpec]]:
    """Check the scenario as this host sees it and return its processes in
    start order; PartError lists every problem (`file:line:col: ...`). key_file:
    the agent's own team keys, which its managers then require (whatever the
    scenario names)."""
    run_dir.mkdir(parents=True, exist_ok=True)
    sent = Path(sent_path or "scenario.yaml")
    local = run_dir / (sent.name if sent.suffix in (".yaml", ".yml") else "scenario.yaml")
    local.write_text(text)
    base = sent.parent if sent.is_absolute() and sent.parent.is_dir() else None
    if sent.is_absolute() and base is None:
        raise PartError(
            [
                f"{sent}: its folder does not exist on host {host}: agents resolve the scenario's "
                "relative paths from the sender's folder (the same checkout path on every host)"
            ]
        )
    try:
        sc = load_scenario(local, base, own_keys=key_file is not None)
    except ConfigError as exc:  # point at the sender's file: same text, same lines
        raise PartError([e.replace(str(local), str(sent)) for e in exc.errors]) from None
    if base is not None:
        sc.path = sent  # world grids and config comments resolve as on the sender
    if key_file is not None:
        sc.key_file = key_file
    if host not in sc.hosts:
        raise PartError([f"{local}: hosts: this agent's host '{host}' is not one of: {', '.join(sc.hosts)}"])
    try:
        url = check_local(sc.lcm_url or url, inside_netns=inside_netns)
    except ValueError as exc:
        raise PartError([f"{local}: lcm_url: {exc}"]) from None
    mine = Scenario(**{**sc.__dict__, "vehicles": sc.vehicles_on(host)})
    missing = [b for b in ("bin/chasm", "bin/chasm-manager", "bin/auv-nav") if not (build / b).exists()]
    if missing:
        raise PartError([f"{build}: {', '.join(missing)} not built on host {host} (make build)"])
    # the same participants as on the clock's host: the recorder too, wherever it runs
    sim_configs, errors = write_configs(sc, mine.vehicles, run_dir, recorder_takes_part(sc, sc.log_recorder))
    navs, nav_errors = nav_configs(mine, sim_configs, run_dir, build)
    frontseats, fs_errors = frontseat_ports(mine, sim_configs)
    errors += nav_errors + fs_errors + check_plans(mine, build)
    if errors:
        raise PartError(errors)
    cmds = _Commands(sc, url, sim_configs, navs, build, frontseats)
    procs = []
    if sc.log_enabled and sc.log_host == host:
        log, stats = run_dir / sc.log_file, run_dir / "recorder.json"
        cmd = recorder_cmd(sc.log_recorder, url, log, stats, build)
        procs.append(ProcSpec("logger", cmd, run_dir / "logger.out"))
    for v in mine.vehicles:
        procs.append(ProcSpec(f"{v.id}.sim", cmds.sim_cmd(v.id), run_dir / f"{v.id}.sim.out", TIER_SIMULATOR))
    for v in mine.vehicles:
        if v.id in navs:
            procs.append(ProcSpec(f"{v.id}.NAV", cmds.nav_cmd(v), run_dir / f"{v.id}.nav.out", TIER_FILTER))
        if v.id in frontseats:
            out = run_dir / f"{v.id}.frontseat.out"
            procs.append(ProcSpec(f"{v.id}.FRONTSEAT", cmds.frontseat_cmd(v), out, TIER_FILTER))
    for v in mine.vehicles:
        for m in v.managers:
            out = run_dir / f"{v.id}.{m.name}.out"
            procs.append(ProcSpec(f"{v.id}.{m.name}", cmds.manager_cmd(v.id, m), out, TIER_MANAGER))
    return sc, procs
