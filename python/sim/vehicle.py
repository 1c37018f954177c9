"""Vehicle parameters: mass properties, hydrodynamic coefficients, actuators.

The defaults are the REMUS 100 of Prestero (2001), as transcribed in
shared/reference/remus100.md. Another vehicle is another set of these numbers
(a `vehicle:` section in the simulator configuration), never other code.

Coefficient names follow Prestero/SNAME: `Xuu` is X_u|u|, `Yvd` is Y_v-dot,
`Yuudr` is Y_uu-delta-r. Body frame at the centre of buoyancy, x forward,
y starboard, z down; SI units.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields

from confcheck import setting

G = 9.81


def _remus_hydro() -> dict[str, float]:
    return {
        # axial drag
        "Xuu": -1.62,
        # added mass
        "Xud": -0.93,
        "Yvd": -35.5,
        "Zwd": -35.5,
        "Yrd": 1.93,
        "Zqd": -1.93,
        "Mwd": -1.93,
        "Nvd": 1.93,
        "Mqd": -4.88,
        "Nrd": -4.88,
        "Kpd": -7.04e-2,
        # cross-flow drag and rolling resistance, thesis Tables C.2/C.3 as
        # printed. Asymmetric on purpose (Y_v|v| = 10 Z_w|w|, M_q|q| = 2 N_r|r|):
        # that is the published data (docs/simulator.md, "The default vehicle").
        "Yvv": -1310.0,
        "Zww": -131.0,
        "Yrr": 0.632,
        "Zqq": -0.632,
        "Mww": 3.18,
        "Nvv": -3.18,
        "Mqq": -188.0,
        "Nrr": -94.0,
        "Kpp": -0.130,
        # added-mass cross terms (the entries of C_A(nu_r) nu_r not already in
        # the combined coefficients below)
        "Xwq": -35.5,
        "Xqq": -1.93,
        "Xvr": 35.5,
        "Xrr": -1.93,
        "Ywp": 35.5,
        "Ypq": 1.93,
        "Zvp": -35.5,
        "Zrp": 1.93,
        "Mvp": -1.93,
        "Mrp": 4.86,
        "Nwp": -1.93,
        "Npq": -4.86,
        # body lift and Munk moment
        "Yuv": -28.6,
        "Zuw": -28.6,
        "Nuv": -24.0,
        "Muw": 24.0,
        # combined added mass + fin lift
        "Yur": 5.22,
        "Zuq": -5.22,
        "Nur": -2.00,
        "Muq": -2.00,
        # control fins (Prestero's sign: + rudder pushes the tail to starboard)
        "Yuudr": 9.64,
        "Zuuds": -9.64,
        "Nuudr": -6.15,
        "Muuds": -6.15,
    }


@dataclass
class VehicleParams:
    name: str = "REMUS 100 (Prestero 2001)"
    mass_kg: float = setting(30.48, gt=0.0)
    buoyancy_n: float = setting(306.0, gt=0.0)
    length_m: float = setting(1.33, gt=0.0)
    diameter_m: float = setting(0.191, gt=0.0)
    # CG relative to the CB (the body origin) [m]
    cg_m: tuple[float, float, float] = (0.0, 0.0, 0.0196)
    inertia_kgm2: tuple[float, float, float] = (0.177, 3.45, 3.45)
    hydro: dict[str, float] = field(default_factory=_remus_hydro)

    # fins
    fin_max_rad: float = setting(math.radians(20.0), ge=0.0)  # MSS REMUS 100 figure
    fin_rate_radps: float = setting(math.radians(40.0), ge=0.0)  # servo slew limit (assumed)
    # The channel contract (actuators_t) says positive rudder turns the bow to
    # starboard. This factor maps a commanded rudder angle onto the model's
    # fin coefficients; set it to -1 for a vehicle whose coefficients use the
    # opposite sign.
    rudder_sign: float = -1.0
    stern_plane_sign: float = 1.0

    # propeller: thrust = kT rpm|rpm|, torque = kQ rpm|rpm|, from one
    # published operating point, with a first-order lag on rpm
    prop_nominal_rpm: float = 1500.0
    prop_nominal_thrust_n: float = 3.86
    prop_nominal_torque_nm: float = -0.543
    prop_max_rpm: float = setting(2450.0, ge=0.0)  # about 2.5 m/s, the published maximum
    prop_time_constant_s: float = setting(0.3, ge=0.0)

    @property
    def weight_n(self) -> float:
        return self.mass_kg * G

    @property
    def radius_m(self) -> float:
        return self.diameter_m / 2.0

    def with_updates(self, updates: dict) -> "VehicleParams":
        """A copy with some fields (and some hydro coefficients) replaced."""
        kw = {f.name: getattr(self, f.name) for f in fields(self)}
        kw["hydro"] = dict(self.hydro)
        for key, value in updates.items():
            if key == "hydro":
                unknown = set(value) - set(kw["hydro"])
                if unknown:
                    raise KeyError(f"unknown hydrodynamic coefficient(s): {sorted(unknown)}")
                kw["hydro"].update(value)
            elif key in kw:
                kw[key] = tuple(value) if isinstance(kw[key], tuple) else value
            else:
                raise KeyError(f"unknown vehicle parameter {key!r}")
        return VehicleParams(**kw)


REMUS100 = VehicleParams()
