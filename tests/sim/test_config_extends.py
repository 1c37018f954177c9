"""Simulator configurations that extend a base (confcheck.extends): the merge
rule, `remove`, and every refusal at its file:line:col."""

from __future__ import annotations

from pathlib import Path

import pytest

from sim.config import ConfigError, load
from sim.sensors import REGISTRY

ROOT = Path(__file__).resolve().parents[2]

BASE = """\
vehicle: {id: AUV1}
simulation: {clock: realtime, warp: 2.0}
environment:
  seed: 3
  current:
    - {depth_m: 0, north_mps: 0.1, east_mps: 0}
    - {depth_m: 30, north_mps: 0.2, east_mps: 0}
sensors:
  ins: {}
  ahrs: {noise: 0.01}
  gps: {}
  leak: {rate_hz: 1}
"""


def write(tmp: Path, files: dict[str, str]) -> None:
    for name, text in files.items():
        (tmp / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp / name).write_text(text)


def refused(path: Path) -> list[str]:
    with pytest.raises(ConfigError) as exc:
        load(path)
    return exc.value.errors


def test_mappings_merge_lists_and_values_replace(tmp_path):
    write(
        tmp_path,
        {
            "base.yaml": BASE,
            "v.yaml": "extends: base.yaml\nsimulation: {warp: 4.0}\n"
            "environment:\n  current:\n    - {depth_m: 0, north_mps: 0.5, east_mps: 0}\n"
            "sensors:\n  ahrs: {bias: 0.02}\n  dvl: {}\n",
        },
    )
    cfg = load(tmp_path / "v.yaml")
    assert cfg.sim.warp == 4.0 and cfg.sim.clock == "realtime"  # merged key by key
    assert cfg.env.seed == 3
    assert [c.north_mps for c in cfg.env.current] == [0.5]  # a list replaces
    assert cfg.sensors["ahrs"].noise == 0.01 and cfg.sensors["ahrs"].bias == 0.02
    # the extending file's keys first, in its order, then the base's others
    assert list(cfg.sensors) == ["ahrs", "dvl", "ins", "gps", "leak"]


def test_remove_drops_a_sensor_of_the_base_and_keeps_the_order(tmp_path):
    write(tmp_path, {"base.yaml": BASE, "v.yaml": "extends: base.yaml\nremove: [sensors.gps, simulation.warp]\n"})
    cfg = load(tmp_path / "v.yaml")
    assert list(cfg.sensors) == ["ins", "ahrs", "leak"]
    assert cfg.sim.warp == 1.0  # the default again


def test_a_chain_of_bases_in_other_folders(tmp_path):
    write(
        tmp_path,
        {
            "bases/base.yaml": BASE,
            "bases/mid.yaml": "extends: base.yaml\nsensors: {lbl: {}}\n",
            "v.yaml": "extends: bases/mid.yaml\nvehicle: {id: AUV7}\n",
        },
    )
    cfg = load(tmp_path / "v.yaml")
    assert cfg.vehicle_id == "AUV7"
    assert list(cfg.sensors) == ["lbl", "ins", "ahrs", "gps", "leak"]


def test_an_error_in_the_base_names_the_base(tmp_path):
    write(
        tmp_path,
        {"base.yaml": BASE.replace("warp: 2.0", "warp: -1"), "v.yaml": "extends: base.yaml\nsensors: {gyro: {}}\n"},
    )
    errs = refused(tmp_path / "v.yaml")
    assert f"{tmp_path / 'base.yaml'}:2:37: simulation.warp: must be > 0" in errs
    assert any(e.startswith(f"{tmp_path / 'v.yaml'}:2:11: sensors.gyro: unknown key") for e in errs), errs


@pytest.mark.parametrize(
    "files,expected",
    [
        ({"v.yaml": "extends: none.yaml\n"}, "v.yaml:1:10: extends: cannot read none.yaml ("),
        ({"v.yaml": "extends: [a]\n"}, "v.yaml:1:10: extends: expected a file name"),
        ({"v.yaml": "extends: v.yaml\n"}, "v.yaml:1:10: extends: cycle: "),
        (
            {"v.yaml": "extends: a.yaml\n", "a.yaml": "# a\nextends: v.yaml\n"},
            "a.yaml:2:10: extends: cycle: ",
        ),
        ({"v.yaml": "remove: [sensors.gps]\n"}, "v.yaml:1:1: remove: only a file that `extends:` a base"),
        (
            {"v.yaml": "extends: base.yaml\nremove: [sensors.gps, sensors.dvl]\n", "base.yaml": BASE},
            "v.yaml:2:23: remove: 'sensors.dvl' is not a key of the base base.yaml",
        ),
        (
            {"v.yaml": "extends: base.yaml\nremove: sensors.gps\n", "base.yaml": BASE},
            "v.yaml:2:9: remove: expected a list of keys",
        ),
        (
            {"v.yaml": "extends: base.yaml\n", "base.yaml": "[1, 2]\n"},
            "v.yaml:1:10: extends: base.yaml is not a mapping",
        ),
        ({"v.yaml": "extends: base.yaml\n", "base.yaml": "a: [\n"}, "base.yaml:2:1: YAML syntax"),
    ],
    ids=[
        "missing",
        "not_a_name",
        "itself",
        "cycle",
        "remove_alone",
        "remove_unknown",
        "remove_not_list",
        "base_list",
        "base_syntax",
    ],
)
def test_refusals_at_their_position(tmp_path, files, expected):
    write(tmp_path, files)
    errs = refused(tmp_path / "v.yaml")
    assert any(e.startswith(f"{tmp_path}/{expected}") for e in errs), errs


def test_a_long_chain_is_refused(tmp_path):
    write(tmp_path, {f"c{i}.yaml": f"extends: c{i + 1}.yaml\n" for i in range(12)} | {"c12.yaml": BASE})
    errs = refused(tmp_path / "c0.yaml")
    assert "extends: more than 8 files deep" in errs[0], errs


def test_the_shipped_vehicles_carry_the_base_sensors_listed_once():
    """A sensor the vehicles carry is one line of remus100_base.yaml: no file
    that extends it names the leak probes again, and each still has them."""
    base = ROOT / "missions" / "sim" / "remus100_base.yaml"
    extending = [p for p in sorted(base.parent.glob("*.yaml")) if "\nextends: remus100_base.yaml\n" in p.read_text()]
    assert len(extending) >= 5, extending
    for p in extending:
        assert "leak:" not in p.read_text(), p
        assert "leak" in load(p).sensors, p


def test_a_sensor_channel_is_bound_in_one_binding_file():
    """Every sensor's input line is in missions/bindings/sensors.bind, which the
    navigator binding files include; no other binding file repeats it."""
    topics = {cls.topic for _, cls in REGISTRY.values()} - {"NAV"}  # the INS's NAV is the navigation solution
    folder = ROOT / "missions" / "bindings"
    for p in sorted(folder.glob("*.bind")):
        bound = {w.split(".", 1)[1] for line in p.read_text().splitlines() for w in line.split()[2:3] if "." in w}
        if p.name == "sensors.bind":
            assert {"GPS", "LEAK"} <= bound
        else:
            assert not bound & topics, (p, bound & topics)
    for name in ("navigator", "navigator_ekf", "team_ri", "team_search"):
        assert 'include      "sensors.bind"' in (folder / f"{name}.bind").read_text()
