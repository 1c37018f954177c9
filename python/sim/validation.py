"""Validation runs on the bare physics: no LCM, no clock, in-process.

Each function flies one case (sim.model.VehicleModel, RK4 at DT) with the
pilot where a case needs it (sim.pilot: the pilot plugin's own C loops,
gains from missions/pilot/pilot.chasm) and returns what it measured. The report that
holds these against published and theoretical figures is sim.validate;
tests/sim/test_validation.py runs a fast subset.
"""

from __future__ import annotations

import math

import numpy as np

from sim.actuators import Command
from sim.dynamics import Dynamics
from sim.environment import Environment, EnvParams
from sim.model import VehicleModel
from sim.pilot import Pilot
from sim.vehicle import REMUS100, VehicleParams

DT = 0.02
PILOT_EVERY = 2  # the pilot runs every second physics step: 25 Hz
SWELL = {"wave_height_m": 0.5, "wave_period_s": 6.0, "wave_direction_rad": 1.57}
# history columns of fly()
T, N, E, Z, PHI, TH, PSI, U, V, W, P, Q, R, PLANE, RPM, ZP = range(16)


def environment(waves: bool = False, seed: int = 3, **kw) -> Environment:
    p = EnvParams(bathymetry_ref="flat:depth=200", seed=seed, **(SWELL if waves else {}))
    for k, v in kw.items():
        setattr(p, k, v)
    return Environment(p)


def trim(vp: VehicleParams, speed: float) -> dict:
    """Straight, level, steady flight at surge `speed`: attitude, fins, thrust.

    Solves the six force and moment balances (Newton) for pitch, roll, sway,
    stern plane, rudder and thrust, with w set so the track is level. A
    positively buoyant hull flies slightly nose down (body lift and plane
    carry the buoyancy) and heels against the propeller torque."""
    d = Dynamics(vp, DT)

    def state(z):
        th, phi, v = z[0], z[1], z[2]
        w = (speed * math.sin(th) - math.cos(th) * math.sin(phi) * v) / (math.cos(th) * math.cos(phi))
        return [0, 0, 50, phi, th, 0, speed, v, w, 0, 0, 0]

    def residual(z):
        d.stern, d.rudder, d.thrust = z[3], z[4], z[5]
        d.torque = vp.prop_nominal_torque_nm * z[5] / vp.prop_nominal_thrust_n
        return np.array(d._deriv(state(z))[6:12])

    z = np.array([0.0, 0.0, 0.0, 0.0, 0.0, -vp.hydro["Xuu"] * speed * speed])
    for _ in range(40):
        f0 = residual(z)
        J = np.empty((6, 6))
        for i in range(6):
            dz = np.zeros(6)
            dz[i] = 1e-7
            J[:, i] = (residual(z + dz) - f0) / 1e-7
        z = z - np.linalg.solve(J, f0)
    x = state(z)
    thrust = float(z[5])
    rpm = vp.prop_nominal_rpm * math.sqrt(max(thrust, 0.0) / vp.prop_nominal_thrust_n)
    return {
        "pitch_rad": float(z[0]),
        "roll_rad": float(z[1]),
        "v_mps": float(z[2]),
        "w_mps": x[8],
        "plane_rad": float(z[3]) * vp.stern_plane_sign,
        "rudder_rad": float(z[4]) * vp.rudder_sign,
        "thrust_n": thrust,
        "rpm": rpm,
        "speed_mps": speed,
        "state": x,
        "residual": float(np.max(np.abs(residual(z)))),
    }


def trim_speed(vp: VehicleParams, rpm: float) -> float:
    """The speed of trimmed level flight at this rpm (bisection on trim())."""
    lo, hi = 0.3, 4.0
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if trim(vp, mid)["rpm"] < rpm else (lo, mid)
    return 0.5 * (lo + hi)


def start(
    vp: VehicleParams, env: Environment, depth: float, speed: float = 1.5, heading: float = 0.0
) -> tuple[VehicleModel, dict]:
    """A model in trimmed level flight at depth and speed."""
    tr = trim(vp, speed)
    m = VehicleModel(vp, env, DT)
    x = tr["state"]
    m.set_pose((0.0, 0.0, depth, x[3], x[4], heading), x[6:12], rpm=tr["rpm"])
    m.act.stern, m.act.rudder = tr["plane_rad"], tr["rudder_rad"]
    return m, tr


def fly(
    m: VehicleModel,
    seconds: float,
    *,
    depth: float | None = None,
    heading: float | None = 0.0,
    speed: float | None = None,
    rpm: float | None = None,
    rudder: float | None = None,
    plane: float | None = None,
    pitch: float | None = None,
    pilot: Pilot | None = None,
) -> np.ndarray:
    """Fly for `seconds`; a fixed value (rudder, plane, rpm) overrides the
    pilot's loop for that actuator. The pilot reads depth as the pressure
    gauge does (the waves' dynamic pressure included). Returns the history
    (columns T..ZP)."""
    if pilot is None:
        pilot = Pilot(dt=DT * PILOT_EVERY)
        x = m.dyn.x
        pilot.start(x[4], m.act.stern, m.act.rpm, m.act.rudder)
    n = int(round(seconds / m.dt))
    hist = np.empty((n, 16))
    tr = m.truth()
    cmd = Command(m.act.rudder, m.act.stern, m.act.rpm)
    for i in range(n):
        if i % PILOT_EVERY == 0:
            tr = m.truth(tr)
            x = m.dyn.x
            dr = rudder if rudder is not None else (pilot.rudder(heading, x[5], x[11]) if heading is not None else 0.0)
            if plane is not None:
                ds = plane
            elif pitch is not None:
                ds = pilot.stern_for_pitch(pitch, x[4], x[10])
            elif depth is not None:
                ds = pilot.stern_for_depth(depth, tr.pressure_depth, x[4], x[10])
            else:
                ds = cmd.stern_plane_rad
            prop = rpm if rpm is not None else (pilot.prop(speed, x[6]) if speed is not None else cmd.prop_rpm)
            cmd = Command(dr, ds, prop)
            m.command = cmd
        m.step()
        x = m.dyn.x
        hist[i, 0] = m.t
        hist[i, 1:13] = x
        hist[i, PLANE], hist[i, RPM] = m.act.stern, m.act.rpm
        hist[i, ZP] = tr.pressure_depth
    return hist


# ------------------------------------------------------------------- cases
def speed_at_rpm(vp: VehicleParams = REMUS100, rpm: float = 1500.0) -> float:
    """Mean surge speed over the last 20 s of 100 s at fixed rpm, depth held."""
    m, _ = start(vp, environment(), 10.0, 1.5)
    h = fly(m, 100.0, depth=10.0, rpm=rpm)
    return float(np.mean(h[-int(20 / DT) :, U]))


def coast_down(vp: VehicleParams = REMUS100, u0: float = 1.5) -> dict:
    """Prop stopped from straight flight, fins amidships: time to half speed.
    Ballasted neutral for this run, so only the axial drag slows the hull:
    (m - X_u.) du/dt = X_u|u| u^2 gives t_half = (m - X_u.) / (-X_u|u| u0)."""
    neutral = vp.with_updates({"buoyancy_n": vp.weight_n})
    m = VehicleModel(neutral, environment(), DT)
    m.set_pose((0.0, 0.0, 50.0, 0.0, 0.0, 0.0), (u0, 0, 0, 0, 0, 0), rpm=0.0)
    h = fly(m, 30.0, heading=None, rudder=0.0, plane=0.0, rpm=0.0)
    below = np.nonzero(h[:, U] <= 0.5 * u0)[0]
    t_half = float(h[below[0], T]) if len(below) else math.inf
    theory = (vp.mass_kg - vp.hydro["Xud"]) / (-vp.hydro["Xuu"] * u0)
    return {"t_half_s": t_half, "theory_s": theory, "u_end_mps": float(h[-1, U])}


def linearised(vp: VehicleParams = REMUS100, speed: float = 1.5) -> dict:
    """The model linearised about trim (fins fixed): Jacobian, eigenvalues by
    plane of motion, the sway-yaw stability index and the roll pendulum."""
    tr = trim(vp, speed)
    d = Dynamics(vp, DT)
    d.stern, d.rudder = vp.stern_plane_sign * tr["plane_rad"], vp.rudder_sign * tr["rudder_rad"]
    d.thrust = tr["thrust_n"]
    d.torque = vp.prop_nominal_torque_nm * tr["thrust_n"] / vp.prop_nominal_thrust_n
    x0 = tr["state"]
    f0 = np.array(d._deriv(x0))
    J = np.empty((12, 12))
    for i in range(12):
        x = list(x0)
        x[i] += 1e-7
        J[:, i] = (np.array(d._deriv(x)) - f0) / 1e-7
    h, m = vp.hydro, vp.mass_kg
    roll_i = vp.inertia_kgm2[0] - h["Kpd"]
    return {
        "J": J,
        "x0": x0,
        "trim": tr,
        "lateral": np.linalg.eigvals(J[np.ix_(LATERAL, LATERAL)]),
        "longitudinal": np.linalg.eigvals(J[np.ix_(LONGITUDINAL, LONGITUDINAL)]),
        # Y_v N_r - N_v (Y_r - m U) per U^2: > 0 directionally stable (linear)
        "yaw_index": h["Yuv"] * h["Nur"] - h["Nuv"] * (h["Yur"] - m),
        "roll_period_s": 2 * math.pi / math.sqrt(vp.weight_n * vp.cg_m[2] / roll_i),
        "roll_inertia": roll_i,
    }


LATERAL = [3, 7, 9, 11]  # roll, v, p, r (yaw angle and position are neutral)
LONGITUDINAL = [4, 6, 8, 10]  # pitch, u, w, q


def disturbance(vp: VehicleParams, axis: int, size: float, seconds: float, speed: float = 1.5) -> np.ndarray:
    """Fins fixed at trim, prop at trim rpm, one state (velocity or angle) kicked."""
    m, tr = start(vp, environment(), 50.0, speed)
    m.dyn.x[axis] += size
    return fly(m, seconds, heading=None, rudder=tr["rudder_rad"], plane=tr["plane_rad"], rpm=tr["rpm"])


def linear_check(vp: VehicleParams, axis: int, watch: int, seconds: float, size: float = 1e-5) -> dict:
    """A small kick flown by the full model against the linearised model's own
    response exp(J t) x0 (a check that the simulation is the published model)."""
    lin = linearised(vp)
    idx = LATERAL if axis in LATERAL else LONGITUDINAL
    A = lin["J"][np.ix_(idx, idx)]
    ev, V = np.linalg.eig(A)
    x0 = np.zeros(len(idx))
    x0[idx.index(axis)] = size
    pred = (V @ np.diag(np.exp(ev * seconds)) @ np.linalg.solve(V, x0)).real[idx.index(watch)]
    h = disturbance(vp, axis, size, seconds)
    sim = h[-1, 1 + watch] - lin["x0"][watch]
    worst = float(max(ev.real))
    return {
        "simulated": float(sim),
        "linear": float(pred),
        "max_real": worst,
        "doubling_s": math.log(2) / worst if worst > 0 else math.inf,
    }


def roll_decay(vp: VehicleParams = REMUS100, roll0_deg: float = 10.0, to_deg: float = 3.0, speed: float = 0.0) -> dict:
    """Released at a roll angle, fins amidships, prop stopped (or at speed):
    period and the time the swing takes to fall below to_deg. Theory at rest:
    period 2 pi sqrt((I_xx - K_p.) / (W z_g)); quadratic damping K_p|p| shrinks
    the amplitude as 1/A = 1/A0 + 4 |K_p|p|| w t / (3 pi (I_xx - K_p.))."""
    if speed > 0.0:
        h = disturbance(vp, 3, math.radians(roll0_deg), 40.0, speed)
    else:
        neutral = vp.with_updates({"buoyancy_n": vp.weight_n})
        m = VehicleModel(neutral, environment(), DT)
        m.set_pose((0.0, 0.0, 50.0, math.radians(roll0_deg), 0.0, 0.0))
        h = fly(m, 40.0, heading=None, rudder=0.0, plane=0.0, rpm=0.0)
    phi = h[:, PHI]
    ups = np.nonzero((phi[:-1] < 0) & (phi[1:] >= 0))[0]
    period = float(np.mean(np.diff(h[ups, T]))) if len(ups) > 2 else math.nan
    peaks = [i for i in range(1, len(phi) - 1) if abs(phi[i]) >= abs(phi[i - 1]) and abs(phi[i]) > abs(phi[i + 1])]
    below = [h[i, T] for i in peaks if abs(phi[i]) < math.radians(to_deg)]
    lin = linearised(vp)
    w = 2 * math.pi / lin["roll_period_s"]
    k = 4 * -vp.hydro["Kpp"] * w / (3 * math.pi * lin["roll_inertia"])
    theory = (1 / math.radians(to_deg) - 1 / math.radians(roll0_deg)) / k
    return {
        "period_s": period,
        "period_theory_s": lin["roll_period_s"],
        "decay_s": float(below[0]) if below else math.inf,
        "decay_theory_s": theory,
    }


def steady_turn_run(vp: VehicleParams = REMUS100, rudder: float = math.radians(20.0), rpm: float = 1500.0) -> dict:
    """Fixed rudder, depth held at 10 m by the stern plane: the steady circle."""
    m, _ = start(vp, environment(), 10.0, 1.5)
    fly(m, 10.0, depth=10.0, rpm=rpm)
    h = fly(m, 100.0, rudder=rudder, depth=10.0, rpm=rpm)
    last = h[-int(40.0 / DT) :]
    north, east = last[:, N], last[:, E]
    A = np.column_stack([north, east, np.ones_like(north)])
    D, Ee, F = np.linalg.lstsq(A, -(north**2 + east**2), rcond=None)[0]
    t = last[:, T]
    speed = float(np.mean(np.hypot(np.gradient(north, t), np.gradient(east, t))))
    r = float(np.mean(np.gradient(np.unwrap(last[:, PSI]), t)))
    return {
        "diameter_m": 2.0 * math.sqrt(D * D / 4 + Ee * Ee / 4 - F),
        "speed_mps": speed,
        "yaw_rate_radps": r,
        "kinematic_diameter_m": 2.0 * speed / abs(r),
        "roll_rad": float(np.mean(last[:, PHI])),
        "rudder_rad": rudder,
    }


def plane_step(vp: VehicleParams = REMUS100, step_rad: float = math.radians(-5.0), seconds: float = 4.0) -> dict:
    """Fins fixed at trim, then the stern plane stepped (negative: bow up).
    The first pitch acceleration against M^-1 tau of the fin moment alone."""
    m, tr = start(vp, environment(), 30.0, 1.5)
    plane = tr["plane_rad"] + step_rad
    h = fly(m, seconds, heading=None, rudder=0.0, plane=plane, rpm=tr["rpm"])
    # the fin slews at its rate: compare once it has arrived
    n_arrive = int(math.ceil(abs(step_rad) / vp.fin_rate_radps / DT))
    q_dot = (h[n_arrive + 1, Q] - h[n_arrive - 1, Q]) / (2 * DT)
    d = Dynamics(vp, DT)
    u = 1.5
    tau = np.array([0, 0, vp.hydro["Zuuds"], 0, vp.hydro["Muuds"], 0]) * u * u * vp.stern_plane_sign * step_rad
    theory = float(np.linalg.solve(d.M, tau)[4])
    return {
        "q_dot0": float(q_dot),
        "q_dot0_theory": theory,
        "pitch_end_rad": float(h[-1, TH]),
        "depth_change_m": float(h[-1, Z] - 30.0),
        "trim_pitch_rad": tr["pitch_rad"],
    }


def pitch_command_dive(vp: VehicleParams = REMUS100, pitch: float = math.radians(-10.0)) -> dict:
    """The pilot's pitch loop holding -10 deg at 1.5 m/s: dive rate vs U sin(theta - alpha)."""
    m, _ = start(vp, environment(), 5.0, 1.5)
    h = fly(m, 25.0, pitch=pitch, speed=1.5)
    last = h[-int(10.0 / DT) :]
    rate = float(np.polyfit(last[:, T], last[:, Z], 1)[0])
    u, w, th = (float(np.mean(last[:, c])) for c in (U, W, TH))
    rise = h[np.nonzero(h[:, TH] <= pitch * 0.9)[0][0], T] if np.any(h[:, TH] <= pitch * 0.9) else math.inf
    return {
        "dive_rate_mps": rate,
        "kinematic_rate_mps": -u * math.sin(th) + w * math.cos(th),
        "pitch_rad": th,
        "rise_s": float(rise),
        "overshoot_rad": float(pitch - h[:, TH].min()),
    }


def depth_hold(
    vp: VehicleParams = REMUS100,
    depth: float = 5.0,
    seconds: float = 120.0,
    speed: float = 1.5,
    waves: bool = True,
    seed: int = 3,
) -> dict:
    """The pilot holding depth, heading (across the swell) and speed; statistics
    after 20 s of settling. The error is the true depth's, not the gauge's."""
    m, _ = start(vp, environment(waves, seed), depth, speed)
    h = fly(m, seconds, depth=depth, speed=speed)
    h = h[int(20.0 / DT) :]
    e = h[:, Z] - depth
    return {
        "rms_m": float(np.sqrt(np.mean(e**2))),
        "spread_m": float(np.ptp(h[:, Z])),
        "mean_error_m": float(np.mean(e)),
        "pitch_std_rad": float(np.std(h[:, TH])),
        "plane_mean_rad": float(np.mean(h[:, PLANE])),
        "u_mps": float(np.mean(h[:, U])),
        "rpm": float(np.mean(h[:, RPM])),
    }


STEPS = {  # kind: (column, start, target): steps of 90 deg, 5 m and 0.5 m/s
    "heading": (PSI, 0.0, math.pi / 2),
    "depth": (Z, 3.0, 8.0),
    "speed": (U, 1.0, 1.5),
}


def step_response(kind: str, vp: VehicleParams = REMUS100, waves: bool = True, seconds: float = 60.0) -> dict:
    """The pilot's step responses in the default swell, the other loops
    holding: rise time 10-90 %, overshoot past the target, steady error (mean
    over the last 10 s)."""
    col, y0, target = STEPS[kind]
    speed0 = y0 if kind == "speed" else 1.5
    depth0 = y0 if kind == "depth" else 5.0
    m, _ = start(vp, environment(waves), depth0, speed0)
    h = fly(
        m,
        seconds,
        heading=target if kind == "heading" else 0.0,
        depth=target if kind == "depth" else depth0,
        speed=target if kind == "speed" else speed0,
    )
    y = h[:, col]
    if kind == "heading":
        y = np.unwrap((y + math.pi) % (2 * math.pi) - math.pi)
    frac = (y - y0) / (target - y0)
    t10 = h[np.argmax(frac >= 0.1), T]
    t90 = h[np.argmax(frac >= 0.9), T] if np.any(frac >= 0.9) else math.inf
    return {
        "rise_s": float(t90 - t10),
        "overshoot": float(max(0.0, np.max(frac) - 1.0) * abs(target - y0)),
        "steady_error": float(np.mean(y[-int(10.0 / DT) :]) - target),
        "step": target - y0,
        "unit": {"heading": "rad", "depth": "m", "speed": "m/s"}[kind],
    }


def wave_amplitudes(depth: float, height: float = 0.5, period: float = 6.0) -> dict:
    """A regular (one-component) wave's amplitudes at a depth, as the simulator
    computes them: orbital speed, particle heave, dynamic pressure."""
    env = environment()
    w = 2 * math.pi / period
    k = w * w / 9.81
    env.set_regular_wave(height, period)
    ts = np.linspace(0.0, period, 241)
    kin = np.array([env.wave_kinematics(t, 0.0, 0.0, depth) for t in ts])
    pressure = np.array([env.wave_pressure(t, 0.0, 0.0, depth) for t in ts])
    speed = np.hypot(kin[:, 0], kin[:, 1])
    acc = np.hypot(kin[:, 2], kin[:, 3])
    # particle heave: the vertical velocity integrated over the period
    dz = np.concatenate([[0.0], np.cumsum(0.5 * (kin[1:, 1] + kin[:-1, 1]) * np.diff(ts))])
    return {
        "orbital_mps": float(speed.max()),
        "heave_m": float(np.ptp(dz) / 2),
        "pressure_pa": float(np.abs(pressure).max()),
        "accel_mps2": float(acc.max()),
        "k": k,
    }
