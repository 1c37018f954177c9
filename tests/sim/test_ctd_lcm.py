"""The CTD from the real simulator over LCM, and a bad ocean grid refused by the
simulator's own check before anything starts (exit 2, file:line:col, the file)."""

from __future__ import annotations

import subprocess
import sys

import lcm
from lcm_proc import pump, start_simulator, stop

from auv import ctd_t, ground_truth_t
from auvlcm.rx import Receiver
from sim.config import load
from sim.environment import Environment

CONFIG = """
vehicle: {{id: AUV1}}
simulation: {{clock: scaled, warp: 10, lcm_url: "{url}"}}
initial: {{depth_m: 8.0, east_m: -40.0}}
environment:
  seed: 4
  bathymetry: "flat:depth=60"
  ocean:
    front: {{offset_m: 0, width_m: 30}}
    water_a: {{temperature_c: 17, salinity_psu: 33}}
    water_b: {{temperature_c: 13, salinity_psu: 34.5}}
sensors:
  depth: {{rate_hz: 10}}
  ctd: {{rate_hz: 16}}
"""


def test_the_simulator_publishes_the_ctd_of_its_ocean(tmp_path, child_env, lcm_url):
    cfg = tmp_path / "sim.yaml"
    cfg.write_text(CONFIG.format(url=lcm_url))
    lc = lcm.LCM(lcm_url)
    rx = Receiver(lc)
    got: dict[str, list] = {"AUV1.CTD": [], "AUV1.TRUTH": []}
    rx.subscribe("AUV1.CTD", ctd_t, lambda ch, m: got[ch].append(m), queue_capacity=5000)
    rx.subscribe("AUV1.TRUTH", ground_truth_t, lambda ch, m: got[ch].append(m), queue_capacity=5000)
    proc = start_simulator(cfg, child_env)
    try:
        assert pump(lc, lambda: len(got["AUV1.CTD"]) >= 64, timeout=30)  # 4 sim s
    finally:
        assert stop(proc) == 0
    ctd = got["AUV1.CTD"]
    span = (ctd[-1].utime - ctd[0].utime) / 1e6
    assert abs(span - (len(ctd) - 1) / 16.0) <= 0.02 + 1e-9  # every sample at 16 Hz, on the 50 Hz physics steps
    assert all(m.valid and m.vehicle == "AUV1" for m in ctd)
    env = Environment(load(cfg).env)
    truth = got["AUV1.TRUTH"][-1]
    north, east, depth = truth.eta[0:3]
    temp, salt = env.temperature_salinity(truth.utime / 1e6, north, east, depth)
    assert 13.0 < temp < 17.0  # in the front, west of its middle
    last = ctd[-1]
    assert abs(last.temperature_c - temp) < 0.05 and abs(last.salinity_psu - salt) < 0.05
    assert abs(last.depth_m - depth) < 0.3 and 1490.0 < last.sound_speed_mps < 1520.0


def test_a_bad_ocean_grid_stops_the_simulator_before_it_starts(tmp_path, child_env):
    (tmp_path / "sea.nc").write_bytes(b"PK\x03\x04 not netcdf at all")
    cfg = tmp_path / "sim.yaml"
    cfg.write_text("environment:\n  ocean:\n    grid: sea.nc\n")
    res = subprocess.run(
        [sys.executable, "-m", "sim", str(cfg), "--check"], capture_output=True, text=True, env=child_env, timeout=60
    )
    assert res.returncode == 2
    assert f"{cfg}:3:11: environment.ocean.grid: {tmp_path / 'sea.nc'}: not a NetCDF file" in res.stderr, res.stderr
