"""The ocean's parameters: what `environment.ocean:` holds and env_model_t carries.

Every field here but `area` and `base_dir` travels in auv.env_model_t
(sim.environment: to_env_model / params_from_env_model), so a multi-HIL client
builds the same ocean as its server. `area` is only what the configuration's
check holds a grid file to (it must cover it); `base_dir` is where a relative
grid file is found on this host (the configuration's folder).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

from confcheck import setting

# The water of a world without an `ocean:` section: uniform, with the constant
# sound speed of environment.sound_speed_mps (the TEOS-10 speed of this water
# is not used there, so that worlds written before the ocean keep their speed).
UNIFORM_TEMPERATURE_C = 12.0
UNIFORM_SALINITY_PSU = 35.0


@dataclass
class WaterMass:
    temperature_c: float = setting(12.0, ge=-2.5, le=40.0, unit="degC")  # in-situ
    salinity_psu: float = setting(35.0, ge=0.0, le=42.0, unit="PSU")  # practical salinity


@dataclass
class Front:
    """A front between two upper water masses: a line through the world that runs
    along `angle_rad` (from north), `offset_m` across it from the origin (to its
    right looking along it), meandering and drifting."""

    offset_m: float = 0.0  # mean distance of the front from the origin, across it [m]
    angle_rad: float = 0.0  # the direction it runs along, from north, clockwise [rad]
    amplitude_m: float = setting(0.0, ge=0.0)  # meander amplitude [m]
    wavelength_m: float = setting(2000.0, gt=0.0)  # meander wavelength along the front [m]
    period_s: float = setting(0.0, ge=0.0)  # a meander's period at a fixed point; 0: standing [s]
    width_m: float = setting(50.0, gt=0.0)  # half-width: tanh(across / width) [m]
    drift_mps: float = 0.0  # the whole front moves across itself (to its right) [m/s]


@dataclass
class Thermocline:
    depth_m: float = setting(25.0, ge=0.0)  # its centre [m]
    thickness_m: float = setting(5.0, gt=0.0)  # half-thickness: tanh((z - depth) / thickness) [m]


@dataclass
class Plume:
    """A patch of anomalous water released at a point and time, carried by the
    current at its depth and spreading by a horizontal diffusivity."""

    north_m: float = 0.0
    east_m: float = 0.0
    depth_m: float = setting(5.0, ge=0.0)
    start_s: float = setting(0.0, ge=0.0)  # released at this sim time [s]
    radius_m: float = setting(50.0, gt=0.0)  # horizontal 1-sigma at release [m]
    thickness_m: float = setting(3.0, gt=0.0)  # vertical 1-sigma [m]
    diffusivity_m2ps: float = setting(0.5, ge=0.0)  # horizontal spreading [m^2/s]
    temperature_c: float = setting(0.0, ge=-20.0, le=20.0)  # anomaly at its centre at release [degC]
    salinity_psu: float = setting(0.0, ge=-30.0, le=10.0)  # anomaly at its centre at release [PSU]


@dataclass
class Area:
    """Where and how long the world is used: a grid file must cover it."""

    north_m: list = setting(factory=list)  # [min, max]; [] the vehicle's start and the transponders
    east_m: list = setting(factory=list)
    max_depth_m: float = setting(-1.0, ge=-1.0)  # -1: the deepest of the start and the transponders
    duration_s: float = setting(-1.0, ge=-1.0)  # -1: simulation.duration_s


@dataclass
class OceanParams:
    front: Front = field(default_factory=Front)
    # the upper water left (a) and right (b) of the front, and below the thermocline
    water_a: WaterMass = field(default_factory=lambda: WaterMass(16.0, 32.5))
    water_b: WaterMass = field(default_factory=lambda: WaterMass(12.0, 34.5))
    deep: WaterMass = field(default_factory=lambda: WaterMass(8.0, 35.0))
    thermocline: Thermocline = field(default_factory=Thermocline)
    plumes: list[Plume] = field(default_factory=list)
    grid: str = ""  # a NetCDF file (CF) instead of front, water masses and thermocline
    grid_start: str = ""  # the file's time at sim time 0 (ISO 8601); "": its first time
    area: Area = field(default_factory=Area, compare=False)  # what a grid must cover (not carried)
    # where a relative grid file is on this host (the configuration's folder):
    # set on the instance by the configuration's check, neither a key nor carried
    base_dir: ClassVar[str] = ""
