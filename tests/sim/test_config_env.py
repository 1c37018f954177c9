"""Configuration errors name file:line and key; environment is deterministic."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from sim.bathymetry import Bathymetry, BathymetryError
from sim.config import ConfigError, load, loads
from sim.environment import CurrentLayer, Environment, EnvParams

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = sorted((ROOT / "missions" / "sim").glob("*.yaml"))


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.name for p in EXAMPLES])
def test_example_configs_load(path):
    cfg = load(path)
    assert cfg.vehicle_id
    Environment(cfg.env, path.parent)


def errors(text: str) -> list[str]:
    with pytest.raises(ConfigError) as exc:
        loads(text, Path("cfg.yaml"))
    return exc.value.errors


def test_every_error_at_once_with_file_line_and_key():
    errs = errors(
        "vehicle:\n  id: auv1\nsimulation:\n  clok: scaled\n  warp: fast\nsensors:\n  dvl: {rate_hz: 0}\n  gyro: {}\n"
    )
    assert errs == [
        "cfg.yaml:2:7: vehicle.id: must be upper-case letters and digits, starting with a letter, "
        "at most 16 characters (it starts every channel name)",
        "cfg.yaml:4:3: simulation.clok: unknown key; did you mean 'clock'?",
        "cfg.yaml:5:9: simulation.warp: expected a number, got 'fast'",
        "cfg.yaml:7:18: sensors.dvl.rate_hz: must be > 0 [Hz]",
        "cfg.yaml:8:3: sensors.gyro: unknown key; expected one of: ahrs, altimeter, ctd, depth, dvl, gps, ins, lbl, leak",
    ]


@pytest.mark.parametrize(
    "text,where,key",
    [
        ("simulation:\n  clock: warp\n", "2:10", "simulation.clock"),
        ("simulation:\n  physics_rate_hz: 20\n", "2:20", "simulation.physics_rate_hz"),
        ("vehicle:\n  hydro: {Xuuu: 1}\n", "2:11", "vehicle.hydro.Xuuu"),
        ("vehicle:\n  cg_m: [0, 0]\n", "2:9", "vehicle.cg_m"),
        ("sensors:\n  depth: {dropout: 1.5}\n", "2:20", "sensors.depth.dropout"),
        ("environment:\n  bathymetry: {shape: hill, depth: 40, heigth: 3}\n", "2:40", "environment.bathymetry.heigth"),
        ("environment:\n  bathymetry: 'grid:nowhere.npz'\n", "2:15", "environment.bathymetry"),
        ("environment:\n  transponders:\n    - {id: 1}\n    - {id: 1}\n", "4:7", "environment.transponders[1].id"),
        ("multihil: {needs: [current, tides]}\n", "1:29", "multihil.needs[1]"),
        ("simulation:\n  warp: 1\n  warp: 2\n", "3:3", "simulation.warp"),
        ("initial:\n  depth_m: .nan\n", "2:12", "initial.depth_m"),
    ],
)
def test_each_error_names_key_and_position(text, where, key):
    errs = errors(text)
    assert len(errs) == 1, errs
    assert errs[0].startswith(f"cfg.yaml:{where}: {key}:"), errs


def test_yaml_syntax_error_has_a_position():
    errs = errors("vehicle:\n  id: [AUV1\n")
    assert errs[0].startswith("cfg.yaml:") and "YAML syntax" in errs[0]


def test_vehicle_overrides_make_another_vehicle():
    cfg = loads("vehicle:\n  id: GLIDER7\n  mass_kg: 52.0\n  hydro: {Xuu: -3.0}\n")
    assert cfg.vehicle_id == "GLIDER7"
    assert cfg.vehicle.mass_kg == 52.0 and cfg.vehicle.hydro["Xuu"] == -3.0
    assert cfg.multihil.client_id == "GLIDER7-sim"


def test_environment_is_a_deterministic_function_of_time_position_seed():
    p = EnvParams(
        seed=11,
        current=[CurrentLayer(0, 0.2, 0.0), CurrentLayer(40, 0.0, 0.1)],
        current_variation_mps=0.1,
        current_variation_period_s=600.0,
        wave_height_m=1.0,
        wave_period_s=7.0,
        wave_direction_rad=0.5,
    )
    a, b = Environment(p), Environment(p)
    pts = [(t, n, e, d) for t in (0.0, 17.3, 900.0) for n, e, d in ((0, 0, 0.5), (100, -50, 20))]
    assert [a.current(*x) for x in pts] == [b.current(*x) for x in pts]
    c = Environment(EnvParams(**{**p.__dict__, "seed": 12}))
    assert [a.current(*x) for x in pts] != [c.current(*x) for x in pts]
    # depth profile: linear between layers (no waves, no variation at depth 20)
    flat = Environment(EnvParams(current=p.current))
    assert flat.current(0, 0, 0, 20.0) == pytest.approx((0.1, 0.05, 0.0))


def test_waves_decay_with_depth_and_have_the_configured_height():
    env = Environment(EnvParams(seed=3, wave_height_m=2.0, wave_period_s=8.0))
    t = np.arange(0.0, 3600.0, 0.5)
    eta = np.array([env.wave_elevation(x, 0.0, 0.0) for x in t])
    assert 4 * eta.std() == pytest.approx(2.0, rel=0.1)
    surf = max(abs(env.wave_orbital(x, 0, 0, 0.0)[0]) for x in t[:200])
    deep = max(abs(env.wave_orbital(x, 0, 0, 80.0)[0]) for x in t[:200])
    assert deep < 0.1 * surf


def test_env_model_round_trip_rebuilds_the_same_world():
    p = load(ROOT / "missions" / "sim" / "remus100.yaml").env
    env = Environment(p)
    msg = env.to_env_model(123, "AUV1-sim", 2)
    from auv import env_model_t

    decoded = env_model_t.decode(msg.encode())
    again = Environment(Environment.params_from_env_model(decoded))
    for x in ((0.0, 0, 0, 1.0), (500.0, 200, -100, 25.0)):
        assert again.current(*x) == env.current(*x)
    assert again.water_depth(120, 30) == env.water_depth(120, 30)
    assert [t.id for t in decoded.transponders] == [1, 2, 3]


def test_bathymetry_shapes_and_grid(tmp_path):
    assert Bathymetry("flat:depth=40").depth(1e4, -3) == 40
    assert Bathymetry("slope:depth=40,dn=0.01").depth(100, 0) == pytest.approx(41)
    hill = Bathymetry("hill:depth=40,height=25,north=100,east=50,radius=30")
    assert hill.depth(100, 50) == pytest.approx(15) and hill.depth(0, 0) > 39
    n, e = np.linspace(0, 100, 11), np.linspace(-50, 50, 21)
    depth = 30 + 0.1 * n[:, None] + 0.0 * e[None, :]
    np.savez(tmp_path / "g.npz", north_m=n, east_m=e, depth_m=depth)
    g = Bathymetry("grid:g.npz", tmp_path)
    assert g.depth(55.0, 3.0) == pytest.approx(35.5)
    assert g.depth(1e6, 0) == pytest.approx(40.0)  # clamped at the edge
    assert len(g.sha256) == 64
    with pytest.raises(BathymetryError, match="unknown parameter"):
        Bathymetry("flat:depht=3")


@pytest.mark.parametrize("value,expected", [("NAV", "NAV"), ("NAV_INS", "NAV_INS"), ("off", "off"), ('"off"', "off")])
def test_ins_channel_is_configurable(value, expected):
    cfg = loads(f"sensors:\n  ins: {{channel: {value}}}\n", Path("cfg.yaml"))
    assert cfg.sensors["ins"].channel == expected
    assert loads("sensors: {ins: {}}\n").sensors["ins"].channel == "NAV"


@pytest.mark.parametrize(
    "value,message",
    [
        ("nav", "expected a channel name"),
        ("on", "expected a channel name"),
        ("AUV1.NAV", "expected a channel name"),
        ("DVL", "one writer per channel"),
        ("TRUTH", "one writer per channel"),
    ],
)
def test_bad_ins_channel_names_key_and_line(value, message):
    errs = errors(f"sensors:\n  ins:\n    channel: {value}\n")
    assert len(errs) == 1 and errs[0].startswith("cfg.yaml:3:14: sensors.ins.channel: ")
    assert message in errs[0]


def test_yes_no_words_stay_words_for_string_keys():
    cfg = loads("simulation: {publish_clock: yes}\nsonar: {publish_targets: no}\n")
    assert cfg.sim.publish_clock == "yes" and cfg.sonar.publish_targets == "no"
    errs = errors("simulation:\n  publish_clock: true\n")
    assert errs == ["cfg.yaml:2:18: simulation.publish_clock: expected one of: auto, yes, no, got 'true'"]
