"""Physics sanity: conservation with no forces, buoyancy, limits, integrator."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sim.actuators import Actuators, Command
from sim.dynamics import Dynamics, submerged_fraction
from sim.environment import CurrentLayer, Environment, EnvParams
from sim.model import VehicleModel
from sim.vehicle import REMUS100


def free_body():
    """REMUS mass properties with every hydrodynamic term off and W = B."""
    zero = {k: 0.0 for k in REMUS100.hydro}
    vp = REMUS100.with_updates({"hydro": zero, "cg_m": (0.0, 0.0, 0.0)})
    return vp.with_updates({"buoyancy_n": vp.weight_n})


def rotation(phi, th, psi):
    cphi, sphi, cth, sth, cpsi, spsi = (
        math.cos(phi),
        math.sin(phi),
        math.cos(th),
        math.sin(th),
        math.cos(psi),
        math.sin(psi),
    )
    return np.array(
        [
            [cpsi * cth, cpsi * sth * sphi - spsi * cphi, spsi * sphi + cpsi * cphi * sth],
            [spsi * cth, cpsi * cphi + sphi * sth * spsi, sth * spsi * cphi - cpsi * sphi],
            [-sth, cth * sphi, cth * cphi],
        ]
    )


def test_free_rigid_body_conserves_energy_and_momentum():
    vp = free_body()
    d = Dynamics(vp, 0.02)
    d.set_state([0, 0, 50, 0.1, 0.2, 0.3], [1.0, 0.2, -0.1, 0.8, 0.05, 0.1])
    m, I = vp.mass_kg, np.diag(vp.inertia_kgm2)

    def invariants():
        R = rotation(*d.x[3:6])
        v, w = np.array(d.x[6:9]), np.array(d.x[9:12])
        energy = 0.5 * m * v @ v + 0.5 * w @ I @ w
        return energy, R @ (m * v), R @ (I @ w)

    e0, p0, h0 = invariants()
    for _ in range(1500):  # 30 s of tumbling
        d.step()
    e1, p1, h1 = invariants()
    assert abs(e1 - e0) / e0 < 1e-5
    assert np.allclose(p1, p0, atol=1e-5 * np.linalg.norm(p0))
    assert np.allclose(h1, h0, atol=1e-4 * np.linalg.norm(h0))
    # straight-line motion in NED: the CB moves at the constant inertial velocity
    assert abs(d.t - 30.0) < 1e-9


def test_rk4_converges_at_fourth_order():
    """Halving dt cuts the error about 16x (a wrong stage weight would not)."""

    def final(dt):
        d = Dynamics(REMUS100, dt)
        d.set_state([0, 0, 20, 0.2, 0.1, 0], [1.2, 0.1, 0.05, 0.3, 0.05, 0.05])
        d.thrust = 3.0
        for _ in range(int(round(4.0 / dt))):
            d.step()
        return np.array(d.x)

    ref = final(0.0025)
    e1 = np.abs(final(0.04) - ref).max()
    e2 = np.abs(final(0.02) - ref).max()
    assert 8.0 < e1 / e2 < 32.0


def test_positive_buoyancy_floats_when_prop_stops():
    env = Environment(EnvParams(bathymetry_ref="flat:depth=100"))
    m = VehicleModel(REMUS100, env, 0.02)
    m.set_pose((0, 0, 20, 0, 0, 0))
    m.command = Command(0, 0, 0)
    for _ in range(int(150 / 0.02)):
        m.step()
    z = m.dyn.x[2]
    # floats awash: CB just under the surface, where B * fraction = W
    frac = REMUS100.weight_n / REMUS100.buoyancy_n
    assert submerged_fraction(z, REMUS100.radius_m) == pytest.approx(frac, abs=0.02)
    assert abs(m.dyn.x[8]) < 0.05  # bobbing: heave damping is quadratic only


def test_neutral_vehicle_stays_put():
    vp = REMUS100.with_updates({"buoyancy_n": REMUS100.weight_n})
    env = Environment(EnvParams(bathymetry_ref="flat:depth=100"))
    m = VehicleModel(vp, env, 0.02)
    m.set_pose((0, 0, 20, 0, 0, 0))
    for _ in range(500):
        m.step()
    assert np.allclose(m.dyn.x, [0, 0, 20, 0, 0, 0, 0, 0, 0, 0, 0, 0], atol=1e-9)


def test_vehicle_moving_with_the_current_feels_no_force():
    """nu_r = 0 in a uniform current: no drag, no added-mass force, no drift,
    while the hull yaws (the nu_c_dot term keeps a rotating frame honest)."""
    vp = free_body()
    vp = vp.with_updates(
        {
            "hydro": dict(
                REMUS100.hydro,
                Kpp=0.0,
                Mqq=0.0,
                Nrr=0.0,
                Xqq=0.0,
                Xrr=0.0,
                Yrr=0.0,
                Zqq=0.0,
                Ypq=0.0,
                Npq=0.0,
                Mrp=0.0,
                Zrp=0.0,
            )
        }
    )
    vp = vp.with_updates({"buoyancy_n": vp.weight_n, "cg_m": (0.0, 0.0, 0.0)})
    env = Environment(EnvParams(bathymetry_ref="flat:depth=100", current=[CurrentLayer(0, 0.3, -0.2, 0)]))
    m = VehicleModel(vp, env, 0.02)
    psi = 1.0
    u = 0.3 * math.cos(psi) - 0.2 * math.sin(psi)
    v = -0.3 * math.sin(psi) - 0.2 * math.cos(psi)
    m.set_pose((0, 0, 20, 0, 0, psi), (u, v, 0, 0, 0, 0))
    for _ in range(int(60 / 0.02)):
        m.step()
    vn, ve, vd = m.truth().velocity_ned()
    assert (vn, ve, vd) == pytest.approx((0.3, -0.2, 0.0), abs=1e-6)
    assert m.dyn.x[0] == pytest.approx(18.0, abs=1e-4)


def test_seabed_stops_a_sinking_vehicle():
    vp = REMUS100.with_updates({"buoyancy_n": 250.0})
    env = Environment(EnvParams(bathymetry_ref="flat:depth=12"))
    m = VehicleModel(vp, env, 0.02)
    m.set_pose((0, 0, 10, 0, 0, 0))
    for _ in range(int(30 / 0.02)):
        m.step()
    assert m.dyn.x[2] == pytest.approx(12 - vp.radius_m, abs=1e-6)
    assert m.grounded_steps > 0


def test_fin_angle_and_rate_limits_and_prop_lag():
    a = Actuators(REMUS100, 0.02)
    for _ in range(5):
        a.step(Command(1.0, -1.0, 1500))
    assert a.rudder == pytest.approx(5 * 0.02 * REMUS100.fin_rate_radps)
    for _ in range(200):
        a.step(Command(1.0, -1.0, 1500))
    assert a.rudder == pytest.approx(REMUS100.fin_max_rad)
    assert a.stern == pytest.approx(-REMUS100.fin_max_rad)
    # first-order lag: 63 % after one time constant
    b = Actuators(REMUS100, 0.02)
    for _ in range(int(round(REMUS100.prop_time_constant_s / 0.02))):
        b.step(Command(0, 0, 1000))
    assert b.rpm == pytest.approx(1000 * (1 - math.exp(-1)), rel=0.01)
    b.rpm = 1500
    b.step(Command(0, 0, 1500))
    assert b.thrust == pytest.approx(REMUS100.prop_nominal_thrust_n, rel=1e-6)
    assert b.torque == pytest.approx(REMUS100.prop_nominal_torque_nm, rel=1e-6)


def test_positive_rudder_turns_bow_to_starboard():
    """The actuators_t contract, whatever the sign of the fin coefficients."""
    env = Environment(EnvParams(bathymetry_ref="flat:depth=100"))
    m = VehicleModel(REMUS100, env, 0.02)
    m.set_pose((0, 0, 10, 0, 0, 0), (1.5, 0, 0, 0, 0, 0), rpm=1500)
    m.command = Command(math.radians(10), 0, 1500)
    for _ in range(25):
        m.step()
    assert m.dyn.x[11] > 0.02  # r > 0
    m2 = VehicleModel(REMUS100, env, 0.02)
    m2.set_pose((0, 0, 10, 0, 0, 0), (1.5, 0, 0, 0, 0, 0), rpm=1500)
    m2.command = Command(0, math.radians(10), 1500)
    for _ in range(25):
        m2.step()
    assert m2.dyn.x[10] < -0.02  # q < 0: bow down
