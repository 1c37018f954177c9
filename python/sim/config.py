"""The simulator configuration file: YAML, checked key by key.

Read and checked by confcheck, like every configuration: every error names
the file, line and column, and the full key, and all errors are reported at
once; unknown keys are errors with a "did you mean" hint (a misspelt key that
is silently ignored is a silent default). Ranges and choices are declared on
the dataclass fields (confcheck.setting): a new setting is one line.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

from confcheck import VEHICLE_ID, Checker, ConfigError, Rule, report, rule_of, setting, vehicle_id_problem
from sim import clock_modes
from sim.actuators import Command
from sim.bathymetry import SHAPES, Bathymetry, BathymetryError, make_ref
from sim.devices.config import INPUT_DEVICE_KEYS, check_distinct, parse_wire
from sim.devices.maestro import ChannelTable, TableError, parse_table
from sim.environment import ENV_VARIABLES, CurrentLayer, EnvParams, Transponder
from sim.sensors import FITTED_UNLESS_LISTED, REGISTRY
from sim.sonar.config import SonarConfig
from sim.vehicle import REMUS100, VehicleParams

__all__ = [
    "ConfigError",
    "ENV_VARIABLES",
    "RESERVED_TOPICS",
    "SimConfig",
    "VEHICLE_ID",
    "load",
    "load_or_report",
    "loads",
]

# <VEHICLE>.<topic> channels the simulator writes or reads besides the INS's:
# its own, and every registered sensor's (sim.sensors.SENSORS)
SIM_TOPICS = {"TRUTH", "ACTUATOR_STATE", "ACTUATORS", "HEALTH", "CONTACTS", "SETPOINT"}
RESERVED_TOPICS = SIM_TOPICS | {cls.topic for name, (_, cls) in REGISTRY.items() if name != "ins"}


@dataclass
class SimSettings:
    # the integrator is validated from 50 Hz up; above 10 kHz a second of sim time costs minutes
    physics_rate_hz: float = setting(50.0, ge=50.0, le=10000.0, unit="Hz")
    clock: str = setting(clock_modes.REALTIME, one_of=clock_modes.MODES, old_names=clock_modes.OLD_NAMES)
    warp: float = setting(1.0, gt=0.0)  # sim seconds per wall second (scaled)
    publish_clock: str = setting("auto", one_of=("auto", "yes", "no"))  # auto: not in lockstep
    clock_rate_hz: float = setting(10.0, gt=0.0, unit="Hz")  # SIM.CLOCK rate when this process publishes it
    truth_rate_hz: float = setting(10.0, gt=0.0, unit="Hz")
    actuator_state_rate_hz: float = setting(10.0, gt=0.0, unit="Hz")
    health_period_s: float = setting(1.0, ge=0.0)  # sim seconds between process_health_t
    command_timeout_s: float = setting(1.0, ge=0.0)
    on_stale: str = setting("hold", one_of=("hold", "safe"))
    duration_s: float = setting(0.0, ge=0.0)  # 0 = until stopped
    seed: int = setting(-1, ge=-1)  # sensor seed; -1 = the environment's seed
    lcm_url: str = ""  # "" = $LCM_DEFAULT_URL or the project default
    publish_thread: bool = False  # messages go out from a sender thread (auvlcm.sender)


@dataclass
class InitialState:
    north_m: float = 0.0
    east_m: float = 0.0
    depth_m: float = 0.0
    roll_rad: float = 0.0
    pitch_rad: float = 0.0
    heading_rad: float = 0.0
    speed_mps: float = 0.0
    prop_rpm: float = 0.0


@dataclass
class MultiHil:
    client_id: str = ""  # "" = "<vehicle>-sim"
    priority: int = 0  # higher wins the env-server role on failover
    needs: list = setting(factory=lambda: list(ENV_VARIABLES), one_of=ENV_VARIABLES)
    sample_rate_hz: float = setting(1.0, gt=0.0, unit="Hz")
    # the rest is docs/multihil.md: joining a world shared by several simulators
    enabled: bool = False  # join a multi-HIL world (server or client)
    step_s: float = setting(0.1, gt=0.0)  # lockstep step (simulation.clock: lockstep)
    lockstep_participants: int = setting(0, ge=0)  # wait for this many participants before step 0
    # ... and for each of these by name (the launcher lists the world's: tools/launch/lockstep_names.py)
    lockstep_names: list = setting(
        factory=list,
        pattern=r"[A-Za-z0-9_.-]{1,95}",
        pattern_hint="a participant name such as AUV1.sim or SIM.RECORDER",
    )
    lockstep_timeout_s: float = setting(5.0, ge=0.0)  # drop a participant silent this long
    heartbeat_hz: float = setting(10.0, gt=0.0, unit="Hz")
    failover_timeout_s: float = setting(0.5, ge=0.0)
    join_window_s: float = setting(1.0, ge=0.0)
    sync_hz: float = setting(10.0, gt=0.0, unit="Hz")
    clock_offset_us: float = 0.0  # tests: inject an offset into this process's clock
    clock_drift_ppm: float = 0.0  # tests: inject a drift into this process's clock


@dataclass
class ActuatorsConfig:
    """`actuators:`: the fins and thruster at the wire (docs/simulator.md, "Fins and
    thruster at the wire"); the actuators' figures are the vehicle's (vehicle:)."""

    wire: Any = None  # sim.devices.config.WireConfig, None: commands on <V>.ACTUATORS


@dataclass
class Actuators:
    """The `actuators:` section, and the channel table its wire names, read."""

    wire: Any = None  # sim.devices.config.WireConfig; None: commands on <V>.ACTUATORS
    table: ChannelTable | None = None


@dataclass
class SimConfig:
    path: Path
    vehicle_id: str
    vehicle: VehicleParams
    sim: SimSettings
    initial: InitialState
    env: EnvParams
    sensors: dict[str, Any]
    multihil: MultiHil
    safe_command: Command
    sonar: SonarConfig | None = None  # None: no sonar section
    modem: Any = None  # sim.modem.ModemConfig, None without a modem: section
    identify: Any = None  # sim.sonar.identify.IdentifyConfig, None without identify:
    actuators: Actuators = dataclasses.field(default_factory=Actuators)
    time_link: Any = None  # sim.time_link.TimeLinkConfig, None without time_link:
    frontseat: Any = None  # sim.frontseat.FrontseatConfig, None without frontseat:


# --------------------------------------------------------------- sections
def _vehicle(doc: Checker, node) -> tuple[str, VehicleParams]:
    items = doc.mapping(node, "vehicle")
    vid = "AUV1"
    if "id" in items:
        _, vnode = items.pop("id")
        vid = str(doc.scalar(vnode)) if isinstance(vnode, yaml.ScalarNode) else ""
        problem = vehicle_id_problem(vid)
        if problem:
            doc.err(vnode, "vehicle.id", problem)
    if "model" in items:
        _, mnode = items.pop("model")
        if doc.scalar(mnode) != "remus100":
            doc.err(
                mnode,
                "vehicle.model",
                "the built-in model is 'remus100'; describe "
                "another vehicle by overriding its parameters in this section",
            )
    vp = REMUS100.with_updates({})
    hydro_items = {}
    if "hydro" in items:
        _, hnode = items.pop("hydro")
        hydro_items = doc.mapping(hnode, "vehicle.hydro")
        doc.unknown(hydro_items, vp.hydro, "vehicle.hydro")
    fields = {f.name: f for f in dataclasses.fields(vp) if f.name != "hydro"}
    doc.unknown(items, set(fields) | {"id", "model", "hydro"}, "vehicle")
    updates: dict[str, Any] = {}
    for name, (_, vnode) in items.items():
        if name not in fields:
            continue
        default = getattr(vp, name)
        if isinstance(default, tuple):
            vals = [doc.scalar(n) for n in doc.sequence(vnode, f"vehicle.{name}")]
            if len(vals) != 3 or not all(
                isinstance(v, (int, float)) and not isinstance(v, bool) and v == v and abs(v) != float("inf")
                for v in vals
            ):
                doc.err(vnode, f"vehicle.{name}", "expected a list of 3 finite numbers")
                continue
            updates[name] = tuple(float(v) for v in vals)
        else:
            v = doc.value(vnode, f"vehicle.{name}", default, rule_of(VehicleParams, name))
            if v is not dataclasses.MISSING:
                updates[name] = v
    hydro = {}
    for name, (_, vnode) in hydro_items.items():
        if name in vp.hydro:
            v = doc.value(vnode, f"vehicle.hydro.{name}", 0.0)
            if v is not dataclasses.MISSING:
                hydro[name] = v
    if hydro:
        updates["hydro"] = hydro
    return vid, vp.with_updates(updates)


def _list_of(doc: Checker, node, key: str, make) -> list:
    return [doc.fill(n, f"{key}[{i}]", make()) for i, n in enumerate(doc.sequence(node, key))]


def _bathymetry(doc: Checker, bnode, base: Path) -> str | None:
    key = "environment.bathymetry"
    ref = None
    if isinstance(bnode, yaml.ScalarNode):
        ref = doc.value(bnode, key, "")
        ref = None if ref is dataclasses.MISSING else ref
    else:
        b = doc.mapping(bnode, key)
        if "grid" in b:
            doc.unknown(b, {"grid"}, key)
            grid = doc.value(b["grid"][1], f"{key}.grid", "")
            ref = None if grid is dataclasses.MISSING else f"grid:{grid}"
        elif "shape" in b:
            shape = doc.value(b["shape"][1], f"{key}.shape", "", Rule(one_of=tuple(sorted(SHAPES))))
            if shape is not dataclasses.MISSING:
                doc.unknown(b, SHAPES[shape] | {"shape"}, key)
                params = {}
                for name in SHAPES[shape]:
                    if name in b:
                        v = doc.value(b[name][1], f"{key}.{name}", 0.0)
                        if v is not dataclasses.MISSING:
                            params[name] = v
                if "depth" not in params:
                    doc.err(bnode, key, f"shape {shape!r} needs 'depth'")
                else:
                    ref = make_ref(shape, params)
        else:
            doc.err(
                bnode,
                key,
                "expected 'shape: ...' with its parameters, "
                "'grid: FILE.npz', or a reference string like 'flat:depth=40'",
            )
    if ref is not None:
        try:
            Bathymetry(ref, base)
            return ref
        except (BathymetryError, ValueError, OSError) as exc:  # a bad grid file included
            doc.err(bnode, key, str(exc).replace("\n", " "))
    return None


def _waves(doc: Checker, wnode, env: EnvParams) -> None:
    w = doc.mapping(wnode, "environment.waves")
    doc.unknown(w, {"height_m", "period_s", "direction_rad"}, "environment.waves")
    for name, attr in (
        ("height_m", "wave_height_m"),
        ("period_s", "wave_period_s"),
        ("direction_rad", "wave_direction_rad"),
    ):
        if name in w:
            v = doc.value(w[name][1], f"environment.waves.{name}", 0.0, rule_of(EnvParams, attr))
            if v is not dataclasses.MISSING:
                setattr(env, attr, v)


def _environment(doc: Checker, node, base: Path, initial: InitialState, duration_s: float) -> EnvParams:
    env = EnvParams()
    items = doc.mapping(node, "environment")
    special = {
        "current": lambda n, k: _list_of(doc, n, k, lambda: CurrentLayer(0.0, 0.0, 0.0, 0.0)),
        "transponders": lambda n, k: _list_of(doc, n, k, lambda: Transponder(0, 0.0, 0.0, 0.0, 0.0)),
    }
    doc.fill(node, "environment", env, skip=("waves", "bathymetry", "bathymetry_ref", "ocean"), special=special)
    if "bathymetry_ref" in items:
        doc.unknown({"bathymetry_ref": items["bathymetry_ref"]}, [], "environment")
    seen: set[int] = set()
    for i, tr in enumerate(env.transponders):
        if tr.id in seen:
            doc.err(
                items["transponders"][1].value[i],
                f"environment.transponders[{i}].id",
                f"duplicate transponder id {tr.id}",
            )
        seen.add(tr.id)
    if "waves" in items:
        _waves(doc, items["waves"][1], env)
    if "bathymetry" in items:
        ref = _bathymetry(doc, items["bathymetry"][1], base)
        if ref is not None:
            env.bathymetry_ref = ref
    if "ocean" in items:
        from sim.ocean.config import check_ocean

        start = (initial.north_m, initial.east_m, initial.depth_m)
        env.ocean = check_ocean(
            doc,
            items["ocean"][1],
            base,
            env.origin_latitude_deg,
            env.origin_longitude_deg,
            start,
            env.transponders,
            duration_s,
        )
    return env


def _sensors(doc: Checker, node, base: Path, wires: dict[str, tuple[Any, Any]]) -> dict[str, Any]:
    """The sensors; each enabled one's wire goes into wires (its key: its wire node and config)."""
    items = doc.mapping(node, "sensors")
    doc.unknown(items, REGISTRY, "sensors")
    out = {}
    for name, (_, snode) in items.items():
        if name in REGISTRY:
            cfg_cls, _ = REGISTRY[name]
            if isinstance(snode, yaml.ScalarNode) and doc.scalar(snode) is False:
                cfg = cfg_cls()
                cfg.enabled = False
            else:
                key = f"sensors.{name}"
                wire = {"wire": lambda n, k, name=name: parse_wire(doc, n, k, name, base)}
                cfg = doc.fill(snode, key, cfg_cls(), special=wire)
                if cfg.wire is not None and cfg.enabled:
                    wires[key] = (doc.mapping(snode, key)["wire"][1], cfg.wire)
            out[name] = cfg
    ins = out.get("ins")
    if ins is not None and ins.channel in RESERVED_TOPICS:
        cnode = doc.mapping(items["ins"][1], "sensors.ins")["channel"][1]
        doc.err(
            cnode,
            "sensors.ins.channel",
            f"{ins.channel} is another channel of this vehicle's simulator or pilot (one writer per channel)",
        )
    return out


def _actuators(doc: Checker, node, base: Path, wires: dict) -> Actuators:
    """`actuators: {wire: {protocol: maestro, ..., table: FILE}}`: the wire, and its
    channel table read with the rules auv-servo reads it by (its errors at the table's
    own file:line:col, under the key that names it)."""
    key = "actuators"
    wire = {"wire": lambda n, k: parse_wire(doc, n, k, key, base, common=INPUT_DEVICE_KEYS)}
    keys = doc.fill(node, key, ActuatorsConfig(), special=wire)
    cfg = Actuators(keys.wire)
    if cfg.wire is None or cfg.wire is dataclasses.MISSING:
        cfg.wire = None
        return cfg
    wnode = doc.mapping(node, key)["wire"][1]
    tnode = doc.mapping(wnode, f"{key}.wire")["table"][1]
    opts = cfg.wire.options
    path = Path(opts.table) if Path(opts.table).is_absolute() else base / opts.table
    opts.table = str(path)
    try:
        cfg.table = parse_table(path.read_text(encoding="ascii", errors="replace"), str(path))
    except OSError as exc:
        doc.err(tnode, f"{key}.wire.table", f"cannot read the channel table {path}: {exc.strerror}")
        return cfg
    except TableError as exc:
        doc.err(tnode, f"{key}.wire.table", str(exc))
        return cfg
    beyond = [c.channel for c in cfg.table.channels if c.channel >= opts.channels]
    if beyond:
        doc.err(tnode, f"{key}.wire.table", f"channel {beyond[0]} is beyond a {opts.channels}-channel Maestro")
    wires[key] = (wnode, cfg.wire)
    return cfg


def _needs_served(doc: Checker, node, sensors: dict[str, Any], mh: MultiHil) -> None:
    """A listed multihil.needs asks the world for what every fitted sensor reads
    (Sensor.env_needs): a sensor is served the environment it needs."""
    items = doc.mapping(node, "multihil")
    if "needs" not in items:
        return  # the default asks for everything
    fitted = sensors or {name: REGISTRY[name][0]() for name in FITTED_UNLESS_LISTED}
    for name, scfg in fitted.items():
        missing = [v for v in REGISTRY[name][1].env_needs if v not in mh.needs]
        if scfg.enabled and missing:
            doc.err(
                items["needs"][1],
                "multihil.needs",
                f"sensors.{name} reads {', '.join(missing)} from the world: add {'them' if len(missing) > 1 else 'it'}",
            )


def load(path: str | Path) -> SimConfig:
    """Read and check a configuration; raise ConfigError listing every problem."""
    path = Path(path)
    return _check(Checker.from_file(path, extends=True), path)


def load_or_report(path: str | Path) -> SimConfig | None:
    """load(), for command-line tools: every problem printed to stderr, then
    a count; None if there was any."""
    try:
        return load(path)
    except ConfigError as exc:
        report(exc, str(path))
        return None


def loads(text: str, path: Path = Path("<config>")) -> SimConfig:
    return _check(Checker.from_text(text, path, extends=True), path)


SECTIONS = (
    "vehicle",
    "simulation",
    "initial",
    "environment",
    "sensors",
    "multihil",
    "safe_command",
    "sonar",
    "modem",
    "identify",
    "actuators",
    "time_link",
    "frontseat",
)


def _wire_of(doc: Checker, node, key: str, cfg, wires: dict[str, tuple[Any, Any]]) -> None:
    """A section's wire (sonar, identify, the time link) into wires, for check_distinct."""
    if cfg is not None and getattr(cfg, "wire", None) is not None:
        wires[key] = (doc.mapping(node, key)["wire"][1], cfg.wire)


def _check(doc: Checker, path: Path) -> SimConfig:
    top = doc.mapping(doc.root, "")
    if not isinstance(doc.root, yaml.MappingNode):
        doc.raise_errors()
    doc.unknown(top, SECTIONS, "")
    get = lambda name: top[name][1] if name in top else None  # noqa: E731
    vid, vp = _vehicle(doc, get("vehicle"))
    sim = doc.fill(get("simulation"), "simulation", SimSettings())
    initial = doc.fill(get("initial"), "initial", InitialState())
    env = _environment(doc, get("environment"), path.parent, initial, sim.duration_s)
    wires: dict[str, tuple[Any, Any]] = {}  # every port of the simulator: no two on one
    sensors = _sensors(doc, get("sensors"), path.parent, wires)
    actuators = _actuators(doc, get("actuators"), path.parent, wires)
    mh = doc.fill(get("multihil"), "multihil", MultiHil())
    _needs_served(doc, get("multihil"), sensors, mh)
    safe = doc.fill(get("safe_command"), "safe_command", Command())
    sonar = None
    if "sonar" in top:
        from sim.sonar.config_check import check_sonar

        sonar = check_sonar(doc, get("sonar"), path.parent)
        _wire_of(doc, get("sonar"), "sonar", sonar, wires)
    from sim.modem.config import parse as parse_modem

    modem = parse_modem(doc, get("modem"), path.parent)
    identify = None
    if "identify" in top:
        from sim.sonar.identify import check_identify

        identify = check_identify(doc, get("identify"), path.parent, "sonar" in top)
        _wire_of(doc, get("identify"), "identify", identify, wires)
    from sim.time_link import check_time_link

    time_link = check_time_link(doc, get("time_link"), path.parent)
    _wire_of(doc, get("time_link"), "time_link", time_link, wires)
    from sim.frontseat import check_frontseat

    frontseat = check_frontseat(doc, get("frontseat"), path.parent)
    _wire_of(doc, get("frontseat"), "frontseat", frontseat, wires)
    if frontseat is not None and actuators.wire is not None:
        doc.err(
            top["frontseat"][1],
            "frontseat",
            "the frontseat commands the fins and the propeller: no actuators.wire beside it",
        )
    check_distinct(doc, wires)
    doc.raise_errors()
    if sim.seed < 0:
        sim.seed = env.seed
    if sonar is not None and sonar.targets.seed < 0:
        sonar.targets.seed = env.seed  # one world, one field: every vehicle's sim agrees
    if not mh.client_id:
        mh.client_id = f"{vid}-sim"
    if modem is not None and modem.seed < 0:
        modem.seed = env.seed  # the world's: the same for every simulator in it
    if identify is not None and identify.targets.seed < 0:
        identify.targets.seed = env.seed  # the same field as the search vehicles' sonars
    return SimConfig(
        path,
        vid,
        vp,
        sim,
        initial,
        env,
        sensors,
        mh,
        safe,
        sonar=sonar,
        modem=modem,
        identify=identify,
        actuators=actuators,
        time_link=time_link,
        frontseat=frontseat,
    )
