"""The gateways over a byte pipe, as at sea (tools/radio/pipe.py, and in C
c/drivers/radio/radio_pipe.c): the framing finds every good frame in noise,
and the two gateways (the shore's in Python, the vehicle's auv-radio in C)
connected through a TCP "air" that adds line noise carry a command byte for
byte and bring the status home: each side reads the other's framing."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import threading
import time

import lcm
from conftest import BUILD
from lcm_proc import stop, wait_for_line

from auv import mission_command_t, nav_solution_t
from auvlcm import programs
from tools.radio.pipe import MAX_FRAME, Deframer, encode
from tools.radio.wire import frame


def _frames(n: int) -> list[bytes]:
    return [frame("SHORE", "AUV1", i, i, os.urandom(10 + 37 * i)) for i in range(n)]


def test_the_deframer_finds_every_good_frame_in_noise():
    good = _frames(6)
    bad_crc = bytearray(encode(good[2]))
    bad_crc[-1] ^= 0xFF
    stream = (
        b"noise"
        + encode(good[0])
        + b"\xa5"
        + encode(good[1])  # a lone half marker
        + bytes(bad_crc)  # dropped, counted
        + b"\xa5\x5a"
        + (MAX_FRAME + 1).to_bytes(4, "big")  # an impossible length
        + encode(good[3])[:-7]  # cut by a dive ...
        + encode(good[4])
        + encode(good[5])  # ... costs that frame only
    )
    d = Deframer()
    got = []
    for i in range(0, len(stream), 7):  # as the bytes trickle in
        got += d.feed(stream[i : i + 7])
    assert [f.seq for f in got] == [0, 1, 4, 5]
    assert all(f.encode() == good[f.seq] for f in got)
    assert d.dropped["bad CRC"] >= 1 and d.dropped["too long"] >= 1 and d.dropped["noise bytes"] >= 5


class Air:
    """Two TCP ports, the shore's radio and the vehicle's: bytes from one go to
    the other, with noise added between writes."""

    def __init__(self) -> None:
        self.listeners = [socket.create_server(("127.0.0.1", 0)) for _ in range(2)]
        self.ports = [s.getsockname()[1] for s in self.listeners]
        self.conns: list[socket.socket] = []
        self.done = False
        threading.Thread(target=self._run, daemon=True).start()

    def _run(self) -> None:
        self.conns = [s.accept()[0] for s in self.listeners]
        a, b = self.conns
        import select

        while not self.done:
            ready, _, _ = select.select([a, b], [], [], 0.05)
            for s in ready:
                data = s.recv(65536)
                if not data:
                    return
                (b if s is a else a).sendall(b"\x00\xa5garbage" + data)


def test_two_gateways_over_a_noisy_pipe_carry_a_command_and_the_status(tmp_path, lcm_url, child_env):
    air = Air()
    lc = lcm.LCM(lcm_url)
    got: list[tuple[str, bytes]] = []
    lc.subscribe(r"AUV1\.MISSION_CMD|SHORE\.AUV1\.RADIO_REPORT", lambda c, d: got.append((c, d)))
    py = sys.executable
    common = ["--clock", "system", "--lcm-url", lcm_url]
    procs = [
        subprocess.Popen(
            [py, "-m", "tools.radio.shore_gateway", "--vehicles", "AUV1", "--tcp", f"127.0.0.1:{air.ports[0]}"]
            + ["--link-timeout-s", "2"]
            + common,
            env=child_env,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        ),
        subprocess.Popen(  # the vehicle's: auv-radio, C on the driver framework, the same framing
            programs.radio_vehicle(
                BUILD,
                vehicle="AUV1",
                spool=tmp_path / "spool",
                lcm_url=lcm_url,
                tcp=f"127.0.0.1:{air.ports[1]}",
                clock="system",
                report_period_s=0.2,
            ),
            env=child_env,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        ),
    ]
    try:
        for p in procs:
            wait_for_line(p, ": ready", timeout=30)
        cmd = mission_command_t()
        cmd.vehicle, cmd.seq, cmd.command, cmd.reason = "AUV1", 11, mission_command_t.CMD_PAUSE, "pipe test"
        data = cmd.encode() + b"SIGNATURE"
        deadline = time.monotonic() + 20
        sent = False
        while time.monotonic() < deadline and not any(c == "AUV1.MISSION_CMD" for c, _ in got):
            nav = nav_solution_t()
            nav.utime, nav.vehicle, nav.depth_m = int(time.time() * 1e6), "AUV1", 0.0
            lc.publish("AUV1.NAV", nav.encode())  # at the surface: it reports home
            if not sent and any(c == "SHORE.AUV1.RADIO_REPORT" for c, _ in got):
                lc.publish("SHORE.AUV1.MISSION_CMD", data)
                sent = True
            lc.handle_timeout(50)
        assert ("AUV1.MISSION_CMD", data) in got, [c for c, _ in got]
    finally:
        air.done = True
        codes = [stop(p, signal.SIGTERM) for p in procs]
        errs = [p.stderr.read() for p in procs]
    assert codes == [0, 0], errs
    assert "pipe dropped {'noise bytes':" in errs[0], errs[0]
    assert "auv-radio AUV1: delivered 1" in errs[1] and "noise bytes" in errs[1], errs[1]
