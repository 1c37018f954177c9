"""One vocabulary for clock modes (sim.clock_modes): realtime, scaled, lockstep
in every file, flag and message; the old names (`stepped` for a simulator,
`fast` for a scenario) are read as lockstep and never written."""

from __future__ import annotations

import subprocess
import sys

import pytest
import yaml
from conftest import ROOT

from auv import sim_clock_t
from sim import clock_modes
from sim.config import loads
from tools.scenario.scenario_file import load_scenario


def test_the_three_modes_are_the_wires_three():
    assert clock_modes.MODES == ("realtime", "scaled", "lockstep")
    assert [clock_modes.WIRE[m] for m in clock_modes.MODES] == [
        sim_clock_t.MODE_REALTIME,
        sim_clock_t.MODE_SCALED,
        sim_clock_t.MODE_LOCKSTEP,
    ]
    assert [clock_modes.name_of_wire(v) for v in (0, 1, 2, 7)] == ["realtime", "scaled", "lockstep", "mode 7"]


@pytest.mark.parametrize(
    "name, want",
    [
        ("lockstep", "lockstep"),
        ("stepped", "lockstep"),
        ("fast", "lockstep"),
        ("scaled", "scaled"),
        ("realtime", "realtime"),
    ],
)
def test_old_names_are_read_as_their_mode(name, want):
    assert clock_modes.canonical(name) == want
    assert loads(f"simulation: {{clock: {name}}}\n").sim.clock == want


def test_an_unknown_mode_is_refused_with_the_vocabulary():
    with pytest.raises(ValueError, match="realtime, scaled, lockstep"):
        clock_modes.canonical("warp")


def test_a_scenario_written_with_fast_loads_as_lockstep(tmp_path):
    sim = ROOT / "missions" / "sim" / "remus100.yaml"
    plan = ROOT / "tests" / "tools" / "scenarios" / "mission.chasm"
    bind = ROOT / "missions" / "bindings" / "direct_actuators.bind"
    sc = {
        "name": "old",
        "time": {"mode": "fast", "limit": 10},
        "vehicles": [
            {
                "id": "AUV1",
                "sim": {"config": str(sim)},
                "managers": [{"name": "NAVIGATOR", "plan": str(plan), "bind": str(bind), "rate": 10}],
            }
        ],
    }
    path = tmp_path / "old.yaml"
    path.write_text(yaml.safe_dump(sc))
    assert load_scenario(path).time.mode == "lockstep"


def test_the_simulators_flag_takes_the_vocabulary_and_the_old_name():
    for name in ("lockstep", "stepped"):
        run = subprocess.run(
            [sys.executable, "-m", "sim", str(ROOT / "missions" / "sim" / "remus100.yaml"), "--clock", name, "--check"],
            capture_output=True,
            text=True,
            timeout=60,
        )
        assert run.returncode == 0, run.stderr
    run = subprocess.run(
        [sys.executable, "-m", "sim", str(ROOT / "missions" / "sim" / "remus100.yaml"), "--clock", "warp", "--check"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert run.returncode == 2 and "realtime, scaled, lockstep" in run.stderr, run.stderr
