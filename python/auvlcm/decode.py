"""Strict decoding: a message either decodes completely or is refused.

lcm-gen's Python decoders read from a BytesIO that silently returns short
reads, so a payload cut inside a trailing string or byte array can come back
as a "message" with missing data. Here a short read or leftover bytes is an
error, exactly like the C side (c/common/lcm_rx.c).

How, without a Python-level read() per field (a quarter of the simulator's
receive cost): the decoder reads from the payload followed by one guard
byte. A decoder that wanted more than the payload holds reads into the guard,
so it ends past the payload's end; one that wanted less ends before it. A
message is complete exactly when the decoder stops at the payload's end.
"""

from __future__ import annotations

import struct
from io import BytesIO


class DecodeError(ValueError):
    """The payload is not a complete message of the expected type."""

    def __init__(self, reason: str, kind: str) -> None:
        super().__init__(reason)
        self.kind = kind  # "wrong_fingerprint" or "malformed"


def decode_strict(cls: type, data: bytes):
    """Decode data as cls, or raise DecodeError saying why not."""
    if bytes(data[:8]) != cls._get_packed_fingerprint():
        raise DecodeError(f"fingerprint is not {cls.__name__}'s", "wrong_fingerprint")
    buf = BytesIO(bytes(data) + b"\0")  # the guard byte
    buf.seek(8)
    try:
        msg = cls._decode_one(buf)
    except (EOFError, struct.error, ValueError, UnicodeDecodeError, IndexError, OverflowError, MemoryError) as exc:
        raise DecodeError(f"truncated or malformed {cls.__name__}: {exc}", "malformed") from None
    end = buf.tell()
    if end > len(data):
        raise DecodeError(f"truncated {cls.__name__}: it needs more than its {len(data)} bytes", "malformed")
    if end < len(data):
        raise DecodeError(f"{len(data) - end} bytes left over after {cls.__name__}", "malformed")
    return msg
