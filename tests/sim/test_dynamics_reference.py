"""The dynamics (c/dynamics/, through sim.dynamics) against figures of the
Python implementation they replaced, and against properties of the physics.

data/dynamics_reference.json holds what python/sim/dynamics.py at commit
e8a9596 (the right-hand side and RK4 in Python) computed for 15 cases: still
water, a current, the waves' acceleration, extra forces, the hull breaking
the surface (submerged_fraction), roll and pitch, yaw and roll across their
wrap, a CG off the centre line. dynamics_reference.py wrote it
(--from-git e8a9596 loads that file from git history) and, run without
arguments, says how far the current code is from it. When the C replaced
the Python, every figure agreed to the last bit; the tolerances below leave
room only for another C library's last-bit sin and cos.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from dynamics_reference import prepared

from sim import dynamics
from sim.dynamics import Dynamics, DynamicsUnavailable, submerged_fraction
from sim.vehicle import REMUS100

REFERENCE = json.loads((Path(__file__).parent / "data" / "dynamics_reference.json").read_text())
CASES = REFERENCE["cases"]


def close(got, want, rtol: float) -> None:
    want = np.asarray(want, dtype=float)
    scale = max(1.0, float(np.max(np.abs(want))))
    np.testing.assert_allclose(np.asarray(got, dtype=float), want, rtol=rtol, atol=rtol * scale)


@pytest.mark.parametrize("c", CASES, ids=[c["name"] for c in CASES])
def test_same_figures_as_the_python_implementation(c):
    d = prepared(Dynamics, REFERENCE["vehicles"], c)
    want = c["expected"]
    close(d._deriv(c["x"]), want["deriv"], 1e-12)
    close(d.forces(), want["forces"], 1e-12)
    d.step()
    close(d.x[0:12], want["x_1"], 1e-12)
    close(d.nu_dot, want["nu_dot_1"], 1e-12)
    for _ in range(c["steps"] - 1):
        d.step()
    # hundreds of steps may grow a last-bit difference: a looser bound
    close(d.x[0:12], want["x_n"], 1e-9)
    close(d.nu_dot, want["nu_dot_n"], 1e-9)
    assert d.t == pytest.approx(want["t_n"], rel=1e-15)


def test_same_submerged_fraction():
    for z, r, f in REFERENCE["submerged_fraction"]:
        assert submerged_fraction(z, r) == pytest.approx(f, rel=1e-12, abs=1e-15)


def test_the_reference_covers_what_it_says():
    """Each case kind the docstring names is there, so a regeneration that
    dropped one would not pass unseen."""
    r = REMUS100.radius_m
    has = {
        "current": any(c["inputs"].get("current_ned") for c in CASES),
        "waves": any(c["inputs"].get("water_accel_ned") for c in CASES),
        "tau": any(c["inputs"].get("external_tau") for c in CASES),
        "surface": any(-r < c["x"][2] < r for c in CASES),
        "yaw wrap": any(min(c["x"][5], 2 * math.pi - c["x"][5]) < 0.01 for c in CASES),
        "roll wrap": any(math.pi - abs(c["x"][3]) < 0.01 for c in CASES),
        "attitude": any(c["x"][3] and c["x"][4] for c in CASES),
    }
    assert all(has.values()), has


NEUTRAL = REMUS100.with_updates({"buoyancy_n": REMUS100.weight_n})


def test_steady_speed_for_a_thrust():
    """Level, neutral, no fins: thrust balances the axial drag, X_u|u| u^2 = -T,
    and the published 3.86 N (1500 rpm) gives Prestero's "about 1.5 m/s"
    (the validation's figure, 1.5 +- 0.05)."""
    d = Dynamics(NEUTRAL.with_updates({"cg_m": (0.0, 0.0, 0.0)}), 0.02)
    d.set_state([0, 0, 10, 0, 0, 0.4])
    d.thrust = REMUS100.prop_nominal_thrust_n
    for _ in range(int(120 / 0.02)):
        d.step()
    u = math.sqrt(d.thrust / -REMUS100.hydro["Xuu"])
    assert d.x[6] == pytest.approx(u, rel=1e-6)
    assert abs(d.x[6] - 1.5) < 0.05
    assert math.atan2(d.x[1], d.x[0]) == pytest.approx(0.4, abs=1e-9)  # straight along its heading
    assert d.x[2] == pytest.approx(10.0, abs=1e-9) and max(map(abs, d.x[7:12])) < 1e-9


def test_heading_and_position_change_nothing_in_still_water():
    """Still water is the same everywhere and in every direction: the body
    accelerations do not depend on north, east or yaw, and the NED velocity
    turns with the yaw."""
    d = Dynamics(REMUS100)
    d.thrust, d.torque, d.rudder, d.stern = 3.0, -0.4, 0.1, -0.1
    nu = [1.2, 0.1, -0.05, 0.2, -0.1, 0.15]
    a = d._deriv([0, 0, 10, 0.2, 0.1, 0.0, *nu])
    b = d._deriv([100, -50, 10, 0.2, 0.1, 2.0, *nu])
    close(b[3:12], a[3:12], 1e-12)
    c, s = math.cos(2.0), math.sin(2.0)
    close(b[0:2], [c * a[0] - s * a[1], s * a[0] + c * a[1]], 1e-12)


def test_port_and_starboard_are_mirror_images():
    """The REMUS has its CG on the centre line: with no propeller torque,
    mirroring the state, the rudder, the current and the waves mirrors the
    derivative (every sway, roll and yaw term has the right sign)."""
    d = Dynamics(REMUS100)
    mirror = np.array([1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 1, -1])
    x = np.array([3, 4, 0.03, 0.2, -0.1, 0.7, 1.2, 0.1, -0.05, 0.3, 0.1, -0.2])
    d.thrust, d.rudder, d.stern = 3.0, 0.2, -0.1
    d.current_ned, d.water_accel_ned, d.external_tau = (0.2, 0.1, 0.02), (0.1, -0.3, 0.2), [1, 0, -2, 0, 0.3, 0]
    f = np.array(d._deriv(x))
    d.rudder, d.current_ned, d.water_accel_ned = -0.2, (0.2, -0.1, 0.02), (0.1, 0.3, 0.2)
    close(d._deriv(mirror * x), mirror * f, 1e-12)


def test_state_is_a_live_view_and_assignable():
    d = Dynamics(REMUS100)
    d.set_state([1, 2, 3, 0.1, 0.2, 0.3], [1, 0, 0, 0, 0, 0])
    x = d.x
    assert x[0:3] == [1.0, 2.0, 3.0] and d.eta == [1, 2, 3, 0.1, 0.2, 0.3] and d.nu == [1, 0, 0, 0, 0, 0]
    x[2] += 1.0  # what the seabed contact and the validation's kicks do
    assert d.x[2] == 4.0 and d.eta[2] == 4.0
    d.x = list(range(12))
    assert np.array(d.x).tolist() == list(range(12))
    with pytest.raises(ValueError):
        d.x = [0.0] * 11
    d.external_tau = [0, 0, 0, 0, 0, 1.0]
    d.set_state([0, 0, 10, 0, 0, 0])
    d.step()
    assert d.x[11] > 0  # a yaw moment turns it
    d.external_tau = None  # and is gone again
    d.set_state([0, 0, 10, 0, 0, 0])
    d.step()
    assert d.x[11] == 0.0


def test_missing_library_says_make_build(monkeypatch, tmp_path):
    monkeypatch.setenv("AUV_BUILD", str(tmp_path))
    dynamics._library.cache_clear()
    try:
        with pytest.raises(DynamicsUnavailable, match=r"libauvdynamics\.so is not built: run `make build`"):
            Dynamics(REMUS100)
    finally:
        dynamics._library.cache_clear()
