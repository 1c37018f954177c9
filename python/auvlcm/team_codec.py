"""The team-link codec in Python: the same bits as the generated C codec.

Reads c/plugins/team/team_link.schema at run time (auvlcm.team_schema), so
the report and tests decode what the team plugin encodes from the one file
both are made from. Rules (docs/modem.md, "The team-link codec"):

- a field's raw value is `value - MIN` (int) or `floor((value - MIN) / STEP + 0.5)`
  (fixed), written in the field's bits, most significant bit first;
- a message is a 4-bit id then its fields; a frame is messages back to back,
  padded with zero bits to whole bytes; id 0, or fewer than 4 bits left, ends it;
- a value outside [MIN, MAX], NaN or not a number is refused (EncodeError),
  never clamped; a message that does not fit the frame is refused (FrameFull)
  and the frame is left as it was;
- decoding stops at a truncated message, an unknown id or a raw value above
  MAX, and reports how many bits it could not decode.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterable, Mapping

from auvlcm.team_schema import DEFAULT_SCHEMA, ID_BITS, Field, Message, Schema, SchemaError, load

__all__ = ["TeamCodec", "FrameWriter", "Decoded", "EncodeError", "FrameFull", "SchemaError"]


class EncodeError(ValueError):
    """A message the codec refuses: unknown name, missing field, bad value."""


class FrameFull(EncodeError):
    """The message does not fit in what is left of the frame."""


def _raw(f: Field, value: object, msg: str) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise EncodeError(f"{msg}.{f.name}: {value!r} is not a number")
    v = float(value)
    if math.isnan(v):
        raise EncodeError(f"{msg}.{f.name}: NaN is refused")
    if not f.lo <= v <= f.hi:
        raise EncodeError(f"{msg}.{f.name}: {value!r} is outside [{f.lo:g}, {f.hi:g}]")
    if f.is_int:
        if not v.is_integer():
            raise EncodeError(f"{msg}.{f.name}: {value!r} is not a whole number")
        return int(v) - int(f.lo)
    return min(math.floor((v - f.lo) / f.step + 0.5), f.steps)


def _value(f: Field, raw: int) -> float | int:
    if f.is_int:
        return int(f.lo) + raw
    # The last step is MAX itself: lo + steps * step can land a hair above it.
    return f.hi if raw == f.steps else f.lo + raw * f.step


@dataclass
class DecodedMessage:
    name: str
    id: int
    values: dict[str, float | int]


@dataclass
class Decoded:
    """What one frame held: its messages up to the first fault, if any."""

    messages: list[DecodedMessage] = field(default_factory=list)
    error: str | None = None  # None: the frame decoded to its end
    fault: str | None = None  # "truncated", "unknown_id" or "corrupt" (C: TEAM_ERR_*)
    undecodable_bits: int = 0  # bits from the fault to the frame's end

    @property
    def ok(self) -> bool:
        return self.error is None


class FrameWriter:
    """Builds one frame of at most max_bytes bytes, message by message."""

    def __init__(self, codec: "TeamCodec", max_bytes: int):
        if max_bytes < 1:
            raise ValueError("a frame holds at least 1 byte")
        self.codec = codec
        self.max_bits = 8 * max_bytes
        self._acc = 0
        self._nbits = 0
        self.count = 0

    def add(self, name: str, values: Mapping[str, object]) -> None:
        """Append one message; EncodeError/FrameFull leave the frame unchanged."""
        acc, nbits = self.codec.encode_bits(name, values)
        if self._nbits + nbits > self.max_bits:
            raise FrameFull(
                f"{name}: {nbits} bits do not fit in the {self.max_bits - self._nbits} bits left of the frame"
            )
        self._acc = (self._acc << nbits) | acc
        self._nbits += nbits
        self.count += 1

    @property
    def bits(self) -> int:
        return self._nbits

    def to_bytes(self) -> bytes:
        nbytes = (self._nbits + 7) // 8
        return (self._acc << (8 * nbytes - self._nbits)).to_bytes(nbytes, "big")


class TeamCodec:
    def __init__(self, schema: Schema | str | Path | None = None):
        if schema is None:
            schema = DEFAULT_SCHEMA
        self.schema = schema if isinstance(schema, Schema) else load(schema)

    def message(self, name: str) -> Message:
        try:
            return self.schema.by_name(name)
        except KeyError as e:
            raise EncodeError(e.args[0]) from None

    def encode_bits(self, name: str, values: Mapping[str, object]) -> tuple[int, int]:
        """One message as (bits as an int, number of bits)."""
        m = self.message(name)
        unknown = set(values) - {f.name for f in m.fields}
        if unknown:
            raise EncodeError(f"{name}: no field(s) {', '.join(sorted(unknown))}")
        acc, nbits = m.id, ID_BITS
        for f in m.fields:
            if f.name not in values:
                raise EncodeError(f"{name}.{f.name}: missing")
            acc = (acc << f.bits) | _raw(f, values[f.name], name)
            nbits += f.bits
        return acc, nbits

    def writer(self, max_bytes: int) -> FrameWriter:
        return FrameWriter(self, max_bytes)

    def encode_frame(self, messages: Iterable[tuple[str, Mapping[str, object]]], max_bytes: int = 256) -> bytes:
        """All messages in one frame; the first refused one raises."""
        w = self.writer(max_bytes)
        for name, values in messages:
            w.add(name, values)
        return w.to_bytes()

    def encode(self, name: str, values: Mapping[str, object]) -> bytes:
        """One message alone in a frame."""
        return self.encode_frame([(name, values)], max_bytes=self.message(name).max_bytes)

    def decode_frame(self, data: bytes) -> Decoded:
        total = 8 * len(data)
        whole = int.from_bytes(bytes(data), "big")
        pos = 0

        def read(bits: int) -> int:
            nonlocal pos
            pos += bits
            return (whole >> (total - pos)) & ((1 << bits) - 1)

        out = Decoded()
        while total - pos >= ID_BITS:
            start = pos
            ident = read(ID_BITS)
            if ident == 0:
                break
            m = self.schema.by_id(ident)
            if m is None:
                out.error, out.fault = f"unknown message id {ident} at bit {start}", "unknown_id"
            elif total - start < m.bits:
                out.error = f"truncated {m.name} at bit {start}: {m.bits} bits needed, {total - start} left"
                out.fault = "truncated"
            else:
                values: dict[str, float | int] = {}
                for f in m.fields:
                    raw = read(f.bits)
                    if raw > f.steps:
                        out.error = f"{m.name}.{f.name} at bit {start}: raw value {raw} above MAX"
                        out.fault = "corrupt"
                        break
                    values[f.name] = _value(f, raw)
                else:
                    out.messages.append(DecodedMessage(m.name, m.id, values))
                    continue
            out.undecodable_bits = total - start
            break
        return out
