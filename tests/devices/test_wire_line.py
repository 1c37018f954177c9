"""The line's timing on a pty: 10 bits a byte at the configured baud, paced by
the wall clock (real time, scaled) or by the simulator's steps (lockstep);
bounded queue, overflow and unheard bytes counted."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from wire_helpers import drain, pacer, read_timed, wait_until

from sim.config import loads
from sim.devices.clocks import StepClock, WallClock
from sim.devices.device import build_devices
from sim.devices.line import Line
from sim.devices.port import Port
from sim.devices.transport import PtyTransport
from sim.hil import build_model, build_sensors
from sim.model import Truth


@pytest.fixture
def pty_port(tmp_path):
    made = []

    def make(clock, baud=9600, queue_bytes=65536):
        port = Port(PtyTransport(tmp_path / "dev" / "gps0"), Line(baud), clock, queue_bytes)
        made.append(port)
        return port

    yield make
    for port in made:
        port.close()


def open_reader(port: Port) -> int:
    seen = port.transport.connects
    fd = os.open(port.transport.link, os.O_RDONLY | os.O_NOCTTY)
    wait_until(lambda: port.transport.connects > seen, what="the port sees its reader")
    return fd


@pytest.mark.parametrize("warp", [1.0, 4.0])
def test_a_burst_takes_n_times_10_over_baud(pty_port, warp):
    """960 bytes at 9600 baud: about a second from the first byte to the last
    (a quarter of it at 4x): measured at the reader, and evenly spread."""
    port = pty_port(WallClock(pacer(warp)))
    fd = open_reader(port)
    try:
        data = bytes(range(256)) * 3 + bytes(192)
        burst = port.write(data, port.clock.now())
        reads = read_timed(fd, len(data))
    finally:
        os.close(fd)
    assert b"".join(d for _, d in reads) == data
    assert burst.t_end - burst.t_start == pytest.approx(960 * 10 / 9600)
    first, last = reads[0][0], reads[-1][0]
    expected = (len(data) - 1) * 10 / 9600 / warp  # first byte complete to last byte complete
    assert expected - 0.03 <= last - first <= expected + 0.1, (last - first, expected)
    # half the bytes are in by half the time (not one lump at the end)
    got, half_at = 0, None
    for t, d in reads:
        got += len(d)
        if got >= len(data) // 2:
            half_at = t - first
            break
    assert abs(half_at - expected / 2) < 0.08, (half_at, expected)


def test_bursts_queue_behind_each_other(pty_port):
    """Two messages measured at once: the second starts when the first has left."""
    clock = StepClock()
    port = pty_port(clock, baud=4800)
    a = port.write(b"A" * 100, 0.0)
    b = port.write(b"B" * 50, 0.0)
    assert a.t_start == 0.0 and b.t_start == pytest.approx(100 * 10 / 4800)
    assert b.t_end == pytest.approx(150 * 10 / 4800)


def test_in_steps_the_bytes_due_by_each_step_go_out(pty_port):
    """Lockstep: nothing moves until the simulator's step does; then exactly the
    bytes complete by the step's sim time (9600 baud: 960 a second)."""
    clock = StepClock()
    port = pty_port(clock)
    fd = open_reader(port)
    try:
        port.write(bytes(960), 0.0)
        assert drain(fd) == b""
        for t, total in ((0.1, 96), (0.5, 480), (0.75, 720), (5.0, 960)):
            clock.advance(t)
            port.wake()
            got = 0
            wait_until(lambda: port.sent == total, what=f"{total} bytes by t={t}")
            got = len(drain(fd, 0.05))
            assert port.sent == total and got > 0
    finally:
        os.close(fd)
    assert port.unheard == port.lost == port.overflows == 0


def test_a_full_queue_refuses_and_counts_and_nobody_listening_is_unheard(pty_port):
    clock = StepClock()
    port = pty_port(clock, queue_bytes=1024)
    assert port.write(bytes(1000), 0.0) is not None
    assert port.write(bytes(100), 0.0) is None
    assert port.overflows == 1
    clock.advance(2.0)
    port.wake()
    wait_until(lambda: port.unheard == 1000, what="the bytes counted unheard")
    # a reader that comes later gets what is written from then on, nothing stale
    fd = open_reader(port)
    try:
        port.write(b"fresh", 2.0)
        clock.advance(3.0)
        port.wake()
        wait_until(lambda: port.sent == 5, what="the fresh bytes")
        assert drain(fd) == b"fresh"
    finally:
        os.close(fd)


def test_the_link_names_the_pty_and_goes_away_on_close(tmp_path):
    link = tmp_path / "gps0"
    port = Port(PtyTransport(link), Line(9600), StepClock())
    assert os.readlink(link).startswith("/dev/pts/")
    port.close()
    assert not link.exists() and not link.is_symlink()


GPS_AT_THE_WIRE = """
initial: {{speed_mps: 1.0}}
sensors:
  gps: {{rate_hz: 1, wire: {{protocol: nmea, pty: gps0, baud: 4800, publish_lcm: {publish}}}}}
  depth: {{}}
"""


@pytest.mark.parametrize("publish", [True, False])
def test_a_wired_sensor_publishes_beside_or_instead(tmp_path, publish):
    """publish_lcm: true, the LCM message beside the bytes; false, the bytes only.
    The pty's path is relative to the configuration's folder."""
    cfg = loads(GPS_AT_THE_WIRE.format(publish=str(publish).lower()), tmp_path / "sim.yaml")
    model = build_model(cfg)
    sensors = build_sensors(cfg, model)
    devices = build_devices(sensors, "AUV1", 1, model.frame, None, stepped=True)
    try:
        assert [d.sensor.name for d in devices.items] == ["gps"]
        assert Path(devices.items[0].port.transport.link) == tmp_path / "gps0"
        gps = devices.items[0]
        poll = devices.poll_for(gps.sensor)
        assert devices.poll_for(sensors[1]) == sensors[1].poll_encoded  # the depth sensor: LCM only
        lcm_bytes = poll(model.truth(Truth()))
        assert (lcm_bytes is not None) == publish
        assert len(gps.records) == 5  # RMC VTG GGA GSA ZDA, back to back on the line
        r = list(gps.records)
        assert all(b.t_start == pytest.approx(a.t_end) for a, b in zip(r, r[1:]))
        assert r[-1].t_end == pytest.approx(sum(x.n_bytes for x in r) * 10 / 4800)
        # under water: the GPS model makes no fix, and nothing goes on the line
        model.set_pose((0, 0, 5.0, 0, 0, 0), (0,) * 6)
        gps.sensor.schedule.restart(0.0)
        assert poll(model.truth(Truth())) is None and len(gps.records) == 5
    finally:
        devices.close()
