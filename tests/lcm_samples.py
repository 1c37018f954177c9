"""Random, fully populated messages of any generated type, from its metadata.

lcm-gen's Python classes list their fields (__slots__), LCM types
(__typenames__) and array dimensions (__dimensions__); that is enough to fill
every field, nested types and variable-length arrays included, without code
per type. Values are drawn from a seeded generator so failures reproduce.
"""

from __future__ import annotations

import random
import struct

from auvlcm.types import by_name

_INT_RANGES = {"int8_t": 8, "int16_t": 16, "int32_t": 32, "int64_t": 64}
_TEXT = "abcXYZ_019 .-/éü→水"


def _scalar(typename: str, rng: random.Random):
    if typename in _INT_RANGES:
        bits = _INT_RANGES[typename]
        return rng.randint(-(1 << (bits - 1)), (1 << (bits - 1)) - 1)
    if typename == "byte":
        return rng.randint(0, 255)
    if typename == "boolean":
        return rng.random() < 0.5
    if typename == "double":
        return rng.choice([0.0, -0.0, 1e300, -1e-300, rng.uniform(-1e6, 1e6)])
    if typename == "float":
        # Only values a float32 holds exactly survive a round trip unchanged.
        return struct.unpack(">f", struct.pack(">f", rng.uniform(-1e4, 1e4)))[0]
    if typename == "string":
        return "".join(rng.choice(_TEXT) for _ in range(rng.randint(0, 12)))
    return random_message(by_name(typename), rng)


def _array(typename: str, dims: list[int], rng: random.Random):
    if len(dims) == 1 and typename == "byte":
        return bytes(rng.randint(0, 255) for _ in range(dims[0]))
    if len(dims) == 1:
        return [_scalar(typename, rng) for _ in range(dims[0])]
    return [_array(typename, dims[1:], rng) for _ in range(dims[0])]


def random_message(cls: type, rng: random.Random, max_len: int = 4):
    """An instance of cls with every field set; variable arrays get 0..max_len items."""
    msg = cls()
    sizes: dict[str, int] = {}
    size_fields = {d for dims in cls.__dimensions__ if dims for d in dims if isinstance(d, str)}
    for name, typename, dims in zip(cls.__slots__, cls.__typenames__, cls.__dimensions__):
        if name in size_fields:
            value = rng.randint(0, max_len)
        elif dims:
            value = _array(typename, [sizes[d] if isinstance(d, str) else d for d in dims], rng)
        else:
            value = _scalar(typename, rng)
        sizes[name] = value if name in size_fields else 0
        setattr(msg, name, value)
    return msg


def same(a, b) -> bool:
    """Field-by-field equality of two decoded messages (tuples equal lists)."""
    if hasattr(a, "__slots__"):
        return type(a) is type(b) and all(same(getattr(a, s), getattr(b, s)) for s in a.__slots__)
    if isinstance(a, (list, tuple)):
        return isinstance(b, (list, tuple)) and len(a) == len(b) and all(map(same, a, b))
    if isinstance(a, (bytes, bytearray)):
        return bytes(a) == bytes(b)
    return a == b
