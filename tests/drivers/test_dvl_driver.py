"""auv-dvl as a process (c/drivers/dvl, docs/drivers.md "auv-dvl"): PD0
ensembles of the simulator's emulator (python/sim/devices/pd0.py) written into
a pseudo-terminal reach LCM as dvl_t in body axes, stamped with their receive
time; garbage, a bad checksum, an ensemble cut by a silent device and a gap in
the ensemble numbers are counted per reason in driver_status_t and in
process_health_t.decode_errors; the raw bytes it recorded (--raw) give the same
dvl_t again through auv-driver-replay."""

from __future__ import annotations

import math
import time

import pytest
from conftest import c_program
from driver_bus import VEHICLE, Bus, Pty, check_usage_errors, finish, raw_messages, replay_print, same_printed, start

from auv import dvl_t, raw_bytes_t
from auvlcm import programs
from sim.devices.pd0 import RTC_EPOCH, SIM_INDEX_OF_BEAM, Pd0Config, Pd0Encoder

BEAM_ANGLE = math.radians(30.0)
YAW = math.radians(37.0)
RANGE_M = 12.0  # every beam's slant range over a flat seabed, level


def measurement(mode: int, velocity=(1.5, 0.2, 0.05), ranges=(RANGE_M,) * 4) -> dvl_t:
    """What the simulator's DVL model measured (beams in its order)."""
    m = dvl_t()
    m.vehicle, m.mode = VEHICLE, mode
    m.velocity_mps = list(velocity)
    m.beam_range_m = list(ranges)
    return m


class Device:
    """The emulated DVL: earth-frame ensembles at a level attitude, heading 37
    degrees, so the driver undoes the heading and the altitude is range x
    cos(beam angle)."""

    def __init__(self) -> None:
        self.enc = Pd0Encoder(Pd0Config(frame="earth"))
        self.t = 100.0

    def ensemble(self, m: dvl_t, number: int | None = None) -> bytes:
        self.t += 0.2
        e = self.enc.ensemble(m, 0.0, 0.0, YAW, self.t, number=number)
        # resync after a refusal walks through the rest of an ensemble: no
        # header inside one, so the counts below are exact
        assert b"\x7f\x7f" not in e[2:]
        return e


def check_dvl(d: dvl_t, m: dvl_t, number: int, t: float) -> None:
    assert d.vehicle == VEHICLE and d.mode == m.mode and d.ensemble == number
    assert d.device_frame == dvl_t.FRAME_EARTH
    assert d.device_utime == round((RTC_EPOCH.timestamp() + t) * 1e6)
    if m.mode == dvl_t.MODE_NONE:
        assert d.velocity_sigma_mps == -1.0 and list(d.velocity_mps) == [0.0, 0.0, 0.0]
    else:
        # 1 mm/s steps and a heading of 0.01 degree
        assert list(d.velocity_mps) == pytest.approx(list(m.velocity_mps), abs=2e-3)
        assert d.velocity_sigma_mps == pytest.approx(0.02)  # --sigma
    want = [m.beam_range_m[i] for i in SIM_INDEX_OF_BEAM]
    # 1 cm steps of the vertical range: 1.2 cm of slant at most
    assert list(d.beam_range_m) == pytest.approx([r if r > 0 else -1.0 for r in want], abs=0.007)
    if all(r > 0 for r in want):
        assert d.altitude_m == pytest.approx(RANGE_M * math.cos(BEAM_ANGLE), abs=0.006)
    else:
        assert d.altitude_m == -1.0


def replay_dvl(tmp_path, raw, child_env, sanitized):
    """The recorded raw messages as a log, through auv-driver-replay --print."""
    return replay_print(tmp_path, raw, child_env, "DVL", programs.dvl_flags(sigma_mps=0.02), sanitized)


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_dvl_on_a_pty(sanitized, lcm_url, tmp_path, child_env):
    bus = Bus(lcm_url, "DVL", dvl_t)
    pty = Pty(tmp_path / "dvl0")
    build = c_program("bin/auv-dvl", sanitized).parent.parent
    cmd = programs.device_driver(
        build,
        "dvl",
        vehicle=VEHICLE,
        lcm_url=lcm_url,
        port=tmp_path / "dvl0",
        baud=115200,
        raw=True,
        extra=programs.dvl_flags(sigma_mps=0.02),
    )
    proc = start(cmd, tmp_path, child_env)
    dev = Device()
    sent: list[tuple[dvl_t, int, float]] = []  # what should come out: measurement, number, time

    def send(m: dvl_t, number: int | None = None, chunk: int = 64) -> None:
        data = dev.ensemble(m, number)
        sent.append((m, dev.enc.number, dev.t))
        for i in range(0, len(data), chunk):  # an ensemble cut anywhere between reads
            pty.write(data[i : i + chunk])

    try:
        s = bus.wait_status(lambda s: s.port_open, "the port open")
        assert s.port == f"{tmp_path / 'dvl0'}@115200"
        before = time.time_ns() // 1000
        send(measurement(dvl_t.MODE_BOTTOM_LOCK))
        send(measurement(dvl_t.MODE_WATER_TRACK, (0.9, -0.3, 0.0), (-1.0,) * 4), chunk=7)
        send(measurement(dvl_t.MODE_NONE, (0.0, 0.0, 0.0), (-1.0,) * 4), chunk=1000)
        bus.wait(lambda: len(bus.msgs) >= 3, "three dvl_t")
        after = time.time_ns() // 1000
        for d, (m, number, t) in zip(bus.msgs, sent):
            check_dvl(d, m, number, t)
            assert before <= d.utime <= after  # the receive time, not the DVL's clock
        assert [d.mode for d in bus.msgs] == [1, 2, 0]
        assert bus.reasons() == {}

        # garbage, then a bad checksum (ensemble 4, sent again whole), then
        # ensemble 5 cut by a device that goes quiet
        pty.write(b"\x00\x01 noise on the line \xff\xfe")
        bad = bytearray(dev.ensemble(measurement(dvl_t.MODE_BOTTOM_LOCK), number=4))
        bad[-1] ^= 0x55
        pty.write(bytes(bad))
        send(measurement(dvl_t.MODE_BOTTOM_LOCK, (1.2, 0.0, 0.1)), number=4)
        bus.wait(lambda: len(bus.msgs) >= 4, "ensemble 4 after its broken copy")
        cut = dev.ensemble(measurement(dvl_t.MODE_BOTTOM_LOCK), number=5)
        pty.write(cut[: len(cut) // 2])
        bus.wait_status(lambda s: "truncated ensemble" in s.reason, "the cut ensemble dropped on silence")
        send(measurement(dvl_t.MODE_BOTTOM_LOCK, (1.0, 0.1, 0.0)), number=5)
        # ensembles 6..8 never arrive: a gap, counted, and 9 is still published
        send(measurement(dvl_t.MODE_BOTTOM_LOCK, (1.1, 0.1, 0.0)), number=9)
        bus.wait(lambda: len(bus.msgs) >= 6, "ensembles 5 and 9")
        for d, (m, number, t) in zip(bus.msgs, sent):
            check_dvl(d, m, number, t)
        assert [d.ensemble for d in bus.msgs] == [1, 2, 3, 4, 5, 9]
        want = {"garbage": 1, "bad checksum": 1, "truncated ensemble": 1, "ensemble gap": 1}
        s = bus.wait_status(lambda s: sum(s.reason_count) >= 4, "every refusal counted")
        assert bus.reasons() == want, s.last_error
        assert s.frames_decoded == 6 and s.messages_published >= 6
        bus.wait(lambda: bus.health and bus.health[-1].decode_errors == 4, "health's decode_errors")
        assert bus.health[-1].process == "auv-dvl"
        bus.wait_status(lambda s: s.bytes_read == sum(raw_bytes_t.decode(d).n_bytes for _, d in bus.raw), "raw")
    finally:
        pty.close()
        text = finish(proc, tmp_path)
    assert "dropped: bad checksum" in text
    # the recorded bytes give the same dvl_t through the same parser
    printed, reasons = replay_dvl(tmp_path, bus.raw, child_env, sanitized)
    assert len(printed) == len(bus.msgs) == 6
    for p, m in zip(printed, bus.msgs):
        same_printed(p, m, f32_fields=("beam_range_m",))
    assert reasons == want


def test_dvl_repeat_and_restart_through_the_replay(tmp_path, child_env):
    """A repeated ensemble number is counted and not published (one ping must
    not count twice); a step back (the device restarted) is counted and
    published."""
    dev = Device()
    m = measurement(dvl_t.MODE_BOTTOM_LOCK)
    raw = raw_messages("DVL", [dev.ensemble(m, number) for number in [7, 8, 8, 1, 2]])
    printed, reasons = replay_print(tmp_path, raw, child_env, "DVL")
    assert [(p["ensemble"], p["utime"]) for p in printed] == [
        ("7", "1000000"),
        ("8", "2000000"),
        ("1", "4000000"),
        ("2", "5000000"),
    ]
    assert reasons == {"repeated ensemble": 1, "ensemble number restarted": 1}, reasons


def test_dvl_mounting_and_usage(tmp_path, child_env):
    """A DVL turned 90 degrees to starboard on its mounting: the same wire gives
    the vehicle's velocity rotated back (auv-driver-replay on a log of it);
    absurd flags are refused."""
    dev = Device()
    m = measurement(dvl_t.MODE_BOTTOM_LOCK, (1.0, 0.0, 0.0))
    raw = raw_messages("DVL", [dev.ensemble(m)], t0_us=5_000_000)
    outs = []
    for mounting in [(0.0, 0.0, 0.0), (90.0, 0.0, 0.0)]:
        (fields,), _ = replay_print(tmp_path, raw, child_env, "DVL", programs.dvl_flags(mounting_deg=mounting))
        assert fields["utime"] == "5000000"
        outs.append([float(x) for x in fields["velocity_mps"].split(",")])
    # the same wire from a DVL whose forward (beam 3) is the vehicle's
    # starboard: its motion along its own forward axis is the vehicle's to starboard
    assert outs[0] == pytest.approx([1.0, 0.0, 0.0], abs=2e-3)
    assert outs[1] == pytest.approx([0.0, 1.0, 0.0], abs=2e-3)

    check_usage_errors(
        "bin/auv-dvl",
        [
            (["--mounting", "0,0"], "--mounting wants"),
            (["--mounting", "0,95,0"], "--mounting wants"),
            (["--sigma", "0"], "--sigma wants"),
            (["--ensemble-timeout", "x"], "--ensemble-timeout wants"),
        ],
        child_env,
        base=["--device", "/dev/null", "--vehicle", "A"],
    )
