"""The steady turn at fixed rudder and thrust, solved algebraically.

An estimate of the turning circle that does not come from integrating the
6-DOF model: the horizontal-plane (surge, sway, yaw) force balance of the
same coefficients, X = Y = N = 0 with u, v, r unknown, level and deeply
submerged (no roll, pitch, heave; no current).

Why not the classic linear steady-turn solution: it divides by the sway-yaw
stability index C = Y_v N_r - N_v (Y_r - m U). For the REMUS 100 table
coefficients C < 0 (directionally unstable), and the linear equilibrium then
turns the wrong way and is itself unstable: the turn the vehicle settles into
is held by the cross-flow drag terms (Y_v|v|, N_r|r|), which only the
nonlinear balance has. An unstable hull also has several equilibria at one
rudder angle; the vehicle can only settle into a stable one, so the roots
are searched from a spread of starting points and the stable root(s) kept.
"""

from __future__ import annotations

import math

import numpy as np

from sim.vehicle import VehicleParams


def _forces(vp: VehicleParams, x: np.ndarray, thrust: float, dr: float) -> np.ndarray:
    """X, Y, N of the model at body velocities (u, v, r), level, no current."""
    h, m = vp.hydro, vp.mass_kg
    xg, yg, _ = vp.cg_m
    u, v, r = x
    uau = u * abs(u)
    X = h["Xuu"] * uau + h["Xvr"] * v * r + h["Xrr"] * r * r + m * (v * r + xg * r * r) + thrust
    Y = (
        h["Yvv"] * v * abs(v)
        + h["Yrr"] * r * abs(r)
        + h["Yuv"] * u * v
        + h["Yur"] * u * r
        + h["Yuudr"] * uau * dr
        + m * (-u * r + yg * r * r)
    )
    N = (
        h["Nvv"] * v * abs(v)
        + h["Nrr"] * r * abs(r)
        + h["Nuv"] * u * v
        + h["Nur"] * u * r
        + h["Nuudr"] * uau * dr
        - m * (xg * u * r + yg * v * r)
    )
    return np.array([X, Y, N])


def _mass3(vp: VehicleParams) -> np.ndarray:
    h, m = vp.hydro, vp.mass_kg
    xg, yg, _ = vp.cg_m
    return np.array(
        [
            [m - h["Xud"], 0.0, -m * yg],
            [0.0, m - h["Yvd"], m * xg - h["Yrd"]],
            [-m * yg, m * xg - h["Nvd"], vp.inertia_kgm2[2] - h["Nrd"]],
        ]
    )


def _jacobian(vp, x, thrust, dr, eps=1e-7) -> np.ndarray:
    f0 = _forces(vp, x, thrust, dr)
    J = np.empty((3, 3))
    for i in range(3):
        dx = np.zeros(3)
        dx[i] = eps
        J[:, i] = (_forces(vp, x + dx, thrust, dr) - f0) / eps
    return J


def _newton(vp, x0, thrust, dr, iters=60) -> np.ndarray | None:
    x = np.array(x0, dtype=float)
    for _ in range(iters):
        f = _forces(vp, x, thrust, dr)
        if np.max(np.abs(f)) < 1e-10:
            return x
        try:
            step = np.linalg.solve(_jacobian(vp, x, thrust, dr), -f)
        except np.linalg.LinAlgError:
            return None
        # damped: |v| and |r| make the balance kinked at zero
        scale = min(1.0, 0.5 / max(1e-12, float(np.max(np.abs(step)))))
        x = x + scale * step
    return x if np.max(np.abs(_forces(vp, x, thrust, dr))) < 1e-8 else None


def equilibria(vp: VehicleParams, rudder_rad: float, rpm: float = 1500.0) -> list[dict]:
    """Every steady turn found at this commanded rudder and rpm, stable or not."""
    n0 = vp.prop_nominal_rpm
    thrust = vp.prop_nominal_thrust_n * (rpm / n0) ** 2
    dr = vp.rudder_sign * rudder_rad  # the model's fin sign
    u0 = math.sqrt(thrust / -vp.hydro["Xuu"])
    minv = np.linalg.inv(_mass3(vp))
    found: list[dict] = []
    for rs in np.linspace(-1.5, 1.5, 13):  # yaw rate guesses [rad/s]
        for vs in (-0.5, 0.0, 0.5):  # sway guesses, fractions of u0
            x = _newton(vp, (u0, vs * u0, rs), thrust, dr)
            if x is None or x[0] <= 0.0 or any(np.allclose(x, e["x"], atol=1e-6) for e in found):
                continue
            ev = np.linalg.eigvals(minv @ _jacobian(vp, x, thrust, dr))
            speed = math.hypot(x[0], x[1])
            found.append(
                {
                    "x": x,
                    "u_mps": x[0],
                    "v_mps": x[1],
                    "yaw_rate_radps": x[2],
                    "speed_mps": speed,
                    "diameter_m": 2.0 * speed / abs(x[2]) if x[2] != 0.0 else math.inf,
                    "stable": bool(np.max(ev.real) < 0.0),
                }
            )
    return found


def steady_turn(vp: VehicleParams, rudder_rad: float | None = None, rpm: float = 1500.0) -> dict:
    """The stable steady turn at full (or the given) rudder; ValueError if none or several."""
    rudder_rad = vp.fin_max_rad if rudder_rad is None else rudder_rad
    stable = [e for e in equilibria(vp, rudder_rad, rpm) if e["stable"]]
    if len(stable) != 1:
        raise ValueError(f"{len(stable)} stable steady turns at rudder {rudder_rad:.3f} rad")
    return stable[0]


def linear_turn(vp: VehicleParams, rudder_rad: float | None = None) -> dict:
    """The linear steady-turn solution (per unit speed), for comparison only."""
    rudder_rad = vp.fin_max_rad if rudder_rad is None else rudder_rad
    h, m = vp.hydro, vp.mass_kg
    dr = vp.rudder_sign * rudder_rad
    A = np.array([[h["Yuv"], h["Yur"] - m], [h["Nuv"], h["Nur"]]])
    v_u, r_u = np.linalg.solve(A, -np.array([h["Yuudr"], h["Nuudr"]]) * dr)  # v/U, r/U [1/m]
    return {
        "r_per_speed": float(r_u),
        "diameter_m": 2.0 / abs(r_u),
        "turns_to_starboard": bool(r_u > 0),
        "index": float(np.linalg.det(A)),
    }
