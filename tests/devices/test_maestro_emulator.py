"""The Maestro emulator (sim.devices.maestro): the published command bytes, speed and
acceleration as published, replies, the protocol error bit, and the channel table's
inverse (pulses back to rudder, stern plane and prop)."""

from __future__ import annotations

import pytest

from sim.devices.maestro import (
    ERR_SERIAL_PROTOCOL,
    Maestro,
    TableError,
    parse_table,
)

TABLE = """# AUV1's fins and thruster
protocol compact
watchdog 0.5
channel 0 rudder      1500 500 1100 1900
channel 1 stern_plane 1500 500 1100 1900 reversed speed 100 accel 4
channel 2 rudder      1500 500 1100 1900 reversed
channel 4 prop        1490 0.25 1000 2000
"""


def test_set_target_published_example_both_framings():
    m = Maestro()
    assert m.feed(bytes([0x84, 0x02, 0x70, 0x2E])) == b""
    assert m.targets()[2] == 6000 and m.positions()[2] == 6000  # from off: at once
    m.feed(bytes([0xAA, 0x0C, 0x04, 0x03, 0x70, 0x2E]))
    assert m.targets()[3] == 6000
    m.feed(bytes([0xAA, 0x0D, 0x04, 0x05, 0x70, 0x2E]))  # device 13: not ours
    assert m.targets()[5] == 0 and m.errors == 0
    # channel 3 off and channel 4 to 1500 us in one command
    m.feed(bytes([0x9F, 0x02, 0x03, 0x00, 0x00, 0x70, 0x2E]))
    assert m.targets()[3:5] == [0, 6000] and m.positions()[3] == 0


def test_replies_position_errors_moving():
    m = Maestro()
    m.feed(bytes([0x84, 0x00, 0x70, 0x2E]))
    assert m.feed(bytes([0x90, 0x00])) == bytes([0x70, 0x17])  # 6000, low byte first
    assert m.feed(bytes([0xAA, 0x0C, 0x10, 0x00])) == bytes([0x70, 0x17])
    assert m.feed(bytes([0x93])) == b"\x00"
    m.feed(bytes([0x87, 0x00, 0x0C, 0x01]))  # speed 140
    m.feed(bytes([0x84, 0x00, 0x50, 0x3E]))  # 8000
    assert m.feed(bytes([0x93])) == b"\x01"
    assert m.feed(bytes([0xA1])) == b"\x00\x00"


@pytest.mark.parametrize(
    "data",
    [
        bytes([0xB0]),  # no such command
        bytes([0x05]),  # a data byte with no command
        bytes([0x84, 0x02, 0x70, 0x90, 0x00]),  # a Set Target cut by a Get Position
        bytes([0x84, 0x18, 0x70, 0x2E]),  # channel 24 of a 24-channel Maestro
        bytes([0x9F, 0x03, 0x16, 0, 0, 0, 0, 0, 0]),  # channels 22..24
        bytes([0x89, 0x00, 0x00, 0x02]),  # acceleration 256
        bytes([0xAA, 0x0C, 0x7F]),  # the Pololu form of no command
    ],
)
def test_bad_commands_set_the_protocol_error_bit(data):
    m = Maestro()
    m.feed(data)
    assert m.errors & ERR_SERIAL_PROTOCOL
    assert m.feed(bytes([0xA1])) == bytes([ERR_SERIAL_PROTOCOL, 0])
    assert m.feed(bytes([0xA1])) == b"\x00\x00"  # read: cleared


def test_targets_clamped_to_the_device_range_and_go_home():
    m = Maestro(n_channels=6)
    m.channels[1].home_qus = 6000
    m.feed(bytes([0x84, 0x00, 0x00, 0x10]))  # 2048: below 3968
    m.feed(bytes([0x84, 0x01, 0x7F, 0x7F]))  # 16383: above 8000
    assert m.targets()[:2] == [3968, 8000]
    m.feed(bytes([0xA2]))
    assert m.targets()[:2] == [0, 6000]
    m.feed(bytes([0x90, 0x06]))  # a 6-channel Maestro has no channel 6
    assert m.errors & ERR_SERIAL_PROTOCOL


def test_speed_limit_in_quarter_us_per_10_ms():
    m = Maestro()
    m.feed(bytes([0x84, 0x00, 0x70, 0x2E]))  # at 6000
    m.feed(bytes([0x87, 0x00, 100, 0]))  # 100 quarter-us per 10 ms
    m.feed(bytes([0x84, 0x00, 0x58, 0x36]))  # 7000
    m.advance(0.05)
    assert m.positions()[0] == 6500
    assert m.feed(bytes([0x90, 0x00])) == (6500).to_bytes(2, "little")  # the ramp, not the target
    m.advance(0.05)
    assert m.positions()[0] == 7000 and not m.moving()


def test_acceleration_ramps_up_and_down():
    m = Maestro()
    m.feed(bytes([0x84, 0x00, 0x70, 0x2E]))
    m.feed(bytes([0x89, 0x00, 8, 0]))  # 8 per 80 ms: 1 quarter-us per 10 ms per 10 ms
    m.feed(bytes([0x84, 0x00, 0x00, 0x32]))  # 6400
    path = []
    for _ in range(100):
        m.advance(0.01)
        path.append(m.channels[0].position)
    steps = [b - a for a, b in zip([6000.0] + path, path)]
    assert all(s >= 0 for s in steps) and max(path) == 6400  # never past the target
    assert all(abs(b - a) <= 1.0 + 1e-9 for a, b in zip([0.0] + steps, steps))  # speed changes by <= 1 a tick
    ticks = next(i for i, p in enumerate(path) if p == 6400) + 1
    assert 38 <= ticks <= 45  # about 2 * sqrt(400 / 1) with ramps both ways


def test_table_inverse_and_its_errors():
    t = parse_table(TABLE, "t.cfg")
    assert t.watchdog_s == 0.5 and not t.pololu and len(t.channels) == 4
    q = [0] * 24
    q[0], q[2], q[1], q[4] = 6400, 5600, 5600, 6360  # rudder +0.2 on both (one reversed), stern +0.2, 400 rpm
    c = t.command(q)
    assert c.rudder_rad == pytest.approx(0.2) and c.stern_plane_rad == pytest.approx(0.2)
    assert c.prop_rpm == pytest.approx(400.0)
    q[0] = q[2] = 0  # both rudder channels off: it drives nothing
    assert t.command(q).rudder_rad == 0.0
    m = t.maestro()
    assert (m.channels[4].min_qus, m.channels[4].max_qus) == (4000, 8000)
    for text, where in [
        ("watchdog 1\nchannel 0 rudder 1500 500 1100 1900\nchannel 0 prop 1500 1 1000 2000\n", "t.cfg:3:9:"),
        ("watchdog 1\nchannel 0 aileron 1500 500 1100 1900\n", "t.cfg:2:11:"),
        ("watchdog 0x10\nchannel 0 rudder 1500 500 1100 1900\n", "t.cfg:1:10:"),
        ("watchdog 1\nchannel 0 rudder 1500 500 1100 1900 speed 1_0\n", "t.cfg:2:43:"),
        ("channel 0 rudder 1500 500 1100 1900\n", "t.cfg:1:1:"),
    ]:
        with pytest.raises(TableError, match=where):
            parse_table(text, "t.cfg")
