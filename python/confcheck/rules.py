"""Ranges and choices declared on dataclass fields.

    rate_hz: float = setting(10.0, gt=0)
    clock: str = setting("realtime", one_of=("realtime", "scaled", "lockstep"))
    step_s: float = setting(0.05, gt=0, key="step")     # the YAML key differs

A subclass that only changes a default (`rate_hz: float = 20.0`) keeps its
base class's rule: rule_of() looks the name up along the class's bases.
"""

from __future__ import annotations

import dataclasses
import re
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class Rule:
    ge: float | None = None
    gt: float | None = None
    le: float | None = None
    lt: float | None = None
    one_of: tuple = ()  # allowed values (also allowed besides `pattern`)
    pattern: str = ""  # a string must match this (fully) ...
    pattern_hint: str = ""  # ... described so: "upper-case letters, ..."
    key: str = ""  # the YAML key, when it is not the field's name
    multiline: bool = False  # a string may hold newlines (never other control chars)
    unit: str = ""  # named in the message: "must be > 0 [Hz]"
    old_names: tuple = ()  # ((old, current), ...): an old spelling, read as the current one

    def canonical(self, value: Any) -> Any:
        """value under its current name (old_names), else value itself."""
        if isinstance(value, str):
            for old, new in self.old_names:
                if value == old:
                    return new
        return value

    def problem(self, value: Any) -> str:
        """Why value breaks the rule ("" if it does not)."""
        if isinstance(value, str):
            if self.one_of and value in self.one_of:
                return ""
            if self.pattern:
                if re.fullmatch(self.pattern, value):
                    return ""
                alt = f" or one of: {', '.join(map(str, self.one_of))}" if self.one_of else ""
                return f"expected {self.pattern_hint or 'a match of ' + self.pattern}{alt}, got {value!r}"
            if self.one_of:
                return f"expected one of: {', '.join(map(str, self.one_of))}, got {value!r}"
            return ""
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            return ""
        if self.one_of and value not in self.one_of:
            return f"expected one of: {', '.join(map(str, self.one_of))}, got {value!r}"
        lo = self.gt if self.gt is not None else self.ge
        hi = self.lt if self.lt is not None else self.le
        ok = (
            (self.gt is None or value > self.gt)
            and (self.ge is None or value >= self.ge)
            and (self.lt is None or value < self.lt)
            and (self.le is None or value <= self.le)
        )
        if ok:
            return ""
        unit = f" [{self.unit}]" if self.unit else ""
        if hi is None:
            return f"must be {'>' if self.gt is not None else '>='} {lo:g}{unit}"
        if lo is None:
            return f"must be {'<' if self.lt is not None else '<='} {hi:g}{unit}"
        return (
            f"must be in {'(' if self.gt is not None else '['}{lo:g}, {hi:g}{')' if self.lt is not None else ']'}{unit}"
        )


NO_RULE = Rule()


def setting(default: Any = dataclasses.MISSING, *, factory: Any = dataclasses.MISSING, **rule: Any) -> Any:
    """A dataclass field whose rule (Rule's keywords) the Checker enforces."""
    if default is not dataclasses.MISSING and factory is not dataclasses.MISSING:
        raise TypeError("setting: a default or a factory, not both")
    meta = {"rule": Rule(**rule)}
    if factory is not dataclasses.MISSING:
        return dataclasses.field(default_factory=factory, metadata=meta)
    return dataclasses.field(default=default, metadata=meta)


def rule_of(cls: type, name: str) -> Rule:
    """The rule declared for cls.name, on cls or the nearest base that declares one."""
    for klass in cls.__mro__:
        fields = getattr(klass, "__dataclass_fields__", None)
        if fields and name in fields and "rule" in fields[name].metadata:
            return fields[name].metadata["rule"]
    return NO_RULE
