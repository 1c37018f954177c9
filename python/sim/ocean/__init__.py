"""The ocean's temperature and salinity, and seawater by TEOS-10 (docs/sampling.md).

params   what `environment.ocean:` holds (and env_model_t carries)
fields   Ocean: the analytic front, thermocline and plumes, or a grid; sound speed
grid     OceanGrid: a NetCDF (CF) file read with xarray, checked, interpolated
teos10   the gsw conversions: sound speed, conductivity, salinity, pressure
config   the `ocean:` section's checks (file:line:col), the grid's coverage
"""

from sim.ocean.fields import Ocean, grid_path
from sim.ocean.grid import OceanError, OceanGrid, load_grid
from sim.ocean.params import (
    UNIFORM_SALINITY_PSU,
    UNIFORM_TEMPERATURE_C,
    Area,
    Front,
    OceanParams,
    Plume,
    Thermocline,
    WaterMass,
)

__all__ = [
    "Area",
    "Front",
    "Ocean",
    "OceanError",
    "OceanGrid",
    "OceanParams",
    "Plume",
    "Thermocline",
    "UNIFORM_SALINITY_PSU",
    "UNIFORM_TEMPERATURE_C",
    "WaterMass",
    "grid_path",
    "load_grid",
]
