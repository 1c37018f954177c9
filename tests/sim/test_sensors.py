"""Sensor statistics: noise and bias as configured, availability rules."""

from __future__ import annotations

import math

import numpy as np
import pytest

from auv import dvl_t
from sim.environment import Environment, EnvParams, Transponder
from sim.geo import LocalFrame
from sim.model import Truth
from sim.sensors import (
    Ahrs,
    AhrsConfig,
    Altimeter,
    AltimeterConfig,
    DepthConfig,
    DepthSensor,
    Dvl,
    DvlConfig,
    Gps,
    GpsConfig,
    Ins,
    InsConfig,
    Lbl,
    LblConfig,
)

N = 4000


def truth(
    t=0.0,
    eta=(10.0, -5.0, 20.0, 0.0, 0.0, 1.0),
    nu=(1.5, 0.0, 0.0, 0, 0, 0.01),
    water_depth=45.0,
    current=(0.0, 0.0, 0.0),
):
    return Truth(t=t, eta=eta, nu=nu, current_ned=current, water_depth_m=water_depth, altitude_m=water_depth - eta[2])


def run(sensor, make_truth, n=N, rate=None):
    out = []
    dt = 1.0 / (rate or sensor.cfg.rate_hz)
    for i in range(n):
        msg = sensor.poll(make_truth(i * dt))
        if msg is not None:
            out.append(msg)
    return out


def test_ahrs_heading_bias_and_noise_match_config():
    cfg = AhrsConfig(noise=math.radians(0.5), bias=math.radians(2.0))
    msgs = run(Ahrs(cfg, seed=7, vehicle="AUV1"), lambda t: truth(t))
    err = np.array([(m.heading_rad - 1.0 + math.pi) % (2 * math.pi) - math.pi for m in msgs])
    assert len(msgs) == N
    assert err.mean() == pytest.approx(cfg.bias, abs=4 * cfg.noise / math.sqrt(N))
    assert err.std() == pytest.approx(cfg.noise, rel=0.05)


def test_depth_bias_noise_and_dropouts():
    cfg = DepthConfig(noise=0.05, bias=0.3, dropout=0.2)
    msgs = run(DepthSensor(cfg, seed=3, vehicle="AUV1"), lambda t: truth(t))
    valid = np.array([m.depth_m for m in msgs if m.valid])
    assert len(msgs) == N
    assert 1 - len(valid) / N == pytest.approx(0.2, abs=0.03)
    assert valid.mean() - 20.0 == pytest.approx(0.3, abs=0.01)
    assert valid.std() == pytest.approx(0.05, rel=0.06)
    assert msgs[0].pressure_pa > 101325 + 1025 * 9.81 * 19


def test_same_seed_same_measurements_other_seed_not():
    a = run(DepthSensor(DepthConfig(noise=0.1), 5, "AUV1"), truth, n=50)
    b = run(DepthSensor(DepthConfig(noise=0.1), 5, "AUV1"), truth, n=50)
    c = run(DepthSensor(DepthConfig(noise=0.1), 6, "AUV1"), truth, n=50)
    assert [m.depth_m for m in a] == [m.depth_m for m in b]
    assert [m.depth_m for m in a] != [m.depth_m for m in c]


def test_sensor_keeps_its_rate_when_polled_at_physics_rate():
    s = DepthSensor(DepthConfig(rate_hz=10.0), 1, "AUV1")
    msgs = run(s, truth, n=50 * 20, rate=50.0)  # 20 s at 50 Hz
    assert len(msgs) == 200


def test_dvl_bottom_lock_below_max_altitude_else_water_track_or_nothing():
    cfg = DvlConfig(noise=0.01, max_altitude_m=30.0, water_track=True)
    cur = (0.2, 0.0, 0.0)
    low = run(Dvl(cfg, 1, "AUV1"), lambda t: truth(t, water_depth=45.0, current=cur), n=500)
    high = run(Dvl(cfg, 1, "AUV1"), lambda t: truth(t, water_depth=90.0, current=cur), n=500)
    assert all(m.mode == dvl_t.MODE_BOTTOM_LOCK for m in low)
    assert np.mean([m.velocity_mps[0] for m in low]) == pytest.approx(1.5, abs=0.002)
    assert all(m.mode == dvl_t.MODE_WATER_TRACK for m in high)
    # through the water: surge minus the current's body-x part (heading 1 rad)
    assert np.mean([m.velocity_mps[0] for m in high]) == pytest.approx(1.5 - 0.2 * math.cos(1.0), abs=0.002)
    none_cfg = DvlConfig(max_altitude_m=30.0, water_track=False)
    gone = run(Dvl(none_cfg, 1, "AUV1"), lambda t: truth(t, water_depth=90.0), n=100)
    assert all(m.mode == dvl_t.MODE_NONE for m in gone)
    assert np.mean([m.beam_range_m[0] for m in low]) == pytest.approx(25.0 / math.cos(math.radians(30)), abs=0.01)


def test_altimeter_range_against_bathymetry_and_its_limit():
    cfg = AltimeterConfig(noise=0.05, bias=0.1, max_range_m=50.0)
    msgs = run(Altimeter(cfg, 2, "AUV1"), lambda t: truth(t, water_depth=45.0))
    rng = np.array([m.range_m for m in msgs])
    assert rng.mean() == pytest.approx(25.1, abs=0.005)
    assert rng.std() == pytest.approx(0.05, rel=0.06)
    far = run(Altimeter(cfg, 2, "AUV1"), lambda t: truth(t, water_depth=100.0), n=50)
    assert not any(m.valid for m in far)


def test_gps_only_at_the_surface():
    frame = LocalFrame(41.5, -70.7)
    cfg = GpsConfig(noise=2.0, max_depth_m=0.2)
    s = Gps(cfg, 4, "AUV1", frame)
    depths = [0.0 if (i // 100) % 2 == 0 else 5.0 for i in range(N)]
    fixes, surfaced = [], 0
    for i, d in enumerate(depths):
        m = s.poll(truth(float(i), eta=(10.0, -5.0, d, 0, 0, 1.0)))
        surfaced += d <= 0.2
        if m is not None:
            assert d <= 0.2
            fixes.append(m)
    assert len(fixes) == surfaced
    north = np.array([f.north_m for f in fixes])
    assert north.std() == pytest.approx(2.0, rel=0.07)
    lat, lon = frame.to_latlon(fixes[0].north_m, fixes[0].east_m)
    assert (fixes[0].latitude_deg, fixes[0].longitude_deg) == pytest.approx((lat, lon))


def lbl_env(gradient=0.0):
    return Environment(
        EnvParams(
            sound_speed_mps=1500.0,
            sound_speed_gradient_per_m=gradient,
            transponders=[
                Transponder(1, 0.0, 0.0, 40.0, 0.05),
                Transponder(2, 300.0, 400.0, 40.0, 0.10),
                Transponder(3, 5000.0, 0.0, 40.0, 0.0),
            ],
        )
    )


def test_lbl_travel_times_match_geometry():
    env = lbl_env()
    cfg = LblConfig(rate_hz=1.0, noise=0.0, outlier_probability=0.0, max_range_m=3000.0)
    s = Lbl(cfg, 1, "AUV1", env)
    still = (0.0, 0.0, 0.0, 0, 0, 0)
    msgs = run(s, lambda t: truth(t, eta=(0.0, 0.0, 10.0, 0, 0, 0), nu=still), n=20, rate=1.0)
    m = msgs[0]
    assert list(m.transponder_id) == [1, 2]  # 3 is out of range
    assert m.two_way_travel_s[0] == pytest.approx(2 * 30.0 / 1500 + 0.05, abs=1e-9)
    assert m.two_way_travel_s[1] == pytest.approx(2 * math.sqrt(300**2 + 400**2 + 30**2) / 1500 + 0.10, abs=1e-9)
    assert m.sound_speed_mps == 1500.0


def test_lbl_noise_and_outliers_are_long():
    env = lbl_env()
    cfg = LblConfig(rate_hz=1.0, noise=1.25, outlier_probability=0.05, outlier_max_m=50.0)
    s = Lbl(cfg, 9, "AUV1", env)
    msgs = run(s, lambda t: truth(t, eta=(0.0, 0.0, 10.0, 0, 0, 0), nu=(0,) * 6), n=3000, rate=1.0)
    rng = np.array([(m.two_way_travel_s[0] - 0.05) * 1500 / 2 - 30.0 for m in msgs])
    inliers = rng[np.abs(rng) < 5 * 1.25]
    assert inliers.std() == pytest.approx(1.25, rel=0.06)
    outliers = rng[np.abs(rng) >= 5 * 1.25]
    assert len(outliers) / len(rng) == pytest.approx(0.05 * 0.875, abs=0.015)
    assert (outliers > 0).all()  # multipath is never shorter


def test_lbl_reply_published_after_the_last_reply_arrives():
    s = Lbl(LblConfig(rate_hz=0.5, noise=0.0, outlier_probability=0.0), 1, "AUV1", lbl_env())
    got = []
    for i in range(200):  # 4 s at 50 Hz
        t = i * 0.02
        m = s.poll(truth(t, eta=(0.0, 0.0, 10.0, 0, 0, 0), nu=(0,) * 6))
        if m is not None:
            got.append((t, m))
    t_pub, m = got[0]
    assert m.utime == 0
    assert t_pub >= max(m.two_way_travel_s) - 1e-9
    assert t_pub < max(m.two_way_travel_s) + 0.021


def test_ins_drift_grows_with_distance_and_gps_resets_it():
    frame = LocalFrame(41.5, -70.7)
    cfg = InsConfig(
        rate_hz=10.0,
        noise=0.0,
        bias=math.radians(1.0),
        heading_random_walk=0.0,
        position_random_walk=0.0,
        velocity_scale_error=0.0,
    )
    s = Ins(cfg, 1, "AUV1", frame)
    # 1000 s north at 1.5 m/s, submerged: a 1 deg heading error drifts 1.75 %
    msgs = run(s, lambda t: truth(t, eta=(1.5 * t, 0.0, 20.0, 0, 0, 0), nu=(1.5, 0, 0, 0, 0, 0)), n=10001)
    last = msgs[-1]
    dist = 1.5 * 1000.0
    assert last.east_m == pytest.approx(dist * math.sin(math.radians(1.0)), rel=0.01)
    assert last.source == last.SOURCE_SIM_INS
    assert last.position_cov_m2[0][0] > 100.0
    up = s.poll(truth(1000.2, eta=(1500.3, 0.0, 0.0, 0, 0, 0), nu=(1.5, 0, 0, 0, 0, 0)))
    assert abs(up.east_m) < 10.0 and up.status & up.STATUS_GPS
