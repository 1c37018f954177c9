"""Messages as JSON, with a JSON Schema per type (MCAP, Foxglove).

The one place both come from is the generated Python classes (lcm-gen writes
each field's LCM type and dimensions into __typenames__ and __dimensions__),
so the schemas follow lcmtypes/ with nothing written by hand. Conventions:
int64 as a JSON integer; a double that is not finite (NaN, inf) as null,
which JSON cannot write; byte arrays as base64 strings (contentEncoding, as
Foxglove reads them); fixed arrays with their length, variable ones as long
as their count field says.
"""

from __future__ import annotations

import base64
import math
from functools import lru_cache
from typing import Any

from auvlcm.types import all_types, by_name

INT_RANGES = {"int8_t": 8, "int16_t": 16, "int32_t": 32, "int64_t": 64}
DRAFT = "https://json-schema.org/draft/2020-12/schema"


def _scalar_schema(typename: str) -> dict[str, Any]:
    if typename in INT_RANGES:
        bits = INT_RANGES[typename]
        return {"type": "integer", "minimum": -(1 << (bits - 1)), "maximum": (1 << (bits - 1)) - 1}
    if typename in ("double", "float"):
        return {"type": ["number", "null"], "description": "null when not finite (NaN, inf)"}
    if typename == "string":
        return {"type": "string"}
    if typename == "boolean":
        return {"type": "boolean"}
    if typename == "byte":
        return {"type": "integer", "minimum": 0, "maximum": 255}
    return _struct_schema(by_name(typename))


def _struct_schema(cls: type) -> dict[str, Any]:
    props: dict[str, Any] = {}
    for name, typename, dims in zip(cls.__slots__, cls.__typenames__, cls.__dimensions__):
        if typename == "byte" and dims and len(dims) == 1:
            props[name] = {"type": "string", "contentEncoding": "base64"}
            continue
        schema = _scalar_schema(typename)
        for dim in reversed(dims or []):
            schema = {"type": "array", "items": schema}
            if isinstance(dim, int):
                schema.update(minItems=dim, maxItems=dim)
        props[name] = schema
    return {
        "type": "object",
        "title": f"auv.{cls.__name__}",
        "properties": props,
        "required": list(cls.__slots__),
        "additionalProperties": False,
    }


@lru_cache(maxsize=None)
def schema_of(cls: type) -> dict[str, Any]:
    """The JSON Schema (draft 2020-12) of one message type."""
    return {"$schema": DRAFT, **_struct_schema(cls)}


def all_schemas() -> dict[str, dict[str, Any]]:
    return {f"auv.{cls.__name__}": schema_of(cls) for cls in all_types()}


def _value(v: Any, typename: str, dims: list | None) -> Any:
    if dims:
        if typename == "byte" and len(dims) == 1:
            return base64.b64encode(bytes(v)).decode()
        return [_value(x, typename, dims[1:]) for x in v]
    if typename in ("double", "float"):
        return v if math.isfinite(v) else None
    if typename in INT_RANGES or typename in ("string", "boolean", "byte"):
        return v
    return to_json(v)


def to_json(msg: Any) -> dict[str, Any]:
    """A decoded message as a JSON-ready dictionary that its schema accepts."""
    cls = type(msg)
    return {
        name: _value(getattr(msg, name), t, d)
        for name, t, d in zip(cls.__slots__, cls.__typenames__, cls.__dimensions__)
    }
