"""The reacquire-identify sensor (`identify:`): looks within range and altitude,
p_identify, p_correct, position noise, determinism, configuration errors; in
process on synthetic tracks, and once in the simulator process over LCM."""

from __future__ import annotations

import math
from pathlib import Path

import lcm
import numpy as np
import pytest

from auv import reacquire_look_t
from sim.config import ConfigError, loads
from sim.model import Truth
from sim.sonar import Target, TargetField
from sim.sonar.identify import Identify, IdentifyConfig

ROOT = Path(__file__).resolve().parents[2]
MINE, NOT_MINE = reacquire_look_t.RESULT_MINE, reacquire_look_t.RESULT_NOT_MINE


def truth(t, north=0.0, east=0.0, altitude=4.0):
    return Truth(
        t=t,
        eta=(north, east, 20.0, 0.0, 0.0, 0.0),
        nu=(1.0, 0, 0, 0, 0, 0),
        water_depth_m=20.0 + altitude,
        altitude_m=altitude,
    )


# objects around the origin: 1 (mine) at 3 m, 2 (clutter) at 5 m, 3 (mine) at 6.5 m
FIELD = TargetField(
    [
        Target(1, 3.0, 0.0, "mine_like", 1.5),
        Target(2, 0.0, -5.0, "clutter", 0.8),
        Target(3, 0.0, 6.5, "mine_like", 1.5),
    ],
    1,
    "seed",
)


def hover(model: Identify, seconds: int, altitude=4.0) -> list:
    out = []
    for k in range(seconds * 10):  # polled at 10 Hz, looks at 1 Hz
        out += model.poll(truth(k / 10, altitude=altitude))
    return out


def nearest(look) -> Target:
    return min(FIELD.targets, key=lambda t: math.hypot(t.north_m - look.north_m, t.east_m - look.east_m))


def test_looks_follow_p_identify_and_p_correct_within_range_only():
    cfg = IdentifyConfig(range_m=6.0, p_identify=0.4, p_correct=0.8, position_sigma_m=0.3)
    model = Identify(cfg, FIELD, seed=3, vehicle="AUV4")
    n = 3000
    looks = hover(model, n)
    assert model.tries == 2 * n  # objects 1 and 2 in range, 3 beyond
    by = {1: [], 2: []}
    for m in looks:
        by[nearest(m).id].append(m)
    assert set(by) == {1, 2} and len(looks) == len(by[1]) + len(by[2])
    for k in (1, 2):  # binomial, 4.5 sigma
        assert abs(len(by[k]) - 0.4 * n) < 4.5 * math.sqrt(n * 0.4 * 0.6)
    right = sum(m.result == MINE for m in by[1]) + sum(m.result == NOT_MINE for m in by[2])
    assert abs(right - 0.8 * len(looks)) < 4.5 * math.sqrt(len(looks) * 0.8 * 0.2)
    dn = np.array([m.north_m - 3.0 for m in by[1]])
    assert dn.std() == pytest.approx(0.3, rel=0.1) and abs(dn.mean()) < 0.05
    m = by[1][0]
    assert m.vehicle == "AUV4" and m.range_m == pytest.approx(3.0) and m.position_sigma_m == 0.3
    assert [x.look_id for x in looks] == list(range(1, len(looks) + 1))
    assert len({x.utime for x in looks}) <= n  # once per period at most
    assert all(x.utime % 1_000_000 == 0 for x in looks)


def test_no_looks_too_high_and_the_navigation_error_moves_them():
    cfg = IdentifyConfig(p_identify=1.0, p_correct=1.0, position_sigma_m=0.0, max_altitude_m=8.0)
    assert hover(Identify(cfg, FIELD, 1, "AUV4"), 50, altitude=9.0) == []
    looks = hover(Identify(cfg, FIELD, 1, "AUV4", nav_error=lambda: (2.0, -1.0)), 5, altitude=7.9)
    assert len(looks) == 10  # two objects in range, every look
    assert {(m.north_m, m.east_m, m.result) for m in looks} == {(5.0, -1.0, MINE), (2.0, -6.0, NOT_MINE)}


def test_same_seed_same_looks_other_seed_not():
    def run(seed):
        cfg = IdentifyConfig(range_m=8.0, p_identify=0.5, p_correct=0.7)
        return [(m.look_id, m.north_m, m.east_m, m.result) for m in hover(Identify(cfg, FIELD, seed, "AUV4"), 200)]

    a, b, c = run(5), run(5), run(6)
    assert a == b and a != c and len(a) > 100


def test_identify_config_errors_name_key_and_line():
    with pytest.raises(ConfigError) as exc:
        loads("identify:\n  range_m: 0\n  p_correct: 1.2\n  perod_s: 2\n", Path("c.yaml"))
    assert exc.value.errors == [
        "c.yaml:2:12: identify.range_m: must be in (0, 200]",
        "c.yaml:3:14: identify.p_correct: must be in [0, 1]",
        "c.yaml:4:3: identify.perod_s: unknown key; did you mean 'period_s'?",
    ]
    with pytest.raises(ConfigError) as exc:
        loads("sonar: {}\nidentify:\n  targets: {mines: 3}\n", Path("c.yaml"))
    assert exc.value.errors == [
        "c.yaml:3:3: identify.targets: this configuration has a sonar section: "
        "its targets are the field (give the field in one place)"
    ]
    with pytest.raises(ConfigError) as exc:
        loads(
            "identify:\n  targets: {mines: 50, min_separation_m: 100, area: {length_m: 50, width_m: 50}}\n",
            Path("c.yaml"),
        )
    assert exc.value.errors[0].startswith("c.yaml:2:20: identify.targets: cannot place")
    cfg = loads("environment: {seed: 4}\nidentify: {range_m: 8}\n")
    assert cfg.identify.range_m == 8 and cfg.identify.targets.seed == 4
    assert loads("identify: false\n").identify is None and loads("{}\n").identify is None


CONFIG = """
vehicle: {{id: AUV4}}
simulation: {{clock: lockstep, lcm_url: "{url}"}}
initial: {{depth_m: 5.0, speed_mps: 1.5, prop_rpm: 1500}}
environment: {{seed: 5, bathymetry: "flat:depth=10"}}
sensors: {{ins: {{rate_hz: 25, bias: 0.0}}, depth: {{}}}}
identify:
  range_m: 6
  p_identify: 1.0
  p_correct: 1.0
  position_sigma_m: 0.2
  targets: {{file: targets.csv}}
"""
# along the track north at east 0: in range (<= 6 m) 1, 2 and 4; 3 is 9 m off
TARGETS = [
    (1, 15.0, 2.0, "mine_like"),
    (2, 25.0, -4.0, "clutter"),
    (3, 30.0, 9.0, "mine_like"),
    (4, 40.0, 5.0, "mine_like"),
]


def test_looks_over_lcm_from_the_simulator(tmp_path, child_env, lcm_url):
    from lcm_proc import start_simulator, stop
    from lockstep import LockstepPilot
    from test_hil_lcm import Recorder

    (tmp_path / "targets.csv").write_text(
        "id,north_m,east_m,kind,length_m\n" + "".join(f"{i},{n},{e},{k},1.0\n" for i, n, e, k in TARGETS)
    )
    cfg = tmp_path / "sim.yaml"
    cfg.write_text(CONFIG.format(url=lcm_url))
    lc = lcm.LCM(lcm_url)
    rec = Recorder(lc)
    rec.sub("AUV4.LOOKS", reacquire_look_t)
    pilot = LockstepPilot(lc, "AUV4", depth_m=5.0)
    proc = start_simulator(cfg, child_env)
    try:
        pilot.fly(32.0)  # past the last object at 40 m north (and 6 m beyond)
        lc.handle_timeout(100)
    finally:
        assert stop(proc) == 0
    looks = rec.msgs["AUV4.LOOKS"]
    seen = {}
    for m in looks:
        t = min(TARGETS, key=lambda x: math.hypot(m.north_m - x[1], m.east_m - x[2]))
        assert math.hypot(m.north_m - t[1], m.east_m - t[2]) < 1.5
        assert m.vehicle == "AUV4" and m.range_m <= 6.0
        assert m.result == (MINE if t[3] == "mine_like" else NOT_MINE)  # p_correct 1
        seen.setdefault(t[0], []).append(m.utime)
    assert set(seen) == {1, 2, 4}, seen
    assert [m.look_id for m in looks] == list(range(1, len(looks) + 1))
    # every second while in range: a 6 m radius crossed at about 1.5 m/s
    assert all(len(v) >= 3 for v in seen.values())
    assert all(u % 1_000_000 == 0 for u in (m.utime for m in looks))
