"""Sensor models. Each turns the true state into the message a real instrument sends.

SENSORS is the one registry: a sensor is declared by its class (name, topic,
config_class, env_needs, uses, nav_config: sim.sensors.base.Sensor) and one
line here (a payload not every vehicle carries, the CTD, is built only where a
configuration lists it: FITTED_UNLESS_LISTED). Everything else that lists
sensors derives from it: the keys of a
configuration's `sensors:`, the channels an INS may not move onto
(sim.config.RESERVED_TOPICS), the navigation filter's figures (tools.nav.navconf).
"""

from sim.sensors.base import Sensor, SensorConfig
from sim.sensors.ctd import Ctd, CtdConfig
from sim.sensors.ins import Ins, InsConfig
from sim.sensors.instruments import (
    Ahrs,
    AhrsConfig,
    Altimeter,
    AltimeterConfig,
    DepthConfig,
    DepthSensor,
    Dvl,
    DvlConfig,
    Gps,
    GpsConfig,
)
from sim.sensors.lbl import Lbl, LblConfig
from sim.sensors.leak import LeakConfig, LeakSensor

# In this order a vehicle whose configuration lists no sensors builds them
# (and publishes those due at the same instant).
SENSORS: tuple[type[Sensor], ...] = (Ahrs, DepthSensor, Dvl, Altimeter, Gps, Lbl, Ins, LeakSensor, Ctd)

# name in the configuration -> (config class, sensor class), derived
REGISTRY = {s.name: (s.config_class, s) for s in SENSORS}
# what a configuration that lists no sensors is fitted with (Sensor.fitted_unless_listed)
FITTED_UNLESS_LISTED = tuple(s.name for s in SENSORS if s.fitted_unless_listed)

__all__ = [
    "Sensor",
    "SensorConfig",
    "SENSORS",
    "REGISTRY",
    "FITTED_UNLESS_LISTED",
    "Ctd",
    "CtdConfig",
    "Ahrs",
    "AhrsConfig",
    "DepthSensor",
    "DepthConfig",
    "Dvl",
    "DvlConfig",
    "Altimeter",
    "AltimeterConfig",
    "Gps",
    "GpsConfig",
    "Lbl",
    "LblConfig",
    "Ins",
    "InsConfig",
    "LeakSensor",
    "LeakConfig",
]
