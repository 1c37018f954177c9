"""Each vehicle's simulator configuration: its base file, the scenario's world
and the vehicle's overrides merged into one file in the run folder, checked by
the simulator's own loader with errors pointing back into the scenario."""

from __future__ import annotations

import re
from pathlib import Path

from confcheck import Checker, ConfigError
from confcheck.extends import locate
from confcheck.reader import dump_yaml
from tools.launch.fault_step import count_in
from tools.launch.lockstep_names import name_them
from tools.scenario.scenario_file import Scenario, Vehicle, position


def merge(base: dict, over: dict) -> dict:
    """base with over's keys replacing it, mappings merged recursively."""
    out = dict(base)
    for k, v in over.items():
        out[k] = merge(out[k], v) if isinstance(v, dict) and isinstance(out.get(k), dict) else v
    return out


def _absolute_grid(env: dict, base: Path) -> dict:
    """A bathymetry or ocean grid file named relative to its own YAML file, made
    absolute: the merged file lives in the run folder."""
    for section in ("bathymetry", "ocean"):
        sub = env.get(section)
        if isinstance(sub, dict) and isinstance(sub.get("grid"), str) and sub["grid"]:
            env = dict(env, **{section: dict(sub, grid=str((base / sub["grid"]).resolve()))})
    return env


def _base(v: Vehicle) -> dict:
    """The vehicle's base simulator configuration as plain data (read and
    checked for YAML limits like every file; its keys are checked after the merge)."""
    c = Checker.from_file(v.sim_config, extends=True)  # with the base it extends merged in
    data = c.plain(c.root)
    c.raise_errors()
    return data if isinstance(data, dict) else {}


def _has_sonar(v: Vehicle) -> bool:
    return "sonar" in _base(v) or "sonar" in v.sim_overrides


def _targets_publisher(sc: Scenario, v: Vehicle, cfg: dict) -> dict:
    """A stepped simulator's `auto` never publishes SIM.TARGETS, on the launcher's
    clock or in a multi-HIL world (its environment nodes do not publish the field
    either): left to `auto`, the first vehicle with a sonar publishes the target
    field, the others not (one writer per channel)."""
    if "sonar" not in cfg:
        return cfg
    if cfg["sonar"].get("publish_targets", "auto") not in ("auto", None):
        return cfg
    first = next(o for o in sc.vehicles if _has_sonar(o))
    return merge(cfg, {"sonar": {"publish_targets": "yes" if first is v else "no"}})


def backseat(cfg: dict) -> bool:
    """Whether a merged simulator configuration is a vehicle flown from its backseat
    (a `frontseat:` section: tools/launch/backseat.py)."""
    return cfg.get("frontseat") not in (None, False)


def _ins_out_of_the_way(v: Vehicle, cfg: dict) -> dict:
    """With the onboard filter (`nav: ekf`) auv-nav owns <ID>.NAV, on a backseat
    vehicle auv-frontseat (the frontseat's navigation): the simulated INS moves to
    <ID>.NAV_INS, kept in the log for comparison (one writer per channel). An
    absent `sensors` section means every sensor at its defaults and a present
    one only the sensors it names, so all are named first."""
    if v.nav.source != "ekf" and not backseat(cfg):
        return cfg
    from sim.sensors import FITTED_UNLESS_LISTED

    sensors = cfg.get("sensors") or {name: {} for name in FITTED_UNLESS_LISTED}
    ins = sensors.get("ins", False)
    if ins is False or (isinstance(ins, dict) and ins.get("channel", "NAV") != "NAV"):
        return dict(cfg, sensors=sensors)  # no INS, or already elsewhere
    return dict(cfg, sensors=merge(sensors, {"ins": merge(ins or {}, {"channel": "NAV_INS"})}))


def vehicle_config(sc: Scenario, v: Vehicle, index: int, recorder: bool = False) -> dict:
    """The merged simulator configuration of one vehicle (plain data); recorder:
    the run records with auv-recorder, a participant of a lockstep world."""
    cfg = _ins_out_of_the_way(v, _targets_publisher(sc, v, _merged_config(sc, v, index)))
    return name_them(sc, cfg, recorder)  # a lockstep world waits for each participant by name


def _merged_config(sc: Scenario, v: Vehicle, index: int) -> dict:
    base = _base(v)
    if isinstance(base.get("environment"), dict):
        base["environment"] = _absolute_grid(base["environment"], v.sim_config.parent)
    cfg = merge(base, {"environment": {"seed": sc.seed}})
    cfg = merge(cfg, {"environment": _absolute_grid(sc.world, sc.path.parent)})
    # Every vehicle's sensors get their own noise: the world seed decides the
    # environment, seed + index + 1 each vehicle's sensors (unless set).
    cfg = merge(cfg, {"simulation": {"seed": sc.seed * 100 + index + 1}})
    cfg = merge(cfg, v.sim_overrides)
    cfg = merge(cfg, {"vehicle": {"id": v.id}})
    for f in sc.faults:  # a planned leak: the probes sense water from its time on
        if f.vehicle == v.id and f.do == "leak":
            from sim.sensors import FITTED_UNLESS_LISTED

            listed = cfg.get("sensors") or {name: {} for name in FITTED_UNLESS_LISTED}  # none listed: all of them
            cfg["sensors"] = merge(listed, {"leak": {"at_s": f.at_s}})
    return count_in(sc, cfg)  # the launcher takes part in a lockstep world (the end, planned losses)


def source_position(v: Vehicle, key: str, sc: Scenario) -> str:
    """Where the simulator key `a.b.c` came from: the scenario's world or the
    vehicle's `sim:` overrides if it is there, else the vehicle's base file."""
    parts = [p for p in re.split(r"[.\[\]]", key) if p and not p.isdigit()]
    if parts[:1] == ["environment"] and sc.world_node is not None:
        pos, found = position(sc.path, sc.world_node, parts[1:])
        if found:
            return pos
    pos, found = position(sc.path, v.sim_node, parts)
    if found:
        return pos
    try:
        base = Checker.from_file(v.sim_config, extends=True)
        bpos, bfound = locate(base, parts)  # in the file or the base it extends
        return bpos if bfound else pos
    except ConfigError:
        return pos


def write_configs(
    sc: Scenario, vehicles: list[Vehicle], out_dir: Path, recorder: bool = False
) -> tuple[dict[str, Path], list[str]]:
    """Write <ID>.sim.yaml per vehicle; return their paths and the scenario errors.
    recorder: the run records with auv-recorder (vehicle_config)."""
    from sim.config import load

    paths, errors = {}, []
    for v in vehicles:
        index = sc.vehicles.index(v)
        path = out_dir / f"{v.id}.sim.yaml"
        try:
            merged = vehicle_config(sc, v, index, recorder)
        except ConfigError as exc:  # the base file itself was refused (its own positions)
            errors += [f"{line} (the sim config of vehicles[{index}])" for line in exc.errors]
            continue
        path.write_text(
            f"# {v.id}: {v.sim_config} merged with the scenario {sc.path.name} by the launcher\n" + dump_yaml(merged)
        )
        try:
            load(path)
        except ConfigError as exc:  # point each error at the line it came from
            for line in exc.errors:
                m = re.match(r".*?:\d+:\d+: ([\w.\[\]]+): (.*)", line)
                key, msg = (m.group(1), m.group(2)) if m else ("sim", line)
                errors.append(f"{source_position(v, key, sc)}: vehicles[{index}].sim: {key}: {msg}")
            continue
        paths[v.id] = path
    return paths, errors
