"""Read one YAML file into a composed node tree (positions kept), with limits.

Every configuration, scenario and override goes through here, so every file
gets the same refusals, each `file:line:col: message`:

- larger than Limits.max_bytes: refused before it is parsed; more than
  Limits.max_nodes values, mappings and lists: refused while parsing (the
  checkers' time grows with the node count; libyaml parses when PyYAML has it);
- not UTF-8: the position of the first bad byte;
- characters YAML does not allow (control characters): their position;
- nested deeper than Limits.max_depth: refused while parsing (PyYAML's
  composer recurses once per level; 5000 nested `[` would end in a
  RecursionError);
- aliases (`*name`) refused, anchors too (nothing to refer to then): an
  alias expands to a copy of its anchor's value, so 600 bytes of nested
  aliases make billions of nodes (a "billion laughs"); no shipped file needs
  them, and the launcher writes its merged files without them;
- explicit tags other than the core schema's (`!!str`, `!!int`, ...):
  refused, since nothing here builds objects from tags;
- empty (or only comments): an error, not "every default".
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import yaml

from confcheck.errors import ConfigError

# libyaml's parser when PyYAML was built with it: 10-50x faster than the pure-Python one
LOADER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
CORE_TAGS = {f"tag:yaml.org,2002:{t}" for t in ("str", "int", "float", "bool", "null", "seq", "map")}


@dataclass(frozen=True)
class Limits:
    max_bytes: int = 256 << 10  # 256 KiB: the largest shipped file is under 4 KB
    max_depth: int = 32  # nesting of mappings and lists; shipped files use 5
    max_nodes: int = 10000  # values, mappings and lists; shipped files hold under 400


LIMITS = Limits()


def _where(path: Path, mark) -> str:
    return f"{path}:{mark.line + 1}:{mark.column + 1}" if mark is not None else f"{path}"


def _decode(path: Path, data: bytes) -> str:
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        col = exc.start - (data.rfind(b"\n", 0, exc.start) + 1) + 1
        raise ConfigError(
            [f"{path}:{line}:{col}: not UTF-8 (byte 0x{data[exc.start]:02x}); save the file as UTF-8"]
        ) from None


def _text_position(text: str, index: int) -> str:
    line = text.count("\n", 0, index) + 1
    return f"{line}:{index - (text.rfind(chr(10), 0, index) + 1) + 1}"


def _scan(path: Path, text: str, limits: Limits) -> None:
    """Walk the event stream (PyYAML's parser keeps its own stack, no recursion)
    and refuse depth, aliases, anchors and tags before anything is composed."""
    depth, nodes = 0, 0
    for ev in yaml.parse(text, Loader=LOADER):
        if isinstance(ev, yaml.AliasEvent):
            raise ConfigError(
                [
                    f"{_where(path, ev.start_mark)}: YAML alias '*{ev.anchor}' refused: "
                    "aliases are not supported (write the value out)"
                ]
            )
        if getattr(ev, "anchor", None):
            raise ConfigError(
                [
                    f"{_where(path, ev.start_mark)}: YAML anchor '&{ev.anchor}' refused: "
                    "anchors and aliases are not supported (write the value out)"
                ]
            )
        tag = getattr(ev, "tag", None)
        if tag is not None and tag != "!" and tag not in CORE_TAGS:
            raise ConfigError(
                [f"{_where(path, ev.start_mark)}: YAML tag '{tag}' refused: only plain values, mappings and lists"]
            )
        if isinstance(ev, (yaml.ScalarEvent, yaml.MappingStartEvent, yaml.SequenceStartEvent)):
            nodes += 1
            if nodes > limits.max_nodes:
                raise ConfigError([f"{_where(path, ev.start_mark)}: more than {limits.max_nodes} values (the limit)"])
        if isinstance(ev, (yaml.MappingStartEvent, yaml.SequenceStartEvent)):
            depth += 1
            if depth > limits.max_depth:
                raise ConfigError(
                    [f"{_where(path, ev.start_mark)}: nested deeper than {limits.max_depth} levels (the limit)"]
                )
        elif isinstance(ev, (yaml.MappingEndEvent, yaml.SequenceEndEvent)):
            depth -= 1


def parse_text(path: Path, text: str, limits: Limits = LIMITS) -> yaml.Node:
    """The root node of YAML text (ConfigError on any refusal above)."""
    if len(text.encode("utf-8", "surrogatepass")) > limits.max_bytes:
        raise ConfigError([f"{path}: larger than {limits.max_bytes} bytes (the limit)"])
    try:  # a command-line value holds undecodable bytes as lone surrogates
        text.encode("utf-8")
    except UnicodeEncodeError as exc:
        raise ConfigError(
            [f"{path}:{_text_position(text, exc.start)}: not UTF-8 (byte 0x{ord(text[exc.start]) & 0xFF:02x})"]
        ) from None
    try:
        _scan(path, text, limits)
        root = yaml.compose(text, Loader=LOADER)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        raise ConfigError([f"{_where(path, mark)}: YAML syntax: {exc.problem or exc}"]) from None
    except yaml.reader.ReaderError as exc:
        # PyYAML's reader counts characters, libyaml's bytes
        at = (
            exc.position
            if LOADER is yaml.SafeLoader
            else len(text.encode("utf-8", "surrogatepass")[: exc.position].decode("utf-8", "replace"))
        )
        bad = text[at] if 0 <= at < len(text) else exc.character
        raise ConfigError(
            [f"{path}:{_text_position(text, at)}: character {bad!r} is not allowed in YAML (a control character?)"]
        ) from None
    except yaml.YAMLError as exc:
        raise ConfigError([f"{path}: YAML: {exc}"]) from None
    if root is None:
        raise ConfigError([f"{path}:1:1: empty file (no settings in it)"])
    return root


def read_yaml(path: str | Path, limits: Limits = LIMITS) -> tuple[yaml.Node, str]:
    """The root node and the text of a YAML file (ConfigError on any refusal)."""
    path = Path(path)
    try:
        size = path.stat().st_size
        if size > limits.max_bytes:
            raise ConfigError([f"{path}: {size} bytes, larger than {limits.max_bytes} (the limit)"])
        data = path.read_bytes()
    except OSError as exc:
        raise ConfigError([f"{path}: cannot read: {exc.strerror or exc}"]) from None
    text = _decode(path, data)
    return parse_text(path, text, limits), text


class _NoAliasDumper(yaml.SafeDumper):
    def ignore_aliases(self, data) -> bool:  # the same object twice is written out twice
        return True


def dump_yaml(data) -> str:
    """YAML text the reader accepts again: no anchors or aliases."""
    return yaml.dump(data, Dumper=_NoAliasDumper, sort_keys=False)
