"""`extends: BASE.yaml`: a configuration that is a base file plus its own keys.

Simulator configurations use it (sim.config) so that what every vehicle shares
(the vehicle, the default sea state, the sensors it carries) is written once.
The merge rule (docs/simulator.md, "A configuration that extends a base"):

- a mapping in both files merges key by key, recursively;
- anything else in the extending file (a list, a value, an empty key)
  replaces the base's;
- a merged mapping lists the extending file's keys first, in its order, then
  the base's other keys in theirs (for `sensors:` that is the order they are
  built and publish in);
- `remove: [sensors.lbl, ...]` deletes keys of the base (dotted paths) before
  the merge: how a vehicle goes without a sensor its base carries.

A base may extend another; a name is resolved relative to the file naming it.
Refused, each at its file:line:col: a base that cannot be read, a cycle, more
than MAX_DEPTH files, `remove` without `extends` or of a key the base lacks.
Nodes keep their own positions; Checker.where() names the file each came from.
"""

from __future__ import annotations

from pathlib import Path

import yaml

from confcheck.errors import ConfigError
from confcheck.reader import LIMITS, Limits, read_yaml

MAX_DEPTH = 8  # files in one chain of bases; the shipped ones use 2
DIRECTIVES = ("extends", "remove")


def _where(path: Path, node) -> str:
    m = node.start_mark
    return f"{path}:{m.line + 1}:{m.column + 1}"


def merge(base: yaml.Node, over: yaml.Node) -> yaml.Node:
    """over merged onto base by the rule above (new mapping nodes; leaves shared)."""
    if not (isinstance(base, yaml.MappingNode) and isinstance(over, yaml.MappingNode)):
        return over
    in_base = {k.value: v for k, v in base.value if isinstance(k, yaml.ScalarNode)}
    named: set[str] = set()
    pairs = []
    for k, v in over.value:
        name = k.value if isinstance(k, yaml.ScalarNode) else None
        if name is not None and name in in_base and name not in named:
            v = merge(in_base[name], v)
        if name is not None:
            named.add(name)
        pairs.append((k, v))
    pairs += [(k, v) for k, v in base.value if not (isinstance(k, yaml.ScalarNode) and k.value in named)]
    return yaml.MappingNode(over.tag, pairs, over.start_mark, over.end_mark, flow_style=over.flow_style)


def _mark(node: yaml.Node, path: Path, sources: dict[int, tuple[Path, yaml.Node]]) -> None:
    """Record path as the file of every node under node not recorded yet. The
    node is kept with it: a node the merge drops must stay alive, or a later
    node could get its id (and its file)."""
    stack = [node]
    while stack:
        n = stack.pop()
        if id(n) in sources:
            continue
        sources[id(n)] = (path, n)
        if isinstance(n, yaml.MappingNode):
            for k, v in n.value:
                stack += [k, v]
        elif isinstance(n, yaml.SequenceNode):
            stack += n.value


def _child(node: yaml.Node | None, name: str) -> yaml.Node | None:
    if not isinstance(node, yaml.MappingNode):
        return None
    return next((v for k, v in node.value if isinstance(k, yaml.ScalarNode) and k.value == name), None)


def _remove(base: yaml.MappingNode, items: yaml.Node, path: Path, base_name: str, errors: list[str]) -> None:
    """Delete the dotted keys listed in items (a `remove:` value) from base, in
    place: base is this load's own tree."""
    if not isinstance(items, yaml.SequenceNode):
        errors.append(f"{_where(path, items)}: remove: expected a list of keys such as [sensors.lbl]")
        return
    for item in items.value:
        key = item.value if isinstance(item, yaml.ScalarNode) else ""
        parts = key.split(".") if isinstance(key, str) and key else []
        parent: yaml.Node | None = base if parts and all(parts) else None
        for part in parts[:-1]:
            parent = _child(parent, part)
        if _child(parent, parts[-1] if parts else "") is None:
            errors.append(f"{_where(path, item)}: remove: '{key}' is not a key of the base {base_name}")
            continue
        parent.value = [
            (k, v) for k, v in parent.value if not (isinstance(k, yaml.ScalarNode) and k.value == parts[-1])
        ]


def compose(
    path: Path,
    root: yaml.Node,
    sources: dict[int, tuple[Path, yaml.Node]],
    limits: Limits = LIMITS,
    chain: tuple[Path, ...] = (),
) -> yaml.Node:
    """root, the tree of the file at path, with the base it extends merged in
    (itself when it extends none). sources gets the file of every node that
    came from a base; ConfigError lists what was refused."""
    if not isinstance(root, yaml.MappingNode):
        return root
    chain = chain or (path.resolve(),)
    directives = {k.value: (k, v) for k, v in root.value if isinstance(k, yaml.ScalarNode) and k.value in DIRECTIVES}
    if not directives:
        return root
    own = yaml.MappingNode(
        root.tag,
        [(k, v) for k, v in root.value if not (isinstance(k, yaml.ScalarNode) and k.value in DIRECTIVES)],
        root.start_mark,
        root.end_mark,
    )
    if "extends" not in directives:
        knode = directives["remove"][0]
        raise ConfigError([f"{_where(path, knode)}: remove: only a file that `extends:` a base removes keys of it"])
    name_node = directives["extends"][1]
    name = name_node.value if isinstance(name_node, yaml.ScalarNode) else ""
    if not isinstance(name, str) or not name.strip():
        raise ConfigError([f"{_where(path, name_node)}: extends: expected a file name (e.g. remus100_base.yaml)"])
    base_path = path.parent / name
    real = base_path.resolve()
    if real in chain:
        names = " -> ".join(str(p) for p in chain) + f" -> {real}"
        raise ConfigError([f"{_where(path, name_node)}: extends: cycle: {names}"])
    if len(chain) >= MAX_DEPTH:
        raise ConfigError([f"{_where(path, name_node)}: extends: more than {MAX_DEPTH} files deep"])
    if not base_path.is_file():
        raise ConfigError([f"{_where(path, name_node)}: extends: cannot read {name} ({base_path}): no such file"])
    base_root, _ = read_yaml(base_path, limits)  # its own refusals name its own positions
    base_root = compose(base_path, base_root, sources, limits, chain + (real,))
    _mark(base_root, base_path, sources)
    if not isinstance(base_root, yaml.MappingNode):
        raise ConfigError([f"{_where(path, name_node)}: extends: {name} is not a mapping of sections"])
    if "remove" in directives:
        errors: list[str] = []
        _remove(base_root, directives["remove"][1], path, name, errors)
        if errors:
            raise ConfigError(errors)
    return merge(base_root, own)


def locate(checker, parts: list[str]) -> tuple[str, bool]:
    """file:line:col of the deepest key of `parts` found in a Checker's tree (in
    whichever file of its bases it came from), and whether all were found."""
    node, found = checker.root, 0
    for part in parts:
        hit = _child(node, part)
        if hit is None:
            break
        node, found = hit, found + 1
    return checker.where(node), found == len(parts) and found > 0
