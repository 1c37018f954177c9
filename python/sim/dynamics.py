"""6-DOF rigid-body dynamics in Fossen's form, Prestero's REMUS coefficients.

    M nu_dot + C_RB(nu) nu + [C_A(nu_r) nu_r + D(nu_r) nu_r] + g(eta) = tau
    eta_dot = J(eta) nu

M = M_RB + M_A is constant, so its inverse is computed once. The bracket is
written out term by term in Prestero's coefficient form: his "combined"
coefficients (Y_ur, M_uw, ...) already hold the C_A entries that are linear
in u, so building C_A from M_A as well would count the Munk moment twice.
Hydrodynamic terms use the velocity relative to the water nu_r = nu - nu_c;
a wave field's acceleration adds the Froude-Krylov force rho V a and the
added-mass force M_A a of the accelerating water (not only its velocity);
rigid-body terms use nu over ground. For a current fixed in NED,
M_A nu_r_dot = M_A nu_dot - M_A nu_c_dot with nu_c_dot = v_c^b x omega, which
is added to the right-hand side so a turning vehicle in a current feels no
spurious force.

The hot path works on plain Python floats: for 6-vectors they are several
times faster than numpy calls, and nothing is allocated per step apart from
the tuples the interpreter reuses. Euler angles (ZYX) are used: valid away
from pitch = +-90 deg, which an AUV never reaches in service.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from math import cos, sin

import numpy as np

from sim.vehicle import G, VehicleParams

ETA = ("north_m", "east_m", "down_m", "roll_rad", "pitch_rad", "yaw_rad")
TWO_PI = 2.0 * math.pi
NU = ("u_mps", "v_mps", "w_mps", "p_radps", "q_radps", "r_radps")


def mass_matrix(vp: VehicleParams) -> np.ndarray:
    """M = M_RB + M_A about the CB (Prestero eq. 3.x; Fossen 2011 eq. 3.44)."""
    h = vp.hydro
    m = vp.mass_kg
    xg, yg, zg = vp.cg_m
    ixx, iyy, izz = vp.inertia_kgm2
    return np.array(
        [
            [m - h["Xud"], 0.0, 0.0, 0.0, m * zg, -m * yg],
            [0.0, m - h["Yvd"], 0.0, -m * zg, 0.0, m * xg - h["Yrd"]],
            [0.0, 0.0, m - h["Zwd"], m * yg, -m * xg - h["Zqd"], 0.0],
            [0.0, -m * zg, m * yg, ixx - h["Kpd"], 0.0, 0.0],
            [m * zg, 0.0, -m * xg - h["Mwd"], 0.0, iyy - h["Mqd"], 0.0],
            [-m * yg, m * xg - h["Nvd"], 0.0, 0.0, 0.0, izz - h["Nrd"]],
        ]
    )


def submerged_fraction(depth_m: float, radius_m: float) -> float:
    """Fraction of a horizontal cylinder's volume under water, CB at depth_m.

    Why: with a positively buoyant hull the buoyancy must fall as the hull
    breaks the surface, or the vehicle would fly out of the water.
    """
    if depth_m >= radius_m:
        return 1.0
    if depth_m <= -radius_m:
        return 0.0
    h = depth_m + radius_m  # submerged height of the section
    rr = radius_m
    seg = rr * rr * math.acos((rr - h) / rr) - (rr - h) * math.sqrt(max(2.0 * rr * h - h * h, 0.0))
    return seg / (math.pi * rr * rr)


@dataclass(frozen=True)
class Coefficients:
    """One vehicle's constants, as the right-hand side reads them (built once).

    The fields named like a hydrodynamic coefficient (Xuu, Yuudr, ...) hold
    that coefficient of VehicleParams.hydro: only those the right-hand side
    uses (the added-mass derivatives Xud... enter through M instead, apart
    from the five below).
    """

    mass_kg: float
    xg: float  # CG relative to the CB [m]
    yg: float
    zg: float
    ixx: float  # rigid-body inertia [kg m^2]
    iyy: float
    izz: float
    weight_n: float
    buoyancy_n: float
    radius_m: float  # the hull breaks the surface within this depth
    Xuu: float
    Xwq: float
    Xqq: float
    Xvr: float
    Xrr: float
    Yvv: float
    Yrr: float
    Yuv: float
    Ywp: float
    Yur: float
    Ypq: float
    Yuudr: float
    Zww: float
    Zqq: float
    Zuw: float
    Zuq: float
    Zvp: float
    Zrp: float
    Zuuds: float
    Kpp: float
    Mww: float
    Mqq: float
    Muw: float
    Muq: float
    Mvp: float
    Mrp: float
    Muuds: float
    Nvv: float
    Nrr: float
    Nuv: float
    Nur: float
    Nwp: float
    Npq: float
    Nuudr: float
    # the added mass a current or the waves' acceleration acts on (positive:
    # -Xud, -Yvd, -Zwd, and the couplings of w into pitch and v into yaw)
    added_u: float
    added_v: float
    added_w: float
    added_qw: float
    added_rv: float

    @classmethod
    def from_vehicle(cls, vp: VehicleParams) -> "Coefficients":
        h = vp.hydro
        xg, yg, zg = vp.cg_m
        ixx, iyy, izz = vp.inertia_kgm2
        return cls(
            mass_kg=vp.mass_kg,
            xg=xg,
            yg=yg,
            zg=zg,
            ixx=ixx,
            iyy=iyy,
            izz=izz,
            weight_n=vp.weight_n,
            buoyancy_n=vp.buoyancy_n,
            radius_m=vp.radius_m,
            added_u=-h["Xud"],
            added_v=-h["Yvd"],
            added_w=-h["Zwd"],
            added_qw=-h["Mwd"],
            added_rv=-h["Nvd"],
            **{f.name: h[f.name] for f in fields(cls) if f.name in h},
        )


class Dynamics:
    """Integrates eta (NED pose) and nu (body velocity) with fixed-step RK4."""

    def __init__(self, vp: VehicleParams, dt: float = 0.02) -> None:
        if not dt > 0.0:
            raise ValueError("physics step must be positive")
        self.vp = vp
        self.dt = dt
        self.M = mass_matrix(vp)
        minv = np.linalg.inv(self.M)
        self._minv = tuple(float(v) for v in minv.ravel())
        self.coefficients = Coefficients.from_vehicle(vp)
        # state: north, east, down, roll, pitch, yaw, u, v, w, p, q, r
        self.x = [0.0] * 12
        self.nu_dot = [0.0] * 6
        self.t = 0.0
        # inputs, held over one step (zero-order hold)
        self.rudder = 0.0
        self.stern = 0.0
        self.thrust = 0.0
        self.torque = 0.0
        self.current_ned = (0.0, 0.0, 0.0)
        # the water's acceleration (NED, m/s^2; waves): Froude-Krylov plus
        # added-mass inertia, held over a step like the current
        self.water_accel_ned = (0.0, 0.0, 0.0)
        self.external_tau: list[float] | None = None  # optional extra body forces (tests, tow)
        self._f = make_rhs(self.coefficients, self._minv)

    # ------------------------------------------------------------------ API
    @property
    def eta(self) -> list[float]:
        return self.x[0:6]

    @property
    def nu(self) -> list[float]:
        return self.x[6:12]

    def set_state(self, eta, nu=(0.0,) * 6) -> None:
        self.x[0:6] = [float(v) for v in eta]
        self.x[6:12] = [float(v) for v in nu]

    def step(self) -> None:
        """Advance one fixed step with classic RK4 (inputs held).

        Written out element by element (list comprehensions over zip() cost
        more than the arithmetic they do): each stage's state is x + h k with
        h = dt/2, dt/2, dt, and x_next = x + dt/6 (k1 + 2 (k2 + k3) + k4).
        """
        dt = self.dt
        h = 0.5 * dt
        cn, ce, cd = self.current_ned
        u = (cn, ce, cd, self.water_accel_ned, self.rudder, self.stern, self.thrust, self.torque, self.external_tau)
        f = self._f
        x0, x1, x2, x3, x4, x5, x6, x7, x8, x9, x10, x11 = x = self.x
        k1 = a0, a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11 = f(x, *u)
        b0, b1, b2, b3, b4, b5, b6, b7, b8, b9, b10, b11 = f(
            (
                x0 + h * a0,
                x1 + h * a1,
                x2 + h * a2,
                x3 + h * a3,
                x4 + h * a4,
                x5 + h * a5,
                x6 + h * a6,
                x7 + h * a7,
                x8 + h * a8,
                x9 + h * a9,
                x10 + h * a10,
                x11 + h * a11,
            ),
            *u,
        )
        c0, c1, c2, c3, c4, c5, c6, c7, c8, c9, c10, c11 = f(
            (
                x0 + h * b0,
                x1 + h * b1,
                x2 + h * b2,
                x3 + h * b3,
                x4 + h * b4,
                x5 + h * b5,
                x6 + h * b6,
                x7 + h * b7,
                x8 + h * b8,
                x9 + h * b9,
                x10 + h * b10,
                x11 + h * b11,
            ),
            *u,
        )
        d0, d1, d2, d3, d4, d5, d6, d7, d8, d9, d10, d11 = f(
            (
                x0 + dt * c0,
                x1 + dt * c1,
                x2 + dt * c2,
                x3 + dt * c3,
                x4 + dt * c4,
                x5 + dt * c5,
                x6 + dt * c6,
                x7 + dt * c7,
                x8 + dt * c8,
                x9 + dt * c9,
                x10 + dt * c10,
                x11 + dt * c11,
            ),
            *u,
        )
        w = dt / 6.0
        # keep roll in (-pi, pi] and yaw in [0, 2pi)
        roll = x3 + w * (a3 + 2.0 * (b3 + c3) + d3)
        if roll > math.pi or roll <= -math.pi:
            roll = (roll + math.pi) % TWO_PI - math.pi
        self.x = [
            x0 + w * (a0 + 2.0 * (b0 + c0) + d0),
            x1 + w * (a1 + 2.0 * (b1 + c1) + d1),
            x2 + w * (a2 + 2.0 * (b2 + c2) + d2),
            roll,
            x4 + w * (a4 + 2.0 * (b4 + c4) + d4),
            (x5 + w * (a5 + 2.0 * (b5 + c5) + d5)) % TWO_PI,
            x6 + w * (a6 + 2.0 * (b6 + c6) + d6),
            x7 + w * (a7 + 2.0 * (b7 + c7) + d7),
            x8 + w * (a8 + 2.0 * (b8 + c8) + d8),
            x9 + w * (a9 + 2.0 * (b9 + c9) + d9),
            x10 + w * (a10 + 2.0 * (b10 + c10) + d10),
            x11 + w * (a11 + 2.0 * (b11 + c11) + d11),
        ]
        self.nu_dot = k1[6:12]
        self.t += dt

    def forces(self) -> list[float]:
        """The generalised force vector (right-hand side) at the current state: M nu_dot."""
        nu_dot = self._deriv(self.x)[6:12]
        return [float(v) for v in self.M @ np.array(nu_dot)]

    # ------------------------------------------------------------ internals
    def _deriv(self, x):
        """x_dot for state x with the inputs held now (the validation's Jacobian)."""
        cn, ce, cd = self.current_ned
        return self._f(
            x, cn, ce, cd, self.water_accel_ned, self.rudder, self.stern, self.thrust, self.torque, self.external_tau
        )


def make_rhs(k: Coefficients, minv: tuple):
    """The right-hand side x_dot = f(x, inputs) for one vehicle's constants.

    A closure: the constants are copied into locals once, here, and read by
    the inner function as free variables (no attribute look-up per call);
    the inputs held over a step come as arguments. Four calls per physics step make this the simulator's hot
    path: a call, a tuple unpacking and an attribute look-up each cost as
    much as several multiplications.
    """
    m, xg, yg, zg = k.mass_kg, k.xg, k.yg, k.zg
    ixx, iyy, izz = k.ixx, k.iyy, k.izz
    W, B, rad = k.weight_n, k.buoyancy_n, k.radius_m
    Xuu, Xwq, Xqq, Xvr, Xrr = k.Xuu, k.Xwq, k.Xqq, k.Xvr, k.Xrr
    Yvv, Yrr, Yuv, Ywp, Yur, Ypq, Yuudr = k.Yvv, k.Yrr, k.Yuv, k.Ywp, k.Yur, k.Ypq, k.Yuudr
    Zww, Zqq, Zuw, Zuq, Zvp, Zrp, Zuuds = k.Zww, k.Zqq, k.Zuw, k.Zuq, k.Zvp, k.Zrp, k.Zuuds
    Kpp = k.Kpp
    Mww, Mqq, Muw, Muq, Mvp, Mrp, Muuds = k.Mww, k.Mqq, k.Muw, k.Muq, k.Mvp, k.Mrp, k.Muuds
    Nvv, Nrr, Nuv, Nur, Nwp, Npq, Nuudr = k.Nvv, k.Nrr, k.Nuv, k.Nur, k.Nwp, k.Npq, k.Nuudr
    ma_u, ma_v, ma_w, ma_qw, ma_rv = k.added_u, k.added_v, k.added_w, k.added_qw, k.added_rv
    # M^-1 row by row (a matrix: its entries are positional by nature)
    (
        i00,
        i01,
        i02,
        i03,
        i04,
        i05,
        i10,
        i11,
        i12,
        i13,
        i14,
        i15,
        i20,
        i21,
        i22,
        i23,
        i24,
        i25,
        i30,
        i31,
        i32,
        i33,
        i34,
        i35,
        i40,
        i41,
        i42,
        i43,
        i44,
        i45,
        i50,
        i51,
        i52,
        i53,
        i54,
        i55,
    ) = minv

    def rhs(x, cn, ce, cd, acc, dr, ds, thrust, torque, et):
        _, _, z, phi, theta, psi, u, v, w, p, q, r = x
        cphi, sphi = cos(phi), sin(phi)
        cth, sth = cos(theta), sin(theta)
        cpsi, spsi = cos(psi), sin(psi)
        # rotation body -> NED
        r00 = cpsi * cth
        r01 = cpsi * sth * sphi - spsi * cphi
        r02 = spsi * sphi + cpsi * cphi * sth
        r10 = spsi * cth
        r11 = cpsi * cphi + sphi * sth * spsi
        r12 = sth * spsi * cphi - cpsi * sphi
        r20 = -sth
        r21 = cth * sphi
        r22 = cth * cphi

        if cn or ce or cd:
            uc = r00 * cn + r10 * ce + r20 * cd
            vc = r01 * cn + r11 * ce + r21 * cd
            wc = r02 * cn + r12 * ce + r22 * cd
            ur, vr, wr = u - uc, v - vc, w - wc
        else:
            uc = vc = wc = 0.0
            ur, vr, wr = u, v, w
        uau = ur * (ur if ur >= 0.0 else -ur)
        vav = vr * (vr if vr >= 0.0 else -vr)
        waw = wr * (wr if wr >= 0.0 else -wr)

        # hydrostatics: buoyancy falls as the hull breaks the surface
        fw = W - (B if z >= rad else B * submerged_fraction(z, rad))
        ex, ey, ez = -sth, r21, r22  # gravity direction, body frame
        pp, qq, rr = p * p, q * q, r * r
        aq = q if q >= 0.0 else -q
        ar = r if r >= 0.0 else -r
        ap = p if p >= 0.0 else -p

        X = (
            Xuu * uau
            + Xwq * wr * q
            + Xqq * qq
            + Xvr * vr * r
            + Xrr * rr
            + m * (v * r - w * q + xg * (qq + rr) - yg * p * q - zg * p * r)
            + fw * ex
            + thrust
        )
        Y = (
            Yvv * vav
            + Yrr * r * ar
            + Yuv * ur * vr
            + Ywp * wr * p
            + Yur * ur * r
            + Ypq * p * q
            + Yuudr * uau * dr
            + m * (w * p - u * r + yg * (rr + pp) - zg * q * r - xg * q * p)
            + fw * ey
        )
        Z = (
            Zww * waw
            + Zqq * q * aq
            + Zuw * ur * wr
            + Zuq * ur * q
            + Zvp * vr * p
            + Zrp * r * p
            + Zuuds * uau * ds
            + m * (u * q - v * p + zg * (pp + qq) - xg * r * p - yg * r * q)
            + fw * ez
        )
        # moments of weight about the CB: W (r_g x e)
        K = (
            Kpp * p * ap
            - (izz - iyy) * q * r
            - m * (yg * (v * p - u * q) - zg * (u * r - w * p))
            + W * (yg * ez - zg * ey)
            + torque
        )
        Mm = (
            Mww * waw
            + Mqq * q * aq
            + Muw * ur * wr
            + Muq * ur * q
            + Mvp * vr * p
            + Mrp * r * p
            + Muuds * uau * ds
            - (ixx - izz) * r * p
            - m * (zg * (w * q - v * r) - xg * (v * p - u * q))
            + W * (zg * ex - xg * ez)
        )
        N = (
            Nvv * vav
            + Nrr * r * ar
            + Nuv * ur * vr
            + Nur * ur * r
            + Nwp * wr * p
            + Npq * p * q
            + Nuudr * uau * dr
            - (iyy - ixx) * p * q
            - m * (xg * (u * r - w * p) - yg * (w * q - v * r))
            + W * (xg * ey - yg * ex)
        )
        # added mass acts on the relative acceleration: + M_A nu_c_dot,
        # nu_c_dot = v_c^b x omega (current fixed in NED)
        if uc or vc or wc:
            acv = wc * p - uc * r
            acw = uc * q - vc * p
            X += ma_u * (vc * r - wc * q)
            Y += ma_v * acv
            Z += ma_w * acw
            Mm += ma_qw * acw
            N += ma_rv * acv
        # The water accelerates (waves): the pressure gradient that drives it
        # pushes on the displaced volume (Froude-Krylov, rho V a, acting at the
        # CB, the body origin, so no moment) and the added mass follows the
        # water, + M_A R^T a (its w and v columns couple into pitch and yaw).
        an, ae, ad = acc
        if an or ae or ad:
            rho_v = (W - fw) / G  # displaced mass, less when surfacing
            abx = r00 * an + r10 * ae + r20 * ad
            aby = r01 * an + r11 * ae + r21 * ad
            abz = r02 * an + r12 * ae + r22 * ad
            X += (rho_v + ma_u) * abx
            Y += (rho_v + ma_v) * aby
            Z += (rho_v + ma_w) * abz
            Mm += ma_qw * abz
            N += ma_rv * aby
        if et is not None:
            X, Y, Z = X + et[0], Y + et[1], Z + et[2]
            K, Mm, N = K + et[3], Mm + et[4], N + et[5]
        tth = sth / cth
        return (
            r00 * u + r01 * v + r02 * w,
            r10 * u + r11 * v + r12 * w,
            r20 * u + r21 * v + r22 * w,
            p + sphi * tth * q + cphi * tth * r,
            cphi * q - sphi * r,
            (sphi * q + cphi * r) / cth,
            i00 * X + i01 * Y + i02 * Z + i03 * K + i04 * Mm + i05 * N,
            i10 * X + i11 * Y + i12 * Z + i13 * K + i14 * Mm + i15 * N,
            i20 * X + i21 * Y + i22 * Z + i23 * K + i24 * Mm + i25 * N,
            i30 * X + i31 * Y + i32 * Z + i33 * K + i34 * Mm + i35 * N,
            i40 * X + i41 * Y + i42 * Z + i43 * K + i44 * Mm + i45 * N,
            i50 * X + i51 * Y + i52 * Z + i53 * K + i54 * Mm + i55 * N,
        )

    return rhs
