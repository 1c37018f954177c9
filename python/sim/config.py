"""The simulator configuration file: YAML, checked key by key.

Every error names the file, line and column, and the full key, and all errors
are reported at once (a user fixing a config should not have to run the
simulator once per typo). Unknown keys are errors with a "did you mean"
hint, because a misspelt key that is silently ignored is a silent default.

Line numbers come from PyYAML's composed node tree (yaml.compose), which
keeps the position of every key and value.
"""

from __future__ import annotations

import dataclasses
import difflib
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from sim.actuators import Command
from sim.bathymetry import SHAPES, Bathymetry, BathymetryError, make_ref
from sim.environment import CurrentLayer, EnvParams, Transponder
from sim.sensors import REGISTRY
from sim.sonar.config import SonarConfig
from sim.vehicle import REMUS100, VehicleParams

ENV_VARIABLES = ("current", "waves", "bathymetry", "sound_speed", "lbl")
CLOCK_MODES = ("realtime", "scaled", "stepped")
VEHICLE_ID = re.compile(r"[A-Z][A-Z0-9]{0,15}")
CHANNEL_SUFFIX = re.compile(r"[A-Z][A-Z0-9_]{0,31}")
# <VEHICLE>.<topic> channels the simulator writes or reads besides the INS's
RESERVED_TOPICS = {"AHRS", "DEPTH", "DVL", "ALTIMETER", "GPS", "LBL", "TRUTH", "ACTUATOR_STATE",
                   "ACTUATORS", "HEALTH", "CONTACTS", "SETPOINT"}


class ConfigError(Exception):
    def __init__(self, errors: list[str]) -> None:
        super().__init__("\n".join(errors))
        self.errors = errors


@dataclass
class SimSettings:
    physics_rate_hz: float = 50.0
    clock: str = "realtime"          # realtime | scaled | stepped
    warp: float = 1.0                # sim seconds per wall second (scaled)
    publish_clock: str = "auto"      # auto (not in stepped mode) | yes | no
    clock_rate_hz: float = 10.0      # SIM.CLOCK rate when this process publishes it
    truth_rate_hz: float = 10.0
    actuator_state_rate_hz: float = 10.0
    health_period_s: float = 1.0     # sim seconds between process_health_t
    command_timeout_s: float = 1.0
    on_stale: str = "hold"           # hold | safe
    duration_s: float = 0.0          # 0 = until stopped
    seed: int = -1                   # sensor seed; -1 = the environment's seed
    lcm_url: str = ""                # "" = $LCM_DEFAULT_URL or the project default
    publish_thread: bool = True      # messages go out from a sender thread (auvlcm.sender)


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
    client_id: str = ""              # "" = "<vehicle>-sim"
    priority: int = 0                # higher wins the env-server role on failover
    needs: list = field(default_factory=lambda: list(ENV_VARIABLES))
    sample_rate_hz: float = 1.0
    # the rest is docs/multihil.md: joining a world shared by several simulators
    enabled: bool = False            # join a multi-HIL world (server or client)
    step_s: float = 0.1              # lockstep step (simulation.clock: stepped)
    lockstep_participants: int = 0   # wait for this many participants before step 0
    lockstep_timeout_s: float = 5.0  # drop a participant silent this long
    heartbeat_hz: float = 10.0
    failover_timeout_s: float = 0.5
    join_window_s: float = 1.0
    sync_hz: float = 10.0
    clock_offset_us: float = 0.0     # tests: inject an offset into this process's clock
    clock_drift_ppm: float = 0.0     # tests: inject a drift into this process's clock


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
    sonar: SonarConfig | None = None     # None: no sonar section
    modem: Any = None                # sim.modem.ModemConfig, None without a modem: section


# ------------------------------------------------------------------ reading
class _Doc:
    """A composed YAML tree with its positions, and the errors found so far."""

    def __init__(self, path: Path, text: str) -> None:
        self.path = path
        self.errors: list[str] = []
        try:
            self.root = yaml.compose(text, Loader=yaml.SafeLoader)
        except yaml.MarkedYAMLError as exc:
            mark = exc.problem_mark or exc.context_mark
            where = f"{path}:{mark.line + 1}:{mark.column + 1}" if mark else str(path)
            raise ConfigError([f"{where}: YAML syntax: {exc.problem or exc}"]) from None

    def err(self, node, key: str, msg: str) -> None:
        m = node.start_mark if node is not None else None
        where = f"{self.path}:{m.line + 1}:{m.column + 1}" if m else f"{self.path}"
        self.errors.append(f"{where}: {key}: {msg}" if key else f"{where}: {msg}")

    def scalar(self, node) -> Any:
        return yaml.SafeLoader(  # a constructor for one node: bool, int, float, str, null
            "").construct_object(node, deep=True)

    def mapping(self, node, key: str) -> dict[str, tuple[Any, Any]]:
        """{name: (key node, value node)} of a mapping, reporting duplicates."""
        if node is None:
            return {}
        if not isinstance(node, yaml.MappingNode):
            if isinstance(node, yaml.ScalarNode) and node.value in ("", "~", "null"):
                return {}
            self.err(node, key, "expected a mapping of keys")
            return {}
        out: dict[str, tuple[Any, Any]] = {}
        for k, v in node.value:
            name = str(k.value)
            if name in out:
                self.err(k, _join(key, name), f"duplicate key (first at line "
                         f"{out[name][0].start_mark.line + 1})")
            out[name] = (k, v)
        return out

    def unknown(self, items: dict, allowed, key: str) -> None:
        for name, (knode, _) in items.items():
            if name not in allowed:
                hint = difflib.get_close_matches(name, list(allowed), n=1)
                extra = f"; did you mean '{hint[0]}'?" if hint else (
                    f"; expected one of: {', '.join(sorted(allowed))}")
                self.err(knode, _join(key, name), f"unknown key{extra}")


def _join(a: str, b: str) -> str:
    return f"{a}.{b}" if a else b


def _typename(t) -> str:
    return {bool: "true/false", int: "an integer", float: "a number", str: "a string",
            list: "a list"}.get(t, t.__name__)


_NONNEG = re.compile(r"(noise|sigma|random_walk|bias_sigma|probability|dropout|max_|_max|"
                     r"timeout|period|duration|radius|height|time_constant|turnaround|rate_radps"
                     r"|scale_error_abs|outlier)")


def _check_value(doc: _Doc, node, key: str, name: str, default: Any) -> Any:
    """Convert one scalar to the type of the field's default, with range rules."""
    want = type(default)
    if want is list:
        if not isinstance(node, yaml.SequenceNode):
            doc.err(node, key, "expected a list")
            return dataclasses.MISSING
        return [doc.scalar(n) for n in node.value]
    if not isinstance(node, yaml.ScalarNode):
        doc.err(node, key, f"expected {_typename(want)}")
        return dataclasses.MISSING
    value = doc.scalar(node)
    if want is str and isinstance(value, bool):
        value = node.value      # YAML 1.1 reads yes/no/on/off as booleans: keep the word
    if name == "channel":
        return _check_channel(doc, node, key, value)
    if want is float and isinstance(value, int) and not isinstance(value, bool):
        value = float(value)
    if type(value) is not want:
        doc.err(node, key, f"expected {_typename(want)}, got {node.value!r}")
        return dataclasses.MISSING
    if want in (int, float):
        if value != value or value in (float("inf"), float("-inf")):
            doc.err(node, key, "must be finite")
            return dataclasses.MISSING
        if name.endswith("_hz") and value <= 0:
            doc.err(node, key, "must be > 0 [Hz]")
        elif name in ("dropout", "outlier_probability") and not 0.0 <= value < 1.0:
            doc.err(node, key, "must be a probability in [0, 1)")
        elif _NONNEG.search(name) and name not in ("bias", "prop_nominal_torque_nm") and value < 0:
            doc.err(node, key, "must be >= 0")
    return value


def _check_channel(doc: _Doc, node, key: str, value: Any) -> Any:
    """A channel suffix such as NAV or NAV_INS, or off."""
    if value == "off":
        return "off"
    if not isinstance(value, str) or not CHANNEL_SUFFIX.fullmatch(value):
        doc.err(node, key, f"expected a channel name (upper-case letters, digits, '_', e.g. "
                f"NAV or NAV_INS) or off, got {node.value!r}")
        return dataclasses.MISSING
    return value


def _fill(doc: _Doc, node, key: str, obj) -> Any:
    """Update a dataclass instance from a mapping node, field by field."""
    items = doc.mapping(node, key)
    names = {f.name: f for f in dataclasses.fields(obj)}
    doc.unknown(items, names, key)
    for name, (_, vnode) in items.items():
        if name not in names:
            continue
        if dataclasses.is_dataclass(getattr(obj, name)):     # a nested section
            _fill(doc, vnode, _join(key, name), getattr(obj, name))
            continue
        v = _check_value(doc, vnode, _join(key, name), name, getattr(obj, name))
        if v is not dataclasses.MISSING:
            setattr(obj, name, v)
    return obj


def _position(msg: str) -> tuple[int, int]:
    m = re.match(r".*?:(\d+):(\d+): ", msg)
    return (int(m.group(1)), int(m.group(2))) if m else (0, 0)


# --------------------------------------------------------------- sections
def _vehicle(doc: _Doc, node) -> tuple[str, VehicleParams]:
    items = doc.mapping(node, "vehicle")
    vid = "AUV1"
    if "id" in items:
        knode, vnode = items.pop("id")
        vid = str(doc.scalar(vnode)) if isinstance(vnode, yaml.ScalarNode) else ""
        if not VEHICLE_ID.fullmatch(vid):
            doc.err(vnode, "vehicle.id", "must be upper-case letters and digits, starting "
                    "with a letter, at most 16 characters (it starts every channel name)")
    if "model" in items:
        _, mnode = items.pop("model")
        if doc.scalar(mnode) != "remus100":
            doc.err(mnode, "vehicle.model", "the built-in model is 'remus100'; describe "
                    "another vehicle by overriding its parameters in this section")
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
            if (not isinstance(vnode, yaml.SequenceNode) or len(vnode.value) != 3):
                doc.err(vnode, f"vehicle.{name}", "expected a list of 3 numbers")
                continue
            vals = [doc.scalar(n) for n in vnode.value]
            if not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in vals):
                doc.err(vnode, f"vehicle.{name}", "expected a list of 3 numbers")
                continue
            updates[name] = tuple(float(v) for v in vals)
        else:
            v = _check_value(doc, vnode, f"vehicle.{name}", name, default)
            if v is not dataclasses.MISSING:
                updates[name] = v
    hydro = {}
    for name, (_, vnode) in hydro_items.items():
        if name in vp.hydro:
            v = _check_value(doc, vnode, f"vehicle.hydro.{name}", name, 0.0)
            if v is not dataclasses.MISSING:
                hydro[name] = v
    for name in ("mass_kg", "buoyancy_n", "length_m", "diameter_m"):
        if name in updates and updates[name] <= 0:
            doc.err(items[name][1], f"vehicle.{name}", "must be > 0")
    if hydro:
        updates["hydro"] = hydro
    return vid, vp.with_updates(updates)


def _list_of(doc: _Doc, node, key: str, make) -> list:
    if node is None:
        return []
    if not isinstance(node, yaml.SequenceNode):
        doc.err(node, key, "expected a list")
        return []
    return [_fill(doc, n, f"{key}[{i}]", make()) for i, n in enumerate(node.value)]


def _environment(doc: _Doc, node, base: Path) -> EnvParams:
    items = doc.mapping(node, "environment")
    env = EnvParams()
    special = {"current", "waves", "bathymetry", "transponders"}
    plain_fields = {f.name for f in dataclasses.fields(env)} - special - {"bathymetry_ref"} | {
        "wave_height_m", "wave_period_s", "wave_direction_rad"}
    doc.unknown(items, plain_fields | special, "environment")
    for name, (_, vnode) in items.items():
        if name in plain_fields:
            v = _check_value(doc, vnode, f"environment.{name}", name, getattr(env, name))
            if v is not dataclasses.MISSING:
                setattr(env, name, v)
    if "current" in items:
        env.current = _list_of(doc, items["current"][1], "environment.current",
                               lambda: CurrentLayer(0.0, 0.0, 0.0, 0.0))
    if "transponders" in items:
        env.transponders = _list_of(doc, items["transponders"][1], "environment.transponders",
                                    lambda: Transponder(0, 0.0, 0.0, 0.0, 0.0))
        seen: set[int] = set()
        for i, tr in enumerate(env.transponders):
            if tr.id in seen:
                doc.err(items["transponders"][1].value[i], f"environment.transponders[{i}].id",
                        f"duplicate transponder id {tr.id}")
            seen.add(tr.id)
    if "waves" in items:
        wnode = items["waves"][1]
        w = doc.mapping(wnode, "environment.waves")
        doc.unknown(w, {"height_m", "period_s", "direction_rad"}, "environment.waves")
        for name, attr in (("height_m", "wave_height_m"), ("period_s", "wave_period_s"),
                           ("direction_rad", "wave_direction_rad")):
            if name in w:
                v = _check_value(doc, w[name][1], f"environment.waves.{name}",
                                 name.replace("_m", "") if name == "height_m" else name, 0.0)
                if v is not dataclasses.MISSING:
                    setattr(env, attr, v)
    if "bathymetry" in items:
        bnode = items["bathymetry"][1]
        key = "environment.bathymetry"
        ref = None
        if isinstance(bnode, yaml.ScalarNode):
            ref = str(doc.scalar(bnode))
        else:
            b = doc.mapping(bnode, key)
            if "grid" in b:
                doc.unknown(b, {"grid"}, key)
                ref = f"grid:{doc.scalar(b['grid'][1])}"
            elif "shape" in b:
                shape = str(doc.scalar(b["shape"][1]))
                if shape not in SHAPES:
                    doc.err(b["shape"][1], f"{key}.shape",
                            f"unknown shape {shape!r}; one of {', '.join(sorted(SHAPES))}")
                else:
                    doc.unknown(b, SHAPES[shape] | {"shape"}, key)
                    params = {}
                    for name in SHAPES[shape]:
                        if name in b:
                            v = _check_value(doc, b[name][1], f"{key}.{name}", name, 0.0)
                            if v is not dataclasses.MISSING:
                                params[name] = v
                    if "depth" not in params:
                        doc.err(bnode, key, f"shape {shape!r} needs 'depth'")
                    else:
                        ref = make_ref(shape, params)
            else:
                doc.err(bnode, key, "expected 'shape: ...' with its parameters, "
                        "'grid: FILE.npz', or a reference string like 'flat:depth=40'")
        if ref is not None:
            try:
                Bathymetry(ref, base)
                env.bathymetry_ref = ref
            except BathymetryError as exc:
                doc.err(bnode, key, str(exc))
    if env.sound_speed_mps <= 0 and "sound_speed_mps" in items:
        doc.err(items["sound_speed_mps"][1], "environment.sound_speed_mps", "must be > 0")
    return env


def _sensors(doc: _Doc, node) -> dict[str, Any]:
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
                cfg = _fill(doc, snode, f"sensors.{name}", cfg_cls())
            out[name] = cfg
    ins = out.get("ins")
    if ins is not None and ins.channel in RESERVED_TOPICS:
        cnode = doc.mapping(items["ins"][1], "sensors.ins")["channel"][1]
        doc.err(cnode, "sensors.ins.channel", f"{ins.channel} is another channel of this "
                "vehicle's simulator or pilot (one writer per channel)")
    return out


def load(path: str | Path) -> SimConfig:
    """Read and check a configuration; raise ConfigError listing every problem."""
    path = Path(path)
    try:
        text = path.read_text()
    except OSError as exc:
        raise ConfigError([f"{path}: cannot read ({exc.strerror})"]) from None
    return loads(text, path)


def load_or_report(path: str | Path) -> SimConfig | None:
    """load(), for command-line tools: every problem printed to stderr, then
    a count; None if there was any."""
    try:
        return load(path)
    except ConfigError as exc:
        for line in exc.errors:
            print(line, file=sys.stderr)
        print(f"{path}: {len(exc.errors)} error(s)", file=sys.stderr)
        return None


def loads(text: str, path: Path = Path("<config>")) -> SimConfig:
    doc = _Doc(path, text)
    top = doc.mapping(doc.root, "")
    sections = ("vehicle", "simulation", "initial", "environment", "sensors", "multihil",
                "safe_command", "sonar", "modem")
    doc.unknown(top, sections, "")
    get = lambda name: top[name][1] if name in top else None  # noqa: E731
    vid, vp = _vehicle(doc, get("vehicle"))
    sim = _fill(doc, get("simulation"), "simulation", SimSettings())
    if "simulation" in top:
        s = doc.mapping(get("simulation"), "simulation")
        if sim.clock not in CLOCK_MODES:
            doc.err(s["clock"][1], "simulation.clock", f"one of {', '.join(CLOCK_MODES)}")
        if sim.on_stale not in ("hold", "safe"):
            doc.err(s["on_stale"][1], "simulation.on_stale", "one of hold, safe")
        if sim.publish_clock not in ("auto", "yes", "no"):
            doc.err(s["publish_clock"][1], "simulation.publish_clock", "one of auto, yes, no")
        if sim.warp <= 0 and "warp" in s:
            doc.err(s["warp"][1], "simulation.warp", "must be > 0")
        if sim.physics_rate_hz < 50 and "physics_rate_hz" in s:
            doc.err(s["physics_rate_hz"][1], "simulation.physics_rate_hz",
                    "must be at least 50 Hz (the integrator is validated from 50 Hz up)")
    initial = _fill(doc, get("initial"), "initial", InitialState())
    env = _environment(doc, get("environment"), path.parent)
    sensors = _sensors(doc, get("sensors"))
    mh = _fill(doc, get("multihil"), "multihil", MultiHil())
    if "multihil" in top:
        m = doc.mapping(get("multihil"), "multihil")
        if "needs" in m:
            for i, v in enumerate(mh.needs):
                if v not in ENV_VARIABLES:
                    doc.err(m["needs"][1].value[i], f"multihil.needs[{i}]",
                            f"unknown environment variable {v!r}; one of {', '.join(ENV_VARIABLES)}")
    safe = _fill(doc, get("safe_command"), "safe_command", Command())
    sonar = None
    if "sonar" in top:
        from sim.sonar.config_check import check_sonar
        sonar = check_sonar(doc, get("sonar"), path.parent, _fill)
    from sim.modem.config import parse as parse_modem
    modem = parse_modem(doc, get("modem"))
    if doc.errors:
        raise ConfigError(sorted(dict.fromkeys(doc.errors), key=_position))
    if sim.seed < 0:
        sim.seed = env.seed
    if sonar is not None and sonar.targets.seed < 0:
        sonar.targets.seed = env.seed    # one world, one field: every vehicle's sim agrees
    if not mh.client_id:
        mh.client_id = f"{vid}-sim"
    if modem is not None and modem.seed < 0:
        modem.seed = env.seed        # the world's: the same for every simulator in it
    return SimConfig(path, vid, vp, sim, initial, env, sensors, mh, safe, sonar=sonar, modem=modem)
