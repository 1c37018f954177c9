"""The DVL at the wire inside the simulator (`wire: {protocol: pd0}`): every
sample of the DVL model is one PD0 ensemble on the pty, and the vehicle's own
decoder (build/bin/auv-pd0-dump, c/drivers/dvl) gets back the velocity the
model published on LCM, to PD0's millimetre, in each frame the unit may be set to."""

from __future__ import annotations

import json
import subprocess
import threading

import pytest
from conftest import BUILD
from test_wire_sim import read_until_hangup
from wire_helpers import wait_until

from auv import dvl_t
from auvlcm.offline import OfflineLcm
from sim.config import loads
from sim.devices.pd0 import SIM_INDEX_OF_BEAM
from sim.hil import Simulator

CONFIG = """
simulation: {{clock: scaled, duration_s: 6.0}}
initial: {{speed_mps: 1.5, prop_rpm: 1500, heading_rad: 0.7}}
environment: {{bathymetry: "flat:depth=12"}}
sensors:
  dvl: {{rate_hz: 5, wire: {{protocol: pd0, pty: {pty}, baud: 115200, frame: {frame}}}}}
"""


@pytest.mark.parametrize("frame", ["earth", "ship", "instrument", "beam"])
def test_each_sample_is_an_ensemble_the_driver_decodes_to_the_models_velocity(tmp_path, frame):
    cfg = loads(CONFIG.format(pty=tmp_path / "dvl0", frame=frame), tmp_path / "sim.yaml")
    lc = OfflineLcm(keep=True)
    sim = Simulator(cfg, fast=True, lc=lc)
    got = bytearray()
    opened = threading.Event()
    reader = threading.Thread(target=read_until_hangup, args=(tmp_path / "dvl0", got, opened), daemon=True)
    reader.start()
    assert opened.wait(5)
    port = sim.devices.items[0].port
    try:
        wait_until(lambda: port.transport.connects == 1, what="the writer sees its reader")
        assert sim.run() == 0
    finally:
        sim.close()
        lc.close()
    reader.join(5)
    published = [dvl_t.decode(d) for ch, d in lc.published if ch == "AUV1.DVL"]
    (tmp_path / "wire.pd0").write_bytes(bytes(got))
    run = subprocess.run(
        [str(BUILD / "bin" / "auv-pd0-dump"), str(tmp_path / "wire.pd0")], capture_output=True, text=True, check=True
    )
    rows = [json.loads(line) for line in run.stdout.splitlines()]
    ensembles = [r for r in rows if r.get("ok")]
    assert not [r for r in rows if r.get("ok") is False], rows
    assert len(published) == 31 and len(ensembles) >= 30  # the last may still be on the line at the end
    locked = 0
    for e, m in zip(ensembles, published):
        assert e["frame"] == frame
        if m.mode != dvl_t.MODE_BOTTOM_LOCK:
            continue
        locked += 1
        assert e["dvl"]["velocity_mps"] == pytest.approx(list(m.velocity_mps), abs=2e-3)
        # the slant ranges, through PD0's vertical range in 1 cm steps
        slant = [m.beam_range_m[i] for i in SIM_INDEX_OF_BEAM]
        assert e["dvl"]["beam_range_m"] == pytest.approx(slant, abs=0.007)
    assert locked >= 25, locked
