"""The `sonar:` section: filled and range-checked by confcheck (the ranges are
declared on sim.sonar.config's fields); here only what spans several fields."""

from __future__ import annotations

from pathlib import Path

import yaml

from confcheck import Checker
from sim.sonar import targets as tg
from sim.sonar.config import SonarConfig, TargetsConfig

REPLACED = ("p_classify", "clutter_as_mine")


def check_sonar(doc: Checker, node, base: Path) -> SonarConfig | None:
    """The checked section, or None for `sonar: false` (errors go to doc)."""
    if isinstance(node, yaml.ScalarNode) and doc.scalar(node) is False:
        return None
    errors_before = len(doc.errors)
    items = doc.mapping(node, "sonar")
    for old in REPLACED:  # the classifier before the score model: say what replaced it
        if old in items:
            doc.err(
                items[old][0],
                f"sonar.{old}",
                "replaced by the score model sonar.score "
                "(mine_a, mine_b, clutter_a, clutter_b, threshold; docs/simulator.md)",
            )
    from sim.devices.config import parse_wire

    wire = {"wire": lambda n, k: parse_wire(doc, n, k, "sonar", base)}
    cfg = doc.fill(node, "sonar", SonarConfig(), skip=REPLACED, special=wire)
    if cfg.max_altitude_m <= cfg.min_altitude_m and "max_altitude_m" in items:
        doc.err(items["max_altitude_m"][1], "sonar.max_altitude_m", "must be > min_altitude_m")
    check_targets(
        doc,
        cfg.targets,
        items["targets"][1] if "targets" in items else None,
        "sonar.targets",
        base,
        place=len(doc.errors) == errors_before,
    )
    return cfg if cfg.enabled else None


def check_targets(doc: Checker, tc: TargetsConfig, tnode, key: str, base: Path, place: bool = True) -> None:
    """The target file reads, or the seeded field fits in its area (errors to doc).
    place=False: other errors already found, the placing is not tried."""
    titems = doc.mapping(tnode, key) if tnode is not None else {}
    try:
        if tc.file:
            tg.load(base / tc.file, lambda n, e: 0.0)
        elif place:
            tg.place(tc, max(tc.seed, 0), lambda n, e: 0.0)
    except ValueError as exc:  # the file's own file:line messages, or an overfull area
        where = titems.get("file", titems.get("mines", (None, tnode)))[1]
        for line in str(exc).splitlines():
            doc.err(where, key, line)
