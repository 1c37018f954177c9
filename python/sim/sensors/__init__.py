"""Sensor models. Each turns the true state into the message a real instrument sends."""

from sim.sensors.base import Sensor, SensorConfig
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

# name in the configuration -> (config class, sensor class)
REGISTRY = {
    "ahrs": (AhrsConfig, Ahrs),
    "depth": (DepthConfig, DepthSensor),
    "dvl": (DvlConfig, Dvl),
    "altimeter": (AltimeterConfig, Altimeter),
    "gps": (GpsConfig, Gps),
    "lbl": (LblConfig, Lbl),
    "ins": (InsConfig, Ins),
    "leak": (LeakConfig, LeakSensor),
}

__all__ = [
    "Sensor",
    "SensorConfig",
    "REGISTRY",
    "Ahrs",
    "DepthSensor",
    "Dvl",
    "Altimeter",
    "Gps",
    "Lbl",
    "Ins",
    "LeakSensor",
]
