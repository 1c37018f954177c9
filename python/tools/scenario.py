"""The scenario file: what the launcher starts (docs/scenarios.md).

Checked key by key; every error is reported at once as
`file:line:col: key: message`, unknown keys with a did-you-mean hint.
Relative paths are relative to the scenario file (or to `base`: a scenario a
host agent received over LCM resolves them from its sender's folder).
"""

from __future__ import annotations

import difflib
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from tools.marked_yaml import MDict, MList, YamlError, load, where

VEHICLE_ID = re.compile(r"[A-Z][A-Z0-9]{0,15}")
MANAGER_NAME = re.compile(r"[A-Z][A-Z0-9_]{0,23}")
HOST_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.-]{0,62}")
TIME_MODES = ("realtime", "scaled", "fast")
CLOCK_SOURCES = ("launcher", "simulators")
DEFAULT_HOST = "local"


@dataclass
class Manager:
    name: str
    plan: Path
    bind: Path
    rate_hz: float = 10.0
    params: dict[str, str] = field(default_factory=dict)    # -D name=value
    plugin_path: list[Path] = field(default_factory=list)
    where: str = ""


@dataclass
class NavChoice:
    """What publishes the vehicle's <ID>.NAV (docs/navigation.md)."""
    source: str = "ins"                   # "ins": the simulator's black-box INS; "ekf": auv-nav
    config: Path | None = None            # auv-nav's nav config; None: derived from the sim config
    rate_hz: float = 20.0


@dataclass
class Vehicle:
    id: str
    host: str
    sim_config: Path                      # base simulator configuration
    sim_overrides: MDict                  # merged over it (same sections as the sim's YAML)
    managers: list[Manager]
    end_manager: str = "NAVIGATOR"        # whose status ends this vehicle's mission
    where: str = ""
    nav: NavChoice = field(default_factory=NavChoice)


@dataclass
class TimeSettings:
    mode: str = "scaled"
    warp: float = 10.0
    step_s: float = 0.05                  # SIM.CLOCK tick [sim s]
    limit_s: float = 3600.0               # mission time limit [sim s]
    wall_limit_s: float = 0.0             # 0 = none [wall s]
    host: str = DEFAULT_HOST              # the host that runs the clock
    source: str = "launcher"              # or "simulators": their multi-HIL nodes keep the time


@dataclass
class Scenario:
    path: Path
    name: str
    seed: int
    lcm_url: str
    world: MDict                          # merged into every simulator's `environment`
    time: TimeSettings
    log_enabled: bool
    log_file: str
    log_host: str
    hosts: list[str]
    vehicles: list[Vehicle]
    text: str = ""
    survey: Path | None = None            # the planner's survey.json, for reports and plots

    def vehicles_on(self, host: str | None) -> list[Vehicle]:
        return [v for v in self.vehicles if host is None or v.host == host]


class _Checker:
    def __init__(self, path: Path, base: Path | None = None) -> None:
        self.path, self.base, self.errors = path, base or path.parent, []

    def err(self, pos: str, key: str, msg: str) -> None:
        self.errors.append(f"{pos or self.path}: {key}: {msg}")

    def mapping(self, value: Any, pos: str, key: str, allowed: tuple[str, ...], required=()) -> MDict:
        if value is None:
            value = MDict()
            value.where, value.key_where = pos, {}
        if not isinstance(value, MDict):
            self.err(pos, key, "expected a mapping of keys")
            empty = MDict()
            empty.where, empty.key_where = pos, {}
            return empty
        for k in value:
            if k not in allowed:
                hint = difflib.get_close_matches(k, allowed, n=1)
                self.err(where(value, k), f"{key}.{k}" if key else k,
                         f"unknown key; did you mean '{hint[0]}'?" if hint
                         else f"unknown key; expected one of: {', '.join(allowed)}")
        for k in required:
            if k not in value:
                self.err(value.where, key or "scenario", f"missing required key '{k}'")
        return value

    def get(self, m: MDict, k: str, key: str, kind: type | tuple, default: Any, check=None) -> Any:
        if k not in m:
            return default
        v = m[k]
        if kind is float and isinstance(v, int) and not isinstance(v, bool):
            v = float(v)
        if not isinstance(v, kind) or (kind is not bool and isinstance(v, bool)):
            names = {str: "a string", float: "a number", int: "an integer", bool: "true/false"}
            self.err(where(m, k), f"{key}.{k}" if key else k,
                     f"expected {names.get(kind, getattr(kind, '__name__', 'a value'))}, got {v!r}")
            return default
        if check is not None:
            problem = check(v)
            if problem:
                self.err(where(m, k), f"{key}.{k}" if key else k, problem)
                return default
        return v

    def file(self, m: MDict, k: str, key: str) -> Path | None:
        """A file path relative to the scenario; a missing key is reported by mapping()."""
        v = self.get(m, k, key, str, None)
        if v is None:
            return None
        p = (self.base / v).resolve()
        if not p.is_file():
            self.err(where(m, k), f"{key}.{k}" if k != key else k, f"no such file: {p}")
        return p


def _positive(v: float) -> str:
    return "" if v > 0 else "must be > 0"


def _nonneg(v: float) -> str:
    return "" if v >= 0 else "must be >= 0"


def _manager(c: _Checker, m: Any, pos: str, key: str) -> Manager | None:
    m = c.mapping(m, pos, key, ("name", "plan", "bind", "rate", "params", "plugin_path"),
                  required=("name", "plan", "bind"))
    name = c.get(m, "name", key, str, "", lambda v: "" if MANAGER_NAME.fullmatch(v) else
                 "upper-case letters, digits and _, starting with a letter")
    plan, bind = c.file(m, "plan", key), c.file(m, "bind", key)
    rate = c.get(m, "rate", key, float, 10.0, _positive)
    params = c.mapping(m.get("params"), where(m, "params"), f"{key}.params",
                       tuple(m.get("params") or ()))
    dparams = {}
    for pk, pv in params.items():
        if isinstance(pv, (dict, list)) or pv is None:
            c.err(where(params, pk), f"{key}.params.{pk}", "expected a value such as 12 or '12 m'")
        else:
            dparams[pk] = str(pv).lower() if isinstance(pv, bool) else str(pv)
    pp = m.get("plugin_path", [])
    if isinstance(pp, str):
        pp = [pp]
    if not isinstance(pp, list) or not all(isinstance(x, str) for x in pp):
        c.err(where(m, "plugin_path"), f"{key}.plugin_path", "expected a directory or a list of them")
        pp = []
    if not name or plan is None or bind is None:
        return None
    return Manager(name, plan, bind, rate, dparams, [(c.base / p).resolve() for p in pp], pos)


NAV_SOURCES = ("ins", "ekf")


def _nav(c: _Checker, v: MDict, key: str) -> NavChoice:
    """`nav: ins` (default), `nav: ekf`, or `nav: {source: ekf, config: FILE.nav, rate: 20}`."""
    raw = v.get("nav", "ins")
    check = lambda s: "" if s in NAV_SOURCES else f"expected one of: {', '.join(NAV_SOURCES)}"  # noqa: E731
    if isinstance(raw, str):
        return NavChoice(c.get(v, "nav", key, str, "ins", check))
    m = c.mapping(raw, where(v, "nav"), f"{key}.nav", ("source", "config", "rate"), required=("source",))
    nav = NavChoice(c.get(m, "source", f"{key}.nav", str, "ins", check))
    nav.config = c.file(m, "config", f"{key}.nav") if "config" in m else None
    nav.rate_hz = c.get(m, "rate", f"{key}.nav", float, nav.rate_hz, _positive)
    return nav


def _vehicle(c: _Checker, v: Any, pos: str, key: str, hosts: list[str]) -> Vehicle | None:
    v = c.mapping(v, pos, key, ("id", "host", "sim", "managers", "end_manager", "nav"),
                  required=("id", "sim", "managers"))
    vid = c.get(v, "id", key, str, "", lambda s: "" if VEHICLE_ID.fullmatch(s) else
                "upper-case letters and digits, starting with a letter, at most 16")
    host = c.get(v, "host", key, str, hosts[0])
    if host not in hosts:
        c.err(where(v, "host"), f"{key}.host", f"unknown host '{host}'; hosts are: {', '.join(hosts)}")
    sim = v.get("sim")
    if not isinstance(sim, MDict):
        if "sim" in v:
            c.err(where(v, "sim"), f"{key}.sim", "expected a mapping with 'config' and overrides")
        return None
    cfg = c.file(sim, "config", f"{key}.sim")
    overrides = MDict({k: x for k, x in sim.items() if k != "config"})
    overrides.where, overrides.key_where = sim.where, dict(sim.key_where)
    mgrs_raw = v.get("managers")
    managers = []
    if not isinstance(mgrs_raw, MList) or not mgrs_raw:
        if "managers" in v:
            c.err(where(v, "managers"), f"{key}.managers", "expected a non-empty list of managers")
    else:
        for i, m in enumerate(mgrs_raw):
            mgr = _manager(c, m, where(mgrs_raw, i), f"{key}.managers[{i}]")
            if mgr is not None:
                managers.append(mgr)
        names = [m.name for m in managers]
        for dup in sorted({n for n in names if names.count(n) > 1}):
            c.err(where(v, "managers"), f"{key}.managers", f"manager name '{dup}' used twice")
    end = c.get(v, "end_manager", key, str, "NAVIGATOR")
    if managers and end not in [m.name for m in managers]:
        c.err(where(v, "end_manager") if "end_manager" in v else where(v, "managers"),
              f"{key}.end_manager", f"no manager named '{end}' (its status ends the mission)")
    nav = _nav(c, v, key)
    if not vid or cfg is None or not managers:
        return None
    return Vehicle(vid, host, cfg, overrides, managers, end, pos, nav)


def _time(c: _Checker, t: Any, pos: str, hosts: list[str]) -> TimeSettings:
    t = c.mapping(t, pos, "time", ("mode", "warp", "step", "limit", "wall_limit", "host", "source"))
    ts = TimeSettings(host=hosts[0])
    ts.mode = c.get(t, "mode", "time", str, ts.mode, lambda v: "" if v in TIME_MODES else
                    f"expected one of: {', '.join(TIME_MODES)}")
    ts.warp = c.get(t, "warp", "time", float, ts.warp, _positive)
    ts.step_s = c.get(t, "step", "time", float, ts.step_s, _positive)
    ts.limit_s = c.get(t, "limit", "time", float, ts.limit_s, _positive)
    ts.wall_limit_s = c.get(t, "wall_limit", "time", float, ts.wall_limit_s, _nonneg)
    ts.host = c.get(t, "host", "time", str, ts.host, lambda h: "" if h in hosts else f"unknown host '{h}'")
    ts.source = c.get(t, "source", "time", str, ts.source, lambda v: "" if v in CLOCK_SOURCES else
                      f"expected one of: {', '.join(CLOCK_SOURCES)}")
    return ts


TOP_KEYS = ("name", "seed", "lcm_url", "world", "time", "logging", "hosts", "vehicles", "survey")


def load_scenario(path: str | Path, base: Path | None = None) -> Scenario:
    """Read and check a scenario; YamlError lists every problem."""
    path = Path(path).resolve()
    c = _Checker(path, base)
    doc = load(path)
    doc = c.mapping(doc, f"{path}:1:1", "", TOP_KEYS, required=("vehicles",))
    hosts_raw = doc.get("hosts", [DEFAULT_HOST])
    if not isinstance(hosts_raw, list) or not hosts_raw or not all(
            isinstance(h, str) and HOST_NAME.fullmatch(h) for h in hosts_raw):
        c.err(where(doc, "hosts"), "hosts", "expected a list of host names (letters, digits, _.-)")
        hosts_raw = [DEFAULT_HOST]
    hosts = list(hosts_raw)
    world = c.mapping(doc.get("world"), where(doc, "world"), "world", tuple(doc.get("world") or ()))
    time = _time(c, doc.get("time"), where(doc, "time"), hosts)
    lg = c.mapping(doc.get("logging"), where(doc, "logging"), "logging", ("enabled", "file", "host"))
    vehicles = []
    vraw = doc.get("vehicles")
    if not isinstance(vraw, MList) or not vraw:
        if "vehicles" in doc:
            c.err(where(doc, "vehicles"), "vehicles", "expected a non-empty list of vehicles")
    else:
        for i, v in enumerate(vraw):
            veh = _vehicle(c, v, where(vraw, i), f"vehicles[{i}]", hosts)
            if veh is not None:
                vehicles.append(veh)
        ids = [v.id for v in vehicles]
        for dup in sorted({i for i in ids if ids.count(i) > 1}):
            c.err(where(doc, "vehicles"), "vehicles", f"vehicle id '{dup}' used twice")
    sc = Scenario(
        path=path,
        name=c.get(doc, "name", "", str, path.stem),
        seed=c.get(doc, "seed", "", int, 1),
        lcm_url=c.get(doc, "lcm_url", "", str, ""),
        world=world, time=time,
        log_enabled=c.get(lg, "enabled", "logging", bool, True),
        log_file=c.get(lg, "file", "logging", str, "run.lcmlog"),
        log_host=c.get(lg, "host", "logging", str, hosts[0]),
        hosts=hosts, vehicles=vehicles, text=path.read_text(), survey=c.file(doc, "survey", "survey"))
    if sc.log_host not in hosts:
        c.err(where(lg, "host"), "logging.host", f"unknown host '{sc.log_host}'")
    if c.errors:
        raise YamlError(c.errors)
    return sc
