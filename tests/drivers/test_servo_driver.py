"""auv-servo as a process (c/drivers/servo, docs/drivers.md "auv-servo"): the
real driver on a pseudo-terminal, actuators_t published over LCM, and the
bytes it writes read on the pty's master and played into the simulator's
Maestro emulator (python/sim/devices/maestro.py), whose replies go back on the
wire. Checked on the channels' targets: neutral at the start, the commanded
pulses, the table's limits, neutral after the watchdog's timeout (a counted
reason), the next command resuming; refused commands and malformed actuators_t
datagrams counted by reason; the Maestro's error bits counted by name; a bad
channel table refused with file:line:col."""

from __future__ import annotations

import errno
import os
import select
import subprocess
import time

import lcm
import pytest
from conftest import c_program
from driver_bus import VEHICLE, Bus, Pty, finish, start

from auv import actuators_t
from auvlcm import programs
from sim.devices.maestro import ERR_SERIAL_PROTOCOL, Maestro

TABLE = """\
protocol compact
watchdog 0.5
#       ch actuator     neutral us/unit  min   max   options
channel 0  rudder       1500    500      1100  1900
channel 1  stern_plane  1500    500      1100  1900  reversed speed 100 accel 4
channel 2  prop         1490    0.25     1000  2000
"""
NEUTRAL = (6000, 6000, 5960)  # quarter-microseconds


def pulses(rudder: float, stern: float, rpm: float) -> tuple[int, int, int]:
    """The table's mapping, written out: neutral + s * us_per_unit * value, clamped."""

    def q(neutral, s, per, v, lo, hi):
        return round(min(max(neutral + s * per * v, lo), hi) * 4)

    return (q(1500, 1, 500, rudder, 1100, 1900), q(1500, -1, 500, stern, 1100, 1900), q(1490, 1, 0.25, rpm, 1000, 2000))


class Wire:
    """The device's side of the pty: every byte the driver writes goes into
    the emulator, its replies go back; the targets of channels 0..2 after each
    read are kept in order (a command's pulses are seen even if the watchdog
    sets neutral again soon after)."""

    def __init__(self, pty: Pty) -> None:
        self.pty = pty
        self.maestro = Maestro()
        for c in self.maestro.channels:  # the whole protocol range: the driver's clamps show
            c.min_qus, c.max_qus = 4, 16383
        self.seen: list[tuple[int, int, int]] = []
        self.written = 0
        self.head = b""  # the first bytes the driver wrote

    def service(self) -> None:
        while select.select([self.pty.master], [], [], 0)[0]:
            try:
                data = os.read(self.pty.master, 4096)
            except OSError as e:  # EIO: no one has the slave open (yet)
                if e.errno != errno.EIO:
                    raise
                return
            self.written += len(data)
            self.head += data[: max(0, 16 - len(self.head))]
            reply = self.maestro.feed(data)
            if reply:
                self.pty.write(reply)
            now = tuple(self.maestro.targets()[:3])
            if not self.seen or self.seen[-1] != now:
                self.seen.append(now)

    def last(self) -> tuple[int, int, int] | None:
        return self.seen[-1] if self.seen else None


class ServoBus(Bus):
    def __init__(self, url: str, wire: Wire) -> None:
        super().__init__(url, "SERVO")
        self.wire = wire
        self.seq = 0

    def wait(self, until, what: str, timeout: float = 20.0) -> None:
        def step() -> bool:
            self.wire.service()
            return until()

        super().wait(step, f"{what} (targets seen: {self.wire.seen[-5:]})", timeout)

    def command(self, rudder: float, stern: float, rpm: float, age_s: float = 0.0) -> None:
        self.seq += 1
        m = actuators_t()
        m.utime = int((time.time() - age_s) * 1e6)
        m.vehicle = VEHICLE
        m.rudder_rad, m.stern_plane_rad, m.prop_rpm, m.seq = rudder, stern, rpm, self.seq
        self.lc.publish(f"{VEHICLE}.ACTUATORS", m.encode())


def servo_cmd(tmp_path, lcm_url, table, sanitized=False) -> list[str]:
    build = c_program("bin/auv-servo", sanitized).parent.parent
    return programs.device_driver(
        build,
        "servo",
        vehicle=VEHICLE,
        lcm_url=lcm_url,
        port=tmp_path / "servo0",
        baud=115200,
        extra=programs.servo_table_flags(table),
    )


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_servo_on_a_pty(sanitized, lcm_url, tmp_path, child_env):
    table = tmp_path / "fins.table"
    table.write_text(TABLE)
    pty = Pty(tmp_path / "servo0")
    wire = Wire(pty)
    bus = ServoBus(lcm_url, wire)
    proc = start(servo_cmd(tmp_path, lcm_url, table, sanitized), tmp_path, child_env)
    try:
        # the start: the baud rate indication (a whole Get Errors: AA, device 12,
        # 21), each channel's limits, then neutral; nothing counted
        bus.wait(lambda: wire.last() == NEUTRAL, "neutral at the start")
        assert wire.head.startswith(b"\xaa\x0c\x21\x87"), wire.head.hex()
        ch1 = wire.maestro.channels[1]
        assert (ch1.speed, ch1.accel) == (100, 4)
        s = bus.wait_status(lambda s: s.port_open, "the port open")
        assert s.port == f"{tmp_path / 'servo0'}@115200" and s.device == "SERVO"
        assert bus.reasons() == {}

        # a command: its pulses (the stern plane's servo is reversed)
        want = pulses(0.2, 0.1, 100.0)
        assert want == (6400, 5800, 6060)
        bus.command(0.2, 0.1, 100.0)
        bus.wait(lambda: want in wire.seen, "the commanded pulses")

        # beyond the limits: clamped by the driver, not by the device
        want = pulses(2.0, -3.0, -10000.0)
        assert want == (7600, 7600, 4000)
        bus.command(2.0, -3.0, -10000.0)
        bus.wait(lambda: want in wire.seen, "the clamped pulses")

        # silence: the watchdog sets neutral once, a counted reason
        bus.wait(lambda: wire.last() == NEUTRAL and bus.reason("watchdog timeout") == 1, "the watchdog")
        assert "watchdog timeout" in bus.last().last_error
        n_seen = len(wire.seen)

        # a new command resumes
        want = pulses(-0.3, 0.2, 400.0)
        bus.command(-0.3, 0.2, 400.0)
        bus.wait(lambda: want in wire.seen[n_seen:], "the resumed pulses")

        # refused whole: a command older than the watchdog, a NaN; the pulses stay
        bus.wait(lambda: bus.reason("watchdog timeout") == 2, "the second timeout")
        at = len(wire.seen)
        bus.command(0.1, 0.1, 0.0, age_s=5.0)
        bus.command(float("nan"), 0.0, 0.0)
        bus.wait(lambda: bus.reason("stale") == 1 and bus.reason("non-finite value") == 1, "the refusals")
        assert wire.seen[at:] in ([], [NEUTRAL])

        # malformed datagrams on the channel: counted, never applied
        good = actuators_t()
        good.vehicle = VEHICLE
        bus.lc.publish(f"{VEHICLE}.ACTUATORS", b"not an actuators_t")
        bus.lc.publish(f"{VEHICLE}.ACTUATORS", good.encode()[:-5])
        bus.wait(lambda: bus.reason("undecodable ACTUATORS") == 2, "the malformed datagrams")

        # the Maestro's own error bits, read by the driver's Get Errors poll
        wire.maestro.feed(b"\x05")  # a data byte without a command: serial protocol error
        assert wire.maestro.errors & ERR_SERIAL_PROTOCOL
        bus.wait(lambda: bus.reason("serial protocol error") == 1, "the error bit counted by name")
        assert bus.reason("unexpected byte") == 0 and bus.reason("reply timeout") == 0
        bus.wait(lambda: bus.health and bus.health[-1].process == "auv-servo", "health")
        # every byte it counts as written is on the wire (the wire read first)
        s = bus.wait_status(lambda s: s.bytes_written > 0, "bytes written")
        assert s.bytes_written <= wire.written
    finally:
        pty.close()
        text = finish(proc, tmp_path)
    assert text.count("dropped: watchdog timeout") == 1, text  # on stderr once
    assert "no command since the start" in text and "resumed" in text and "clamped" in text


def test_servo_refuses_a_bad_table(lcm_url, tmp_path, child_env):
    bad = TABLE.replace("stern_plane  1500    500 ", "stern_plane  1500    -5  ")
    table = tmp_path / "bad.table"
    table.write_text(bad)
    line = bad.splitlines()[4]
    col = line.index("-5") + 1
    p = subprocess.run(servo_cmd(tmp_path, lcm_url, table), capture_output=True, text=True, env=child_env, timeout=30)
    assert p.returncode == 2, p.stderr
    assert f"auv-servo: {table}:5:{col}: microseconds per unit: -5 is outside" in p.stderr
    # and none at all
    cmd = [a for a in servo_cmd(tmp_path, lcm_url, table) if a not in ("--table", str(table))]
    p = subprocess.run(cmd, capture_output=True, text=True, env=child_env, timeout=30)
    assert p.returncode != 0 and "--table FILE is required" in p.stderr


def test_servo_replay_ignores_subscriptions(tmp_path, child_env):
    """The replay knows the device (its flags, its replies) but has no LCM input:
    an empty log runs through without a table."""
    log = lcm.EventLog(str(tmp_path / "empty.lcmlog"), "w")
    log.close()
    build = c_program("bin/auv-driver-replay").parent.parent
    cmd = programs.driver_replay(build, log=tmp_path / "empty.lcmlog", vehicle=VEHICLE, device="SERVO")
    p = subprocess.run(cmd, capture_output=True, text=True, env=child_env, timeout=30)
    assert p.returncode == 0, p.stderr
