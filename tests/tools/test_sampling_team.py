"""The front-sampling team end to end (docs/sampling.md, "A sampling team"): auv-launch
flies missions/scenarios/sampling_team (three simulators with CTDs, PILOT and NAVIGATOR
managers, auv-front-estimate on each, the acoustic team link, lockstep), and the report's
grade is read from its log.

- The vehicles' own fits travel: every vehicle's frames carry front summaries (decoded from
  <V>.MODEM_TX with the link's codec), and every vehicle's team estimate fitted teammates'
  summaries (peers_used).
- The rule steers: each navigator's front_rule fell back to the planned course until an
  estimate came, then sent it somewhere along the front, and the vehicles' targets differ.
- The grade: the team's map error at the end is a small part of the water's spread, no
  worse than the vehicles' own-samples estimates, and the straight-front parameters are
  near the world's (the offset within the meander's amplitude and a few metres).
- A teammate lost degrades the estimate, never the mission: AUV3 is lost at 100 s (a
  planned fault, every process killed); AUV1 and AUV2 find it lost, fly on and end done,
  and their estimates still grade as above.

The grader itself, on fields made by hand: an estimate equal to the world's straight front
in a world without a meander has no map error; the other form of the same front (angle +
pi) is graded the same; a wrong offset is an error of that many metres.
"""

from __future__ import annotations

import math
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import yaml
from conftest import ROOT

from auv import front_estimate_t, team_event_t
from auvlcm import team_codec
from tools.report import front_grade as fg
from tools.report.run_data import load_run

SCENARIO = ROOT / "missions" / "scenarios" / "sampling_team" / "sampling_team.yaml"
LAUNCH = [sys.executable, "-m", "tools.launch"]
CODEC = team_codec.TeamCodec()


LOST_AT_S = 100.0
SURVEY_MIN = 3


def with_a_loss(tmp_path: Path) -> Path:
    """sampling_team.yaml with its paths absolute, AUV3 lost at LOST_AT_S, and each plan's
    survey SURVEY_MIN minutes (the suite's time: the shipped 6 min is the demo's)."""
    doc = yaml.safe_load(SCENARIO.read_text())
    base = SCENARIO.parent
    for v in doc["vehicles"]:
        v["sim"]["config"] = str((base / v["sim"]["config"]).resolve())
        for m in v["managers"]:
            m["plan"], m["bind"] = str((base / m["plan"]).resolve()), str((base / m["bind"]).resolve())
            if m["name"] == "NAVIGATOR":
                plan = Path(m["plan"]).read_text()
                assert "param survey_time = 6 min" in plan
                plan = plan.replace("param survey_time = 6 min", f"param survey_time = {SURVEY_MIN} min")
                plan = plan.replace('include "../../common/', f'include "{ROOT}/missions/common/')
                m["plan"] = str(tmp_path / f"{v['id']}.chasm")
                Path(m["plan"]).write_text(plan)
    doc["faults"] = [{"at": LOST_AT_S, "vehicle": "AUV3", "do": "lose"}]
    path = tmp_path / "sampling_team.yaml"
    path.write_text(yaml.safe_dump(doc, sort_keys=False))
    return path


def test_the_team_maps_the_front_and_shares_it(tmp_path, lcm_url, child_env):
    out = tmp_path / "run"
    run = subprocess.run(
        LAUNCH + [str(with_a_loss(tmp_path)), "--out", str(out), "--lcm-url", lcm_url, "--progress", "0"],
        env=child_env,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    data = load_run(out / "run.lcmlog")
    assert data.vehicles == ["AUV1", "AUV2", "AUV3"]
    assert data.outcome["vehicles"]["AUV3"]["outcome"] == "lost", data.outcome
    for v in ("AUV1", "AUV2"):
        assert data.outcome["vehicles"][v]["outcome"] == "done", data.outcome
        lost = [e for e in data.log.messages.get(f"{v}.TEAM_EVENT", []) if e.kind == team_event_t.PEER_LOST]
        assert [e.origin for e in lost] == ["AUV3"], v
    for v in data.vehicles:
        # the link carried this vehicle's summaries
        fronts = 0
        for f in data.log.messages.get(f"{v}.MODEM_TX", []):
            frame = CODEC.decode_frame(bytes(f.payload[: f.n_bytes]))
            assert frame.ok, (v, frame.error)
            fronts += sum(1 for m in frame.messages if m.name == "front")
        assert fronts >= 3, (v, fronts)  # AUV3 from its first estimate (about 45 s) until its loss
        team = data.log[f"{v}.FRONT_TEAM"]
        ok = team["status"] == front_estimate_t.STATUS_OK
        assert ok.any() and team["peers_used"][ok].max() >= 1, v
        text = (out / f"{v}.NAVIGATOR.out").read_text()
        assert "front_rule: no team estimate yet: the planned course 0.300 rad" in text
        assert re.search(r"front_rule: to -?\d+ m along the front", text), text[-2000:]
    firsts = {
        re.search(r"front_rule: to (-?\d+) m", (out / f"{v}.NAVIGATOR.out").read_text()).group(1) for v in data.vehicles
    }
    assert len(firsts) == 3  # the rule shared the front out: three different places
    grade = fg.sampling_section(data)
    assert grade is not None
    print(
        f"map error {grade['team_map_rms_c']:.3f} degC (own samples {grade['own_map_rms_c']:.3f}, "
        f"spread {grade['spread_c']:.2f}); {grade['final']}"
    )
    assert grade["team_map_rms_c"] < 0.15 * grade["spread_c"]
    assert grade["team_map_rms_c"] <= grade["own_map_rms_c"] + 0.01
    for v, f in grade["final"].items():
        # the world's meander (15 m) is not in the straight model: the offset is off by up to that
        assert abs(f["offset_m"]) < 25 and abs(f["angle_rad"]) < 0.05, (v, f)
        assert abs(f["temperature_a_c"]) < 0.1 and abs(f["temperature_b_c"]) < 0.1 and abs(f["width_m"]) < 5, (v, f)


class _Params:
    def __init__(self, **kw):
        self.__dict__.update(kw)


class _Ocean:
    """A world's straight front with no meander, as sim.ocean.fields.Ocean gives it."""

    def __init__(self, offset, angle, ta=16.0, tb=12.0, width=20.0):
        front = _Params(offset_m=offset, angle_rad=angle, width_m=width)
        self.params = _Params(front=front, water_a=_Params(temperature_c=ta), water_b=_Params(temperature_c=tb))
        self.grid = None

    def fields(self, t, north, east, depth):
        f = self.params.front
        x = -north * math.sin(f.angle_rad) + east * math.cos(f.angle_rad) - f.offset_m
        w = 0.5 * (1 + np.tanh(x / f.width_m))
        ta, tb = self.params.water_a.temperature_c, self.params.water_b.temperature_c
        return ta + w * (tb - ta), None


def _estimate(offset, angle, ta=16.0, tb=12.0, width=20.0):
    return {
        "offset_m": offset,
        "angle_rad": angle,
        "temperature_a_c": ta,
        "temperature_b_c": tb,
        "width_m": width,
        "meander": 0.0,
    }


def test_the_grader_on_fronts_made_by_hand():
    ocean = _Ocean(300.0, 0.3)
    gn, ge = np.meshgrid(np.arange(-100, 700, 5.0), np.arange(150, 550, 5.0))
    area = fg.Area(gn.ravel(), ge.ravel(), 5.0, (-100, 700, 150, 550))
    truth = ocean.fields(0, area.north, area.east, 5.0)[0]
    exact = fg.model_temperature(_estimate(300.0, 0.3), area.north, area.east)
    assert np.sqrt(np.mean((exact - truth) ** 2)) < 1e-9
    # the other form of the same front: angle + pi, offset and waters swapped
    assert fg.true_front(_Ocean(-300.0, 0.3 + math.pi, 12.0, 16.0))["offset_m"] == 300.0
    flipped = fg.true_front(_Ocean(-300.0, 0.3 + math.pi, 12.0, 16.0))
    assert math.isclose(flipped["angle_rad"], 0.3) and flipped["temperature_a_c"] == 16.0
    # a front 10 m off: an error in the map, growing with the offset's error
    off10 = fg.model_temperature(_estimate(310.0, 0.3), area.north, area.east)
    off20 = fg.model_temperature(_estimate(320.0, 0.3), area.north, area.east)
    e10, e20 = (float(np.sqrt(np.mean((x - truth) ** 2))) for x in (off10, off20))
    assert 0.05 < e10 < e20
