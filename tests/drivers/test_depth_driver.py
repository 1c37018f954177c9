"""auv-depth as a process (c/drivers/depth, docs/drivers.md "auv-depth") against
the simulator's Digiquartz-style emulator (python/sim/devices/digiquartz.py) on a
pseudo-terminal: the driver sets the unit (EW, UN), polls P3 at its rate and Q3
every N polls, and publishes depth_t with the depth model's pressure, the
stated depth (p - p_atm) / (rho g) and the temperature, stamped with the
answer's receive time; a sensor that stops answering is counted "no answer"
and nothing is published; a sensor that answers again is polled again."""

from __future__ import annotations

import time

import pytest
from conftest import c_program
from driver_bus import VEHICLE, Bus, Pty, PtyDevice, check_usage_errors, finish, start
from lcm_proc import pump

from auv import depth_t
from auvlcm import programs
from sim.devices.digiquartz import Digiquartz, DigiquartzOptions
from sim.devices.emulator import DeviceContext
from sim.model import Truth
from sim.sensors import DepthConfig, DepthSensor

DEPTH_M = 37.5


class Sensor:
    """The emulator behind the pty's master: what the driver writes, it reads
    and answers, on a thread; `mute` stops it answering."""

    def __init__(self, pty: Pty) -> None:
        self.pty = pty
        self.emu = Digiquartz(DeviceContext(VEHICLE, "depth", 5, DigiquartzOptions()))
        self.emu.send = lambda data, t: pty.write(data)
        model = DepthSensor(DepthConfig(noise=0.0, water_temperature_c=8.25), seed=5, vehicle=VEHICLE)
        self.sample = model.measure(Truth(t=1.0, eta=(0.0, 0.0, DEPTH_M, 0.0, 0.0, 0.0), nu=(0.0,) * 6))
        self.emu.encode(self.sample, None)
        self.heard = bytearray()
        self.mute = False
        self.device = PtyDevice(pty, self._on_data)

    def _on_data(self, data: bytes) -> None:
        self.heard += data
        if not self.mute:
            self.emu.receive(data, time.time())

    def close(self) -> None:
        self.device.close()


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_depth_on_a_pty(sanitized, lcm_url, tmp_path, child_env):
    bus = Bus(lcm_url, "DEPTH", depth_t)
    pty = Pty(tmp_path / "depth0")
    sensor = Sensor(pty)
    rho, g, p_atm = 1027.0, 9.80, 101000.0
    flags = ["--rate", "10", "--temp-every", "3", "--units", "2", "--rho", str(rho), "--g", str(g)]
    flags += ["--p-atm", str(p_atm)]
    cmd = programs.device_driver(
        c_program("bin/auv-depth", sanitized).parent.parent,
        "depth",
        vehicle=VEHICLE,
        lcm_url=lcm_url,
        port=tmp_path / "depth0",
        baud=9600,
        extra=flags,
    )
    before = time.time()
    proc = start(cmd, tmp_path, child_env)
    try:
        bus.wait(lambda: len(bus.msgs) >= 8, "eight depth_t")
        after = time.time()
        assert bytes(sensor.heard).startswith(b"*0100EW\r\n*0100UN=2\r\n*0100P3\r\n")
        assert sensor.emu.unit == 2
        want_pa = sensor.sample.pressure_pa
        for m in bus.msgs:
            assert m.vehicle == VEHICLE and m.valid
            assert m.pressure_pa == pytest.approx(want_pa, abs=0.01)  # hPa to 10 digits
            assert m.depth_m == pytest.approx((want_pa - p_atm) / (rho * g), abs=1e-6)
            assert before * 1e6 <= m.utime <= after * 1e6
        # a Q3 after every third pressure: the temperature from then on
        assert any(m.temperature_c == pytest.approx(8.25) for m in bus.msgs[3:])
        assert bytes(sensor.heard).count(b"*0100Q3\r\n") >= 2
        # 10 Hz, give or take the 100 ms tick
        span = (bus.msgs[7].utime - bus.msgs[0].utime) / 1e6
        assert 0.4 < span < 1.5, span
        s = bus.wait_status(lambda s: s.frames_decoded >= 8, "frames counted")
        assert bus.reasons() == {}, s.last_error
        # the sensor goes mute: each poll is "no answer", nothing published
        sensor.mute = True
        bus.wait_status(lambda s: dict(zip(s.reason, s.reason_count)).get("no answer", 0) >= 2, "no answer")
        n = len(bus.msgs)
        pump(bus.lc, lambda: False, 0.5)
        assert len(bus.msgs) == n
        sensor.mute = False
        bus.wait(lambda: len(bus.msgs) >= n + 3, "depth_t again")
        assert set(bus.reasons()) == {"no answer"}
    finally:
        sensor.close()
        pty.close()
        finish(proc, tmp_path)


def test_usage_errors(child_env):
    check_usage_errors(
        "bin/auv-depth",
        [
            (["--units", "9"], "--units wants"),
            (["--rate", "50"], "--rate wants"),
            (["--rho", "10"], "--rho wants"),
            (["--address", "0"], "--address wants"),
        ],
        child_env,
        base=["--device", "/dev/null", "--vehicle", "A"],
    )
