"""Command authentication's two implementations against each other, without
LCM traffic: the shared vectors (tests/auth/vectors.txt) in Python and in C
(auv-auth-probe, both builds); key files (mode, format, rotation) in both;
and the hostile cases (forged, replayed, reordered, truncated, wrong key id,
counter rolled back, a valid MAC on a modified body, stale) through both
verifiers, which must agree message by message."""

from __future__ import annotations

import hashlib
import hmac
import subprocess
from pathlib import Path

import pytest
from conftest import c_program
from make_vectors import HERE, KEY, RFC4231, lines

from auv import mission_command_t, plugin_upload_t
from auvlcm import auth

VECTORS = HERE / "vectors.txt"
NOW = 1_764_000_000_000_000
BOTH = pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])


def probe(*args, sanitized=False) -> subprocess.CompletedProcess:
    cmd = [str(c_program("bin/auv-auth-probe", sanitized)), *map(str, args)]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=60)


def key_file(path: Path, *keys: tuple[str, bytes], mode: int = 0o600) -> Path:
    path.write_text("# test keys\n" + "".join(f"{k} {s.hex()}\n" for k, s in keys))
    path.chmod(mode)
    return path


def test_hmac_is_the_standard_one_and_the_vectors_are_current():
    for k, d, m in RFC4231:
        assert auth.hmac_sha256(bytes.fromhex(k), bytes.fromhex(d)).hex() == m
    assert VECTORS.read_text() == "\n".join(lines()) + "\n", "vectors.txt differs: make_vectors.py changed?"


def test_python_signs_the_vectors_messages_byte_for_byte():
    """Each command vector decodes, and signing it again gives the same MAC:
    the signed bytes are the LCM encoding with mac_len 0."""
    cmds = [ln.split() for ln in VECTORS.read_text().splitlines() if ln.startswith("hmac " + KEY.hex())]
    assert len(cmds) == 4
    ring = auth.KeyRing((auth.Key("team-a", KEY),))
    for _, _, body, mac in cmds[:3]:
        raw = bytes.fromhex(body)
        cls = mission_command_t if raw[:8] == mission_command_t._get_packed_fingerprint() else plugin_upload_t
        msg = cls.decode(raw)
        assert msg.auth.key_id == "team-a" and msg.auth.mac_len == 0
        auth.sign(msg, ring, msg.auth.sender, counter=msg.auth.counter)
        assert bytes(msg.auth.mac).hex() == mac
        assert auth.Verifier(ring).verify(msg, now_us=msg.auth.counter) == auth.OK


@BOTH
def test_c_checks_the_same_vectors(sanitized):
    run = probe("vectors", VECTORS, sanitized=sanitized)
    assert run.returncode == 0, run.stdout + run.stderr
    assert run.stdout.strip() == "ok 10"
    bad = VECTORS.read_text().replace("5bdcc146", "5bdcc147")
    f = HERE.parent.parent / "build" / "auth_bad_vectors.txt"
    f.write_text(bad)
    assert probe("vectors", f, sanitized=sanitized).returncode == 1


@BOTH
def test_key_files_loose_malformed_and_rotated(tmp_path, sanitized):
    old, new = ("team-old", bytes(range(32))), ("team-new", bytes(range(32, 64)))
    good = key_file(tmp_path / "team.key", old, new)
    run = probe("keys", good, sanitized=sanitized)
    assert run.returncode == 0 and run.stdout.split("\n")[:2] == ["team-old", "team-new (signs)"]
    ring = auth.load_keys(good)
    assert ring.signing.id == "team-new" and ring.find("team-old").secret == old[1]
    cases = {
        key_file(tmp_path / "loose.key", old, mode=0o640): "open to group or others (mode 0640): chmod 600 it",
        key_file(tmp_path / "world.key", old, mode=0o604): "open to group or others (mode 0604)",
        key_file(tmp_path / "short.key", ("k", b"x" * 8)): ":2: secret must be 16 to 64 bytes",
        key_file(tmp_path / "twice.key", old, old): ":3: key id listed twice",
        key_file(tmp_path / "id.key", ("bad/id", old[1])): ":2: key id of letters",
        key_file(tmp_path / "empty.key"): "no key in it",
    }
    for path, why in cases.items():
        run = probe("keys", path, sanitized=sanitized)
        assert run.returncode == 1 and why in run.stderr, (path.name, run.stderr)
        with pytest.raises(auth.KeyFileError, match=why.replace("(", r"\(").replace(")", r"\)")):
            auth.load_keys(path)


def _hostile_sequence(ring: auth.KeyRing, other: auth.KeyRing) -> list[tuple[str, bytes]]:
    """(expected result, encoded message) in the order offered."""

    def cmd(seq: int, reason: str = "x") -> mission_command_t:
        m = mission_command_t()
        m.utime, m.vehicle, m.seq, m.command, m.reason = NOW, "AUV1", seq, m.CMD_PAUSE, reason
        return m

    first = auth.sign(cmd(1), ring, "op", counter=NOW)
    later = auth.sign(cmd(2), ring, "op", counter=NOW + 2000)
    earlier = auth.sign(cmd(3), ring, "op", counter=NOW + 1000)  # signed before `later`, arrives after
    forged = cmd(4)
    forged.auth.key_id, forged.auth.sender, forged.auth.counter = "team-new", "op", NOW + 5000
    forged.auth.mac, forged.auth.mac_len = hashlib.sha256(b"guess").digest(), 32
    modified = auth.sign(cmd(5), ring, "op", counter=NOW + 6000)
    modified.command = mission_command_t.CMD_ABORT  # the MAC of the pause it was
    cut = auth.sign(cmd(6), ring, "op", counter=NOW + 7000)
    cut.auth.mac, cut.auth.mac_len = bytes(cut.auth.mac)[:16], 16
    wrong_id = auth.sign(cmd(7), other, "op", counter=NOW + 8000)
    stale = auth.sign(cmd(8), ring, "op", counter=NOW - auth.STALE_US - 1)
    future = auth.sign(cmd(9), ring, "op", counter=NOW + auth.STALE_US + 10)
    other_sender = auth.sign(cmd(10), ring, "op2", counter=NOW + 1)  # its own counter
    old_key = auth.sign(cmd(11), auth.KeyRing(ring.keys[:1]), "op", counter=NOW + 9000)
    rolled_back = auth.sign(cmd(12), auth.KeyRing(ring.keys[:1]), "op", counter=NOW + 8500)  # per (key id, sender)
    unsigned = cmd(13)
    up = plugin_upload_t()
    up.utime, up.vehicle, up.seq, up.plugin_name, up.data = NOW, "AUV1", 14, "p", b"\x7fELF" * 100
    up.n_bytes, up.sha256_hex = len(up.data), hashlib.sha256(up.data).hexdigest()
    upload = auth.sign(up, ring, "op", counter=NOW + 9500)
    return [
        ("ok", first.encode()),
        ("replay", first.encode()),
        ("ok", later.encode()),
        ("replay", earlier.encode()),  # reordered: older than the newest from its sender
        ("bad_mac", forged.encode()),
        ("bad_mac", modified.encode()),
        ("bad_mac", cut.encode()),
        ("unknown_key", wrong_id.encode()),
        ("stale", stale.encode()),
        ("stale", future.encode()),
        ("ok", other_sender.encode()),
        ("ok", old_key.encode()),  # rotation: the older key still verifies
        ("replay", rolled_back.encode()),
        ("unsigned", unsigned.encode()),
        ("ok", upload.encode()),
        ("undecodable", upload.encode()[:-40]),  # truncated on the wire
    ]


@BOTH
def test_hostile_commands_get_the_same_verdict_in_c_and_python(tmp_path, sanitized):
    keys = (("team-old", bytes(range(32))), ("team-new", bytes(range(32, 64))))
    path = key_file(tmp_path / "team.key", *keys)
    ring = auth.load_keys(path)
    other = auth.KeyRing((auth.Key("team-x", bytes(32)),))
    seq = _hostile_sequence(ring, other)
    files = []
    for i, (_, data) in enumerate(seq):
        files.append(tmp_path / f"{i:02d}.bin")
        files[-1].write_bytes(data)
    run = probe("verify", path, NOW, *files, sanitized=sanitized)
    assert run.returncode == 0, run.stderr
    assert run.stdout.split() == [want for want, _ in seq]
    v = auth.Verifier(ring)
    got = []
    for _, data in seq:
        try:
            msg = (
                mission_command_t if data[:8] == mission_command_t._get_packed_fingerprint() else plugin_upload_t
            ).decode(data)
        except (ValueError, Exception):
            got.append("undecodable")
            continue
        got.append(v.verify(msg, now_us=NOW))
    assert got == [want for want, _ in seq]
    assert v.counts["bad_mac"] == 3 and v.counts["replay"] == 3 and v.counts["ok"] == 5


@BOTH
def test_acoustic_tags_and_window_agree(sanitized):
    payload = b"\x03abort AUV2"
    frames = [(c, payload, auth.acoustic_tag(KEY, payload, c)) for c in (5, 7, 6, 7, 100, 80, 69, 80, 68)]
    frames.append((101, payload, frames[-1][2] ^ 1))  # forged: a tag off by one bit
    want = ["0", "0", "0", "2", "0", "0", "0", "2", "3", "1"]
    args = [f"{c}:{p.hex()}:{t:08x}" for c, p, t in frames]
    run = probe("acoustic", KEY.hex(), *args, sanitized=sanitized)
    assert run.returncode == 0, run.stderr
    assert run.stdout.split() == want
    v = auth.AcousticVerifier(KEY)
    names = {"ok": "0", "bad_mac": "1", "replay": "2", "stale": "3"}
    assert [names[v.verify(p, c, t)] for c, p, t in frames] == want
    assert hmac.compare_digest(
        auth.acoustic_tag(KEY, b"", 0).to_bytes(4, "big"), auth.hmac_sha256(KEY, auth.ACOUSTIC_LABEL + bytes(3))[:4]
    )
