"""auv-keygen writes 0600 key files and rotates them; a scenario's key_file is
checked at load (present, mode, format) and reaches every manager the
launcher starts as --key-file."""

from __future__ import annotations

import stat
from pathlib import Path

import pytest

from auvlcm import auth
from confcheck import ConfigError
from tools.keys.keygen import main as keygen
from tools.launch.launcher import manager_cmd
from tools.scenario.scenario_file import load_scenario

SCEN = Path(__file__).resolve().parent / "scenarios"


def test_keygen_new_rotate_retire(tmp_path, capsys):
    f = tmp_path / "team.key"
    assert keygen([str(f), "--id", "k1"]) == 0
    assert stat.S_IMODE(f.stat().st_mode) == 0o600
    first = auth.load_keys(f)
    assert [k.id for k in first.keys] == ["k1"] and len(first.signing.secret) == 32
    assert keygen([str(f), "--id", "k9"]) == 1 and "exists (use --rotate" in capsys.readouterr().err
    assert keygen([str(f), "--rotate", "--id", "k2"]) == 0
    ring = auth.load_keys(f)
    assert [k.id for k in ring.keys] == ["k1", "k2"] and ring.find("k1") == first.signing
    assert stat.S_IMODE(f.stat().st_mode) == 0o600
    assert keygen([str(f), "--rotate", "--id", "k3"]) == 0
    assert [k.id for k in auth.load_keys(f).keys] == ["k2", "k3"]  # two at most: the oldest goes
    assert keygen([str(f), "--retire"]) == 0
    assert [k.id for k in auth.load_keys(f).keys] == ["k3"]
    assert keygen([str(tmp_path / "x.key"), "--id", "bad id"]) == 1
    f.chmod(0o644)
    assert keygen([str(f), "--rotate"]) == 1 and "chmod 600" in capsys.readouterr().err


def _scenario(tmp_path: Path, key: Path) -> Path:
    path = tmp_path / "s.yaml"
    path.write_text((SCEN / "two_vehicles.yaml").read_text() + f"key_file: {key}\n")
    return path


def test_scenario_key_file_is_checked_and_given_to_managers(tmp_path):
    key = tmp_path / "team.key"
    assert keygen([str(key)]) == 0
    sc = load_scenario(_scenario(tmp_path, key), base=SCEN)
    assert sc.key_file == key.resolve()
    m = sc.vehicles[0].managers[0]
    cmd = manager_cmd(Path("build"), "udpm://x", sc.vehicles[0].id, m, sc.key_file)
    assert cmd[cmd.index("--key-file") + 1] == str(key.resolve())
    key.chmod(0o640)
    with pytest.raises(ConfigError) as e:
        load_scenario(_scenario(tmp_path, key), base=SCEN)
    assert [x for x in e.value.errors if "key_file" in x and "(mode 0640): chmod 600 it" in x], e.value.errors
    with pytest.raises(ConfigError) as e:
        load_scenario(_scenario(tmp_path, tmp_path / "nothere.key"), base=SCEN)
    assert any("no such file" in x for x in e.value.errors)


def test_an_agent_with_its_own_keys_ignores_the_senders_key_path(tmp_path):
    """A host agent started with --key-file verifies with its own keys: the scenario's
    key_file is a path on the sender's host, which need not exist on the agent's."""
    from conftest import ROOT

    from tools.hosts.agent_part import PartError, host_part

    scenario = ROOT / "missions" / "scenarios" / "mcm_team" / "mcm_team.yaml"
    text = scenario.read_text() + "key_file: /nowhere/on/this/host/team.key\n"
    own = tmp_path / "own.key"
    assert keygen([str(own)]) == 0
    url = "udpm://239.255.76.67:7667?ttl=0"
    build = ROOT / "build"
    sc, specs = host_part(text, str(scenario), "local", tmp_path / "run", url, build, False, key_file=own)
    assert sc.key_file == own and specs
    assert all(str(own) in " ".join(map(str, s.cmd)) for s in specs if "chasm-manager" in str(s.cmd[0]))
    with pytest.raises(PartError, match="no such file: /nowhere"):  # without keys of its own it needs the sender's
        host_part(text, str(scenario), "localhost", tmp_path / "run2", url, build, False)
