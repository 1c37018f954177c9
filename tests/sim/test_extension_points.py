"""The simulator's extension points (docs/simulator.md, "Extension points"):
what a part plugged into it (the lockstep follower, the multi-HIL hook) may
change, each through a method of its own instead of the simulator's insides."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

from auv import actuators_t
from auvlcm.offline import OfflineLcm
from sim.clock import Pacer
from sim.config import load
from sim.environment import Environment
from sim.hil import Simulator

CONFIG = Path(__file__).resolve().parents[2] / "missions" / "sim" / "remus100.yaml"


@pytest.fixture
def sim():
    lc = OfflineLcm(keep=False)
    s = Simulator(load(CONFIG), fast=True, lc=lc)
    yield s
    s.close()
    lc.close()


def test_replace_world_reaches_every_part_holding_the_world(sim):
    env, frame = sim.model.env, sim.model.frame
    gps = next(s for s in sim.sensors if s.name == "gps")
    lbl = next(s for s in sim.sensors if s.name == "lbl")
    params = dataclasses.replace(
        env.params, origin_latitude_deg=45.0, origin_longitude_deg=-60.0, bathymetry_ref="flat:depth=25"
    )
    sim.replace_world(Environment(params))
    # the same objects, changed in place: the sensors hold them
    assert sim.model.env is env and sim.model.frame is frame and gps.frame is frame
    assert lbl.env is env and env.water_depth(0.0, 0.0) == 25.0
    tr = sim.model.truth()
    assert (tr.latitude_deg, tr.longitude_deg) == pytest.approx(frame.to_latlon(*tr.eta[0:2])) and abs(
        tr.latitude_deg - 45.0
    ) < 0.01


def test_a_command_filter_decides_when_a_command_acts(sim):
    held = []
    sim.set_command_filter(lambda channel, msg: held.append((channel, msg)))
    with pytest.raises(RuntimeError):  # a second filter would bypass the first
        sim.set_command_filter(lambda channel, msg: None)
    m = actuators_t()
    m.utime, m.vehicle, m.seq = 0, sim.vid, 1
    m.rudder_rad, m.stern_plane_rad, m.prop_rpm = 0.1, -0.05, 1200.0
    sim.apply_command("AUV1.ACTUATORS", m)  # what the filter calls when the time comes
    assert (sim.model.command.rudder_rad, sim.model.command.prop_rpm) == (0.1, 1200.0)


class _Source:
    def __init__(self) -> None:
        self.now: float | None = None

    def global_now_s(self) -> float | None:
        return self.now


def test_a_clock_source_paces_the_free_running_steps():
    pacer = Pacer("scaled", 4.0, 0.02, fast=False)
    src = _Source()
    pacer.set_clock_source(src)
    assert not pacer.may_step(10.0, 0.0) and pacer.wait_s(10.0, 0.0) == 0.05  # no time yet
    src.now = 10.02
    assert pacer.may_step(10.0, 0.0)
    src.now = 10.01
    assert not pacer.may_step(10.0, 0.0) and pacer.wait_s(10.0, 0.0) == pytest.approx(0.0025)


def test_clock_started_says_when_the_simulator_joined(sim):
    assert not sim.clock_started
    sim.join_at(5.0)
    assert sim.clock_started and sim.model.t == 5.0
