"""Writes tests/auth/vectors.txt, the test vectors C (auv-auth-probe vectors)
and Python (tests/auth/test_auth_vectors.py) are both held to. Run it only to
change the vectors on purpose (`.venv/bin/python tests/auth/make_vectors.py`):
the commit says why. RFC 4231's first two HMAC-SHA-256 cases anchor the MAC
to the standard, independently of this script."""

from __future__ import annotations

from pathlib import Path

from auv import agent_command_t, mission_command_t, plugin_upload_t
from auvlcm import auth

HERE = Path(__file__).resolve().parent
KEY = bytes(range(1, 33))
RING = auth.KeyRing((auth.Key("team-a", KEY),))
COUNTER = 1_764_000_000_000_000  # 2025-11-24 16:00 UTC, in microseconds

RFC4231 = [
    ("0b" * 20, b"Hi There".hex(), "b0344c61d8db38535ca8afceaf0bf12b881dc200c9833da726e9376c2e32cff7"),
    (
        b"Jefe".hex(),
        b"what do ya want for nothing?".hex(),
        "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843",
    ),
]


def commands() -> list[tuple[str, object]]:
    c = mission_command_t()
    c.utime, c.vehicle, c.manager, c.seq, c.command, c.reason = COUNTER, "AUV1", "", 7, c.CMD_ABORT, "vectors"
    load = mission_command_t()
    load.utime, load.vehicle, load.seq, load.command = COUNTER, "AUV2", 8, load.CMD_LOAD_PLAN
    load.plan_name, load.plan_text = "p.chasm", 'mission "v"\nstate a {\n}\n'
    up = plugin_upload_t()
    up.utime, up.vehicle, up.seq, up.plugin_name, up.plugin_version = COUNTER, "AUV1", 9, "survey", "1.0"
    up.data = bytes(range(256)) * 3
    up.n_bytes, up.sha256_hex = len(up.data), __import__("hashlib").sha256(up.data).hexdigest()
    ag = agent_command_t()
    ag.utime, ag.host, ag.sender, ag.seq, ag.command = COUNTER, "alpha", "agentctl@ops", 10, ag.CMD_STOP
    return [
        ("mission_command_t abort", c),
        ("mission_command_t load", load),
        ("plugin_upload_t", up),
        ("agent_command_t stop", ag),
    ]


def lines() -> list[str]:
    out = [
        "# Shared test vectors of command authentication (docs/security.md), written by make_vectors.py.",
        "# hmac KEYHEX DATAHEX MACHEX | acoustic KEYHEX COUNTER PAYLOADHEX(- for none) TAGHEX",
        "# RFC 4231 cases 1 and 2",
    ]
    out += [f"hmac {k} {d} {m}" for k, d, m in RFC4231]
    for name, msg in commands():
        auth.sign(msg, RING, "vectors", counter=COUNTER)
        body = auth._unsigned_encoding(msg)
        out += [f"# {name}: its LCM encoding with mac_len 0, signed by key team-a as 'vectors' at counter {COUNTER}"]
        out += [f"hmac {KEY.hex()} {body.hex()} {bytes(msg.auth.mac).hex()}"]
    out += ["# acoustic frame tags"]
    for counter, payload in [(0, b""), (1, b"\x03abort"), (0xFFFFFF, bytes(32)), (4660, b"\x01pause AUV2")]:
        tag = auth.acoustic_tag(KEY, payload, counter)
        out += [f"acoustic {KEY.hex()} {counter} {payload.hex() or '-'} {tag:08x}"]
    return out


if __name__ == "__main__":
    (HERE / "vectors.txt").write_text("\n".join(lines()) + "\n")
