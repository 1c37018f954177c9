"""The sidescan model: detections against the lateral range curve, nadir gap, false
alarms, determinism, target fields, coverage. In-process, on synthetic tracks."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from sim.config import ConfigError, loads
from sim.model import Truth
from sim.sonar import LateralRangeCurve, SonarConfig, Target, TargetField, TargetFileError, TargetsConfig, coverage_grid
from sim.sonar import targets as tg
from sim.sonar.sidescan import Sidescan

ALONG = 50.0  # the targets' northing: the track passes them going north


def truth(t, north, east=0.0, heading=0.0, altitude=6.0):
    return Truth(
        t=t,
        eta=(north, east, 20.0, 0.0, 0.0, heading),
        nu=(1.5, 0, 0, 0, 0, 0),
        water_depth_m=20.0 + altitude,
        altitude_m=altitude,
    )


def row_of_targets(offsets, kind=tg.MINE_LIKE) -> TargetField:
    return TargetField([Target(i + 1, ALONG, float(y), kind, 1.5) for i, y in enumerate(offsets)], 1, "seed")


def fly_passes(sonar: Sidescan, passes: int, altitude: float, heading_north=True) -> list:
    """Straight passes north from 45 m to 56 m at 1.5 m/s, 20 s apart in time."""
    contacts = []
    t = 0.0
    for _ in range(passes):
        for k in range(int(11.0 / 1.5 * sonar.cfg.update_hz) + 1):
            n = 45.0 + k * 1.5 / sonar.cfg.update_hz
            contacts += sonar.poll(truth(t + k / sonar.cfg.update_hz, n, altitude=altitude))
        t += 20.0
    return contacts


@pytest.mark.parametrize("altitude", [3.0, 6.0, 12.0])
def test_detections_follow_the_lateral_range_curve_over_many_passes(altitude):
    """Each target's detected fraction over N passes against P(y, h): binomial, 4.5 sigma;
    exactly none inside the nadir gap and beyond the far limit."""
    cfg = SonarConfig(false_alarms_per_km2=0.0)
    offsets = np.arange(-60.0, 60.5, 1.0)
    sonar = Sidescan(cfg, row_of_targets(offsets), seed=3, vehicle="AUV1")
    n = 200
    fly_passes(sonar, n, altitude)
    curve = LateralRangeCurve(cfg)
    g, k, far = curve.limits(altitude)
    assert g == pytest.approx(altitude) and far == pytest.approx(min(50.0, altitude / math.tan(cfg.min_grazing_rad)))
    # one look per pass for every target abeam within the far limit, nadir gap included
    assert np.all(sonar.looks == np.where(np.abs(offsets) < far, n, 0))
    for y, hits in zip(offsets, sonar.detections):
        p = curve.pd(y, altitude)
        if p in (0.0, 1.0):
            assert hits == p * n, (y, hits)
        else:
            assert abs(hits / n - p) <= 4.5 * math.sqrt(p * (1 - p) / n), (y, hits / n, p)
    # all targets together: a shift of the curve by a percent would show here
    p_all = np.array([curve.pd(y, altitude) for y in offsets])
    assert abs(sonar.detections.sum() - n * p_all.sum()) <= 4.5 * math.sqrt(n * np.sum(p_all * (1 - p_all)))
    inside_gap = np.abs(offsets) < g
    assert sonar.detections[inside_gap].sum() == 0 and inside_gap.sum() >= 5


def test_sweep_width_is_the_integral_of_the_curve_and_matches_detections():
    cfg = SonarConfig()
    curve = LateralRangeCurve(cfg)
    ys = np.linspace(-80, 80, 160001)
    for h in (2.0, 4.0, 6.0, 10.0, 20.0):
        numeric = np.trapezoid(curve.pd(ys, h), ys)
        assert curve.sweep_width(h) == pytest.approx(numeric, rel=1e-3)
    # W rises with altitude while grazing limits the far range, then falls: the
    # range setting caps F and the nadir gap keeps growing
    w = [curve.sweep_width(h) for h in (2.0, 4.0, 8.0, 20.0, 29.0)]
    assert w[0] < w[1] < w[2] and w[2] > w[3] > w[4]
    assert curve.sweep_width(0.5) == 0.0 and curve.sweep_width(40.0) == 0.0  # out of altitude
    # empirical: detections per pass of a dense row, times the spacing, is W
    sonar = Sidescan(
        SonarConfig(false_alarms_per_km2=0.0), row_of_targets(np.arange(-59.75, 60.0, 0.5)), seed=9, vehicle="AUV1"
    )
    fly_passes(sonar, 60, 6.0)
    assert sonar.detections.sum() * 0.5 / 60 == pytest.approx(curve.sweep_width(6.0), rel=0.03)


def test_false_alarm_rate_and_placement():
    rate = 400.0  # per km^2: high, so the count says something
    cfg = SonarConfig(false_alarms_per_km2=rate)
    sonar = Sidescan(cfg, TargetField([], 1, "seed"), seed=4, vehicle="AUV1")
    contacts = []
    updates = int(20000 / 0.3)  # 20 km north at 0.3 m per update
    for k in range(updates):
        contacts += sonar.poll(truth(k * 0.2, k * 0.3, altitude=6.0))
    g, far = LateralRangeCurve(cfg).imaged_band(6.0)
    run = (updates - 1) * 0.3
    expected = rate * 2 * (far - g) * run / 1e6
    assert sonar.imaged_area_m2 == pytest.approx(2 * (far - g) * run, rel=1e-6)
    assert len(contacts) == sonar.false_alarms
    assert abs(len(contacts) - expected) <= 4.5 * math.sqrt(expected), (len(contacts), expected)
    east = np.array([c.east_m for c in contacts])  # heading north: across track is east
    # placed in the imaged band on both sides (plus the sonar's range error)
    assert np.all((np.abs(east) > g - 1.5) & (np.abs(east) < far + 1.5))
    assert abs(np.mean(east > 0) - 0.5) < 0.05
    assert {c.classification for c in contacts} == {"mine_like", "unknown"}


def test_same_seed_same_contacts_other_seed_not():
    def run(seed):
        cfg = SonarConfig(false_alarms_per_km2=200.0)
        sonar = Sidescan(cfg, row_of_targets(np.arange(-40, 41, 4.0)), seed=seed, vehicle="AUV1")
        return [(c.contact_id, c.north_m, c.east_m, c.classification, c.confidence) for c in fly_passes(sonar, 20, 6.0)]

    a, b, c = run(1), run(1), run(2)
    assert a == b and a != c and len(a) > 50


def test_contact_position_error_and_fields():
    cfg = SonarConfig(false_alarms_per_km2=0.0, along_track_sigma_m=0.5, range_sigma_m=0.3, pd_max=1.0)
    sonar = Sidescan(cfg, row_of_targets([-20.0, 25.0]), seed=5, vehicle="AUV1", nav_error=lambda: (3.0, -2.0))
    contacts = fly_passes(sonar, 400, 6.0)
    assert len(contacts) == 800
    port = [c for c in contacts if c.side == 0]
    stbd = [c for c in contacts if c.side == 1]
    assert len(port) == len(stbd) == 400
    dn = np.array([c.north_m - ALONG for c in stbd]) - 3.0  # minus the navigation error
    de = np.array([c.east_m - 25.0 for c in stbd]) + 2.0
    assert dn.std() == pytest.approx(0.5, rel=0.12) and abs(dn.mean()) < 0.1
    assert de.std() == pytest.approx(0.3, rel=0.12) and abs(de.mean()) < 0.1
    c = stbd[0]
    assert c.vehicle == "AUV1" and c.slant_range_m == pytest.approx(math.hypot(c.ground_range_m, 6.0))
    assert c.position_sigma_m == pytest.approx(math.hypot(0.5, 0.3))
    assert [m.contact_id for m in contacts] == list(range(1, 801))
    # classification = score >= threshold, the score of a mine from Beta(6, 2)
    assert np.mean([m.classification == "mine_like" for m in contacts]) == pytest.approx(
        beta_above(6, 2, 0.5), abs=0.03
    )
    assert {m.classification for m in contacts} == {"mine_like", "unknown"}


def beta_above(a: int, b: int, x: float) -> float:
    """P(Beta(a, b) >= x) for whole a, b: P(Binomial(a + b - 1, x) < a)."""
    n = a + b - 1
    return sum(math.comb(n, k) * x**k * (1 - x) ** (n - k) for k in range(a))


def test_scores_follow_the_confusion_model_and_set_the_classification():
    """Mines' scores from Beta(mine_a, mine_b), clutter's and false alarms' from
    Beta(clutter_a, clutter_b): means, the fraction over the threshold, the overlap."""
    from sim.sonar import ScoreModel

    cfg = SonarConfig(
        false_alarms_per_km2=0.0,
        pd_max=1.0,
        score=ScoreModel(mine_a=5, mine_b=3, clutter_a=2, clutter_b=4, threshold=0.6),
    )
    mines = Sidescan(cfg, row_of_targets([-20.0, 25.0]), seed=8, vehicle="AUV1")
    clutter = Sidescan(cfg, row_of_targets([-20.0, 25.0], kind=tg.CLUTTER), seed=8, vehicle="AUV1")
    cm, cc = fly_passes(mines, 500, 6.0), fly_passes(clutter, 500, 6.0)
    sm = np.array([c.confidence for c in cm])
    sc = np.array([c.confidence for c in cc])
    assert len(sm) == len(sc) == 1000
    assert sm.mean() == pytest.approx(5 / 8, abs=0.02) and sc.mean() == pytest.approx(2 / 6, abs=0.02)
    assert np.mean(sm >= 0.6) == pytest.approx(beta_above(5, 3, 0.6), abs=0.05)
    assert np.mean(sc >= 0.6) == pytest.approx(beta_above(2, 4, 0.6), abs=0.03)
    assert 0 < np.mean(sc >= 0.6) and np.mean(sm < 0.6) > 0  # they overlap
    for c in cm:
        assert c.classification == ("mine_like" if c.confidence >= np.float32(0.6) else "unknown")
    for c in cc:
        assert c.classification == ("mine_like" if c.confidence >= np.float32(0.6) else "clutter")
    # false alarms are scored like clutter
    fa = Sidescan(SonarConfig(false_alarms_per_km2=5000.0, score=cfg.score), row_of_targets([]), seed=2, vehicle="AUV1")
    sf = np.array([c.confidence for k in range(3000) for c in fa.poll(truth(k * 0.2, k * 0.3))])
    assert len(sf) > 300 and sf.mean() == pytest.approx(2 / 6, abs=0.03)


def test_score_model_config_is_checked_and_the_old_keys_say_what_replaced_them():
    with pytest.raises(ConfigError) as exc:
        loads("sonar:\n  p_classify: 0.8\n  score: {mine_a: 0, threshold: 1.5, clutter_bb: 3}\n", Path("c.yaml"))
    assert exc.value.errors == [
        "c.yaml:2:3: sonar.p_classify: replaced by the score model sonar.score (mine_a, mine_b, "
        "clutter_a, clutter_b, threshold; docs/simulator.md)",
        "c.yaml:3:19: sonar.score.mine_a: must be in (0, 1000]",
        "c.yaml:3:33: sonar.score.threshold: must be in [0, 1]",
        "c.yaml:3:38: sonar.score.clutter_bb: unknown key; did you mean 'clutter_b'?",
    ]
    s = loads("sonar:\n  score: {mine_a: 9, threshold: 0.7}\n").sonar.score
    assert (s.mine_a, s.mine_b, s.threshold) == (9, 2, 0.7)


def test_no_image_when_rolling_hard_or_out_of_altitude():
    sonar = Sidescan(SonarConfig(pd_max=1.0), row_of_targets([20.0]), seed=1, vehicle="AUV1")
    for k in range(40):  # too high above the seabed: passes unlooked
        sonar.poll(truth(k * 0.2, 45 + k * 0.3, altitude=35.0))
    assert sonar.looks[0] == 0
    tr = [truth(100 + k * 0.2, 45 + k * 0.3) for k in range(40)]
    for x in tr:
        x.eta = x.eta[:3] + (0.4,) + x.eta[4:]  # 23 deg of roll
        sonar.poll(x)
    assert sonar.looks[0] == 0


# ------------------------------------------------------------ target fields
def test_targets_placed_by_seed_in_the_area_apart_and_reproducible():
    tc = TargetsConfig(mines=12, clutter=40, min_separation_m=8.0)
    tc.area.north_m, tc.area.east_m, tc.area.length_m, tc.area.width_m = 100, -50, 300, 200
    f1 = tg.place(tc, 7, lambda n, e: 30.0 + 0.01 * n)
    f2 = tg.place(tc, 7, lambda n, e: 30.0 + 0.01 * n)
    f3 = tg.place(tc, 8, lambda n, e: 30.0 + 0.01 * n)
    assert [(t.north_m, t.east_m) for t in f1.targets] == [(t.north_m, t.east_m) for t in f2.targets]
    assert [(t.north_m, t.east_m) for t in f1.targets] != [(t.north_m, t.east_m) for t in f3.targets]
    assert len(f1.mines()) == 12 and len(f1.targets) == 52
    pts = np.array([(t.north_m, t.east_m) for t in f1.targets])
    assert np.all((pts[:, 0] >= 100) & (pts[:, 0] <= 400) & (pts[:, 1] >= -50) & (pts[:, 1] <= 150))
    d = np.hypot(pts[:, None, 0] - pts[None, :, 0], pts[:, None, 1] - pts[None, :, 1])
    assert d[np.triu_indices(len(pts), 1)].min() >= 8.0
    assert f1.targets[0].depth_m == pytest.approx(30.0 + 0.01 * f1.targets[0].north_m)
    msg = f1.to_lcm(5, "bay")
    from auv import target_field_t

    back = target_field_t.decode(msg.encode())
    assert back.n_targets == 52 and back.seed == 7 and back.world == "bay"
    assert sum(t.kind == 0 for t in back.targets) == 12


def test_target_file_is_read_and_its_errors_name_the_line(tmp_path):
    good = tmp_path / "t.csv"
    good.write_text("# two objects\nid,north_m,east_m,kind,length_m\n1,10,5,mine_like,1.5\n2,20,-5,clutter,0.5\n")
    f = tg.load(good, lambda n, e: 40.0)
    assert [(t.id, t.kind, t.depth_m) for t in f.targets] == [(1, "mine_like", 40.0), (2, "clutter", 40.0)]
    assert f.seed == 0 and f.source == str(good)
    bad = tmp_path / "bad.csv"
    bad.write_text(
        "id,north_m,east_m,kind,length_m\n1,10,5,mine,1\n1,x,5,clutter,1\n2,1,2,clutter,1\n2,1,2,clutter,1\n3,1,2\n"
    )
    with pytest.raises(TargetFileError) as exc:
        tg.load(bad, lambda n, e: 0.0)
    lines = str(exc.value).splitlines()
    assert [ln.split(": ")[0] for ln in lines] == [f"{bad}:2", f"{bad}:3", f"{bad}:5", f"{bad}:6"]
    assert "kind 'mine'" in lines[0] and "duplicate id 2" in lines[2]


def test_sonar_config_errors_name_key_and_line(tmp_path):
    with pytest.raises(ConfigError) as exc:
        loads(
            "sonar:\n  range_m: -5\n  knee_fraction: 1.5\n  targets:\n    mines: 2.5\n"
            "    area: {widht_m: 3}\n  publish_targets: maybe\n",
            Path("c.yaml"),
        )
    assert exc.value.errors == [
        "c.yaml:2:12: sonar.range_m: must be > 0",
        "c.yaml:3:18: sonar.knee_fraction: must be in [0, 1]",
        "c.yaml:5:12: sonar.targets.mines: expected an integer, got '2.5'",
        "c.yaml:6:12: sonar.targets.area.widht_m: unknown key; did you mean 'width_m'?",
        "c.yaml:7:20: sonar.publish_targets: expected one of: auto, yes, no, got 'maybe'",
    ]
    (tmp_path / "t.csv").write_text("id,north_m,east_m,kind,length_m\n1,0,0,rock,1\n")
    cfgfile = tmp_path / "s.yaml"
    cfgfile.write_text("sonar:\n  targets: {file: t.csv}\n")
    with pytest.raises(ConfigError) as exc:
        from sim.config import load

        load(cfgfile)
    assert exc.value.errors == [
        f"{cfgfile}:2:19: sonar.targets: {tmp_path / 't.csv'}:2: kind 'rock' is not one of mine_like, clutter"
    ]
    assert loads("sonar: false\n").sonar is None
    assert loads("environment: {seed: 11}\nsonar: {}\n").sonar.targets.seed == 11


# ------------------------------------------------------------------ coverage
def test_coverage_counts_looks_per_pass_and_their_detection_probability():
    cfg = SonarConfig()
    curve = LateralRangeCurve(cfg)
    h = 6.0
    n = np.arange(0.0, 200.0, 0.15)  # north along east = 0
    g, k, far = curve.limits(h)
    cov = coverage_grid(
        n, np.zeros_like(n), np.zeros_like(n), np.full_like(n, h), curve, cell=1.0, bounds=(0, 200, -60, 60)
    )
    cn, ce = cov.centres()
    row = np.searchsorted(cn, 100.0)
    for j, e in enumerate(ce):
        y = abs(e)
        if g + 0.5 < y < far - 0.5:
            assert cov.looks[row, j] == 1
            assert cov.pd[row, j] == pytest.approx(curve.pd(y, h), abs=0.05)
        elif y < g - 0.5 or y > far + 0.5:
            assert cov.looks[row, j] == 0 and cov.pd[row, j] == 0.0
    assert cov.area_with(1) == pytest.approx(200 * 2 * (far - g), rel=0.03)
    # the same line back south is a second pass: two looks, 1 - (1 - P)^2
    n2 = np.concatenate([n, n[::-1]])
    yaw = np.concatenate([np.zeros_like(n), np.full_like(n, math.pi)])
    cov2 = coverage_grid(n2, np.zeros_like(n2), yaw, np.full_like(n2, h), curve, cell=1.0, bounds=(0, 200, -60, 60))
    j = np.searchsorted(ce, 20.0)
    assert cov2.looks[row, j] == 2
    assert cov2.pd[row, j] == pytest.approx(1 - (1 - curve.pd(ce[j], h)) ** 2, abs=0.01)
    assert cov2.area_with(2) == pytest.approx(cov.area_with(1), rel=0.03)
