"""YAML read into plain dicts and lists that remember where each value was.

A checker can then say `file:line:col: key: message` for any value, which is
what a user needs to fix a scenario without guessing. Positions come from
PyYAML's composed node tree.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml


class YamlError(Exception):
    """One or more problems, each already formatted as file:line:col: key: message."""

    def __init__(self, errors: list[str]) -> None:
        super().__init__("\n".join(errors))
        self.errors = errors


class MDict(dict):
    """A mapping with the position of itself (`where`) and of each key (`key_where`)."""
    where: str = ""
    key_where: dict


class MList(list):
    where: str = ""
    item_where: list


def _pos(path: Path, node) -> str:
    m = node.start_mark
    return f"{path}:{m.line + 1}:{m.column + 1}"


def _build(path: Path, node, errors: list[str]) -> Any:
    if isinstance(node, yaml.MappingNode):
        out = MDict()
        out.where, out.key_where = _pos(path, node), {}
        for knode, vnode in node.value:
            key = str(knode.value)
            if key in out:
                errors.append(f"{_pos(path, knode)}: {key}: duplicate key (first at "
                              f"{out.key_where[key].rsplit(':', 2)[1]})")
                continue
            out[key] = _build(path, vnode, errors)
            out.key_where[key] = _pos(path, vnode)
        return out
    if isinstance(node, yaml.SequenceNode):
        lst = MList(_build(path, n, errors) for n in node.value)
        lst.where, lst.item_where = _pos(path, node), [_pos(path, n) for n in node.value]
        return lst
    return yaml.SafeLoader("").construct_object(node, deep=True)


def load(path: str | Path) -> Any:
    """Read a YAML file into MDict/MList/scalars; YamlError on a syntax error."""
    path = Path(path)
    try:
        text = path.read_text()
    except OSError as exc:
        raise YamlError([f"{path}: cannot read: {exc.strerror}"]) from None
    try:
        root = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        where = f"{path}:{mark.line + 1}:{mark.column + 1}" if mark else str(path)
        raise YamlError([f"{where}: YAML syntax: {exc.problem or exc}"]) from None
    errors: list[str] = []
    data = _build(path, root, errors) if root is not None else MDict()
    if errors:
        raise YamlError(errors)
    return data


def where(container: Any, key: Any = None) -> str:
    """Position of container[key] (or of the container itself)."""
    if key is None:
        return getattr(container, "where", "")
    if isinstance(container, MDict):
        return container.key_where.get(key, container.where)
    if isinstance(container, MList) and isinstance(key, int) and key < len(container.item_where):
        return container.item_where[key]
    return getattr(container, "where", "")


def plain(value: Any) -> Any:
    """The same data as ordinary dicts and lists (for yaml.safe_dump)."""
    if isinstance(value, dict):
        return {k: plain(v) for k, v in value.items()}
    if isinstance(value, list):
        return [plain(v) for v in value]
    return value
