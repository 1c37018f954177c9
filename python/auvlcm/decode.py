"""Strict decoding: a message either decodes completely or is refused.

lcm-gen's Python decoders read from a BytesIO that silently returns short
reads, so a payload cut inside a trailing string or byte array can come back
as a "message" with missing data. Here a short read or leftover bytes is an
error, exactly like the C side (c/common/lcm_rx.c).
"""

from __future__ import annotations

import struct
from io import BytesIO


class DecodeError(ValueError):
    """The payload is not a complete message of the expected type."""

    def __init__(self, reason: str, kind: str) -> None:
        super().__init__(reason)
        self.kind = kind  # "wrong_fingerprint" or "malformed"


class _StrictReader(BytesIO):
    def read(self, n: int | None = -1) -> bytes:  # type: ignore[override]
        data = super().read(n)
        if n is not None and n >= 0 and len(data) != n:
            raise EOFError(f"needed {n} bytes, {len(data)} left")
        return data


def decode_strict(cls: type, data: bytes):
    """Decode data as cls, or raise DecodeError saying why not."""
    if bytes(data[:8]) != cls._get_packed_fingerprint():
        raise DecodeError(f"fingerprint is not {cls.__name__}'s", "wrong_fingerprint")
    buf = _StrictReader(bytes(data))
    buf.seek(8)
    try:
        msg = cls._decode_one(buf)
    except (EOFError, struct.error, ValueError, UnicodeDecodeError, IndexError, OverflowError, MemoryError) as exc:
        raise DecodeError(f"truncated or malformed {cls.__name__}: {exc}", "malformed") from None
    if buf.tell() != len(data):
        raise DecodeError(f"{len(data) - buf.tell()} bytes left over after {cls.__name__}", "malformed")
    return msg
