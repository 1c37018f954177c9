"""The Digiquartz-style emulator answers P3, Q3 and UN as the protocol
(c/drivers/pressure/digiquartz.h) says, from the depth model's measurement, and
ignores what a sensor ignores."""

from __future__ import annotations

import pytest

from sim.devices.digiquartz import PASCALS_PER_UNIT, Digiquartz, DigiquartzOptions
from sim.devices.emulator import DeviceContext
from sim.devices.registry import protocols_of
from sim.model import Truth
from sim.sensors import DepthConfig, DepthSensor


def setup(**opts):
    emu = Digiquartz(DeviceContext("AUV1", "depth", 3, DigiquartzOptions(**opts)))
    sent: list[bytes] = []
    emu.send = lambda data, t: sent.append(data)
    sensor = DepthSensor(DepthConfig(noise=0.0), seed=3, vehicle="AUV1")
    msg = sensor.measure(Truth(t=1.0, eta=(0.0, 0.0, 42.0, 0.0, 0.0, 0.0), nu=(0.0,) * 6))
    assert emu.encode(msg, None) == []  # a polled device says nothing by itself
    return emu, sent, msg


def test_registered_for_the_depth_sensor():
    assert protocols_of("depth") == {"digiquartz": Digiquartz}


def test_pressure_in_the_factory_unit_and_temperature():
    emu, sent, msg = setup()
    emu.receive(b"*0100P3\r\n*01", 1.0)  # a command cut between two steps
    emu.receive(b"00Q3\r\n", 1.1)
    assert len(sent) == 2 and sent[0].startswith(b"*0001") and sent[0].endswith(b"\r\n")
    assert float(sent[0][5:]) * PASCALS_PER_UNIT[1] == pytest.approx(msg.pressure_pa, rel=1e-9)
    assert sent[1] == b"*000112.000\r\n"


def test_un_needs_ew_and_echoes():
    emu, sent, msg = setup()
    emu.receive(b"*0100UN=4\r\n", 1.0)  # no EW: ignored
    assert sent == [] and emu.unit == 1
    emu.receive(b"*0100EW\r\n*0100UN=4\r\n*0100P3\r\n", 1.0)
    assert sent[0] == b"*0001UN=4\r\n"
    assert float(sent[1][5:]) * 1e3 == pytest.approx(msg.pressure_pa, rel=1e-9)
    emu.receive(b"*0100EW\r\n*0100P3\r\n*0100UN=2\r\n", 1.0)  # EW holds for the next command only
    assert len(sent) == 3 and emu.unit == 4


def test_other_addresses_garbage_and_a_dropout_are_not_answered():
    emu, sent, _ = setup(address=7)
    emu.receive(b"*0100P3\r\nhello\r\n*0700XX\r\n", 1.0)
    assert sent == [] and emu.ignored > 0
    emu.receive(b"*0705P3\r\n", 1.0)
    assert sent and sent[0].startswith(b"*0507")
    sensor = DepthSensor(DepthConfig(), seed=3, vehicle="AUV1")
    emu.encode(sensor.dropout_message(Truth(t=2.0, eta=(0.0,) * 6, nu=(0.0,) * 6)), None)
    emu.receive(b"*0705P3\r\n", 2.0)
    assert len(sent) == 1  # mute until the next sample
