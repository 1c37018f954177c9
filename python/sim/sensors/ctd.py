"""A CTD: conductivity, temperature and pressure, as a Sea-Bird SBE 49 class
instrument measures them, with salinity, depth and sound speed derived by
TEOS-10 as its software does (docs/sampling.md, "The CTD").

    sensors:
      ctd: {rate_hz: 16, temperature_tau_s: 0.5}

Each sample reads the ocean's in-situ temperature and practical salinity at
the vehicle (Environment.temperature_salinity: uniform 12 degC, 35 PSU in a
world without `ocean:`) and the pressure of the depth a gauge reads (the
waves' dynamic pressure included), then:

- the conductivity cell sees the water as it is: C = gsw.C_from_SP(S, T, p);
- the thermistor lags the water by a first order of time constant
  `temperature_tau_s`, solved exactly for water whose temperature changes
  linearly between two samples (a ramp of slope k over dt, a = e^(-dt/tau):
  T_s1 = T1 - k tau + (T_s0 - T0 + k tau) a), started at the water's
  temperature: through a steady gradient it reads k tau behind, and after a
  step it has 63 % of it one tau later;
- each has its white noise and offset, is quantised to its resolution, and
  conductivity is never negative;
- salinity = gsw.SP_from_C(C measured, T measured, p measured): conductivity
  is the water's now, the temperature a moment ago, so across a front the
  derived salinity spikes, as a real CTD's does before its lag is corrected;
- depth = -gsw.z_from_p(p, latitude), sound speed = gsw.sound_speed from the
  measured values (sim.ocean.teos10).

A dropout (the `dropout` probability) is published with `valid` false.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from auv import ctd_t
from confcheck import setting
from sim.model import Truth
from sim.ocean import teos10
from sim.sensors.base import Sensor, SensorConfig, utime


@dataclass
class CtdConfig(SensorConfig):
    rate_hz: float = setting(16.0, gt=0.0, unit="Hz")  # the SBE 49's 16 scans a second
    noise: float = setting(0.0005, ge=0.0)  # temperature, 1-sigma [degC]
    bias: float = 0.0  # temperature offset [degC]
    conductivity_noise: float = setting(0.0001, ge=0.0)  # 1-sigma [S/m]
    conductivity_bias: float = 0.0  # [S/m]
    pressure_noise: float = setting(0.01, ge=0.0)  # 1-sigma [dbar]
    pressure_bias: float = 0.0  # [dbar]
    temperature_resolution_c: float = setting(0.0001, ge=0.0)  # 0: not quantised
    conductivity_resolution_s_per_m: float = setting(0.00005, ge=0.0)
    pressure_resolution_dbar: float = setting(0.007, ge=0.0)  # 0.002 % of a 350 dbar range
    temperature_tau_s: float = setting(0.5, ge=0.0)  # the thermistor's first-order lag; 0: none


def quantise(x: float, step: float) -> float:
    return round(x / step) * step if step > 0.0 else x


class Ctd(Sensor):
    name = "ctd"
    topic = "CTD"
    config_class = CtdConfig
    env_needs = ("ocean",)  # the water's temperature and salinity
    uses = ("env",)
    fitted_unless_listed = False  # a payload: fitted where a configuration lists it
    cfg: CtdConfig

    def __init__(self, cfg, seed, vehicle, env) -> None:
        super().__init__(cfg, seed, vehicle)
        self.env = env
        self.lagged_c: float | None = None  # the thermistor's temperature
        self._last_t = 0.0
        self._last_water_c = 0.0

    def restart(self, t: float) -> None:
        super().restart(t)
        self.lagged_c = None

    def _thermistor(self, t: float, water_c: float) -> float:
        tau = self.cfg.temperature_tau_s
        dt = t - self._last_t
        if self.lagged_c is None or tau <= 0.0:
            self.lagged_c = water_c
        elif dt > 0.0:
            k = (water_c - self._last_water_c) / dt  # the water's ramp since the last sample
            a = math.exp(-dt / tau)
            self.lagged_c = water_c - k * tau + (self.lagged_c - self._last_water_c + k * tau) * a
        self._last_t, self._last_water_c = t, water_c
        return self.lagged_c

    def measure(self, tr: Truth):
        c = self.cfg
        gauss = self.gauss
        n, e, d = tr.eta[0], tr.eta[1], tr.eta[2]
        water_c, water_psu = self.env.temperature_salinity(tr.t, n, e, d)
        lat, lon = tr.latitude_deg, tr.longitude_deg
        p_true = float(teos10.pressure_dbar(max(tr.pressure_depth, 0.0), lat))
        cond = float(teos10.conductivity_s_per_m(water_psu, water_c, p_true))
        temp = quantise(self._thermistor(tr.t, water_c) + c.bias + gauss(c.noise), c.temperature_resolution_c)
        cond = quantise(
            max(cond + c.conductivity_bias + gauss(c.conductivity_noise), 0.0), c.conductivity_resolution_s_per_m
        )
        pres = quantise(p_true + c.pressure_bias + gauss(c.pressure_noise), c.pressure_resolution_dbar)
        m = ctd_t()
        m.utime, m.vehicle, m.valid = utime(tr.t), self.vehicle, True
        m.temperature_c, m.conductivity_s_per_m, m.pressure_dbar = temp, cond, pres
        m.salinity_psu = float(teos10.salinity_from_conductivity(cond, temp, pres))
        m.depth_m = float(teos10.depth_from_pressure(pres, lat))
        m.sound_speed_mps = float(teos10.sound_speed_p(temp, m.salinity_psu, max(pres, 0.0), lat, lon))
        return m

    def dropout_message(self, tr: Truth):
        m = ctd_t()
        m.utime, m.vehicle, m.valid = utime(tr.t), self.vehicle, False
        return m
