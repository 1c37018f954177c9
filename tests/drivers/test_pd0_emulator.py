"""The simulator's DVL at the wire (python/sim/devices/pd0.py) against two
independent readers: the driver's decoder (build/bin/auv-pd0-dump) turns its
bytes back into the dvl_t the simulator's model measured, in every frame; and
dolfyn, a published PD0 reader, reads the same bytes to the velocities, bottom
ranges, attitude and ensemble numbers that were encoded."""

from __future__ import annotations

import json
import math
import subprocess
from pathlib import Path

import numpy as np
import pytest

from auv import dvl_t
from sim.devices.pd0 import RTC_EPOCH, SIM_INDEX_OF_BEAM, Pd0Config, Pd0Dvl
from sim.model import Truth
from sim.sensors import Dvl, DvlConfig

RATE_HZ = 5.0
PINGS = 40


def trajectory(i: int) -> Truth:
    """A vehicle turning, pitching and rolling over a seabed that drops away
    below its bottom-lock range after half the pings (then water track)."""
    t = 100.0 + i / RATE_HZ
    depth = 20.0 + 0.1 * i
    water = 45.0 if i < PINGS // 2 else 90.0
    eta = (3.0 * i, -1.0 * i, depth, math.radians(6 * math.sin(i / 5)), math.radians(-9 + 0.4 * i), 2.5 + 0.08 * i)
    nu = (1.5 + 0.01 * i, 0.2 * math.cos(i / 3), 0.05, 0.0, 0.0, 0.0)
    return Truth(t=t, eta=eta, nu=nu, current_ned=(0.3, -0.1, 0.0), water_depth_m=water, altitude_m=water - depth)


def measurements() -> list[tuple[Truth, dvl_t]]:
    cfg = DvlConfig(rate_hz=RATE_HZ, noise=0.0, range_noise=0.0, max_altitude_m=30.0)
    dvl = Dvl(cfg, 1, "AUV1")
    out = []
    for i in range(PINGS):
        tr = trajectory(i)
        m = dvl.poll(tr)
        assert m is not None
        out.append((tr, m))
    return out


def write_stream(path: Path, frame: str, pings: list[tuple[Truth, dvl_t]], extra: int = 0) -> None:
    dev = Pd0Dvl(Pd0Config(frame=frame))
    data = b"".join(dev.bytes_for(m, tr) for tr, m in pings)
    # dolfyn reads an ensemble only when the next one follows it: one more at the end
    for tr, m in pings[-1:] * extra:
        data += dev.bytes_for(m, tr)
    path.write_bytes(data)


def decode(path: Path, env: dict[str, str], exe: Path | None = None) -> list[dict]:
    from conftest import c_program

    exe = exe or c_program("bin/auv-pd0-dump")
    p = subprocess.run([str(exe), str(path)], env=env, capture_output=True, text=True, timeout=60)
    assert p.returncode == 0, p.stderr
    lines = [json.loads(line) for line in p.stdout.splitlines()]
    assert lines[-1]["summary"] and not lines[-1]["refused"], lines[-1]
    return lines[:-1]


@pytest.mark.parametrize("frame", ["earth", "ship", "instrument", "beam"])
def test_the_driver_decodes_what_the_simulator_measured(frame, tmp_path, child_env):
    pings = measurements()
    path = tmp_path / f"{frame}.pd0"
    write_stream(path, frame, pings)
    got = decode(path, child_env)
    assert len(got) == PINGS
    modes = [m.mode for _, m in pings]
    assert dvl_t.MODE_BOTTOM_LOCK in modes and dvl_t.MODE_WATER_TRACK in modes
    for k, ((tr, m), e) in enumerate(zip(pings, got)):
        d = e["dvl"]
        assert e["frame"] == frame and e["ensemble"] == k + 1 == d["ensemble"]
        assert d["mode"] == m.mode
        # 1 mm/s steps and 0.01 degree attitude; along the beams, a little more
        assert d["velocity_mps"] == pytest.approx(list(m.velocity_mps), abs=2e-3)
        assert d["beam_range_m"] == pytest.approx([m.beam_range_m[i] for i in SIM_INDEX_OF_BEAM], abs=0.007)
        if all(r > 0 for r in m.beam_range_m):
            assert d["altitude_m"] == pytest.approx(tr.altitude_m, abs=0.02)
        assert d["device_utime"] == round((RTC_EPOCH.timestamp() + tr.t) * 1e6)
        assert e["heading_deg"] == pytest.approx(math.degrees(tr.eta[5]) % 360, abs=0.006)
        assert e["roll_deg"] == pytest.approx(math.degrees(tr.eta[3]), abs=0.006)
        assert e["depth_m"] == pytest.approx(tr.depth, abs=0.06)


def dolfyn_read(path: Path):
    """dolfyn 1.3.0, its last release, predates numpy 2 and scipy 1.14: the
    aliases it still uses are put back before it is imported."""
    import scipy.integrate

    for name, value in (
        ("NaN", np.nan),
        ("float_", np.float64),
        ("product", np.prod),
        ("RankWarning", np.exceptions.RankWarning),
    ):
        if not hasattr(np, name):
            setattr(np, name, value)
    if not hasattr(scipy.integrate, "cumtrapz"):
        scipy.integrate.cumtrapz = scipy.integrate.cumulative_trapezoid
    import dolfyn

    return dolfyn.read(str(path), userdata=False)


@pytest.mark.parametrize("frame", ["earth", "instrument"])
def test_dolfyn_reads_what_we_encoded(frame, tmp_path, child_env):
    pings = measurements()
    path = tmp_path / f"{frame}.pd0"
    write_stream(path, frame, pings, extra=1)
    ds = dolfyn_read(path)
    ours = decode(path, child_env)[:PINGS]
    assert ds.attrs["coord_sys"] == ("earth" if frame == "earth" else "inst")
    assert ds.attrs["beam_angle"] == 30 and ds.attrs["n_cells"] == 8
    assert list(ds["number"].values[:PINGS]) == list(range(1, PINGS + 1))
    heading = ds["heading"].values[:PINGS]
    pitch = ds["pitch"].values[:PINGS]
    roll = ds["roll"].values[:PINGS]
    vel_bt = ds["vel_bt"].values[:, :PINGS]  # (4, time) in the frame, invalid as -32.768
    dist_bt = ds["dist_bt"].values[:, :PINGS]
    vel = ds["vel"].values[:, :, :PINGS]  # (4, cell, time), NaN where invalid
    for k, ((tr, m), e) in enumerate(zip(pings, ours)):
        # what was encoded: the true attitude, the bottom's velocity relative to
        # the DVL (minus the vehicle's), its slant ranges in RDI's beam order
        assert heading[k] == pytest.approx(math.degrees(tr.eta[5]) % 360, abs=0.006)
        assert roll[k] == pytest.approx(math.degrees(tr.eta[3]), abs=0.006)
        assert pitch[k] == pytest.approx(e["pitch_deg"], abs=1e-4)
        # (PD0's range 0 is "no bottom"; the simulator says -1), as RDI's vertical
        # range: slant x cos(beam angle)
        ranges = [max(m.beam_range_m[i], 0.0) * math.cos(math.radians(30.0)) for i in SIM_INDEX_OF_BEAM]
        assert dist_bt[:, k] == pytest.approx(ranges, abs=0.006)
        if m.mode == dvl_t.MODE_BOTTOM_LOCK:
            if frame == "earth":
                vn, ve, vd = tr.velocity_ned()
                expected = [-ve, -vn, vd]
            else:
                expected = [-tr.nu[1], -tr.nu[0], tr.nu[2]]  # X stbd, Y fwd, Z up
            assert vel_bt[:3, k] == pytest.approx(expected, abs=6e-4)
            assert vel_bt[:, k] == pytest.approx(e["bt_velocity_mps"], abs=1e-6)
        else:
            assert np.all(vel_bt[:, k] == pytest.approx(-32.768))
            assert all(v is None for v in e["bt_velocity_mps"])
        # the profile: the same numbers as the driver's decoder, cell by cell
        for cell in range(8):
            assert vel[:, cell, k] == pytest.approx(e["velocity_mps"][cell], abs=1e-6)
