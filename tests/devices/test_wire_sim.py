"""A wired sensor inside the simulator, stepped (`--fast`: the lockstep rule): the
bytes due by each step go out in it, a driver on the pty reads every epoch whole,
and `publish_lcm: false` leaves the channel to the driver."""

from __future__ import annotations

import errno
import math
import os
import select
import threading
from pathlib import Path

import pynmea2
import pytest
from wire_helpers import wait_until

from auvlcm.offline import OfflineLcm
from sim.config import loads
from sim.hil import Simulator

CONFIG = """
simulation: {{clock: scaled, duration_s: 10.0}}
initial: {{speed_mps: 1.5, prop_rpm: 1500}}
environment: {{bathymetry: "flat:depth=50"}}
sensors:
  gps: {{phase_s: 0.5, wire: {{protocol: nmea, pty: {pty}, baud: 4800, publish_lcm: false}}}}
  depth: {{}}
"""


def read_until_hangup(path: Path, out: bytearray, opened: threading.Event) -> None:
    fd = os.open(path, os.O_RDONLY | os.O_NOCTTY)
    opened.set()
    try:
        while True:
            select.select([fd], [], [], 1.0)
            try:
                data = os.read(fd, 4096)
            except OSError as e:  # the simulator closed the pty
                assert e.errno == errno.EIO
                return
            if not data:
                return
            out += data
    finally:
        os.close(fd)


def test_a_stepped_simulator_delivers_each_epoch_in_sim_time(tmp_path):
    cfg = loads(CONFIG.format(pty=tmp_path / "gps0"), tmp_path / "sim.yaml")
    lc = OfflineLcm(keep=True)
    sim = Simulator(cfg, fast=True, lc=lc)
    got = bytearray()
    opened = threading.Event()
    reader = threading.Thread(target=read_until_hangup, args=(tmp_path / "gps0", got, opened), daemon=True)
    reader.start()
    assert opened.wait(5)
    device = sim.devices.items[0]
    port = device.port
    try:
        wait_until(lambda: port.transport.connects == 1, what="the writer sees its reader")
        assert sim.run() == 0
    finally:
        sim.close()
        lc.close()
    reader.join(5)
    assert not reader.is_alive()
    channels = {ch for ch, _ in lc.published}
    assert "AUV1.GPS" not in channels and "AUV1.DEPTH" in channels
    assert port.unheard == port.lost == port.overflows == 0
    assert len(got) == port.sent > 0
    records = list(device.records)
    epochs = sorted({r.t_measured for r in records})
    assert epochs == pytest.approx([0.5 + k for k in range(10)])  # 1 Hz from phase_s
    for t in epochs:
        burst = [r for r in records if r.t_measured == t]
        assert burst[0].t_start == t  # the line is idle again by the next fix
        n = sum(r.n_bytes for r in burst)
        assert burst[-1].t_end == pytest.approx(t + n * 10 / 4800)
    # exactly the bytes complete by the last step's sim time (10.0 s), the last epoch's in part
    due = sum(min(r.n_bytes, max(0, math.floor((10.0 - r.t_start) * 480 + 1e-9))) for r in records)
    assert len(got) == due and records[-1].t_end > 10.0
    lines = bytes(got).split(b"\r\n")
    for line in lines[:-1]:
        pynmea2.parse(line.decode("ascii"), check=True)
    assert sum(1 for line in lines if line[3:6] == b"GGA") >= 9
