"""Command authentication (docs/security.md): team key files, signing and
verifying commands, and the acoustic link's 32-bit frame tags.

The same scheme as the C library (c/common/auth_*.c), byte for byte: both are
held to tests/auth/vectors.txt. The MAC is HMAC-SHA-256 from the standard
library (`hmac`, `hashlib`: OpenSSL underneath), over the LCM encoding of the
whole message with its authenticator's `mac_len` 0 (its key id, sender and
counter included). The counter is the signer's clock in microseconds, so a
signer keeps no state across runs; a verifier refuses a counter more than 5
minutes from its own clock (stale) or not above the newest it accepted from
the same (key id, sender) (replay).

Key file: mode 0600, one key a line `KEY_ID HEX_SECRET`, `#` comments. Every key
verifies, the last one signs: during a rotation a file holds the old and the
new key.
"""

from __future__ import annotations

import argparse
import hashlib
import hmac
import os
import socket
import stat
import sys
import threading
import time
from collections import OrderedDict
from dataclasses import dataclass
from pathlib import Path
from typing import Any

MAC_BYTES = 32
STALE_US = 300 * 1_000_000
MAX_PEERS = 64
MAX_KEYS = 4
MAX_KEY_ID = 32
MAX_SENDER = 64
ACOUSTIC_LABEL = b"CHASM-ACOUSTIC-1"
ACOUSTIC_WINDOW = 32
ACOUSTIC_MAX_PAYLOAD = 256
_ID_CHARS = set("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-.")

# The results, with the texts the C verifier puts in its acks (auth_verify.c).
OK = "ok"
RESULT_TEXT = {
    "ok": "ok",
    "unsigned": "unsigned command (this receiver requires authenticated commands)",
    "unknown_key": "unknown key id",
    "bad_mac": "bad MAC",
    "replay": "replay (counter not above the newest from its sender)",
    "stale": "stale (counter more than 5 min from this host's clock)",
}
NOT_AUTHENTICATED = "commands are not authenticated"


class KeyFileError(ValueError):
    """A key file that cannot be used: 'path[:line]: reason'."""


@dataclass(frozen=True)
class Key:
    id: str
    secret: bytes


@dataclass(frozen=True)
class KeyRing:
    keys: tuple[Key, ...]

    @property
    def signing(self) -> Key:
        return self.keys[-1]

    def find(self, key_id: str) -> Key | None:
        return next((k for k in self.keys if k.id == key_id), None)


def _parse_line(text: str) -> Key | str:
    parts = text.split()
    if len(parts) != 2:
        return "a key line is 'KEY_ID HEX_SECRET'"
    kid, hexs = parts
    if len(kid) > MAX_KEY_ID:
        return "key id longer than 32 characters"
    if not set(kid) <= _ID_CHARS:
        return "key id of letters, digits, '_', '-' and '.' only"
    if len(hexs) % 2 or not 16 <= len(hexs) // 2 <= 64:
        return "secret must be 16 to 64 bytes in hex (auv-keygen writes 32)"
    try:
        return Key(kid, bytes.fromhex(hexs))
    except ValueError:
        return "secret is not hex"


def load_keys(path: str | Path) -> KeyRing:
    """The key file's keys; KeyFileError when it is open to group or others,
    or malformed (the same rules as auth_keys_load in C)."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_CLOEXEC | os.O_NOFOLLOW)
    except OSError as e:
        raise KeyFileError(f"{path}: {e.strerror}") from None
    with os.fdopen(fd, "r", encoding="ascii", errors="replace") as f:
        st = os.fstat(f.fileno())
        if not stat.S_ISREG(st.st_mode):
            raise KeyFileError(f"{path}: not a regular file")
        if st.st_mode & 0o077:
            mode = stat.S_IMODE(st.st_mode)
            raise KeyFileError(f"{path}: key file open to group or others (mode {mode:04o}): chmod 600 it")
        keys: list[Key] = []
        for n, line in enumerate(f, 1):
            text = line.strip()
            if not text or text.startswith("#"):
                continue
            k = "more than 4 keys" if len(keys) >= MAX_KEYS else _parse_line(text)
            if isinstance(k, Key) and any(x.id == k.id for x in keys):
                k = "key id listed twice"
            if isinstance(k, str):
                raise KeyFileError(f"{path}:{n}: {k}")
            keys.append(k)
    if not keys:
        raise KeyFileError(f"{path}: no key in it (write one with auv-keygen)")
    return KeyRing(tuple(keys))


def announce_unauthenticated(tool: str, _said: set[str] = set()) -> None:  # noqa: B006 (once per process)
    """Says once per process (on stderr) that tool sends or takes unsigned commands."""
    if tool not in _said:
        _said.add(tool)
        print(f"{tool}: {NOT_AUTHENTICATED} (no key file: docs/security.md)", file=sys.stderr)


KEY_FILE_ENV = "AUV_KEY_FILE"


def add_key_file_argument(ap: argparse.ArgumentParser) -> None:
    """--key-file FILE, default $AUV_KEY_FILE: the team key file a tool signs with."""
    ap.add_argument(
        "--key-file",
        type=Path,
        default=os.environ.get(KEY_FILE_ENV) or None,
        help=f"team key file to sign commands with (auv-keygen; default ${KEY_FILE_ENV}); "
        f"without one {NOT_AUTHENTICATED}",
    )


def ring_for(path: str | Path | None, tool: str) -> KeyRing | None:
    """The key ring of path (KeyFileError when it is refused), or None, said once."""
    if path is None or str(path) == "":
        announce_unauthenticated(tool)
        return None
    return load_keys(path)


def hmac_sha256(key: bytes, data: bytes) -> bytes:
    return hmac.new(key, data, hashlib.sha256).digest()


def _unsigned_encoding(msg: Any) -> bytes:
    """msg's LCM encoding with its authenticator's mac_len 0: what is signed."""
    a = msg.auth
    mac, n = a.mac, a.mac_len
    a.mac, a.mac_len = b"", 0
    try:
        return msg.encode()
    finally:
        a.mac, a.mac_len = mac, n


_last_counter = 0
_counter_lock = threading.Lock()  # a launcher signs on two threads (commands, keepalives)


def next_counter() -> int:
    """Microseconds since the epoch, strictly increasing within this process."""
    global _last_counter
    with _counter_lock:
        _last_counter = max(time.time_ns() // 1000, _last_counter + 1)
        return _last_counter


def default_sender(tool: str) -> str:
    return f"{tool}@{socket.gethostname()}:{os.getpid()}"[:MAX_SENDER]


def sign(msg: Any, ring: KeyRing, sender: str, counter: int | None = None) -> Any:
    """Signs msg (a mission_command_t, plugin_upload_t or agent_command_t) in
    place with ring's newest key, after every other field is final; returns it."""
    key = ring.signing
    a = msg.auth
    a.key_id, a.sender = key.id, sender[:MAX_SENDER]
    a.counter = next_counter() if counter is None else counter
    a.mac = hmac_sha256(key.secret, _unsigned_encoding(msg))
    a.mac_len = MAC_BYTES
    return msg


class Verifier:
    """Checks signed commands against a key ring; counts results by reason
    (`counts`, keys of RESULT_TEXT). With no ring everything passes (and
    nothing is counted): commands are then not authenticated."""

    def __init__(self, ring: KeyRing | None) -> None:
        self.ring = ring
        self.counts = dict.fromkeys(RESULT_TEXT, 0)
        self._peers: OrderedDict[tuple[str, str], int] = OrderedDict()

    def _check(self, msg: Any, now_us: int) -> str:
        assert self.ring is not None
        a = msg.auth
        if not a.key_id or a.mac_len == 0:
            return "unsigned"
        key = self.ring.find(a.key_id)
        if key is None:
            return "unknown_key"
        want = hmac_sha256(key.secret, _unsigned_encoding(msg))
        if a.mac_len != MAC_BYTES or not hmac.compare_digest(want, bytes(a.mac)):
            return "bad_mac"
        if abs(a.counter - now_us) > STALE_US:
            return "stale"
        peer = (a.key_id, a.sender[:MAX_SENDER])
        if peer in self._peers and a.counter <= self._peers[peer]:
            return "replay"
        self._peers[peer] = a.counter
        self._peers.move_to_end(peer)
        if len(self._peers) > MAX_PEERS:
            self._peers.popitem(last=False)  # the least recently heard sender goes
        return OK

    def verify(self, msg: Any, now_us: int | None = None) -> str:
        """OK, or the reason's key in RESULT_TEXT."""
        if self.ring is None:
            return OK
        r = self._check(msg, time.time_ns() // 1000 if now_us is None else now_us)
        self.counts[r] += 1
        return r


# ------------------------------------------------------------ acoustic frames


def acoustic_tag(key: bytes, payload: bytes, counter24: int) -> int:
    """The 32-bit tag of an acoustic frame: the first 4 bytes (big-endian) of
    HMAC-SHA-256(key, ACOUSTIC_LABEL || counter (3 bytes, big-endian) || payload)."""
    if len(payload) > ACOUSTIC_MAX_PAYLOAD:
        raise ValueError(f"acoustic payload of {len(payload)} bytes (at most {ACOUSTIC_MAX_PAYLOAD})")
    mac = hmac_sha256(key, ACOUSTIC_LABEL + (counter24 & 0xFFFFFF).to_bytes(3, "big") + payload)
    return int.from_bytes(mac[:4], "big")


class AcousticVerifier:
    """A frame's tag and 24-bit counter: accepted once, the counter above the
    newest or within the ACOUSTIC_WINDOW below it and not seen yet (frames
    arrive out of order over a relay); the same as AuthAcousticWindow in C."""

    def __init__(self, key: bytes) -> None:
        self.key = key
        self.newest = -1
        self.seen = 0  # bit i: counter newest - i accepted

    def verify(self, payload: bytes, counter24: int, tag: int) -> str:
        if not 0 <= counter24 <= 0xFFFFFF:
            return "bad_mac"
        if not hmac.compare_digest(
            acoustic_tag(self.key, payload, counter24).to_bytes(4, "big"), tag.to_bytes(4, "big")
        ):
            return "bad_mac"
        if counter24 > self.newest:
            shift = counter24 - self.newest
            self.seen = ((self.seen << shift) | 1) & ((1 << ACOUSTIC_WINDOW) - 1) if shift < ACOUSTIC_WINDOW else 1
            self.newest = counter24
            return OK
        back = self.newest - counter24
        if back >= ACOUSTIC_WINDOW:
            return "stale"
        if self.seen >> back & 1:
            return "replay"
        self.seen |= 1 << back
        return OK
