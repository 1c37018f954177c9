"""The validation figures of docs/simulator.md, held to their tolerances."""

from __future__ import annotations

import math

import pytest

from sim import validation as v
from sim.vehicle import REMUS100


def test_steady_speed_at_nominal_rpm():
    assert v.steady_speed() == pytest.approx(1.5, abs=0.075)


def test_steady_speed_scales_with_rpm():
    # thrust ~ rpm^2 and drag ~ u^2: speed ~ rpm, once no trim angle of
    # attack is needed to carry positive buoyancy (neutral vehicle)
    neutral = REMUS100.with_updates({"buoyancy_n": REMUS100.weight_n})
    ratio = v.steady_speed(neutral, rpm=1200.0) / v.steady_speed(neutral, rpm=1500.0)
    assert ratio == pytest.approx(0.8, abs=0.01)


def test_turning_circle_full_rudder_is_a_consistent_starboard_circle():
    tc = v.turning_circle()
    assert tc["yaw_rate_radps"] > 0
    assert tc["diameter_m"] == pytest.approx(tc["kinematic_diameter_m"], rel=0.05)
    assert 0.5 * REMUS100.length_m < tc["diameter_m"] < 30 * REMUS100.length_m


def test_steady_dive_matches_its_kinematics():
    dv = v.steady_dive()
    assert dv["dive_rate_mps"] > 0.1
    assert dv["dive_rate_mps"] == pytest.approx(dv["kinematic_rate_mps"], abs=0.02)


def test_buoyant_ascent_rate_matches_drag_balance():
    a = v.buoyant_ascent()
    assert a["rise_rate_mps"] == pytest.approx(a["expected_mps"], rel=0.1)
    assert a["final_depth_m"] < 0.5


def test_linearised_model_matches_coefficient_theory():
    lm = v.linear_modes()
    assert lm["stability_index"] == pytest.approx(
        -28.6 * -2.0 - (-24.0) * (5.22 - 30.48), rel=1e-9)
    assert lm["max_real"] == pytest.approx(lm["sway_yaw_max_real"], rel=0.1)


def test_report_command_prints_every_case(capsys):
    assert v.main([]) == 0
    out = capsys.readouterr().out
    for name in ("steady speed", "turning circle", "steady dive", "buoyant ascent"):
        assert name in out
