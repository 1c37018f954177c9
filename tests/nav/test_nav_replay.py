"""The filter on simulated surveys, through the replay driver (the same code
as auv-nav, deterministic and fast): consistency against ground truth, LBL
outliers, GPS loss, DVL dropout, water track, startup and undecodable
messages.

NEES bounds. The time-averaged NEES of one run is not chi-square distributed
(consecutive samples are correlated), so the bounds here are stated per
quantity: for position (2 dof), samples every 30 s of an LBL-aided run are
treated as independent (each ping every 10 s renews the position error) and
their mean must lie in the two-sided 99 % interval of chi-square(2K)/K; the
run-averaged heading (1 dof), velocity (3 dof) and depth (1 dof) NEES must lie
within [0.25, 2.5] times their degrees of freedom, a band that rejects a filter
off by a factor of two in standard deviation either way. Monte Carlo bounds
with 100 runs are in the C++ unit tests (test_consistency.cpp)."""

from __future__ import annotations

import bisect
import csv
import math
import struct

import lcm
import pytest
from nav_common import TruthTrack, replay
from nav_fixtures import survey, water_track_survey  # noqa: F401 (fixtures)

from auvlcm.log import read_events


def _rows(path):
    return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open(path))]


def _chi2_99(dof: float) -> tuple[float, float]:
    """Wilson-Hilferty two-sided 99 % interval of chi-square(dof)."""
    a = 2.0 / (9.0 * dof)
    return tuple(dof * (1 - a + z * math.sqrt(a)) ** 3 for z in (-2.5758, 2.5758))


def test_nees_is_consistent_on_the_lbl_aided_survey(survey, tmp_path):
    out = tmp_path / "est.csv"
    s = replay(survey.nav_config, survey.log, "--csv", out)
    rows = _rows(out)
    samples = [r["nees_pos"] for r in rows if r["t_s"] >= 60 and abs(r["t_s"] / 30 - round(r["t_s"] / 30)) < 1e-6]
    k = len(samples)
    lo, hi = _chi2_99(2 * k)
    mean = sum(samples) / k
    assert k >= 10 and lo / k <= mean <= hi / k, (mean, lo / k, hi / k, k)
    assert 0.25 <= s["nees_heading_mean"] <= 2.5, s
    assert 0.75 <= s["nees_vel_mean"] <= 7.5, s
    assert 0.25 <= s["nees_depth_mean"] <= 2.5, s
    assert s["h_err_rms_m"] < 1.5 and s["trusted_fraction"] > 0.95, s
    assert s["altitude_err_mean_m"] < 0.2 and s["altitude_unknown_fraction"] < 0.01, s
    assert s["undecodable_total"] == 0 and s["truth_skipped"] == 0


def test_lbl_long_outliers_are_gated(survey, tmp_path):
    """Every reply is scored against the true range from ground truth: the
    long outliers the simulator injects are rejected, good replies kept, and
    without the gate the same data gives a worse track."""
    lbl = tmp_path / "lbl.csv"
    gated = replay(survey.nav_config, survey.log, "--lbl-csv", lbl)
    truth = TruthTrack(survey.log)
    xt = {}
    for line in survey.nav_config.read_text().splitlines():
        if line.startswith("transponder "):
            _, i, n, e, d, _ = line.split()
            xt[int(i)] = (float(n), float(e), float(d))
    outliers = good = outliers_rejected = good_accepted = 0
    for r in _rows(lbl):
        if r["accepted"] < 0:
            continue
        x = xt[int(r["id"])]
        p0 = truth.at(r["t_s"])
        p1 = truth.at(r["t_s"] + r["two_way_travel_s"])
        true_range = (math.dist(x, p0) + math.dist(x, p1)) / 2
        err = r["range_m"] - true_range
        if err > 8.0:  # > 6 sigma: a multipath outlier
            outliers += 1
            outliers_rejected += r["accepted"] == 0
        elif abs(err) < 3 * 1.25:
            good += 1
            good_accepted += r["accepted"] == 1
    assert outliers >= 2, "the recorded survey should contain long LBL outliers (5 % per reply)"
    assert outliers_rejected == outliers
    assert good_accepted >= 0.97 * good and good > 50
    cfg = survey.nav_config.parent / "nogate.nav"
    cfg.write_text(survey.nav_config.read_text() + "gate_probability 1\n")
    ungated = replay(cfg, survey.log)
    assert ungated["lbl_rejected"] == 0
    assert ungated["h_err_rms_m"] > 1.2 * gated["h_err_rms_m"], (ungated["h_err_rms_m"], gated["h_err_rms_m"])


def test_gps_loss_dead_reckons_without_divergence(survey, tmp_path):
    """GPS only for the first 20 s, no LBL: compass + DVL dead reckoning. The
    error grows with distance as the 1 deg compass bias makes it (about 1.7 %
    of the displacement), and the covariance grows with it: largest at the far
    end of the first line, smaller again when the second line comes back
    (a heading bias rotates the whole track about its start)."""
    out = tmp_path / "dr.csv"
    s = replay(survey.nav_config, survey.log, "--drop", "gps:20:1e9", "--drop", "lbl", "--csv", out)
    rows = _rows(out)
    assert s["gps_accepted"] <= 21 and s["lbl_accepted"] == 0
    for r in rows[::50]:
        if r["distance_m"] > 50:
            assert r["h_err_m"] < 0.03 * r["distance_m"] + 3, r
    assert s["nees_pos_max"] < 20.0 and 0.1 < s["nees_pos_mean"] < 6.0, s
    far = max(rows, key=lambda r: math.hypot(r["true_n"], r["true_e"]))
    at_20s = next(r for r in rows if r["t_s"] >= 20)
    sd = lambda r: math.hypot(r["sd_n"], r["sd_e"])  # noqa: E731
    assert math.hypot(far["true_n"], far["true_e"]) > 250
    assert sd(far) > 3 * sd(at_20s), (sd(far), sd(at_20s))
    assert far["h_err_m"] < 3 * sd(far)
    assert s["gps_resets"] == 0 and s["dvl_resets"] == 0 and s["ahrs_resets"] == 0


def test_dvl_dropout_degrades_then_recovers(survey, tmp_path):
    out = tmp_path / "dvl.csv"
    s = replay(survey.nav_config, survey.log, "--drop", "dvl:200:260", "--csv", out)
    rows = _rows(out)
    during = [r for r in rows if 212 <= r["t_s"] <= 260]
    after = [r for r in rows if r["t_s"] >= 300]
    assert during and all(int(r["status"]) & 32 for r in during)  # DEGRADED
    assert all(not r["trusted"] for r in during)
    assert sum(r["trusted"] for r in after) > 0.95 * len(after)
    assert max(r["h_err_m"] for r in rows) < 10.0, s
    assert max(r["h_err_m"] for r in after) < 4.0
    assert max(r["nees_pos"] for r in rows) < 30.0


def test_startup_aligns_on_the_first_gps_fix(survey):
    s = replay(survey.nav_config, survey.log)
    assert s["align_time_s"] == 0.0 and s["aligned_samples"] == s["truth_samples"]
    late = replay(survey.nav_config, survey.log, "--drop", "gps:0:20.5")
    first_fix = min(
        ev.msg.utime / 1e6 for ev in read_events(survey.log) if ev.channel == "AUV1.GPS" and ev.msg.utime / 1e6 > 20.5
    )
    assert late["align_time_s"] == pytest.approx(first_fix, abs=0.15)
    assert late["aligned_samples"] < late["truth_samples"] - 200
    assert late["h_err_rms_m"] < 2.0


def test_water_track_estimates_the_current(water_track_survey, tmp_path):
    out = tmp_path / "wt.csv"
    s = replay(water_track_survey.nav_config, water_track_survey.log, "--csv", out)
    assert s["dvl_accepted"] > 500
    every = _rows(out)
    rows = [r for r in every if r["t_s"] > 120]
    # The true water velocity at the vehicle carries the swell's orbital motion,
    # which the hull now rides (waves act as forces): water track cannot see it
    # and no filter state should follow it. The current is its mean over two
    # wave periods (12 s).
    t = [r["t_s"] for r in every]

    def mean_current(t0: float) -> tuple[float, float]:
        lo, hi = bisect.bisect_left(t, t0 - 6.0), bisect.bisect_right(t, t0 + 6.0)
        seg = every[lo:hi]
        return sum(r["true_cn"] for r in seg) / len(seg), sum(r["true_ce"] for r in seg) / len(seg)

    dc = []
    for r in rows:
        cn, ce = mean_current(r["t_s"])
        dc.append(math.hypot(r["est_cn"] - cn, r["est_ce"] - ce))
    assert sum(dc) / len(dc) < 0.05, sum(dc) / len(dc)
    assert s["h_err_rms_m"] < 3.0 and s["nees_pos_mean"] < 6.0, s
    assert all(int(r["status"]) & 4 for r in rows[::20])  # DVL_WATER


def test_undecodable_messages_are_counted_and_dropped(survey, tmp_path):
    """The log again with garbage on sensor channels: counted per channel,
    never used, and the estimate is exactly the clean one."""
    dirty = tmp_path / "dirty.lcmlog"
    src = lcm.EventLog(str(survey.log), "r")
    dst = lcm.EventLog(str(dirty), "w", overwrite=True)
    n = 0
    for ev in src:
        dst.write_event(ev.timestamp, ev.channel, ev.data)
        if ev.channel == "AUV1.DVL" and n < 3:
            dst.write_event(ev.timestamp, "AUV1.DVL", ev.data[:-5])  # truncated
            dst.write_event(ev.timestamp, "AUV1.LBL", struct.pack(">q", 42) + b"junk")  # wrong type
            n += 1
    src.close()
    dst.close()
    clean = replay(survey.nav_config, survey.log)
    got = replay(survey.nav_config, dirty)
    assert got["undecodable AUV1.DVL"] == 3 and got["undecodable AUV1.LBL"] == 3
    assert got["undecodable_total"] == 6
    for key in ("h_err_rms_m", "h_err_final_m", "nees_pos_mean", "dvl_accepted", "lbl_accepted"):
        assert got[key] == clean[key], key
