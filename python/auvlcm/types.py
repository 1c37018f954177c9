"""Every generated message class, by name and by fingerprint."""

from __future__ import annotations

import inspect
import struct
from functools import lru_cache
from types import ModuleType

try:
    import auv as _generated
except ImportError as exc:  # pragma: no cover - only without a build
    raise ImportError("generated LCM types not found: run `make` first") from exc


def package() -> ModuleType:
    return _generated


@lru_cache(maxsize=1)
def all_types() -> tuple[type, ...]:
    """Every struct in lcmtypes/, nested ones included, sorted by name."""
    found = [
        obj for _, obj in inspect.getmembers(_generated, inspect.isclass) if hasattr(obj, "_get_packed_fingerprint")
    ]
    return tuple(sorted(found, key=lambda c: c.__name__))


def full_name(cls: type) -> str:
    """The LCM name lcm-spy shows, e.g. 'auv.nav_solution_t'."""
    return f"{_generated.__name__}.{cls.__name__}"


def fingerprint(cls: type) -> int:
    """The signed 64-bit fingerprint, as C's get_hash() and Java's LCM_FINGERPRINT."""
    return struct.unpack(">q", cls._get_packed_fingerprint())[0]


@lru_cache(maxsize=1)
def by_fingerprint() -> dict[bytes, type]:
    return {cls._get_packed_fingerprint(): cls for cls in all_types()}


def by_name(name: str) -> type:
    """'nav_solution_t' or 'auv.nav_solution_t' -> class; KeyError if unknown."""
    bare = name.rsplit(".", 1)[-1]
    for cls in all_types():
        if cls.__name__ == bare:
            return cls
    raise KeyError(f"unknown LCM type {name!r}")


def type_of(data: bytes) -> type | None:
    """The class whose fingerprint starts this encoded message, if any."""
    return by_fingerprint().get(bytes(data[:8]))
