"""Fast encoders for the fixed-layout messages the simulator publishes.

lcm-gen's Python `encode()` writes each field group with its own
struct.pack into a BytesIO: about 15 us for a nav_solution_t, several times
the cost of the physics step that produced it. Every message the simulator
sends at a sensor rate has a fixed layout (no variable-length arrays) and
strings that never change in a run (the vehicle id, the process name), so
the whole message is one precompiled struct.Struct: fingerprint, strings and
all. The output is byte-identical to lcm-gen's (tests/sim/test_wire.py checks
it against random messages of every type the simulator sends).

The per-type pack function is generated from the class's own metadata
(__slots__, __typenames__, __dimensions__), as lcm-gen generates encode():
one `pack(...)` call with every field inline is what makes it fast; a
generic loop over fields would cost as much as lcm-gen's encoder.
"""

from __future__ import annotations

import struct
from typing import Any, Callable

_CODES = {
    "int8_t": "b",
    "int16_t": "h",
    "int32_t": "i",
    "int64_t": "q",
    "float": "f",
    "double": "d",
    "boolean": "b",
    "byte": "B",
}


class Encoder:
    """encode(msg) -> bytes for one type, with its string fields fixed.

    `encode(msg)` takes a message object; `pack(*values)` takes the
    non-string fields in declaration order, arrays flattened row by row,
    for callers that never need the object at all.
    """

    def __init__(self, cls: type, **strings: str) -> None:
        fmt = [">8s"]
        args = ["FP"]  # arguments of pack() in encode(msg)
        params: list[str] = []  # parameters of pack_values(...)
        values: list[str] = []  # their use in pack()
        consts: dict[str, Any] = {"FP": cls._get_packed_fingerprint()}
        for name, tn, dims in zip(cls.__slots__, cls.__typenames__, cls.__dimensions__):
            if tn == "string":
                if name not in strings:
                    raise ValueError(f"{cls.__name__}.{name}: a string field needs its fixed value")
                raw = strings[name].encode("utf-8") + b"\0"
                fmt.append(f"I{len(raw)}s")
                consts[f"S_{name}"] = raw
                args.append(f"{len(raw)}, S_{name}")
                values.append(f"{len(raw)}, S_{name}")
                continue
            if tn not in _CODES:
                raise ValueError(f"{cls.__name__}.{name}: {tn} is not a fixed-layout field")
            if dims is None:
                fmt.append(_CODES[tn])
                args.append(f"m.{name}")
                params.append(name)
                values.append(name)
                continue
            if any(not isinstance(d, int) for d in dims) or len(dims) > 2:
                raise ValueError(f"{cls.__name__}.{name}: variable or >2-D array")
            count = 1
            for d in dims:
                count *= d
            fmt.append(f"{count}{_CODES[tn]}")
            if len(dims) == 1:
                args.append(f"*m.{name}[:{dims[0]}]")
            else:
                args.append(", ".join(f"*m.{name}[{i}][:{dims[1]}]" for i in range(dims[0])))
            flat = [f"{name}_{i}" for i in range(count)]
            params.extend(flat)
            values.extend(flat)
        unknown = set(strings) - set(cls.__slots__)
        if unknown:
            raise ValueError(f"{cls.__name__} has no field(s) {sorted(unknown)}")
        self.cls = cls
        self.struct = struct.Struct("".join(fmt))
        self.size = self.struct.size
        self.n_values = len(params)
        consts["pack"] = self.struct.pack
        src = (
            f"def encode(m):\n    return pack({', '.join(args)})\n"
            f"def pack_values({', '.join(params)}):\n"
            f"    return pack(FP, {', '.join(values)})\n"
        )
        exec(compile(src, f"<Encoder {cls.__name__}>", "exec"), consts)  # noqa: S102
        self.encode: Callable[[Any], bytes] = consts["encode"]
        self.pack: Callable[..., bytes] = consts["pack_values"]


def fixed_layout(cls: type) -> bool:
    """Whether every field of cls has a fixed size (strings aside)."""
    for tn, dims in zip(cls.__typenames__, cls.__dimensions__):
        if tn != "string" and tn not in _CODES:
            return False
        if dims is not None and any(not isinstance(d, int) for d in dims):
            return False
    return True


def encoder_for(cls: type, vehicle: str) -> Encoder | None:
    """An Encoder for a sensor message type whose only string is the vehicle id,
    None if the type has variable-length fields or other strings."""
    strings = [n for n, tn in zip(cls.__slots__, cls.__typenames__) if tn == "string"]
    if not fixed_layout(cls) or strings != ["vehicle"]:
        return None
    return Encoder(cls, vehicle=vehicle)
