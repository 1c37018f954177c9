"""The checker: a composed YAML tree, its positions, and every error found.

Errors are collected, not raised one by one (a user fixing a file should not
run the tool once per typo): `file:line:col: key: message`, unknown keys with
a did-you-mean hint, then raise_errors() raises them all, in file order.
"""

from __future__ import annotations

import dataclasses
import difflib
import math
import unicodedata
from pathlib import Path
from typing import Any, Callable, Iterable

import yaml

from confcheck.errors import ConfigError, position
from confcheck.extends import compose
from confcheck.reader import LIMITS, Limits, parse_text, read_yaml
from confcheck.rules import NO_RULE, Rule, rule_of

_TYPE_NAMES = {bool: "true/false", int: "an integer", float: "a number", str: "a string", list: "a list"}
_EMPTY = ("", "~", "null", "Null", "NULL")


def join(a: str, b: str) -> str:
    return f"{a}.{b}" if a else b


def control_character(s: str, multiline: bool = False) -> str:
    """The first control character of s, as a name ("" if none)."""
    for ch in s:
        if multiline and ch in "\n\t":
            continue
        if unicodedata.category(ch) in ("Cc", "Cf", "Zl", "Zp") and ch != "\ufeff":
            return {"\n": "a newline", "\r": "a carriage return", "\t": "a tab"}.get(
                ch, f"control character U+{ord(ch):04X}"
            )
    return ""


class Checker:
    def __init__(self, path: Path, root: yaml.Node | None) -> None:
        self.path = path
        self.root = root
        self.errors: list[str] = []
        # id -> (file, node) of each node that came from a base (confcheck.extends); others are path's
        self.sources: dict[int, tuple[Path, Any]] = {}
        self._constructor = yaml.constructor.SafeConstructor()  # scalars only (no tags reach it)

    @classmethod
    def from_file(cls, path: str | Path, limits: Limits = LIMITS, extends: bool = False) -> "Checker":
        """extends: the file may name a base (`extends:`, confcheck.extends), merged in."""
        path = Path(path)
        root, text = read_yaml(path, limits)
        return cls._made(path, root, text, limits, extends)

    @classmethod
    def from_text(cls, text: str, path: Path, limits: Limits = LIMITS, extends: bool = False) -> "Checker":
        return cls._made(path, parse_text(path, text, limits), text, limits, extends)

    @classmethod
    def _made(cls, path: Path, root: yaml.Node, text: str, limits: Limits, extends: bool) -> "Checker":
        sources: dict[int, tuple[Path, Any]] = {}
        if extends:
            root = compose(path, root, sources, limits)
        c = cls(path, root)
        c.sources = sources
        c.text = text
        return c

    # ------------------------------------------------------------ errors
    def where(self, node) -> str:
        m = node.start_mark if node is not None else None
        path = self.sources[id(node)][0] if id(node) in self.sources else self.path
        return f"{path}:{m.line + 1}:{m.column + 1}" if m else f"{path}"

    def err(self, node, key: str, msg: str) -> None:
        self.errors.append(f"{self.where(node)}: {key}: {msg}" if key else f"{self.where(node)}: {msg}")

    def raise_errors(self) -> None:
        if self.errors:
            raise ConfigError(sorted(dict.fromkeys(self.errors), key=position))

    # ------------------------------------------------------------ structure
    def scalar(self, node) -> Any:
        """bool, int, float, str or None of a scalar node (a date stays its text)."""
        try:
            value = self._constructor.construct_object(node, deep=True)
        except yaml.YAMLError:
            return node.value
        return value if isinstance(value, (bool, int, float, str, type(None))) else node.value

    def is_empty(self, node) -> bool:
        return node is None or (
            isinstance(node, yaml.ScalarNode) and node.value in _EMPTY and node.tag.endswith(":null")
        )

    def mapping(self, node, key: str) -> dict[str, tuple[Any, Any]]:
        """{name: (key node, value node)} of a mapping, reporting duplicates and odd keys."""
        if self.is_empty(node):
            return {}
        if not isinstance(node, yaml.MappingNode):
            self.err(node, key, "expected a mapping of keys")
            return {}
        out: dict[str, tuple[Any, Any]] = {}
        for k, v in node.value:
            if not isinstance(k, yaml.ScalarNode):
                self.err(k, key, "a key must be a plain name")
                continue
            name = str(k.value)
            bad = control_character(name)
            if bad:
                self.err(k, join(key, repr(name)), f"a key must not hold {bad}")
                continue
            if name in out:
                self.err(k, join(key, name), f"duplicate key (first at line {out[name][0].start_mark.line + 1})")
                continue
            out[name] = (k, v)
        return out

    def unknown(self, items: dict, allowed: Iterable[str], key: str) -> None:
        allowed = list(allowed)
        for name, (knode, _) in items.items():
            if name not in allowed:
                hint = difflib.get_close_matches(name, allowed, n=1)
                extra = (
                    f"; did you mean '{hint[0]}'?"
                    if hint
                    else (f"; expected one of: {', '.join(sorted(allowed))}" if allowed else "")
                )
                self.err(knode, join(key, name), f"unknown key{extra}")

    def required(self, items: dict, names: Iterable[str], node, key: str) -> None:
        for name in names:
            if name not in items:
                self.err(node, key or str(self.path.name), f"missing required key '{name}'")

    def sequence(self, node, key: str) -> list:
        if self.is_empty(node):
            return []
        if not isinstance(node, yaml.SequenceNode):
            self.err(node, key, "expected a list")
            return []
        return list(node.value)

    def plain(self, node, key: str = "") -> Any:
        """The node as plain dicts, lists and scalars (for merging and dumping)."""
        if isinstance(node, yaml.MappingNode):
            return {name: self.plain(v, join(key, name)) for name, (_, v) in self.mapping(node, key).items()}
        if isinstance(node, yaml.SequenceNode):
            return [self.plain(n, f"{key}[{i}]") for i, n in enumerate(node.value)]
        value = self.scalar(node)
        if isinstance(value, str):
            bad = control_character(value)
            if bad:
                self.err(node, key, f"must not hold {bad}")
        return value

    # ------------------------------------------------------------ values
    def value(self, node, key: str, default: Any, rule: Rule = NO_RULE) -> Any:
        """One value converted to the type of `default` and checked against `rule`;
        dataclasses.MISSING (after reporting) if it does not fit."""
        want = type(default)
        if want is list:
            items = self.sequence(node, key)
            if not items and not isinstance(node, yaml.SequenceNode):
                return dataclasses.MISSING if not self.is_empty(node) else []
            out = []
            for i, n in enumerate(items):
                elem = default[0] if default else ""
                v = self.value(n, f"{key}[{i}]", elem, rule) if isinstance(n, yaml.ScalarNode) else None
                if v is None:
                    self.err(n, f"{key}[{i}]", "expected a plain value")
                if v is None or v is dataclasses.MISSING:
                    return dataclasses.MISSING
                out.append(v)
            return out
        if not isinstance(node, yaml.ScalarNode):
            self.err(node, key, f"expected {_TYPE_NAMES.get(want, want.__name__)}")
            return dataclasses.MISSING
        value = self.scalar(node)
        if want is str and isinstance(value, bool):
            value = node.value  # YAML 1.1 reads yes/no/on/off as booleans: keep the word
        if want is float and isinstance(value, int) and not isinstance(value, bool):
            value = float(value)
        if type(value) is not want:
            self.err(node, key, f"expected {_TYPE_NAMES.get(want, want.__name__)}, got {node.value!r}")
            return dataclasses.MISSING
        if want is str:
            bad = control_character(value, rule.multiline)
            if bad:
                self.err(node, key, f"must not hold {bad}")
                return dataclasses.MISSING
        if want in (int, float) and not math.isfinite(value):
            self.err(node, key, "must be finite")
            return dataclasses.MISSING
        value = rule.canonical(value)
        problem = rule.problem(value)
        if problem:
            self.err(node, key, problem)
            return dataclasses.MISSING
        return value

    def fill(
        self,
        node,
        key: str,
        obj: Any,
        skip: Iterable[str] = (),
        special: dict[str, Callable[[Any, str], Any]] | None = None,
    ) -> Any:
        """Update a dataclass instance from a mapping node, field by field.

        Nested dataclass fields are filled recursively; `special` maps a YAML key
        to a function (value node, key) -> value or MISSING for fields that need
        more than a type and a rule; `skip` names keys the caller handles."""
        items = self.mapping(node, key)
        cls = type(obj)
        by_key = {rule_of(cls, f.name).key or f.name: f for f in dataclasses.fields(obj)}
        skip = set(skip)
        self.unknown({k: v for k, v in items.items() if k not in skip}, list(by_key), key)
        for name, (_, vnode) in items.items():
            f = by_key.get(name)
            if f is None or name in skip:
                continue
            current = getattr(obj, f.name)
            if special and name in special:
                v = special[name](vnode, join(key, name))
            elif dataclasses.is_dataclass(current):  # a nested section
                self.fill(vnode, join(key, name), current)
                continue
            else:
                v = self.value(vnode, join(key, name), current, rule_of(cls, f.name))
            if v is not dataclasses.MISSING:
                setattr(obj, f.name, v)
        return obj


def resolved(path: str | Path, limits: Limits = LIMITS) -> dict:
    """A file's plain data (dicts, lists, values) with the bases it extends merged
    in: what a tool that edits a configuration and writes it elsewhere starts from
    (a copy of the file's text would name its base relative to the wrong folder)."""
    c = Checker.from_file(path, limits, extends=True)
    data = c.plain(c.root)
    c.raise_errors()
    return data if isinstance(data, dict) else {}
