"""6-DOF rigid-body dynamics in Fossen's form, Prestero's REMUS coefficients.

    M nu_dot + C_RB(nu) nu + [C_A(nu_r) nu_r + D(nu_r) nu_r] + g(eta) = tau
    eta_dot = J(eta) nu

The equations and the RK4 step are C: c/dynamics/auv_dynamics.c, built as
build/lib/libauvdynamics.so (`make build`) and called here through ctypes.
They are the one copy; this module holds what is built once per vehicle
(the mass matrix M = M_RB + M_A, inverted here once; the constants the
equations read, Coefficients) and Dynamics, the integrator the simulator
drives. Why C: in Python the right-hand side, four calls a step, was the
hot path of a simulator running as fast as it can (docs/simulator.md,
"Performance").

Hydrodynamic terms use the velocity relative to the water nu_r = nu - nu_c;
a wave field's acceleration adds the Froude-Krylov force and the added-mass
force of the accelerating water; a current fixed in NED adds M_A nu_c_dot
(the C file says why, term by term). Euler angles (ZYX) are used: valid away
from pitch = +-90 deg, which an AUV never reaches in service.
"""

from __future__ import annotations

import ctypes
import functools
import struct
from dataclasses import dataclass, fields
from pathlib import Path

import numpy as np

from auvlcm.paths import build_dir
from sim.vehicle import G, VehicleParams

LIBRARY = "libauvdynamics.so"
ETA = ("north_m", "east_m", "down_m", "roll_rad", "pitch_rad", "yaw_rad")
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
    """Fraction of a horizontal cylinder's volume under water, its axis at
    depth_m: how much of the buoyancy is left as the hull breaks the surface."""
    return _library().auv_dyn_submerged_fraction(depth_m, radius_m)


@dataclass(frozen=True)
class Coefficients:
    """One vehicle's constants, as the right-hand side reads them (built once).

    Dynamics copies them into the C struct by name: each field is a field of
    auv_dyn_t (c/dynamics/auv_dynamics.h, AUV_DYN_CONSTANTS) of the same name.

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
    g_mps2: float  # the buoyancy's displaced mass is (its force) / g
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
            g_mps2=G,
            added_u=-h["Xud"],
            added_v=-h["Yvd"],
            added_w=-h["Zwd"],
            added_qw=-h["Mwd"],
            added_rv=-h["Nvd"],
            **{f.name: h[f.name] for f in fields(cls) if f.name in h},
        )


# --------------------------------------------------------------- the binding
# The held inputs as auv_dyn_t holds them, one after the other, so that a
# step writes them with one struct.pack_into (the cheapest way found to get
# ten floats into C memory). _library() checks this order against the C.
_INPUTS = (("rudder", 1), ("stern", 1), ("thrust", 1), ("torque", 1), ("current_ned", 3), ("water_accel_ned", 3))
_PACK_INPUTS = struct.Struct("=10d").pack_into
_PACK_TAU = struct.Struct("=6d").pack_into
_NO_TAU = (0.0,) * 6


class DynamicsUnavailable(RuntimeError):
    """The dynamics library is not built (or is not the one this module knows)."""


def library_path() -> Path:
    return build_dir() / "lib" / LIBRARY


@functools.cache
def _library() -> ctypes.PyDLL:
    """The dynamics library, loaded once.

    PyDLL, not CDLL: a call keeps the GIL, which a step (about a microsecond)
    is far cheaper than releasing and taking back."""
    path = library_path()
    if not path.exists():
        raise DynamicsUnavailable(f"{path} is not built: run `make build` (the dynamics are C, c/dynamics/)")
    lib = ctypes.PyDLL(str(path))
    vp, doubles = ctypes.c_void_p, ctypes.POINTER(ctypes.c_double)
    lib.auv_dyn_size.argtypes, lib.auv_dyn_size.restype = [], ctypes.c_size_t
    lib.auv_dyn_constant_count.argtypes, lib.auv_dyn_constant_count.restype = [], ctypes.c_size_t
    lib.auv_dyn_field.argtypes = [ctypes.c_char_p, ctypes.POINTER(ctypes.c_size_t)]
    lib.auv_dyn_field.restype = ctypes.c_long
    lib.auv_dyn_rhs.argtypes, lib.auv_dyn_rhs.restype = [vp, doubles, doubles], None
    lib.auv_dyn_step.argtypes, lib.auv_dyn_step.restype = [vp], None
    lib.auv_dyn_submerged_fraction.argtypes = [ctypes.c_double, ctypes.c_double]
    lib.auv_dyn_submerged_fraction.restype = ctypes.c_double
    # Every constant named alike on both sides, the inputs in _INPUTS' order:
    # a mismatch would feed the equations wrong numbers without a word.
    names = [f.name for f in fields(Coefficients)]
    unknown = [n for n in names if _field(lib, n)[0] < 0]
    if unknown or lib.auv_dyn_constant_count() != len(names):
        raise DynamicsUnavailable(f"{path} does not hold Coefficients' fields (unknown: {unknown}): rebuild it")
    start = _field(lib, _INPUTS[0][0])[0]
    where = [_field(lib, name) for name, _ in _INPUTS]
    if where != [(start + 8 * sum(k for _, k in _INPUTS[:i]), n) for i, (_, n) in enumerate(_INPUTS)]:
        raise DynamicsUnavailable(f"{path}: the inputs are not where sim.dynamics puts them: rebuild it")
    return lib


def _field(lib, name: str) -> tuple[int, int]:
    """Byte offset and length (doubles) of a field of auv_dyn_t; offset -1: none."""
    count = ctypes.c_size_t()
    return lib.auv_dyn_field(name.encode(), ctypes.byref(count)), count.value


class Dynamics:
    """Integrates eta (NED pose) and nu (body velocity) with fixed-step RK4.

    The state and the inputs live in one C struct (auv_dyn_t) per vehicle:
    `x` is a live view of its state (12 doubles: index it, slice it for a
    list, assign an element or all of it), `nu_dot` the body acceleration at
    the start of the last step. The inputs are plain attributes, held over a
    step: step() hands them to C (one pack) and makes one C call.
    """

    def __init__(self, vp: VehicleParams, dt: float = 0.02) -> None:
        if not dt > 0.0:
            raise ValueError("physics step must be positive")
        lib = _library()
        self.vp = vp
        self.dt = dt
        self.M = mass_matrix(vp)
        self.coefficients = k = Coefficients.from_vehicle(vp)
        # the struct, zeroed, as doubles (every field of it is one)
        self._buf = buf = (ctypes.c_double * (lib.auv_dyn_size() // 8))()

        def view(name: str) -> ctypes.Array:
            off, n = _field(lib, name)
            return (ctypes.c_double * n).from_buffer(buf, off)

        for f in fields(Coefficients):
            view(f.name)[0] = getattr(k, f.name)
        view("minv")[:] = [float(v) for v in np.linalg.inv(self.M).ravel()]
        view("dt")[0] = dt
        # state: north, east, down, roll, pitch, yaw, u, v, w, p, q, r
        self._x = view("x")
        self._nu_dot = view("nu_dot")
        self._inputs_at = _field(lib, _INPUTS[0][0])[0]
        self._tau_at = _field(lib, "tau")[0]
        self._tau_set = False
        self._xin, self._xdot = (ctypes.c_double * 12)(), (ctypes.c_double * 12)()
        self._c_step, self._c_rhs = lib.auv_dyn_step, lib.auv_dyn_rhs
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

    # ------------------------------------------------------------------ API
    @property
    def x(self) -> ctypes.Array:
        return self._x

    @x.setter
    def x(self, value) -> None:
        self._x[:] = value

    @property
    def eta(self) -> list[float]:
        return self._x[0:6]

    @property
    def nu(self) -> list[float]:
        return self._x[6:12]

    @property
    def nu_dot(self) -> list[float]:
        return self._nu_dot[:]

    def set_state(self, eta, nu=(0.0,) * 6) -> None:
        self._x[0:6] = [float(v) for v in eta]
        self._x[6:12] = [float(v) for v in nu]

    def step(self) -> None:
        """Advance one fixed step with classic RK4 (inputs held), in C."""
        self._hand_inputs()
        self._c_step(self._buf)
        self.t += self.dt

    def forces(self) -> list[float]:
        """The generalised force vector (right-hand side) at the current state: M nu_dot."""
        nu_dot = self._deriv(self._x)[6:12]
        return [float(v) for v in self.M @ np.array(nu_dot)]

    # ------------------------------------------------------------ internals
    def _hand_inputs(self) -> None:
        """The held inputs into the C struct."""
        cn, ce, cd = self.current_ned
        an, ae, ad = self.water_accel_ned
        _PACK_INPUTS(
            self._buf, self._inputs_at, self.rudder, self.stern, self.thrust, self.torque, cn, ce, cd, an, ae, ad
        )
        et = self.external_tau
        if et is not None:
            _PACK_TAU(self._buf, self._tau_at, *et)
            self._tau_set = True
        elif self._tau_set:
            _PACK_TAU(self._buf, self._tau_at, *_NO_TAU)
            self._tau_set = False

    def _deriv(self, x) -> list[float]:
        """x_dot for state x with the inputs held now (the validation's Jacobian)."""
        self._hand_inputs()
        self._xin[:] = x
        self._c_rhs(self._buf, self._xin, self._xdot)
        return self._xdot[:]
