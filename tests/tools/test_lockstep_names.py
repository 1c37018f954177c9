"""A multi-HIL lockstep world waits before step 0 for every participant by
name (tools/launch/lockstep_names.py, issue 14: the same run under any load).

The team scenario counts its simulators, pilots and navigators (12), but the
recorder takes part too: under load the world began with one simulator still
starting, which joined at step 1, and two runs differed from their start.
The launcher now writes every participant's name into each simulator's
configuration, and the serving simulator waits for all of them; the launcher
takes part too, as SIM.LAUNCHER (it ends the world at a defined step:
tools/launch/fault_step.py), and counts itself in."""

from __future__ import annotations

import pytest
import yaml
from conftest import ROOT

from auv import lockstep_t
from confcheck import ConfigError
from sim.config import load
from sim.multihil.hook import node_config
from sim.multihil.lockstep import LockstepTracker, lockstep_msg
from sim.multihil.server import LockstepServer
from tools.launch.simconfig import write_configs
from tools.scenario.scenario_file import load_scenario

TEAM = ROOT / "missions" / "scenarios" / "mcm_team" / "mcm_team.yaml"


def team_names(recorder: bool) -> set[str]:
    names = {f"AUV{i}.{p}" for i in range(1, 5) for p in ("sim", "PILOT", "NAVIGATOR")} | {"SIM.LAUNCHER"}
    return names | {"SIM.RECORDER"} if recorder else names


def test_each_simulator_names_every_participant_of_the_world(tmp_path):
    sc = load_scenario(TEAM)
    for recorder in (True, False):
        out = tmp_path / str(recorder)
        out.mkdir()
        paths, errors = write_configs(sc, sc.vehicles, out, recorder)
        assert not errors and sorted(paths) == ["AUV1", "AUV2", "AUV3", "AUV4"]
        for path in paths.values():
            mh = yaml.safe_load(path.read_text())["multihil"]
            assert set(mh["lockstep_names"]) == team_names(recorder), mh
            assert mh["lockstep_participants"] == 13  # the scenario's count and the launcher: both must hold
            node = node_config(load(path))  # the simulator reads them as they were written
            assert set(node.lockstep_names) == team_names(recorder) and node.lockstep_expect == 13


def test_a_world_whose_count_is_met_by_the_wrong_set_waits_for_the_missing_name(tmp_path):
    sc = load_scenario(TEAM)
    paths, _ = write_configs(sc, sc.vehicles, tmp_path, recorder=True)
    node = node_config(load(paths["AUV1"]))
    tracker = LockstepTracker(timeout_s=None)
    server = LockstepServer(tracker, 100_000, node.lockstep_expect, expect_names=set(node.lockstep_names))
    late = "AUV2.sim"
    for name in sorted(team_names(True) - {late}):  # 13 registrations: the count is met
        tracker.on_message(lockstep_msg(name, lockstep_t.KIND_REGISTER, 0, 0))
    assert len(tracker.parts) == 13
    assert server.poll() is None, "step 0 went without AUV2.sim"
    tracker.on_message(lockstep_msg(late, lockstep_t.KIND_REGISTER, 0, 0))
    assert server.poll() == 0


def test_a_participant_name_in_a_simulator_configuration_is_checked(tmp_path):
    sc = load_scenario(TEAM)
    paths, _ = write_configs(sc, sc.vehicles[:1], tmp_path)
    cfg = yaml.safe_load(paths["AUV1"].read_text())
    cfg["multihil"]["lockstep_names"] = ["AUV1.sim", "bad name"]
    bad = tmp_path / "bad.yaml"
    bad.write_text(yaml.safe_dump(cfg))
    with pytest.raises(ConfigError) as err:
        load(bad)
    assert "lockstep_names" in str(err.value) and "participant name" in str(err.value), err.value
