"""The console's water layer (python/tools/console/world.py): a world with an ocean, as
SIM.ENV serves it (env_model_t) or a simulator's configuration annotated into the log,
gives the map the water's temperature at 5 m over the area of interest: warm shelf water
west of the front of missions/sim/remus100_sampling.yaml, cool water east of it, the
front where the world puts it; a world without an ocean has no water layer."""

from __future__ import annotations

import math
from pathlib import Path

from conftest import ROOT

from auv import log_annotation_t
from sim.config import load
from sim.environment import Environment
from tools.console.model import Model
from tools.console.world import WorldBuilder

SAMPLING = ROOT / "missions" / "sim" / "remus100_sampling.yaml"


def _front_east(north: float) -> float:
    """Where the sampling world's straight front is (offset 300 m, 0.3 rad from north)."""
    return (300.0 + north * math.sin(0.3)) / math.cos(0.3)


def test_water_from_sim_env():
    cfg = load(SAMPLING)
    model = Model()
    world = WorldBuilder(model)
    world.observe("SIM.ENV", Environment(cfg.env, SAMPLING.parent).to_env_model(0))
    water = model.world["water"]
    assert water and "error" not in water and water["depth_m"] == 5.0
    temps = [v for row in water["temp"] for v in row]
    assert 11.9 < min(temps) and max(temps) < 16.1
    # each row runs west to east: warm west of the front, cool east of it, the step where the front is
    for i, row in enumerate(water["temp"]):
        north = water["north0"] + (i + 0.5) * water["dn"]
        easts = [water["east0"] + (j + 0.5) * water["de"] for j in range(len(row))]
        for e, v in zip(easts, row):
            if e < _front_east(north) - 60:  # meander 15 m, width 20 m
                assert v > 15.5, (north, e, v)
            elif e > _front_east(north) + 60:
                assert v < 12.5, (north, e, v)


def test_water_from_the_logs_annotation_and_none_without_an_ocean(tmp_path: Path):
    model = Model()
    world = WorldBuilder(model)
    note = log_annotation_t()
    note.kind, note.vehicle, note.name = 1, "AUV1", "AUV1.sim.yaml"
    note.text = SAMPLING.read_text().replace(
        "extends: remus100_ctd.yaml", f"extends: {SAMPLING.parent}/remus100_ctd.yaml"
    )
    note.text += "initial: {north_m: 400, east_m: 380}\n"
    world.observe("SIM.ANNOTATION", note)
    water = model.world["water"]
    assert water and "error" not in water
    # the vehicle's start is inside the drawn area
    assert water["north0"] < 400 < water["north0"] + len(water["temp"]) * water["dn"]
    assert water["east0"] < 380 < water["east0"] + len(water["temp"][0]) * water["de"]
    plain = Model()
    WorldBuilder(plain).observe("SIM.ENV", Environment(load(ROOT / "missions/sim/remus100.yaml").env).to_env_model(0))
    assert plain.world["water"] is None
