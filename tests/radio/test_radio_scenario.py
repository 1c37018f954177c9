"""The scenario's `radio:` section: read and checked like the rest of the file."""

from __future__ import annotations

import pytest
import yaml
from conftest import ROOT

from confcheck import ConfigError
from tools.scenario.scenario_file import load_scenario

SIM = str(ROOT / "missions" / "sim" / "remus100_multihil.yaml")
PLAN = str(ROOT / "tests" / "tools" / "scenarios" / "mission.chasm")
BIND = str(ROOT / "missions" / "bindings" / "direct_actuators.bind")


def _scenario(tmp_path, radio) -> str:
    sc = {
        "name": "radio",
        "vehicles": [
            {"id": "AUV1", "sim": {"config": SIM}, "managers": [{"name": "NAVIGATOR", "plan": PLAN, "bind": BIND}]}
        ],
    }
    if radio is not None:
        sc["radio"] = radio
    path = tmp_path / "radio.yaml"
    path.write_text(yaml.safe_dump(sc, sort_keys=False))
    return str(path)


def test_a_scenario_without_radio_has_none(tmp_path):
    assert load_scenario(_scenario(tmp_path, None)).radio is None


def test_radio_keys_are_read(tmp_path):
    keys = {
        "bitrate_bps": 9600,
        "acoustic": {"AUV1": 3},
        "report_period_s": 1,
        "shore_lcm_url": "udpm://x",
        "peers": True,
    }
    r = load_scenario(_scenario(tmp_path, keys)).radio
    assert r.bitrate_bps == 9600 and r.acoustic == {"AUV1": 3} and r.report_period_s == 1
    assert r.shore_lcm_url == "udpm://x" and r.peers is True


@pytest.mark.parametrize(
    "radio, error",
    [
        ({"bitrate": 9600}, "radio.bitrate: unknown key; did you mean 'bitrate_bps'?"),
        ({"loss": 2}, "radio.loss"),
        ({"acoustic": {"AUV9": 0}}, "radio.acoustic.AUV9: not a vehicle of the scenario"),
        ({"acoustic": {"AUV1": 15}}, "radio.acoustic.AUV1: a team index 0 .. 14"),
    ],
)
def test_bad_radio_keys_are_refused_with_their_place(tmp_path, radio, error):
    with pytest.raises(ConfigError) as e:
        load_scenario(_scenario(tmp_path, radio))
    assert error in str(e.value) and "radio.yaml:" in str(e.value), str(e.value)
