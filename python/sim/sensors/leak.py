"""The hull leak detector: water-sensing probes, with a fault-injection
switch (docs/simulator.md, "Leak detector").

    sensors:
      leak: {rate_hz: 1, at_s: 300, probes: 2}

From `at_s` (sim seconds; -1: never) on, water is in the hull: every sample
says `detected` with `probes_wet` probes wet. A scenario's planned fault
`{at: 300, vehicle: AUV1, do: leak}` sets `at_s` (docs/scenarios.md). A dropout
(the `dropout` probability) loses a sample, as for every sensor."""

from __future__ import annotations

from dataclasses import dataclass

from auv import leak_t
from confcheck import setting
from sim.model import Truth
from sim.sensors.base import Sensor, SensorConfig, utime


@dataclass
class LeakConfig(SensorConfig):
    rate_hz: float = setting(1.0, gt=0.0, unit="Hz")
    at_s: float = setting(-1.0, ge=-1.0)  # water from this sim time on [s]; -1: never
    probes: int = setting(2, ge=1, le=16)  # probes fitted


class LeakSensor(Sensor):
    name = "leak"
    topic = "LEAK"
    config_class = LeakConfig
    cfg: LeakConfig

    def measure(self, tr: Truth):
        c = self.cfg
        m = leak_t()
        m.utime, m.vehicle = utime(tr.t), self.vehicle
        m.detected = 0.0 <= c.at_s <= tr.t + 1e-9
        m.probes = c.probes
        m.probes_wet = c.probes if m.detected else 0
        return m
