"""The scenario file: what the launcher starts (docs/scenarios.md).

Read and checked by confcheck like every configuration: every error is
reported at once as `file:line:col: key: message`, unknown keys with a
did-you-mean hint. Relative paths are relative to the scenario file (or to
`base`: a scenario a host agent received over LCM resolves them from its
sender's folder).
"""

from __future__ import annotations

import dataclasses
import difflib
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from auvlcm import auth
from confcheck import Checker, Rule, join, rule_of, setting, vehicle_id_problem
from confcheck.checker import control_character
from sim import clock_modes
from tools.scenario import radio_section
from tools.scenario.faults import PlannedFault, check_faults
from tools.scenario.plan_params import declared_params

MANAGER_NAME = r"[A-Z][A-Z0-9_]{0,23}"
PARAM_NAME = r"[A-Za-z_][A-Za-z0-9_]{0,63}"
HOST_NAME = r"[A-Za-z0-9][A-Za-z0-9_.-]{0,62}"
# the launcher's clock is lockstep in every mode (tools/launch/worldclock.py): the mode is its pace
# (sim.clock_modes: lockstep = as fast as the slowest participant; `fast`, its old name, is read so).
TIME_MODES = clock_modes.MODES
RECORDERS = ("auv-recorder", "lcm-logger")  # what records the run's log (docs/tools.md, "Recorder")
CLOCK_SOURCES = ("launcher", "simulators")
NAV_SOURCES = ("ins", "ekf")
DEFAULT_HOST = "local"
MAX_PARAM_CHARS = 1000  # a -D value on a command line


@dataclass
class Manager:
    name: str = setting(
        "", pattern=MANAGER_NAME, pattern_hint="upper-case letters, digits and _, starting with a letter"
    )
    plan: Path = Path()
    bind: Path = Path()
    rate_hz: float = setting(10.0, gt=0.0, key="rate")
    # <V>.CHASM.<NAME> per second of mission time at most, plus one at once on every
    # change of state or of a drop count; 0: every cycle (chasm-manager --status-rate)
    status_rate_hz: float = setting(0.0, ge=0.0, le=1000.0, key="status_rate")
    params: dict[str, str] = field(default_factory=dict)  # -D name=value
    plugin_path: list[Path] = field(default_factory=list)
    where: str = ""


@dataclass
class NavChoice:
    """What publishes the vehicle's <ID>.NAV (docs/navigation.md)."""

    source: str = setting("ins", one_of=NAV_SOURCES)  # "ins": the simulator's INS; "ekf": auv-nav
    config: Path | None = None  # auv-nav's nav config; None: derived from the sim config
    rate_hz: float = setting(20.0, gt=0.0, key="rate")


@dataclass
class BackseatLimits:
    """auv-frontseat's limits on a vehicle flown from its backseat (docs/frontseat.md,
    "The team in backseat mode"): its simulator configuration has a `frontseat:`;
    the defaults are auv-frontseat's own."""

    max_depth_m: float = setting(100.0, ge=0.0, le=6000.0, key="max_depth")  # deeper: clamped
    min_speed_mps: float = setting(0.5, ge=0.0, le=20.0, key="min_speed")  # slower: refused
    max_speed_mps: float = setting(2.5, ge=0.01, le=20.0, key="max_speed")  # faster: clamped
    silent_after_s: float = setting(3.0, ge=0.2, le=600.0, key="silent_after")  # the frontseat is silent


@dataclass
class FrontEstimator:
    """auv-front-estimate beside the vehicle's managers (docs/sampling.md, "The on-board
    front estimator"): `front_estimate: {rate: 0.2, max_age: 1800, max_depth: 15}`."""

    rate_hz: float = setting(0.2, gt=0.0, le=10.0, key="rate")  # estimates per second of mission time
    max_age_s: float = setting(1800.0, gt=0.0, le=86400.0, key="max_age")  # readings older are not fitted
    max_depth_m: float = setting(15.0, gt=0.0, le=11000.0, key="max_depth")  # deeper readings are not fitted


@dataclass
class Vehicle:
    id: str
    host: str
    sim_config: Path  # base simulator configuration
    sim_overrides: dict  # merged over it (same sections as the sim's YAML)
    managers: list[Manager]
    end_manager: str = "NAVIGATOR"  # whose status ends this vehicle's mission
    where: str = ""
    nav: NavChoice = field(default_factory=NavChoice)
    sim_node: Any = None  # the `sim:` mapping node, for error positions
    backseat: BackseatLimits | None = None  # `backseat:` given (the mode itself is the sim's `frontseat:`)
    backseat_where: str = ""  # file:line:col of `backseat:`
    front_estimate: FrontEstimator | None = None  # `front_estimate:` given: run auv-front-estimate


@dataclass
class TimeSettings:
    mode: str = setting("scaled", one_of=TIME_MODES, old_names=clock_modes.OLD_NAMES)
    warp: float = setting(10.0, gt=0.0)
    step_s: float = setting(0.05, gt=0.0, key="step")  # SIM.CLOCK tick [sim s]
    limit_s: float = setting(3600.0, gt=0.0, key="limit")  # mission time limit [sim s]
    wall_limit_s: float = setting(0.0, ge=0.0, key="wall_limit")  # 0 = none [wall s]
    host: str = DEFAULT_HOST  # the host that runs the clock
    source: str = setting("launcher", one_of=CLOCK_SOURCES)  # or "simulators": their multi-HIL nodes


@dataclass
class Scenario:
    path: Path
    name: str
    seed: int
    lcm_url: str
    world: dict  # merged into every simulator's `environment`
    time: TimeSettings
    log_enabled: bool
    log_file: str
    log_host: str
    log_recorder: str
    hosts: list[str]
    vehicles: list[Vehicle]
    text: str = ""
    survey: Path | None = None  # the planner's survey.json, for reports and plots
    world_node: Any = None  # the `world:` mapping node, for error positions
    faults: list[PlannedFault] = field(default_factory=list)  # tools/scenario/faults.py
    radio: Any = None  # tools/scenario/radio_section.RadioSection: the surface radio, docs/radio.md
    key_file: Path | None = None  # team keys (docs/security.md): managers verify, the launcher signs

    def vehicles_on(self, host: str | None) -> list[Vehicle]:
        return [v for v in self.vehicles if host is None or v.host == host]


def position(path: Path, node: Any, parts: list[str]) -> tuple[str, bool]:
    """file:line:col of the deepest key of `parts` found under a mapping node,
    and whether all of them were found."""
    best, found = node, 0
    for part in parts:
        if not isinstance(node, yaml.MappingNode):
            break
        hit = next((v for k, v in node.value if isinstance(k, yaml.ScalarNode) and k.value == part), None)
        if hit is None:
            break
        best = node = hit
        found += 1
    m = best.start_mark if best is not None else None
    return (f"{path}:{m.line + 1}:{m.column + 1}" if m else str(path)), found == len(parts) and found > 0


class _Scenario:
    """The checks of one scenario file (errors collect in self.c)."""

    def __init__(self, c: Checker, base: Path | None = None) -> None:
        self.c, self.base = c, base or c.path.parent

    def get(self, items: dict, k: str, key: str, default: Any, rule: Rule = Rule()) -> Any:
        if k not in items:
            return default
        v = self.c.value(items[k][1], join(key, k), default, rule)
        return default if v is dataclasses.MISSING else v

    def file(self, items: dict, k: str, key: str) -> Path | None:
        v = self.get(items, k, key, "")
        if not v:
            return None
        p = (self.base / v).resolve()
        if not p.is_file():
            self.c.err(items[k][1], join(key, k), f"no such file: {p}")
        return p

    def key_file(self, items: dict) -> Path | None:
        """key_file: a team key file (auv-keygen) that loads: mode 0600, well formed."""
        p = self.file(items, "key_file", "")
        if p is not None and p.is_file():
            try:
                auth.load_keys(p)
            except auth.KeyFileError as exc:
                self.c.err(items["key_file"][1], "key_file", str(exc))
        return p

    def params(self, node, key: str, plan: Path | None) -> dict[str, str]:
        c, out = self.c, {}
        items = c.mapping(node, key)
        declared = declared_params(plan) if plan is not None and plan.is_file() else None
        for pk, (knode, vnode) in items.items():
            pkey = join(key, pk)
            if not re.fullmatch(PARAM_NAME, pk):
                c.err(knode, pkey, "a parameter name is letters, digits and _, starting with a letter")
                continue
            if declared is not None and pk not in declared:
                hint = difflib.get_close_matches(pk, sorted(declared), n=1)
                c.err(
                    knode,
                    pkey,
                    f"the plan {plan.name} declares no parameter '{pk}'"
                    + (
                        f"; did you mean '{hint[0]}'?"
                        if hint
                        else f"; it declares: {', '.join(sorted(declared)) or 'none'}"
                    ),
                )
                continue
            if not isinstance(vnode, yaml.ScalarNode) or c.is_empty(vnode):
                c.err(vnode, pkey, "expected a value such as 12 or '12 m'")
                continue
            v = c.scalar(vnode)
            text = str(v).lower() if isinstance(v, bool) else v if isinstance(v, str) else vnode.value
            if len(text) > MAX_PARAM_CHARS:
                c.err(vnode, pkey, f"longer than {MAX_PARAM_CHARS} characters")
                continue
            bad = control_character(text)
            if bad:
                c.err(vnode, pkey, f"must not hold {bad} (the value goes into the plan as -D {pk}=...)")
                continue
            out[pk] = text
        return out

    def section(self, node, key: str, allowed: tuple, required: tuple) -> dict | None:
        """A mapping's items, its keys checked; None if it is not a mapping (reported)."""
        items = self.c.mapping(node, key)
        if not isinstance(node, yaml.MappingNode):
            return None
        self.c.unknown(items, allowed, key)
        self.c.required(items, required, node, key)
        return items

    def manager(self, node, key: str) -> Manager | None:
        c = self.c
        items = self.section(
            node,
            key,
            ("name", "plan", "bind", "rate", "status_rate", "params", "plugin_path"),
            ("name", "plan", "bind"),
        )
        if items is None:
            return None
        m = Manager(where=c.where(node))
        m.name = self.get(items, "name", key, "", rule_of(Manager, "name"))
        plan, bind = self.file(items, "plan", key), self.file(items, "bind", key)
        m.rate_hz = self.get(items, "rate", key, 10.0, rule_of(Manager, "rate_hz"))
        m.status_rate_hz = self.get(items, "status_rate", key, 0.0, rule_of(Manager, "status_rate_hz"))
        if "params" in items:
            m.params = self.params(items["params"][1], join(key, "params"), plan)
        pp: list = []
        if "plugin_path" in items:
            pnode = items["plugin_path"][1]
            if isinstance(pnode, yaml.ScalarNode):
                one = self.get(items, "plugin_path", key, "")
                pp = [one] if one else []
            else:
                got = c.value(pnode, join(key, "plugin_path"), [""])
                pp = [] if got is dataclasses.MISSING else got
        if not m.name or plan is None or bind is None:
            return None
        m.plan, m.bind, m.plugin_path = plan, bind, [(self.base / p).resolve() for p in pp]
        return m

    def nav(self, items: dict, key: str) -> NavChoice:
        """`nav: ins` (default), `nav: ekf`, or `nav: {source: ekf, config: FILE.nav, rate: 20}`."""
        nav = NavChoice()
        if "nav" not in items:
            return nav
        node = items["nav"][1]
        if isinstance(node, yaml.ScalarNode):
            nav.source = self.get(items, "nav", key, "ins", Rule(one_of=NAV_SOURCES))
            return nav
        n = self.c.mapping(node, join(key, "nav"))
        self.c.required(n, ("source",), node, join(key, "nav"))
        self.c.fill(node, join(key, "nav"), nav, skip=("config",))  # config: a file, below
        nav.config = self.file(n, "config", join(key, "nav")) if "config" in n else None
        return nav

    def backseat(self, items: dict, key: str) -> BackseatLimits | None:
        """`backseat: {max_depth: 40, min_speed: 0.5, max_speed: 2, silent_after: 3}`: auv-frontseat's limits."""
        if "backseat" not in items:
            return None
        node = items["backseat"][1]
        errors_before = len(self.c.errors)
        lim = self.c.fill(node, join(key, "backseat"), BackseatLimits())
        if len(self.c.errors) == errors_before and lim.min_speed_mps >= lim.max_speed_mps:
            self.c.err(
                node,
                join(key, "backseat"),
                f"min_speed {lim.min_speed_mps:g} m/s is not below max_speed {lim.max_speed_mps:g} m/s",
            )
        return lim

    def front_estimate(self, items: dict, key: str) -> FrontEstimator | None:
        """`front_estimate: {}` (auv-front-estimate's defaults) or with rate, max_age, max_depth."""
        if "front_estimate" not in items:
            return None
        return self.c.fill(items["front_estimate"][1], join(key, "front_estimate"), FrontEstimator())

    def vehicle(self, node, key: str, hosts: list[str]) -> Vehicle | None:
        c = self.c
        items = self.section(
            node,
            key,
            ("id", "host", "sim", "managers", "end_manager", "nav", "backseat", "front_estimate"),
            ("id", "sim", "managers"),
        )
        if items is None:
            return None
        vid = self.get(items, "id", key, "")
        problem = vehicle_id_problem(vid) if "id" in items else ""
        if problem:
            c.err(items["id"][1], join(key, "id"), problem)
            vid = ""
        host = self.host(items, "host", key, hosts)
        cfg, overrides, sim_node = None, {}, None
        if "sim" in items:
            sim_node = items["sim"][1]
            sim = c.mapping(sim_node, join(key, "sim"))
            if isinstance(sim_node, yaml.MappingNode):
                c.required(sim, ("config",), sim_node, join(key, "sim"))
                cfg = self.file(sim, "config", join(key, "sim"))
                overrides = {k: c.plain(v, join(join(key, "sim"), k)) for k, (_, v) in sim.items() if k != "config"}
        managers = []
        mnodes = c.sequence(items["managers"][1], join(key, "managers")) if "managers" in items else []
        if "managers" in items and not mnodes and isinstance(items["managers"][1], yaml.SequenceNode):
            c.err(items["managers"][1], join(key, "managers"), "expected a non-empty list of managers")
        for i, mn in enumerate(mnodes):
            mgr = self.manager(mn, f"{key}.managers[{i}]")
            if mgr is not None:
                managers.append(mgr)
        names = [m.name for m in managers]
        for dup in sorted({n for n in names if names.count(n) > 1}):
            c.err(items["managers"][1], join(key, "managers"), f"manager name '{dup}' used twice")
        end = self.get(items, "end_manager", key, "NAVIGATOR")
        if managers and end not in names:
            c.err(
                (items.get("end_manager") or items["managers"])[1],
                join(key, "end_manager"),
                f"no manager named '{end}' (its status ends the mission)",
            )
        nav = self.nav(items, key)
        backseat = self.backseat(items, key)
        front = self.front_estimate(items, key)
        if not vid or cfg is None or not managers:
            return None
        veh = Vehicle(vid, host, cfg, overrides, managers, end, c.where(node), nav, sim_node, backseat)
        if backseat is not None:
            veh.backseat_where = c.where(items["backseat"][1])
        veh.front_estimate = front
        return veh

    def host(self, items: dict, k: str, key: str, hosts: list[str]) -> str:
        """One of the scenario's hosts (the first if not given)."""
        h = self.get(items, k, key, hosts[0])
        if h not in hosts:
            self.c.err(items[k][1], join(key, k), f"unknown host '{h}'; hosts are: {', '.join(hosts)}")
            return hosts[0]
        return h

    def hosts(self, items: dict) -> list[str]:
        if "hosts" not in items:
            return [DEFAULT_HOST]
        got = self.c.value(
            items["hosts"][1], "hosts", [""], Rule(pattern=HOST_NAME, pattern_hint="a host name (letters, digits, _.-)")
        )
        if got is dataclasses.MISSING or not got:
            if got == []:
                self.c.err(items["hosts"][1], "hosts", "expected a non-empty list of host names")
            return [DEFAULT_HOST]
        return got


TOP_KEYS = (
    "name",
    "seed",
    "lcm_url",
    "world",
    "time",
    "logging",
    "hosts",
    "vehicles",
    "survey",
    "faults",
    "key_file",
    "radio",
)


def load_scenario(path: str | Path, base: Path | None = None, own_keys: bool = False) -> Scenario:
    """Read and check a scenario; ConfigError lists every problem. own_keys: the reader
    has team keys of its own (a host agent's --key-file), so the scenario's key_file,
    a path on the sender's host, is neither read nor checked here."""
    path = Path(path).resolve()
    c = Checker.from_file(path)
    s = _Scenario(c, base)
    top = c.mapping(c.root, "")
    if not isinstance(c.root, yaml.MappingNode):
        c.raise_errors()
    c.unknown(top, TOP_KEYS, "")
    c.required(top, ("vehicles",), c.root, "")
    hosts = s.hosts(top)
    world_node = top["world"][1] if "world" in top else None
    world = c.plain(world_node, "world") if world_node is not None else {}
    if world_node is not None and not isinstance(world, dict):
        c.err(world_node, "world", "expected a mapping of keys")
        world = {}
    time = TimeSettings(host=hosts[0])
    tnode = top["time"][1] if "time" in top else None
    t_items = c.mapping(tnode, "time")
    c.fill(tnode, "time", time, skip=("host",))
    time.host = s.host(t_items, "host", "time", hosts)
    lg_items = c.mapping(top["logging"][1], "logging") if "logging" in top else {}
    c.unknown(lg_items, ("enabled", "file", "host", "recorder"), "logging")
    vehicles = []
    if "vehicles" in top:
        vnode = top["vehicles"][1]
        vnodes = c.sequence(vnode, "vehicles")
        if not vnodes and isinstance(vnode, yaml.SequenceNode) or c.is_empty(vnode):
            c.err(vnode, "vehicles", "expected a non-empty list of vehicles")
        for i, n in enumerate(vnodes):
            veh = s.vehicle(n, f"vehicles[{i}]", hosts)
            if veh is not None:
                vehicles.append(veh)
        ids = [v.id for v in vehicles]
        for dup in sorted({i for i in ids if ids.count(i) > 1}):
            c.err(vnode, "vehicles", f"vehicle id '{dup}' used twice")
    sc = Scenario(
        path=path,
        name=s.get(
            top,
            "name",
            "",
            path.stem,
            Rule(
                pattern=r"[A-Za-z0-9][A-Za-z0-9_.-]{0,63}",
                pattern_hint="letters, digits, _.- (it names the run folder)",
            ),
        ),
        seed=s.get(top, "seed", "", 1, Rule(ge=0, le=2**31 - 1)),
        lcm_url=s.get(top, "lcm_url", "", ""),
        world=world,
        time=time,
        log_enabled=s.get(lg_items, "enabled", "logging", True),
        log_file=s.get(
            lg_items,
            "file",
            "logging",
            "run.lcmlog",
            Rule(pattern=r"[A-Za-z0-9_][A-Za-z0-9_.-]{0,127}", pattern_hint="a file name in the run folder"),
        ),
        log_host=s.host(lg_items, "host", "logging", hosts),
        log_recorder=s.get(lg_items, "recorder", "logging", RECORDERS[0], Rule(one_of=RECORDERS)),
        hosts=hosts,
        vehicles=vehicles,
        text=c.text,
        survey=s.file(top, "survey", ""),
        world_node=world_node,
        faults=check_faults(c, top["faults"][1] if "faults" in top else None, [v.id for v in vehicles], time.limit_s),
        key_file=None if own_keys else s.key_file(top),
        radio=radio_section.parse(c, top["radio"][1] if "radio" in top else None, [v.id for v in vehicles]),
    )
    c.raise_errors()
    return sc
