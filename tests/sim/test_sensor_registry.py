"""One sensor registry (sim.sensors.SENSORS): what lists sensors elsewhere is
derived from each sensor's class, and a sensor is given what it declares."""

from __future__ import annotations

from pathlib import Path

import pytest

from sim.config import ENV_VARIABLES, RESERVED_TOPICS, SIM_TOPICS, ConfigError, loads
from sim.hil import build_model, build_sensors
from sim.sensors import FITTED_UNLESS_LISTED, REGISTRY, SENSORS, SensorConfig


def test_every_sensor_declares_itself_completely():
    assert len({s.name for s in SENSORS}) == len(SENSORS) == len(REGISTRY)
    for s in SENSORS:
        assert issubclass(s.config_class, SensorConfig), s
        assert set(s.env_needs) <= set(ENV_VARIABLES), s
        assert set(s.uses) <= {"env", "frame"}, s


def test_reserved_topics_are_every_sensors_but_the_ins():
    assert RESERVED_TOPICS == SIM_TOPICS | {"AHRS", "DEPTH", "DVL", "ALTIMETER", "GPS", "LBL", "LEAK", "CTD"}
    # the leak probes' channel was missing from the hand-kept list: an INS could publish over it
    with pytest.raises(ConfigError) as exc:
        loads("sensors:\n  ins: {channel: LEAK}\n", Path("c.yaml"))
    assert "c.yaml:2:18: sensors.ins.channel: LEAK is another channel" in exc.value.errors[0]


def test_each_sensor_gets_the_world_it_uses():
    cfg = loads("vehicle: {id: AUV1}\n", Path("c.yaml"))
    model = build_model(cfg)
    built = {s.name: s for s in build_sensors(cfg, model)}
    # none listed: all the vehicle's own, in the registry's order; a payload (the CTD) only where listed
    assert list(built) == [s.name for s in SENSORS if s.fitted_unless_listed] == list(FITTED_UNLESS_LISTED)
    assert "ctd" not in built and "ctd" in REGISTRY
    assert built["lbl"].env is model.env
    assert built["gps"].frame is model.frame and built["ins"].frame is model.frame
    listed = loads("sensors: {ctd: {}, depth: {}}\n", Path("c.yaml"))
    ctd = {s.name: s for s in build_sensors(listed, build_model(listed))}["ctd"]
    assert ctd.env is not None and ctd.topic == "CTD"


def test_a_listed_multihil_needs_serves_the_fitted_sensors():
    ok = "sensors: {ahrs: {}, leak: {}}\nmultihil: {needs: [current]}\n"
    assert loads(ok, Path("c.yaml")).multihil.needs == ["current"]
    with pytest.raises(ConfigError) as exc:
        loads("sensors: {lbl: {}, dvl: {}}\nmultihil: {needs: [current]}\n", Path("c.yaml"))
    assert exc.value.errors == [
        "c.yaml:2:19: multihil.needs: sensors.lbl reads sound_speed, lbl from the world: add them",
        "c.yaml:2:19: multihil.needs: sensors.dvl reads bathymetry from the world: add it",
    ]
    with pytest.raises(ConfigError) as exc:
        loads("sensors: {ctd: {}}\nmultihil: {needs: [current]}\n", Path("c.yaml"))
    assert exc.value.errors == ["c.yaml:2:19: multihil.needs: sensors.ctd reads ocean from the world: add it"]
