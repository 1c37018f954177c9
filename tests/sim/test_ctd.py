"""The CTD (sim.sensors.ctd, docs/sampling.md "The CTD"): its values against
TEOS-10, the thermistor's lag (63 % of a step one tau later, tau behind a ramp),
the salinity spike the lag makes across a front, noise, resolution, dropouts."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sim.environment import Environment, EnvParams
from sim.model import Truth
from sim.ocean import Front, OceanParams, Thermocline, WaterMass, teos10
from sim.sensors import Ctd, CtdConfig

LAT, LON = 41.52, -70.67
QUIET = dict(
    noise=0.0,
    conductivity_noise=0.0,
    pressure_noise=0.0,
    temperature_resolution_c=0.0,
    conductivity_resolution_s_per_m=0.0,
    pressure_resolution_dbar=0.0,
)


class Water:
    """A stand-in world: the water's temperature as a function of time."""

    def __init__(self, temperature, salinity=35.0):
        self.temperature, self.salinity = temperature, salinity

    def temperature_salinity(self, t, north, east, depth):
        return self.temperature(t), self.salinity


def truth(t, north=0.0, east=0.0, depth=10.0):
    return Truth(t=t, eta=(north, east, depth, 0.0, 0.0, 0.0), latitude_deg=LAT, longitude_deg=LON)


def samples(sensor, make_truth, seconds):
    out = []
    dt = 1.0 / sensor.cfg.rate_hz
    for i in range(int(round(seconds * sensor.cfg.rate_hz)) + 1):
        m = sensor.poll(make_truth(i * dt))
        if m is not None:
            out.append((i * dt, m))
    return out


def test_a_quiet_ctd_reads_the_water_and_derives_by_teos10():
    env = Environment(EnvParams(ocean=OceanParams(water_a=WaterMass(14.0, 33.0), water_b=WaterMass(14.0, 33.0))))
    s = Ctd(CtdConfig(temperature_tau_s=0.0, **QUIET), 1, "AUV1", env)
    m = s.poll(truth(0.0, depth=12.0))
    temp, salt = env.temperature_salinity(0.0, 0.0, 0.0, 12.0)
    p = float(teos10.pressure_dbar(12.0, LAT))
    assert m.valid and m.vehicle == "AUV1" and m.utime == 0
    assert m.temperature_c == pytest.approx(temp) and m.pressure_dbar == pytest.approx(p)
    assert m.conductivity_s_per_m == pytest.approx(float(teos10.conductivity_s_per_m(salt, temp, p)))
    assert m.salinity_psu == pytest.approx(salt, abs=1e-9)  # PSS-78 both ways
    assert m.depth_m == pytest.approx(12.0, abs=1e-6)
    assert m.sound_speed_mps == pytest.approx(float(teos10.sound_speed(temp, salt, 12.0, LAT, LON)), abs=1e-6)
    # a world without `ocean:`: uniform 12 degC, 35 PSU
    plain = Ctd(CtdConfig(**QUIET), 1, "AUV1", Environment(EnvParams()))
    m = plain.poll(truth(0.0))
    assert (m.temperature_c, m.salinity_psu) == pytest.approx((12.0, 35.0), abs=1e-9)


def test_the_thermistor_has_63_percent_of_a_step_one_tau_later():
    """A step of 10 degC at t = 2 s between two samples, tau 0.5 s, 16 Hz: the
    reading one tau after the step is 63 % of it, within the half sample the
    step's time is known to (the lag takes the water as a ramp between samples)."""
    tau, step_t = 0.5, 2.0 + 1.0 / 32
    s = Ctd(CtdConfig(temperature_tau_s=tau, **QUIET), 1, "AUV1", Water(lambda t: 10.0 if t < step_t else 20.0))
    got = dict(samples(s, truth, 8.0))
    times = np.array(sorted(got))
    reading = np.array([got[t].temperature_c for t in times])
    assert reading[times < step_t] == pytest.approx(10.0)
    frac = np.interp(step_t + tau, times, reading - 10.0) / 10.0
    dt = 1.0 / 16
    lo, hi = 1 - math.exp(-(tau - dt / 2) / tau), 1 - math.exp(-(tau + dt / 2) / tau)
    assert lo <= frac <= hi and frac == pytest.approx(1 - math.exp(-1), abs=0.025)
    assert reading[-1] == pytest.approx(20.0, abs=1e-4)  # settled after 12 tau
    # and the time constant as a fit of the whole response: ln(remaining) falls 1/tau a second
    after = (times > step_t + dt) & (times < step_t + 2.0)
    slope = np.polyfit(times[after], np.log(20.0 - reading[after]), 1)[0]
    assert -1.0 / slope == pytest.approx(tau, rel=1e-6)


def test_through_a_steady_gradient_the_thermistor_reads_k_tau_behind():
    s = Ctd(CtdConfig(temperature_tau_s=0.5, **QUIET), 1, "AUV1", Water(lambda t: 10.0 + 0.2 * t))
    got = samples(s, truth, 8.0)
    t, m = got[-1]
    assert m.temperature_c == pytest.approx(10.0 + 0.2 * t - 0.2 * 0.5, abs=1e-6)


def test_the_lag_spikes_the_salinity_across_a_front():
    """Through a sharp temperature front (16 to 12 degC, salinity 34.0 to 34.2)
    at 1.5 m/s: the conductivity cell sees the cold water at once, the
    thermistor a moment later, so the derived salinity dips far below both
    waters (by 0.47 PSU), as a real CTD's does before its lag is corrected; with
    no lag it stays between them."""
    ocean = OceanParams(
        front=Front(offset_m=30.0, width_m=2.0),
        water_a=WaterMass(16.0, 34.0),
        water_b=WaterMass(12.0, 34.2),
        thermocline=Thermocline(200.0, 5.0),
    )
    env = Environment(EnvParams(ocean=ocean))

    def crossing(tau):
        s = Ctd(CtdConfig(temperature_tau_s=tau, **QUIET), 1, "AUV1", env)
        return np.array([m.salinity_psu for _, m in samples(s, lambda t: truth(t, east=1.5 * t, depth=5.0), 40.0)])

    lagged, prompt = crossing(0.5), crossing(0.0)
    assert prompt.min() >= 34.0 - 1e-6 and prompt.max() <= 34.2 + 1e-6
    assert lagged.min() == pytest.approx(33.53, abs=0.01)  # the spike: warm thermistor, cold water's conductivity
    assert lagged[0] == pytest.approx(34.0, abs=1e-6) and lagged[-1] == pytest.approx(34.2, abs=1e-4)


def test_noise_offsets_and_resolution_are_as_configured():
    cfg = CtdConfig(
        noise=0.01,
        bias=0.02,
        conductivity_noise=0.002,
        pressure_noise=0.05,
        pressure_bias=-0.1,
        temperature_tau_s=0.0,
    )
    s = Ctd(cfg, 3, "AUV1", Water(lambda t: 11.0, 34.0))
    msgs = [m for _, m in samples(s, lambda t: truth(t, depth=20.0), 250.0)]
    assert len(msgs) == 4001  # 16 Hz
    temp = np.array([m.temperature_c for m in msgs])
    cond = np.array([m.conductivity_s_per_m for m in msgs])
    pres = np.array([m.pressure_dbar for m in msgs])
    p = float(teos10.pressure_dbar(20.0, LAT))
    c = float(teos10.conductivity_s_per_m(34.0, 11.0, p))
    n = len(msgs)
    for x, mean, sigma in ((temp, 11.02, 0.01), (cond, c, 0.002), (pres, p - 0.1, 0.05)):
        assert x.mean() == pytest.approx(mean, abs=4 * sigma / math.sqrt(n))
        assert x.std() == pytest.approx(sigma, rel=0.05)
    # quantised to the SBE 49's resolution
    assert np.allclose(temp / 1e-4, np.round(temp / 1e-4), atol=1e-6)
    assert np.allclose(cond / 5e-5, np.round(cond / 5e-5), atol=1e-6)
    assert np.allclose(pres / 0.007, np.round(pres / 0.007), atol=1e-6)
    # the same seed, the same readings; another, others
    again = Ctd(cfg, 3, "AUV1", Water(lambda t: 11.0, 34.0))
    assert [m.temperature_c for _, m in samples(again, lambda t: truth(t, depth=20.0), 2.0)] == list(temp[:33])


def test_a_dropout_is_published_invalid():
    s = Ctd(CtdConfig(dropout=0.3), 2, "AUV1", Water(lambda t: 11.0))
    msgs = [m for _, m in samples(s, truth, 60.0)]
    bad = [m for m in msgs if not m.valid]
    assert len(msgs) == 961 and 0.25 < len(bad) / len(msgs) < 0.35
    assert all(m.temperature_c == 0.0 and m.salinity_psu == 0.0 for m in bad)
