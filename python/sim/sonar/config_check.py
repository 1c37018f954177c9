"""The `sonar:` section: filled and range-checked by confcheck (the ranges are
declared on sim.sonar.config's fields); here only what spans several fields."""

from __future__ import annotations

from pathlib import Path

import yaml

from confcheck import Checker
from sim.sonar import targets as tg
from sim.sonar.config import SonarConfig


def check_sonar(doc: Checker, node, base: Path) -> SonarConfig | None:
    """The checked section, or None for `sonar: false` (errors go to doc)."""
    if isinstance(node, yaml.ScalarNode) and doc.scalar(node) is False:
        return None
    errors_before = len(doc.errors)
    cfg = doc.fill(node, "sonar", SonarConfig())
    items = doc.mapping(node, "sonar")
    if cfg.max_altitude_m <= cfg.min_altitude_m and "max_altitude_m" in items:
        doc.err(items["max_altitude_m"][1], "sonar.max_altitude_m", "must be > min_altitude_m")
    tnode = items["targets"][1] if "targets" in items else None
    titems = doc.mapping(tnode, "sonar.targets") if tnode is not None else {}
    try:
        if cfg.targets.file:
            tg.load(base / cfg.targets.file, lambda n, e: 0.0)
        elif len(doc.errors) == errors_before:
            tg.place(cfg.targets, max(cfg.targets.seed, 0), lambda n, e: 0.0)
    except ValueError as exc:   # the file's own file:line messages, or an overfull area
        where = titems.get("file", titems.get("mines", (None, tnode)))[1]
        for line in str(exc).splitlines():
            doc.err(where, "sonar.targets", line)
    return cfg if cfg.enabled else None
