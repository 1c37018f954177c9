"""auv-radio, the vehicle's radio gateway (c/drivers/radio), as a process on a
TCP byte pipe the test holds, over real LCM: a command crosses byte for byte
(bytes appended by the operator's tool, a signature, pass) while a flood of
garbage, frames for another node and chunks of unknown transfers change
nothing; every chunk is answered, in the pipe's framing as Python reads it
(tools/radio/pipe.py), and nothing else is; acoustic commands with the team's
keys are checked (the shore gateway's frame run; a stranger's, an untagged and
a forged frame refused, a replay refused) and the command issued is signed; after a key rotation the old key
still verifies."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import time

import lcm
import pytest
from lcm_proc import stop, wait_for_line

from auv import driver_status_t, mission_command_t, modem_rx_t, modem_tx_t, radio_ack_t, radio_frame_t
from auvlcm import auth
from auvlcm.team_codec import TeamCodec
from tools.radio.outbox import Outbox
from tools.radio.pipe import Deframer, encode
from tools.radio.shore_gateway import ShoreGateway
from tools.radio.shore_gateway import parser as shore_parser
from tools.radio.wire import frame


class Radio:
    """auv-radio on a TCP port of the test's: what it writes is read back with Python's deframer."""

    def __init__(self, exe, tmp_path, url: str, env: dict, *extra: str) -> None:
        self.listener = socket.create_server(("127.0.0.1", 0))
        port = self.listener.getsockname()[1]
        cmd = [str(exe), "--tcp", f"127.0.0.1:{port}", "--vehicle", "AUV1", "--clock", "system"]
        cmd += ["--lcm-url", url, "--spool", str(tmp_path / "spool"), *extra]
        self.proc = subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.listener.settimeout(20)
        self.conn, _ = self.listener.accept()
        wait_for_line(self.proc, ": ready", timeout=20)
        self.deframer = Deframer()
        self.heard: list[radio_frame_t] = []

    def send(self, data: bytes) -> None:
        self.conn.sendall(data)

    def read(self, until, timeout: float = 20.0) -> bool:
        self.conn.settimeout(0.05)
        deadline = time.monotonic() + timeout
        while not until() and time.monotonic() < deadline:
            try:
                self.heard += self.deframer.feed(self.conn.recv(65536))
            except TimeoutError:
                pass
        return until()

    def stop(self) -> tuple[int, str]:
        """Stop it, then read what it wrote to the pipe's end (its exit closes
        the pipe): nothing it sent is left unread, and no wait on wall time."""
        code = stop(self.proc, signal.SIGTERM)
        self.conn.settimeout(20)
        while chunk := self.conn.recv(65536):
            self.heard += self.deframer.feed(chunk)
        self.conn.close()
        self.listener.close()
        return code, self.proc.stderr.read()


def signed_command() -> bytes:
    m = mission_command_t()
    m.vehicle, m.seq, m.command, m.reason = "AUV1", 7, mission_command_t.CMD_PAUSE, "test"
    return m.encode() + b"HMAC" + os.urandom(32)  # fields another branch appends


def chunk_frames(data: bytes, tid: int) -> list[bytes]:
    box = Outbox("AUV1", chunk_bytes=64, window=10**6)
    box.submit("MISSION_CMD", data, 1, "test", 0.0).tid = tid
    box.heard(0.0)
    return [encode(frame("SHORE", "AUV1", i, 0, c.encode())) for i, c in enumerate(box.due(0.0, 0))]


def test_a_command_crosses_byte_for_byte_and_a_flood_changes_nothing(variant_dir, tmp_path, lcm_url, child_env):
    lc = lcm.LCM(lcm_url)
    cmds: list[tuple[str, bytes]] = []
    lc.subscribe(r"AUV1\.(MISSION_CMD|PLUGIN_UPLOAD)", lambda c, d: cmds.append((c, d)))
    radio = Radio(variant_dir / "bin" / "auv-radio", tmp_path, lcm_url, child_env)
    try:
        flood = bytearray()
        for i in range(3000):  # garbage frames, frames for another node, noise between them
            payload = os.urandom(i % 200) if i % 2 else b""
            flood += b"\x00\xa5noise" + encode(frame("SHORE", "AUV1" if i % 3 else "AUV2", i, 0, payload))
        radio.send(bytes(flood))
        unknown = chunk_frames(b"x" * 500, 99)[1:]  # never its first chunk
        radio.send(b"".join(unknown))
        data = signed_command()
        good = chunk_frames(data, 7)
        radio.send(b"".join(good))
        deadline = time.monotonic() + 20
        while not cmds and time.monotonic() < deadline:
            lc.handle_timeout(50)
        acks = lambda: [radio_ack_t.decode(bytes(f.payload)) for f in radio.heard]  # noqa: E731
        assert radio.read(lambda: len(radio.heard) >= len(unknown) + len(good))
    finally:
        code, err = radio.stop()
    assert code == 0, err
    assert cmds == [("AUV1.MISSION_CMD", data)]  # as the operator's tool encoded it, signature and all
    got = acks()  # every chunk answered, in order, and no garbage frame
    assert len(got) == len(unknown) + len(good), got
    assert [a.reason for a in got[: len(unknown)]] == [
        f"chunk {i} of a transfer not held: send from 0" for i in range(1, 8)
    ]
    assert got[-1].state == radio_ack_t.STATE_DONE and got[-1].transfer_id == 7
    assert all(f.src == "AUV1" and f.dst == "SHORE" for f in radio.heard)
    assert "auv-radio AUV1: delivered 1, acoustic commands 0, frames dropped 3000" in err, err
    assert "unknown transfer 7" in err and "noise bytes" in err and not list((tmp_path / "spool").glob("*.part"))


def _modem_rx(payload: bytes) -> bytes:
    m = modem_rx_t()
    m.vehicle, m.src_vehicle, m.kind = "AUV1", "SHORE", modem_tx_t.KIND_TEAM
    m.payload, m.n_bytes = payload, len(payload)
    return m.encode()


def _tagged(codec: TeamCodec, key: bytes, vals: dict) -> bytes:
    t = auth.acoustic_tag(key, codec.encode("command", dict(vals, mac_hi=0, mac_lo=0)), vals["counter"])
    return codec.encode("command", dict(vals, mac_hi=t >> 16, mac_lo=t & 0xFFFF))


@pytest.mark.parametrize("variant_dir", ["normal"], indirect=True)
def test_acoustic_commands_with_team_keys_are_checked_and_signed(variant_dir, tmp_path, lcm_url, child_env):
    from tools.keys.keygen import main as keygen

    team, stranger = tmp_path / "team.key", tmp_path / "stranger.key"
    assert keygen([str(team)]) == 0 and keygen([str(stranger)]) == 0
    ring, strange = auth.load_keys(team), auth.load_keys(stranger)
    codec = TeamCodec()
    # the shore gateway's own acoustic abort, tagged with the team's newest key
    shore_lc = lcm.LCM("memq://")
    sargs = shore_parser().parse_args(["--vehicles", "AUV1", "--clock", "system", "--acoustic", "AUV1=2"])
    sargs.ring = ring
    shore = ShoreGateway(shore_lc, sargs)
    modem: list[bytes] = []
    shore_lc.subscribe(r"SHORE\.MODEM_TX", lambda c, d: modem.append(d))
    abort = mission_command_t()
    abort.vehicle, abort.seq, abort.command = "AUV1", 9, mission_command_t.CMD_ABORT
    shore._on_command("SHORE.AUV1.MISSION_CMD", abort.encode())
    shore.tick()
    while shore_lc.handle_timeout(0):
        pass
    good = bytes(modem_tx_t.decode(modem[0]).payload)
    vals = codec.decode_frame(good).messages[0].values
    assert (vals["mac_hi"], vals["mac_lo"]) != (0, 0) and vals["kind"] == 1
    c0 = vals["counter"]
    lc = lcm.LCM(lcm_url)
    cmds: list[bytes] = []
    lc.subscribe(r"AUV1\.MISSION_CMD", lambda c, d: cmds.append(d))
    exe = variant_dir / "bin" / "auv-radio"
    radio = Radio(exe, tmp_path, lcm_url, child_env, "--team-index", "2", "--key-file", str(team))
    try:
        heard = [
            codec.encode("command", dict(vals, counter=c0 + 1)),  # a stranger's frame: a new counter, the old tag
            codec.encode("command", dict(vals, counter=c0 + 2, mac_hi=0, mac_lo=0)),  # a modem with no key
            _tagged(codec, strange.signing.secret, dict(vals, counter=c0 + 3)),  # another team's key
            good,  # the shore's: run
        ]
        heard += [_tagged(codec, ring.signing.secret, dict(vals, kind=2, counter=c0 + 10 + i)) for i in range(16)]
        heard.append(good)  # out of the 16 counters remembered: the replay window refuses it
        for h in heard:
            lc.publish("AUV1.MODEM_RX", _modem_rx(h))
        # its status counts the last frame's refusal: every frame before it was
        # handled, and each command it issued is in this LCM's queue
        status: list[driver_status_t] = []
        lc.subscribe("AUV1.DRIVER.RADIO", lambda c, d: status.append(driver_status_t.decode(d)))
        deadline = time.monotonic() + 20
        while time.monotonic() < deadline and not (
            status and dict(zip(status[-1].reason, status[-1].reason_count)).get("acoustic replay") == 1
        ):
            lc.handle_timeout(50)
        while lc.handle_timeout(0):
            pass
    finally:
        code, err = radio.stop()
    assert code == 0, err
    assert len(cmds) == 17, err
    issued = mission_command_t.decode(cmds[0])
    assert issued.command == mission_command_t.CMD_ABORT and issued.seq == c0 and issued.manager == ""
    assert f"acoustic abort #{c0}" in issued.reason
    verifier = auth.Verifier(ring)
    assert all(verifier.verify(mission_command_t.decode(c)) == auth.OK for c in cmds)  # a manager with the key acts
    assert "acoustic bad_mac 3" in err and "acoustic replay 1" in err, err
    # a rotation: the vehicle holds the old and the new key; a shore not rotated yet still tags with the old
    assert keygen([str(team), "--rotate", "--id", "team-next"]) == 0
    cmds.clear()
    radio = Radio(exe, tmp_path, lcm_url, child_env, "--team-index", "2", "--key-file", str(team))
    try:
        lc.publish("AUV1.MODEM_RX", _modem_rx(_tagged(codec, ring.signing.secret, dict(vals, counter=c0 + 100))))
        deadline = time.monotonic() + 20
        while not cmds and time.monotonic() < deadline:
            lc.handle_timeout(50)
    finally:
        code, err = radio.stop()
    assert code == 0 and len(cmds) == 1, err
    assert mission_command_t.decode(cmds[0]).auth.key_id == "team-next"  # signed with the newest key
    assert "acoustic commands 1" in err and "bad_mac" not in err, err
