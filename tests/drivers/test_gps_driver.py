"""auv-gps as a process (c/drivers/gps, docs/drivers.md): NMEA written into a
pseudo-terminal (behind a udev-style symlink, at a set baud) or a TCP port
reaches LCM as gps_fix_t; garbage, bad checksums, an endless line and absurd
values with valid checksums are counted per reason in driver_status_t and in
process_health_t.decode_errors; a port that vanishes is reopened (reopens
counted); the raw bytes it recorded (--raw) give the same fixes again through
auv-driver-replay; --clock sim stamps with SIM.CLOCK."""

from __future__ import annotations

import math
import socket
from functools import reduce

import pytest
from conftest import c_program
from driver_bus import VEHICLE, Bus, Pty, check_usage_errors, finish, replay_print, same_printed, start

from auv import gps_fix_t, raw_bytes_t, sim_clock_t
from auvlcm import programs
from sim.geo import LocalFrame

ORIGIN = (48.1, 11.5)


def nmea(body: str) -> bytes:
    return f"${body}*{reduce(lambda a, c: a ^ ord(c), body, 0):02X}\r\n".encode()


def epoch(tod: str, lat: str = "4807.038", lon: str = "01131.000") -> bytes:
    """One epoch of a receiver that sends RMC and GGA."""
    return nmea(f"GPRMC,{tod},A,{lat},N,{lon},E,001.9,084.4,150724,,,A") + nmea(
        f"GPGGA,{tod},{lat},N,{lon},E,1,09,1.1,12.5,M,46.9,M,,"
    )


def degrees(ddmm: str, deg_digits: int) -> float:
    return int(ddmm[:deg_digits]) + float(ddmm[deg_digits:]) / 60.0


HOSTILE = (
    b"\x00\xff\xfe junk between sentences "
    + nmea("GPGSA,A,3,04,05,,09,12,,,24,,,,,2.5,1.1,2.1").replace(b"*", b"0*", 1)  # bad checksum
    + b"$GPGGA,"
    + b"9" * 2000
    + b"\r\n"  # an endless line
    + nmea("GPGGA,120005,20000.000,N,01131.000,E,1,08,0.9,5.4,M,46.9,M,,")  # latitude 200
    + nmea("GPRMC,120005,A,4807.038,N,01131.000,E,001.9,084.4,150780,,,A")  # a date in 1980
)
HOSTILE_REASONS = {"garbage": 1, "bad checksum": 1, "line too long": 1, "bad latitude": 1, "date out of range": 1}


def check_fix(m: gps_fix_t, lat: str, lon: str) -> None:
    want_lat, want_lon = degrees(lat, 2), degrees(lon, 3)
    assert m.vehicle == VEHICLE and m.fix_type == gps_fix_t.FIX_3D and m.quality == 1
    assert m.latitude_deg == pytest.approx(want_lat, abs=1e-12)
    assert m.longitude_deg == pytest.approx(want_lon, abs=1e-12)
    north, east = LocalFrame(*ORIGIN).to_ned(want_lat, want_lon)  # the simulator's frame
    assert m.north_m == pytest.approx(north, abs=1e-6) and m.east_m == pytest.approx(east, abs=1e-6)
    assert m.satellites == 9 and m.hdop == pytest.approx(1.1) and m.altitude_m == pytest.approx(12.5)
    assert m.speed_mps == pytest.approx(1.9 * 1852 / 3600)


def replay_fixes(tmp_path, raw, child_env, sanitized=False):
    """The recorded raw messages as a log, through auv-driver-replay --print."""
    return replay_print(tmp_path, raw, child_env, "GPS", programs.gps_origin_flags(*ORIGIN), sanitized)


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_gps_on_a_pty(sanitized, lcm_url, tmp_path, child_env):
    bus = Bus(lcm_url, "GPS", gps_fix_t)
    pty = Pty(tmp_path / "gps0")
    build = c_program("bin/auv-gps", sanitized).parent.parent
    cmd = programs.device_driver(
        build,
        "gps",
        vehicle=VEHICLE,
        lcm_url=lcm_url,
        port=tmp_path / "gps0",
        baud=4800,
        raw=True,
        extra=programs.gps_origin_flags(*ORIGIN),
    )
    proc = start(cmd, tmp_path, child_env)
    try:
        s = bus.wait_status(lambda s: s.port_open, "the port open")
        assert s.port == f"{tmp_path / 'gps0'}@4800" and s.reopens == 0
        # three epochs, cut anywhere between writes
        stream = epoch("120001") + epoch("120002", "4807.100") + epoch("120003", "4807.200", "01131.500")
        for i in range(0, len(stream), 50):
            pty.write(stream[i : i + 50])
        bus.wait(lambda: len(bus.msgs) >= 3, "three fixes")
        check_fix(bus.msgs[0], "4807.038", "01131.000")
        check_fix(bus.msgs[2], "4807.200", "01131.500")
        # one read may hold several epochs: they share its receive time
        assert bus.msgs[0].utime <= bus.msgs[1].utime <= bus.msgs[2].utime
        assert bus.msgs[0].utc_utime == 1721044801_000000  # 2024-07-15 12:00:01 UTC
        # every kind of bad input, each with its reason; nothing published from it
        pty.write(HOSTILE)
        bus.wait_status(lambda s: sum(s.reason_count) >= len(HOSTILE_REASONS), "the hostile input counted")
        assert bus.reasons() == HOSTILE_REASONS, bus.last().last_error
        assert len(bus.msgs) == 3
        bus.wait(lambda: bus.health and bus.health[-1].decode_errors == 5, "health's decode_errors")
        assert bus.health[-1].process == "auv-gps" and bus.health[-1].cpu_load < 0.5
        # the device vanishes and comes back behind the same path
        pty.swap()
        s = bus.wait_status(lambda s: s.reopens == 1 and s.port_open, "the port reopened")
        pty.write(epoch("120010", "4807.300"))
        bus.wait(lambda: len(bus.msgs) >= 4, "a fix after the reopening")
        check_fix(bus.msgs[3], "4807.300", "01131.000")
        n_raw = len(bus.raw)
        bus.wait_status(lambda s: s.bytes_read == sum(raw_bytes_t.decode(d).n_bytes for _, d in bus.raw), "raw")
        assert n_raw > 0
    finally:
        pty.close()
        text = finish(proc, tmp_path)
    assert "reopened" in text and "dropped: bad checksum" in text
    # the recorded bytes give the same fixes through the same parser
    printed, reasons = replay_fixes(tmp_path, bus.raw, child_env, sanitized)
    assert len(printed) == len(bus.msgs) == 4
    for p, m in zip(printed, bus.msgs):
        same_printed(p, m)
    assert reasons == HOSTILE_REASONS


def test_gps_on_tcp(lcm_url, tmp_path, child_env):
    bus = Bus(lcm_url, "GPS", gps_fix_t)
    server = socket.create_server(("127.0.0.1", 0))
    server.settimeout(20)
    port = server.getsockname()[1]
    cmd = programs.device_driver(
        c_program("bin/auv-gps").parent.parent,
        "gps",
        vehicle=VEHICLE,
        lcm_url=lcm_url,
        tcp=f"127.0.0.1:{port}",
        extra=programs.gps_origin_flags(*ORIGIN),
    )
    proc = start(cmd, tmp_path, child_env)
    try:
        conn, _ = server.accept()
        conn.sendall(epoch("120001") + b"\x01\x02 noise " + epoch("120002"))
        bus.wait(lambda: len(bus.msgs) >= 2, "two fixes over TCP")
        check_fix(bus.msgs[1], "4807.038", "01131.000")
        # the peer closes mid-sentence: the half sentence is forgotten, the
        # driver connects again
        conn.sendall(b"$GPGGA,120003,4807")
        conn.close()
        conn, _ = server.accept()
        conn.sendall(epoch("120004", "4807.500"))
        bus.wait(lambda: len(bus.msgs) >= 3, "a fix after the reconnection")
        check_fix(bus.msgs[2], "4807.500", "01131.000")
        s = bus.wait_status(lambda s: s.reopens == 1 and s.port_open, "reopens counted")
        assert s.port == f"tcp:127.0.0.1:{port}"
        assert bus.reasons() == {"garbage": 1}  # no "truncated": the cut sentence died with its port
        conn.close()
    finally:
        server.close()
        finish(proc, tmp_path)


def test_gps_sim_clock_stamps(lcm_url, tmp_path, child_env):
    bus = Bus(lcm_url, "GPS", gps_fix_t)
    pty = Pty(tmp_path / "gps0")
    cmd = programs.device_driver(
        c_program("bin/auv-gps").parent.parent,
        "gps",
        vehicle=VEHICLE,
        lcm_url=lcm_url,
        port=tmp_path / "gps0",
        clock="sim",
    )
    proc = start(cmd, tmp_path, child_env)
    try:
        bus.wait_status(lambda s: s.port_open, "the port open")
        pty.write(epoch("120001"))  # before any SIM.CLOCK: no time to stamp with
        bus.wait_status(lambda s: "no clock yet" in s.reason, "bytes before the clock counted")
        clock = sim_clock_t()
        clock.utime, clock.server_id, clock.mode = 42_000_000, "test", sim_clock_t.MODE_LOCKSTEP
        bus.lc.publish("SIM.CLOCK", clock.encode())
        bus.wait_status(lambda s: s.utime == 42_000_000, "the driver on the world's clock")
        pty.write(epoch("120002"))
        bus.wait(lambda: len(bus.msgs) >= 1, "a fix")
        assert bus.msgs[0].utime == 42_000_000 and math.isnan(bus.msgs[0].north_m)  # no --origin
    finally:
        pty.close()
        finish(proc, tmp_path)


def test_usage_errors(child_env):
    check_usage_errors(
        "bin/auv-gps",
        [
            ([], "exactly one of --device"),
            (["--device", "/dev/null", "--tcp", "h:1", "--vehicle", "A"], "exactly one of --device"),
            (["--device", "/dev/null", "--baud", "1234", "--vehicle", "A"], "--baud must be one of"),
            (["--tcp", "nohostport", "--vehicle", "A"], "HOST:PORT"),
            (["--device", "/dev/null"], "--vehicle ID is required"),
            (["--device", "/dev/null", "--vehicle", "A", "--origin", "91,0"], "--origin wants"),
            (["--device", "/dev/null", "--vehicle", "A", "--clock", "gps"], "--clock is system or sim"),
        ],
        child_env,
    )
