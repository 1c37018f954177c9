"""auv-gps as a process (c/drivers/gps, docs/drivers.md): NMEA written into a
pseudo-terminal (behind a udev-style symlink, at a set baud) or a TCP port
reaches LCM as gps_fix_t; garbage, bad checksums, an endless line and absurd
values with valid checksums are counted per reason in driver_status_t and in
process_health_t.decode_errors; a port that vanishes is reopened (reopens
counted); the raw bytes it recorded (--raw) give the same fixes again through
auv-driver-replay; --clock sim stamps with SIM.CLOCK."""

from __future__ import annotations

import math
import os
import re
import signal
import socket
import subprocess
from functools import reduce

import lcm
import pytest
from conftest import c_program
from lcm_proc import pump, stop

from auv import driver_status_t, gps_fix_t, process_health_t, raw_bytes_t, sim_clock_t
from auvlcm import programs
from sim.geo import LocalFrame

VEHICLE = "AUV1"
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


class Bus:
    """What the driver publishes, as it arrives."""

    def __init__(self, url: str) -> None:
        self.lc = lcm.LCM(url)
        self.fixes: list[gps_fix_t] = []
        self.status: list[driver_status_t] = []
        self.health: list[process_health_t] = []
        self.raw: list[tuple[str, bytes]] = []
        # queues that hold a loaded run's bursts (LCM's default, 30, drops the newest)
        self.lc.subscribe(f"{VEHICLE}.GPS", lambda c, d: self.fixes.append(gps_fix_t.decode(d))).set_queue_capacity(
            10000
        )
        self.lc.subscribe(
            f"{VEHICLE}.DRIVER.GPS", lambda c, d: self.status.append(driver_status_t.decode(d))
        ).set_queue_capacity(10000)
        self.lc.subscribe(
            f"{VEHICLE}.HEALTH", lambda c, d: self.health.append(process_health_t.decode(d))
        ).set_queue_capacity(10000)
        self.lc.subscribe(f"{VEHICLE}.RAW.GPS", lambda c, d: self.raw.append((c, d))).set_queue_capacity(10000)

    def wait(self, until, what: str, timeout: float = 20.0) -> None:
        assert pump(self.lc, until, timeout), f"waited {timeout} s for {what}; last status: {self.last()}"

    def last(self):
        return self.status[-1] if self.status else None

    def reasons(self) -> dict[str, int]:
        s = self.last()
        return dict(zip(s.reason, s.reason_count)) if s else {}

    def wait_status(self, pred, what: str, timeout: float = 20.0) -> driver_status_t:
        self.wait(lambda: bool(self.status) and pred(self.status[-1]), what, timeout)
        return self.status[-1]


class Pty:
    """A pseudo-terminal behind a stable path, as udev gives a device: swap()
    puts a new one behind the path and hangs the old one up (a device that
    vanished and came back)."""

    def __init__(self, link) -> None:
        self.link = link
        self.master = -1
        self._new()

    def _new(self) -> None:
        master, slave = os.openpty()
        name = os.ttyname(slave)
        os.close(slave)  # the driver opens it itself
        tmp = self.link.with_suffix(".new")
        os.symlink(name, tmp)
        os.replace(tmp, self.link)
        old, self.master = self.master, master
        if old >= 0:
            os.close(old)

    def swap(self) -> None:
        self._new()

    def write(self, data: bytes) -> None:
        os.write(self.master, data)

    def close(self) -> None:
        if self.master >= 0:
            os.close(self.master)
            self.master = -1


def start(cmd, tmp_path, child_env) -> subprocess.Popen:
    err = open(tmp_path / "driver.stderr", "w")
    return subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=err, env=child_env)


def finish(proc: subprocess.Popen, tmp_path) -> str:
    rc = stop(proc, signal.SIGTERM)
    text = (tmp_path / "driver.stderr").read_text()
    assert rc == 0, f"exit {rc}:\n{text}"
    assert "runtime error" not in text and "Sanitizer" not in text, text
    return text


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
    log = lcm.EventLog(str(tmp_path / "raw.lcmlog"), "w")
    for channel, data in raw:
        log.write_event(raw_bytes_t.decode(data).utime, channel, data)
    log.close()
    build = c_program("bin/auv-driver-replay", sanitized).parent.parent
    cmd = programs.driver_replay(
        build,
        log=tmp_path / "raw.lcmlog",
        vehicle=VEHICLE,
        device="GPS",
        extra=programs.gps_origin_flags(*ORIGIN),
    )
    p = subprocess.run(cmd, capture_output=True, text=True, env=child_env, timeout=60)
    assert p.returncode == 0, p.stderr
    fixes = []
    for line in p.stdout.splitlines():
        assert line.startswith(f"{VEHICLE}.GPS "), line
        fields = dict(re.findall(r'(\w+)=("(?:[^"\\]|\\.)*"|\S+)', line))
        fixes.append(fields)
    summary = p.stderr.strip().splitlines()[-1]  # "... N dropped: reason: n, reason: n"
    reasons = {k: int(v) for k, v in re.findall(r"[:,] ([a-z ]+): (\d+)", summary.rsplit(" dropped", 1)[1])}
    return fixes, reasons


def same_fix(printed: dict, m: gps_fix_t) -> None:
    for name in gps_fix_t.__slots__:
        value = getattr(m, name)
        text = printed[name]
        if isinstance(value, str):
            assert text == f'"{value}"', name
        elif isinstance(value, float) and math.isnan(value):
            assert text in ("nan", "-nan"), name
        else:
            assert float(text) == value, (name, text, value)


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_gps_on_a_pty(sanitized, lcm_url, tmp_path, child_env):
    bus = Bus(lcm_url)
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
        bus.wait(lambda: len(bus.fixes) >= 3, "three fixes")
        check_fix(bus.fixes[0], "4807.038", "01131.000")
        check_fix(bus.fixes[2], "4807.200", "01131.500")
        # one read may hold several epochs: they share its receive time
        assert bus.fixes[0].utime <= bus.fixes[1].utime <= bus.fixes[2].utime
        assert bus.fixes[0].utc_utime == 1721044801_000000  # 2024-07-15 12:00:01 UTC
        # every kind of bad input, each with its reason; nothing published from it
        pty.write(HOSTILE)
        bus.wait_status(lambda s: sum(s.reason_count) >= len(HOSTILE_REASONS), "the hostile input counted")
        assert bus.reasons() == HOSTILE_REASONS, bus.last().last_error
        assert len(bus.fixes) == 3
        bus.wait(lambda: bus.health and bus.health[-1].decode_errors == 5, "health's decode_errors")
        assert bus.health[-1].process == "auv-gps" and bus.health[-1].cpu_load < 0.5
        # the device vanishes and comes back behind the same path
        pty.swap()
        s = bus.wait_status(lambda s: s.reopens == 1 and s.port_open, "the port reopened")
        pty.write(epoch("120010", "4807.300"))
        bus.wait(lambda: len(bus.fixes) >= 4, "a fix after the reopening")
        check_fix(bus.fixes[3], "4807.300", "01131.000")
        n_raw = len(bus.raw)
        bus.wait_status(lambda s: s.bytes_read == sum(raw_bytes_t.decode(d).n_bytes for _, d in bus.raw), "raw")
        assert n_raw > 0
    finally:
        pty.close()
        text = finish(proc, tmp_path)
    assert "reopened" in text and "dropped: bad checksum" in text
    # the recorded bytes give the same fixes through the same parser
    printed, reasons = replay_fixes(tmp_path, bus.raw, child_env, sanitized)
    assert len(printed) == len(bus.fixes) == 4
    for p, m in zip(printed, bus.fixes):
        same_fix(p, m)
    assert reasons == HOSTILE_REASONS


def test_gps_on_tcp(lcm_url, tmp_path, child_env):
    bus = Bus(lcm_url)
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
        bus.wait(lambda: len(bus.fixes) >= 2, "two fixes over TCP")
        check_fix(bus.fixes[1], "4807.038", "01131.000")
        # the peer closes mid-sentence: the half sentence is forgotten, the
        # driver connects again
        conn.sendall(b"$GPGGA,120003,4807")
        conn.close()
        conn, _ = server.accept()
        conn.sendall(epoch("120004", "4807.500"))
        bus.wait(lambda: len(bus.fixes) >= 3, "a fix after the reconnection")
        check_fix(bus.fixes[2], "4807.500", "01131.000")
        s = bus.wait_status(lambda s: s.reopens == 1 and s.port_open, "reopens counted")
        assert s.port == f"tcp:127.0.0.1:{port}"
        assert bus.reasons() == {"garbage": 1}  # no "truncated": the cut sentence died with its port
        conn.close()
    finally:
        server.close()
        finish(proc, tmp_path)


def test_gps_sim_clock_stamps(lcm_url, tmp_path, child_env):
    bus = Bus(lcm_url)
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
        bus.wait(lambda: len(bus.fixes) >= 1, "a fix")
        assert bus.fixes[0].utime == 42_000_000 and math.isnan(bus.fixes[0].north_m)  # no --origin
    finally:
        pty.close()
        finish(proc, tmp_path)


def test_usage_errors(child_env):
    exe = str(c_program("bin/auv-gps"))
    for args, text in [
        ([], "exactly one of --device"),
        (["--device", "/dev/null", "--tcp", "h:1", "--vehicle", "A"], "exactly one of --device"),
        (["--device", "/dev/null", "--baud", "1234", "--vehicle", "A"], "--baud must be one of"),
        (["--tcp", "nohostport", "--vehicle", "A"], "HOST:PORT"),
        (["--device", "/dev/null"], "--vehicle ID is required"),
        (["--device", "/dev/null", "--vehicle", "A", "--origin", "91,0"], "--origin wants"),
        (["--device", "/dev/null", "--vehicle", "A", "--clock", "gps"], "--clock is system or sim"),
    ]:
        p = subprocess.run([exe, *args], capture_output=True, text=True, env=child_env, timeout=30)
        assert p.returncode == 2 and text in p.stderr, (args, p.stderr)
