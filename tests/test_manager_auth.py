"""A manager with --key-file over real LCM: only signed mission commands and
uploads are acted on; forged, replayed, reordered, cut, stale, unsigned and
wrong-key ones are refused with the reason in the ack and counted per reason
in its status; a flood of bad MACs leaves its cycle rate alone; a key file
open to others stops it at start; without a key it says that commands are
not authenticated. Both builds."""

from __future__ import annotations

import hashlib
import signal
import subprocess
import time
from pathlib import Path

import lcm
import pytest
from conftest import manager_cmd
from lcm_proc import pump, stop
from test_manager import HERE, World, start_manager

from auv import chasm_status_t, mission_ack_t, mission_command_t, plugin_upload_t
from auvlcm import auth
from auvlcm.rx import Receiver
from tools.console.model import Model

BOTH = pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
OLD, NEW = auth.Key("team-old", bytes(range(32))), auth.Key("team-new", bytes(range(100, 132)))
RING = auth.KeyRing((OLD, NEW))


def write_keys(path: Path, mode: int = 0o600) -> Path:
    path.write_text("".join(f"{k.id} {k.secret.hex()}\n" for k in RING.keys))
    path.chmod(mode)
    return path


class Sender:
    def __init__(self, w: World) -> None:
        self.w, self.seq = w, 0

    def cmd(self, command: int = mission_command_t.CMD_PAUSE) -> mission_command_t:
        self.seq += 1
        m = mission_command_t()
        m.utime, m.vehicle, m.seq, m.command = self.w.utime, "AUV1", self.seq, command
        return m

    def send(self, msg, channel: str = "AUV1.MISSION_CMD") -> mission_ack_t:
        before = len(self.w.acks)
        self.w.lc.publish(channel, msg.encode())
        assert pump(self.w.lc, lambda: len(self.w.acks) > before, timeout=30), f"no ack {msg.seq}"
        assert self.w.acks[-1].seq == msg.seq
        return self.w.acks[-1]


@BOTH
def test_only_signed_commands_are_acted_on(lcm_url, child_env, tmp_path, sanitized):
    w = World(lcm_url)
    mgr = start_manager(lcm_url, child_env, sanitized, extra=["--key-file", write_keys(tmp_path / "team.key")])
    try:
        w.wait_for_first_cycle()
        s = Sender(w)
        ok = auth.sign(s.cmd(), RING, "test")
        assert s.send(ok).message == "paused"
        replay = s.send(ok)  # the same bytes again
        assert replay.result == mission_ack_t.RESULT_REJECTED and "replay" in replay.message
        assert "unsigned" in s.send(s.cmd(mission_command_t.CMD_ABORT)).message
        forged = s.cmd(mission_command_t.CMD_ABORT)
        forged.auth.key_id, forged.auth.sender, forged.auth.counter = NEW.id, "test", auth.next_counter()
        forged.auth.mac, forged.auth.mac_len = hashlib.sha256(b"guess").digest(), 32
        assert s.send(forged).message == "refused: bad MAC"
        modified = auth.sign(s.cmd(mission_command_t.CMD_RESUME), RING, "test")
        modified.command = mission_command_t.CMD_ABORT
        assert s.send(modified).message == "refused: bad MAC"
        cut = auth.sign(s.cmd(mission_command_t.CMD_ABORT), RING, "test")
        cut.auth.mac, cut.auth.mac_len = bytes(cut.auth.mac)[:31], 31
        assert s.send(cut).message == "refused: bad MAC"
        other = auth.KeyRing((auth.Key("team-x", NEW.secret),))
        assert s.send(auth.sign(s.cmd(mission_command_t.CMD_ABORT), other, "test")).message == "refused: unknown key id"
        stale = auth.sign(s.cmd(mission_command_t.CMD_ABORT), RING, "test", counter=auth.next_counter() - 301_000_000)
        assert "stale" in s.send(stale).message
        assert s.send(auth.sign(s.cmd(mission_command_t.CMD_RESUME), RING, "test")).message == "resumed"
        late = auth.sign(s.cmd(mission_command_t.CMD_ABORT), RING, "test", counter=ok.auth.counter + 1)
        assert "replay" in s.send(late).message  # reordered: signed before the resume, arrived after
        old_key = auth.sign(s.cmd(mission_command_t.CMD_RESUME), auth.KeyRing((OLD,)), "test")
        assert s.send(old_key).message == "resumed"  # a rotation: the older key still verifies
        up = plugin_upload_t()
        up.utime, up.vehicle, up.seq, up.plugin_name, up.plugin_version = w.utime, "AUV1", 500, "test_basic", "1"
        up.data = b"\x7fELF" * 64
        up.n_bytes, up.sha256_hex = len(up.data), hashlib.sha256(up.data).hexdigest()
        assert "unsigned" in s.send(up, "AUV1.PLUGIN_UPLOAD").message
        up.seq = 501
        signed_up = s.send(auth.sign(up, RING, "test"), "AUV1.PLUGIN_UPLOAD")
        assert "takes no uploads" in signed_up.message  # past authentication, refused for what it is
        w.tick(0.1, depth=0.0)
        st = w.status[-1]
        assert (st.auth_unsigned, st.auth_unknown_key, st.auth_bad_mac, st.auth_replay, st.auth_stale) == (
            2,
            1,
            3,
            2,
            1,
        )
        assert st.commands_refused == 9 and st.run_state == chasm_status_t.RUN_RUNNING
        model = Model()  # what the console and `auvctl status` show of it
        model.apply("AUV1.CHASM.NAVIGATOR", st)
        shown = model.vehicles["AUV1"]["managers"]["NAVIGATOR"]["auth_refused"]
        assert shown == {"unsigned": 2, "unknown_key": 1, "bad_mac": 3, "replay": 2, "stale": 1}
    finally:
        rc = stop(mgr, signal.SIGTERM)
    assert rc == 0, mgr.stderr.read()


@BOTH
def test_a_flood_of_bad_macs_leaves_the_cycle_rate(lcm_url, child_env, tmp_path, sanitized):
    keys = write_keys(tmp_path / "team.key")
    cmd = manager_cmd(HERE / "dive.chasm", HERE / "vehicle.bind", lcm_url, "--key-file", keys, sanitized=sanitized)
    cmd[cmd.index("--clock") + 1] = "system"
    lc = lcm.LCM(lcm_url)
    rx = Receiver(lc)
    status: list = []
    rx.subscribe("AUV1.CHASM.NAVIGATOR", chasm_status_t, lambda c, m: status.append(m), 5000)
    err = tmp_path / "manager.err"
    mgr = subprocess.Popen(cmd, env=child_env, stderr=err.open("w"), text=True)
    try:
        assert pump(lc, lambda: len(status) >= 3, timeout=30), "no status"
        status.clear()
        forged = mission_command_t()
        forged.vehicle, forged.command, forged.reason = "AUV1", mission_command_t.CMD_ABORT, "x" * 200
        forged.auth.key_id, forged.auth.sender, forged.auth.mac_len = NEW.id, "flood", 32
        sent, t0, wall0 = 0, time.monotonic(), time.time() * 1e6
        while time.monotonic() - t0 < 1.0:
            for _ in range(50):
                sent += 1
                forged.seq, forged.auth.counter = sent, auth.next_counter()
                forged.auth.mac = hashlib.sha256(sent.to_bytes(4, "big")).digest()
                lc.publish("AUV1.MISSION_CMD", forged.encode())
            lc.handle_timeout(1)
        pump(lc, lambda: bool(status) and status[-1].utime > wall0 + 1.3e6, timeout=10)
        # the manager's clock is the system's: its cycles stamped within the flood's second
        during = [m for m in status if wall0 + 0.1e6 <= m.utime <= wall0 + 1.1e6]
        assert len(during) >= 7, f"{len(during)} cycles in 1 s of flood at 10 Hz ({sent} messages sent)"
        assert status[-1].auth_bad_mac > 100 and status[-1].run_state != chasm_status_t.RUN_ABORTED
    finally:
        rc = stop(mgr, signal.SIGTERM)
    log = err.read_text()
    assert rc == 0, log
    lines, refused = log.count("refused: bad MAC"), status[-1].auth_bad_mac
    assert lines <= 10 + refused // 1000, f"{lines} log lines for {refused} refusals: one per 1000 after the first 10"


@BOTH
def test_a_loose_key_file_stops_the_manager_and_no_key_is_said(lcm_url, child_env, tmp_path, sanitized):
    loose = write_keys(tmp_path / "team.key", mode=0o644)
    cmd = manager_cmd(HERE / "dive.chasm", HERE / "vehicle.bind", lcm_url, "--key-file", loose, sanitized=sanitized)
    run = subprocess.run(cmd, env=child_env, capture_output=True, text=True, timeout=60)
    assert run.returncode == 2
    assert f"--key-file {loose}: key file open to group or others (mode 0644): chmod 600 it" in run.stderr
    cmd = manager_cmd(tmp_path / "none.chasm", HERE / "vehicle.bind", lcm_url, sanitized=sanitized)
    run = subprocess.run(cmd, env=child_env, capture_output=True, text=True, timeout=60)
    assert run.returncode == 1 and run.stderr.count("commands are not authenticated") == 1
