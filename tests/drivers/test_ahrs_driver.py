"""auv-ahrs as a process (c/drivers/ahrs, docs/drivers.md "auv-ahrs"): the AHRS
emulator's bytes (python/sim/devices/ahrs_nmea.py) for the simulator's own
measurements, written into a pseudo-terminal, reach LCM as ahrs_t with the
measurement's roll, pitch and heading (to the sentences' 0.01 degree), body
rates NaN and the receive time as stamp; an absurd roll, a heading without its
T flag and a bad checksum are each counted under their reason in
driver_status_t and publish nothing; the sign and offset flags apply. With the
emulator's VectorNav $VNYMR the rates arrive too, finite and the simulator's to
the sentence's 1e-6 rad/s, so auv-nav can take the messages; a VNYMR with an
absurd rate is counted and publishes nothing."""

from __future__ import annotations

import math
import time

import pytest
from conftest import c_program
from driver_bus import VEHICLE, Bus, Pty, check_usage_errors, finish, start
from test_gps_driver import nmea

from auv import ahrs_t
from auvlcm import programs
from sim.devices.ahrs_nmea import AhrsNmea, AhrsNmeaOptions
from sim.devices.emulator import DeviceContext
from sim.model import Truth
from sim.sensors import Ahrs, AhrsConfig

# the sentences carry 0.01 degree: half of it, and a margin for the rounding of radians
TOL_RAD = math.radians(0.006)
# VNYMR: 0.001 degree and 1e-6 rad/s
VN_TOL_RAD = math.radians(0.0006)
VN_TOL_RATE = 6e-7

HOSTILE = (
    nmea("PASHR,010203.000,090.00,T,200.00,1.00,,0.100,0.100,0.500,0,1")  # roll 200 degrees
    + nmea("HEHDT,123.40,M")  # magnetic, not true
    + nmea("HEHDT,123.40,T").replace(b"*", b"0*", 1)  # bad checksum
)
HOSTILE_REASONS = {"attitude out of range": 1, "heading not true": 1, "bad checksum": 1}


def samples(n: int = 5) -> list[ahrs_t]:
    """The simulator's AHRS measurements of a vehicle rolling and turning."""
    ahrs = Ahrs(AhrsConfig(), seed=7, vehicle=VEHICLE)
    out = []
    for i in range(n):
        roll, pitch, heading = math.radians(-20 + 9 * i), math.radians(5 - 3 * i), math.radians(350 + 7 * i)
        tr = Truth(t=10.0 + 0.05 * i, eta=(0.0, 0.0, 5.0, roll, pitch, heading), nu=(1.0, 0, 0, 0.01, 0.02, 0.03))
        out.append(ahrs.measure(tr))
    return out


def wire_bytes(msgs: list[ahrs_t], sentences: tuple[str, ...] = ("PASHR", "HDT")) -> bytes:
    emu = AhrsNmea(DeviceContext(VEHICLE, "ahrs", 7, AhrsNmeaOptions(sentences=list(sentences))))
    return b"".join(b for m in msgs for b in emu.encode(m, None))


def wrap_pi(a: float) -> float:
    return (a + math.pi) % (2 * math.pi) - math.pi


def run_driver(build, tmp_path, lcm_url, child_env, extra=()):
    cmd = programs.device_driver(
        build, "ahrs", vehicle=VEHICLE, lcm_url=lcm_url, port=tmp_path / "ahrs0", baud=19200, extra=extra
    )
    return start(cmd, tmp_path, child_env)


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_ahrs_on_a_pty(sanitized, lcm_url, tmp_path, child_env):
    bus = Bus(lcm_url, "AHRS", ahrs_t)
    pty = Pty(tmp_path / "ahrs0")
    proc = run_driver(c_program("bin/auv-ahrs", sanitized).parent.parent, tmp_path, lcm_url, child_env)
    try:
        bus.wait_status(lambda s: s.port_open, "the port open")
        want = samples()
        stream = wire_bytes(want)
        before = time.time()
        for i in range(0, len(stream), 37):  # sentences cut anywhere between writes
            pty.write(stream[i : i + 37])
        bus.wait(lambda: len(bus.msgs) >= len(want), "one ahrs_t per PASHR")
        after = time.time()
        for got, w in zip(bus.msgs, want):
            assert got.vehicle == VEHICLE and got.valid
            assert abs(wrap_pi(got.heading_rad - w.heading_rad)) < TOL_RAD
            assert 0.0 <= got.heading_rad < 2 * math.pi
            assert got.roll_rad == pytest.approx(w.roll_rad, abs=TOL_RAD)
            assert got.pitch_rad == pytest.approx(w.pitch_rad, abs=TOL_RAD)
            assert math.isnan(got.p_radps) and math.isnan(got.q_radps) and math.isnan(got.r_radps)
            assert before * 1e6 - 1e6 <= got.utime <= after * 1e6 + 1e6  # the receive time, on the system clock
        # every HDT is a decoded frame too, and publishes nothing of its own
        s = bus.wait_status(lambda s: s.frames_decoded == 2 * len(want), "PASHR and HDT decoded")
        assert s.messages_published == len(want) and bus.reasons() == {}
        pty.write(HOSTILE)
        bus.wait_status(lambda s: sum(s.reason_count) >= len(HOSTILE_REASONS), "the hostile input counted")
        assert bus.reasons() == HOSTILE_REASONS, bus.status[-1].last_error
        assert len(bus.msgs) == len(want)
    finally:
        pty.close()
        text = finish(proc, tmp_path)
    assert "attitude out of range" in text


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_vnymr_brings_the_rates(sanitized, lcm_url, tmp_path, child_env):
    bus = Bus(lcm_url, "AHRS", ahrs_t)
    pty = Pty(tmp_path / "ahrs0")
    proc = run_driver(c_program("bin/auv-ahrs", sanitized).parent.parent, tmp_path, lcm_url, child_env)
    try:
        bus.wait_status(lambda s: s.port_open, "the port open")
        want = samples()
        stream = wire_bytes(want, ("VNYMR",))
        for i in range(0, len(stream), 41):  # sentences cut anywhere between writes
            pty.write(stream[i : i + 41])
        bus.wait(lambda: len(bus.msgs) >= len(want), "one ahrs_t per VNYMR")
        for got, w in zip(bus.msgs, want):
            assert got.vehicle == VEHICLE and got.valid
            assert abs(wrap_pi(got.heading_rad - w.heading_rad)) < VN_TOL_RAD
            assert 0.0 <= got.heading_rad < 2 * math.pi  # yaw -10 is heading 350
            assert got.roll_rad == pytest.approx(w.roll_rad, abs=VN_TOL_RAD)
            assert got.pitch_rad == pytest.approx(w.pitch_rad, abs=VN_TOL_RAD)
            rates = (got.p_radps, got.q_radps, got.r_radps)
            assert all(math.isfinite(x) for x in rates)  # what auv-nav asks of an ahrs_t
            assert rates == pytest.approx((w.p_radps, w.q_radps, w.r_radps), abs=VN_TOL_RATE)
        s = bus.wait_status(lambda s: s.frames_decoded == len(want), "every VNYMR decoded")
        assert s.messages_published == len(want) and bus.reasons() == {}
        absurd = nmea("VNYMR,+010.000,+000.000,+000.000,+0.2000,+0.0000,+0.4700,+00.000,+00.000,-09.807,0,0,+99.0")
        pty.write(absurd)
        bus.wait_status(lambda s: sum(s.reason_count) >= 1, "the absurd rate counted")
        assert bus.reasons() == {"rate out of range": 1}
        assert len(bus.msgs) == len(want)
    finally:
        pty.close()
        finish(proc, tmp_path)


def test_signs_and_heading_offset(lcm_url, tmp_path, child_env):
    bus = Bus(lcm_url, "AHRS", ahrs_t)
    pty = Pty(tmp_path / "ahrs0")
    flags = ["--roll-sign", "-1", "--pitch-sign", "-1", "--heading-offset", "15"]
    proc = run_driver(c_program("bin/auv-ahrs").parent.parent, tmp_path, lcm_url, child_env, flags)
    try:
        bus.wait_status(lambda s: s.port_open, "the port open")
        want = samples(2)
        pty.write(wire_bytes(want) + wire_bytes(want, ("PRDID",)))  # RDI's attitude sentence too
        bus.wait(lambda: len(bus.msgs) >= 4, "four ahrs_t")
        for got, w in zip(bus.msgs, want + want):
            assert math.isnan(got.p_radps) and got.valid
            assert got.roll_rad == pytest.approx(-w.roll_rad, abs=TOL_RAD)
            assert got.pitch_rad == pytest.approx(-w.pitch_rad, abs=TOL_RAD)
            assert abs(wrap_pi(got.heading_rad - w.heading_rad - math.radians(15))) < TOL_RAD
            assert 0.0 <= got.heading_rad < 2 * math.pi  # 350 + 15 wraps
    finally:
        pty.close()
        finish(proc, tmp_path)


def test_usage_errors(child_env):
    check_usage_errors(
        "bin/auv-ahrs",
        [
            (["--roll-sign", "2"], "--roll-sign wants 1 or -1"),
            (["--pitch-sign", "x"], "--pitch-sign wants 1 or -1"),
            (["--heading-offset", "400"], "--heading-offset wants degrees"),
        ],
        child_env,
        base=["--device", "/dev/null", "--vehicle", "A"],
    )
