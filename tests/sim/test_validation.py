"""The validation report (python -m sim.validate, its fast subset) and the
physics behind it: waves as forces, the depth gauge in waves, the trim."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest
from conftest import ROOT

from sim import validate
from sim import validation as v
from sim.actuators import Command
from sim.model import VehicleModel
from sim.pilot import gain_names, plan_gains
from sim.vehicle import REMUS100

NEUTRAL = REMUS100.with_updates({"buoyancy_n": REMUS100.weight_n})


def test_quick_report_passes_and_says_so(capsys):
    figs = validate.run(quick=True)
    out = capsys.readouterr().out
    assert figs and all(f.ok for f in figs), [f.name for f in figs if not f.ok]
    for name in (
        "wave dynamic pressure at 3 m",
        "speed at 1500 rpm",
        "roll: natural period",
        "turn diameter, 20 deg rudder",
        "plane step",
        "depth hold at 5 m",
        "PASS",
    ):
        assert name in out
    assert "FAIL" not in out


def test_command_line_usage_error_and_bad_config(tmp_path):
    run = [sys.executable, "-m", "sim.validate"]
    env_dir = ROOT / "python"
    r = subprocess.run(run + ["--bogus"], cwd=env_dir, capture_output=True, text=True)
    assert r.returncode == 2 and "Traceback" not in r.stderr
    bad = tmp_path / "bad.yaml"
    bad.write_text("vehicle: [\n")
    r = subprocess.run(run + ["--config", str(bad)], cwd=env_dir, capture_output=True, text=True)
    assert r.returncode == 2 and "Traceback" not in r.stderr and "bad.yaml" in r.stderr


def test_a_failing_figure_fails_the_report():
    assert not validate.Figure("x", 1.2, 1.0, 0.1, "", "").ok
    assert not validate.Figure("x", 0.31, 0.3, 0.0, "m", "", limit=True).ok
    assert not validate.Figure("x", math.nan, 1.0, 0.1, "", "").ok
    assert validate.Figure("x", 0.29, 0.3, 0.0, "m", "", limit=True).ok


@pytest.mark.parametrize("depth,speed,heave,pressure", [(3, 0.187, 0.18, 1800), (8, 0.107, 0.10, 1030)])
def test_regular_wave_matches_linear_theory(depth, speed, heave, pressure):
    a = v.wave_amplitudes(depth)
    assert a["orbital_mps"] == pytest.approx(speed, rel=0.01)
    assert a["heave_m"] == pytest.approx(heave, abs=0.01)
    assert a["pressure_pa"] == pytest.approx(pressure, rel=0.01)
    # linear amplitude A w, plus the steady second-order (u . grad) u = -k A^2 (up)
    amp = a["orbital_mps"]
    assert a["accel_mps2"] == pytest.approx(amp * 2 * math.pi / 6.0, abs=1.1 * a["k"] * amp**2)


def test_spectrum_has_its_significant_height_and_follows_the_seed():
    env = v.environment(waves=True, seed=5)
    t = np.arange(0.0, 1800.0, 0.5)
    eta = np.array([env.wave_elevation(x, 0.0, 0.0) for x in t])
    assert 4 * np.std(eta) == pytest.approx(0.5, rel=0.1)
    same = v.environment(waves=True, seed=5)
    other = v.environment(waves=True, seed=6)
    pts = [(1.0, 3.0, 4.0, 5.0), (17.0, -20.0, 8.0, 3.0)]
    assert [env.water(*p) for p in pts] == [same.water(*p) for p in pts]
    assert [env.water(*p) for p in pts] != [other.water(*p) for p in pts]
    assert [env.wave_pressure(*p) for p in pts] == [same.wave_pressure(*p) for p in pts]


def _float_in_wave(vp, with_acceleration: bool = True) -> np.ndarray:
    """A hull at 5 m in a regular 0.5 m 6 s wave, fins amidships, no prop."""
    env = v.environment()
    env.set_regular_wave(0.5, 6.0)
    m = VehicleModel(vp, env, v.DT)
    # launched with the water's velocity: quadratic drag would take minutes
    # to take out a start from rest, and the hull would drift meanwhile
    (cn, ce, cd), _ = env.water(0.0, 0.0, 0.0, 5.0)
    m.set_pose((0.0, 0.0, 5.0, 0.0, 0.0, 0.0), (cn, ce, cd, 0.0, 0.0, 0.0))
    z = []
    for _ in range(int(24.0 / v.DT)):
        m.command = Command(0.0, 0.0, 0.0)
        if not with_acceleration:
            x = m.dyn.x
            m.dyn.current_ned, _ = env.water(m.t, x[0], x[1], x[2])
            m.act.step(m.command)
            m.act.apply(m.dyn)
            m.dyn.water_accel_ned = (0.0, 0.0, 0.0)
            m.dyn.step()
        else:
            m.step()
        z.append(m.dyn.x[2])
    return np.array(z[int(6.0 / v.DT) :])


def test_a_neutral_hull_rides_the_wave_like_the_water():
    """Froude-Krylov plus added-mass inertia: a neutrally buoyant body moves
    with the water particles (Airy heave at 5 m: +-0.143 m); with the wave
    felt only as a current it lags far behind (drag alone)."""
    heave = np.ptp(_float_in_wave(NEUTRAL)) / 2
    assert heave == pytest.approx(0.143, rel=0.1)
    current_only = np.ptp(_float_in_wave(NEUTRAL, with_acceleration=False)) / 2
    assert current_only < 0.5 * heave


def test_depth_gauge_sees_the_dynamic_pressure():
    env = v.environment()
    env.set_regular_wave(0.5, 6.0)
    m = VehicleModel(NEUTRAL, env, v.DT)
    m.set_pose((0.0, 0.0, 3.0, 0.0, 0.0, 0.0))
    readings = []
    for k in range(int(6.0 / 0.1)):
        tr = m.truth()
        readings.append(tr.pressure_depth - tr.depth)
        for _ in range(5):
            m.step()
    # +-1800 Pa at 3 m is +-0.179 m of sea water
    assert np.ptp(readings) / 2 == pytest.approx(1800 / (1025 * 9.81), rel=0.05)


def test_level_trim_exists_from_1_to_2_3_mps_and_max_rpm_is_about_2_5_mps():
    for speed in (1.0, 1.5, 2.3):
        tr = v.trim(REMUS100, speed)
        assert tr["residual"] < 1e-9
        assert abs(tr["plane_rad"]) < REMUS100.fin_max_rad * 0.9  # authority left
        assert tr["rpm"] < REMUS100.prop_max_rpm
    assert v.trim_speed(REMUS100, REMUS100.prop_max_rpm) == pytest.approx(2.5, abs=0.1)


def test_pilot_gains_come_from_the_plan_only(tmp_path):
    g = plan_gains()
    assert sorted(g) == sorted(gain_names())  # every gain the C loops take, no other
    text = (ROOT / "missions" / "pilot" / "pilot.chasm").read_text()
    assert "param pitch_kd       = 8.0" in text and g["pitch_kd"] == 8.0
    assert g["max_rudder"] == pytest.approx(math.radians(20.0))
    short = tmp_path / "pilot.chasm"
    short.write_text("\n".join(line for line in text.splitlines() if not line.startswith("param depth_kp")))
    with pytest.raises(ValueError, match="depth_kp"):
        plan_gains(short)
