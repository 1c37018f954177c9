"""The time link's simulator side (python/sim/time_link.py, sim.devices.time_link;
docs/simulator.md, "The time link"): each sentence's time is the sim time of its
own last byte at the far end, exactly as the line's records say in a stepped
run; the section and the payload wires are checked at their file:line:col."""

from __future__ import annotations

import re
import threading
from pathlib import Path

import pytest
from test_wire_sim import read_until_hangup
from wire_helpers import wait_until

from auvlcm.offline import OfflineLcm
from confcheck import ConfigError
from sim.config import loads
from sim.devices.lcmframe import crc16, frame
from sim.devices.time_link import pauvt, stamped_sentence
from sim.hil import Simulator

CONFIG = """
simulation: {{clock: scaled, duration_s: 3.0}}
environment: {{bathymetry: "flat:depth=50"}}
sensors: {{depth: {{}}}}
time_link: {{rate_hz: 10, wire: {{protocol: pauvt, pty: {pty}, baud: 9600}}}}
"""


def test_the_sentence_is_stamped_with_its_last_byte():
    assert pauvt(12500000, 1.0) == b"$PAUVT,12500000,1*71\r\n"  # as c/drivers/timesync writes it
    for t0 in (0.0, 0.9999, 9.99999, 123.456):
        data = stamped_sentence(t0, 5.0, 10 / 9600)
        utime = int(re.match(rb"\$PAUVT,(\d+),5\*", data)[1])
        assert utime == round((t0 + len(data) * 10 / 9600) * 1e6)


def test_a_stepped_simulator_sends_each_sentence_at_its_time(tmp_path):
    cfg = loads(CONFIG.format(pty=tmp_path / "tl0"), tmp_path / "sim.yaml")
    lc = OfflineLcm(keep=True)
    sim = Simulator(cfg, fast=True, lc=lc)
    got = bytearray()
    opened = threading.Event()
    reader = threading.Thread(target=read_until_hangup, args=(tmp_path / "tl0", got, opened), daemon=True)
    reader.start()
    assert opened.wait(5)
    device = sim.devices.items[-1]
    try:
        wait_until(lambda: device.port.transport.connects == 1, what="the writer sees its reader")
        assert sim.run() == 0
    finally:
        sim.close()
        lc.close()
    reader.join(5)
    records = list(device.records)
    assert [r.t_start for r in records] == pytest.approx([0.1 * k for k in range(len(records))])
    times = [int(m) for m in re.findall(rb"\$PAUVT,(\d+),0\*", bytes(got))]  # --fast: warp 0
    assert len(times) >= 29
    for utime, r in zip(times, records):
        assert utime == round(r.t_end * 1e6)  # the last byte's sim time, to the microsecond


def test_frames_are_what_the_driver_reads():
    f = frame("CONTACTS", b"\x01" * 9)
    assert f[:3] == b"\xa5\x4c\x08" and f[3:11] == b"CONTACTS" and f[11:13] == b"\x00\x09"
    assert int.from_bytes(f[-2:], "big") == crc16(f[:-2]) and crc16(b"123456789") == 0x29B1
    with pytest.raises(ValueError):
        frame("contacts", b"x")


@pytest.mark.parametrize(
    "text,error",
    [
        ("time_link: {rate_hz: 20}\n", "1:12: time_link: missing required key 'wire'"),
        ("time_link: {wire: {protocol: nmea, pty: a}}\n", "1:30: time_link.wire.protocol: expected one of: pauvt"),
        ("time_link: {rate_hz: 0, wire: {protocol: pauvt, pty: a}}\n", "1:22: time_link.rate_hz:"),
        ("time_link: {wire: {protocol: pauvt, pty: a, publish_lcm: false}}\n", "time_link.wire.publish_lcm: the"),
        ("sonar: {wire: {protocol: pauvt, pty: a}}\n", "sonar.wire.protocol: expected one of: lcmframe"),
        (
            "sonar: {wire: {protocol: lcmframe, pty: a}}\nidentify: {wire: {protocol: lcmframe, pty: a}}\n",
            "2:18: identify.wire: sonar is on this port already",
        ),
        (
            "sensors: {gps: {wire: {protocol: nmea, tcp: '*:4010'}}}\n"
            "time_link: {wire: {protocol: pauvt, tcp: '*:4010'}}\n",
            "2:19: time_link.wire: sensors.gps is on this port already",
        ),
    ],
)
def test_sections_checked(text, error, tmp_path: Path):
    with pytest.raises(ConfigError) as exc:
        loads(text, tmp_path / "v.yaml")
    assert any(error in e for e in exc.value.errors), exc.value.errors
