"""Range checks of the `sonar:` section, reported like every config error (file:line:col: key)."""

from __future__ import annotations

import math
from pathlib import Path

import yaml

from sim.sonar import targets as tg
from sim.sonar.config import SonarConfig

# name: (low, high, low inclusive, high inclusive)
_RANGES = {
    "range_m": (0.0, math.inf, False, True),
    "nadir_gap_per_altitude": (0.0, math.inf, True, True),
    "min_grazing_rad": (0.0, math.pi / 2, False, False),
    "knee_fraction": (0.0, 1.0, True, True),
    "pd_max": (0.0, 1.0, True, True),
    "clutter_pd_factor": (0.0, math.inf, True, True),
    "min_altitude_m": (0.0, math.inf, True, True),
    "p_classify": (0.0, 1.0, True, True),
    "clutter_as_mine": (0.0, 1.0, True, True),
    "false_alarms_per_km2": (0.0, math.inf, True, True),
    "relook_s": (0.0, math.inf, True, True),
    "mines": (0, math.inf, True, True),
    "clutter": (0, math.inf, True, True),
    "min_separation_m": (0.0, math.inf, True, True),
    "mine_length_m": (0.0, math.inf, False, True),
    "clutter_length_m": (0.0, math.inf, False, True),
    "length_m": (0.0, math.inf, False, True),
    "width_m": (0.0, math.inf, False, True),
}


def _describe(lo, hi, lo_in, hi_in) -> str:
    if hi == math.inf:
        return f"must be {'>=' if lo_in else '>'} {lo:g}"
    return f"must be in {'[' if lo_in else '('}{lo:g}, {hi:g}{']' if hi_in else ')'}"


def _check_ranges(doc, node, key: str, obj) -> None:
    items = doc.mapping(node, key)
    for name, (_, vnode) in items.items():
        value = getattr(obj, name, None)
        if name in _RANGES and isinstance(value, (int, float)) and not isinstance(value, bool):
            lo, hi, lo_in, hi_in = _RANGES[name]
            ok = (value >= lo if lo_in else value > lo) and (value <= hi if hi_in else value < hi)
            if not ok:
                doc.err(vnode, f"{key}.{name}", _describe(lo, hi, lo_in, hi_in))
        elif isinstance(vnode, yaml.MappingNode) and hasattr(obj, name):
            _check_ranges(doc, vnode, f"{key}.{name}", getattr(obj, name))


def check_sonar(doc, node, base: Path, fill) -> SonarConfig | None:
    """The checked section, or None for `sonar: false` (errors go to doc)."""
    if isinstance(node, yaml.ScalarNode) and doc.scalar(node) is False:
        return None
    cfg = fill(doc, node, "sonar", SonarConfig())
    _check_ranges(doc, node, "sonar", cfg)
    items = doc.mapping(node, "sonar")
    if cfg.publish_targets not in ("auto", "yes", "no") and "publish_targets" in items:
        doc.err(items["publish_targets"][1], "sonar.publish_targets", "one of auto, yes, no")
    if cfg.max_altitude_m <= cfg.min_altitude_m and "max_altitude_m" in items:
        doc.err(items["max_altitude_m"][1], "sonar.max_altitude_m", "must be > min_altitude_m")
    tnode = items["targets"][1] if "targets" in items else None
    titems = doc.mapping(tnode, "sonar.targets") if tnode is not None else {}
    try:
        if cfg.targets.file:
            tg.load(base / cfg.targets.file, lambda n, e: 0.0)
        elif not doc.errors:
            tg.place(cfg.targets, max(cfg.targets.seed, 0), lambda n, e: 0.0)
    except ValueError as exc:   # the file's own file:line messages, or an overfull area
        where = titems.get("file", titems.get("mines", (None, tnode)))[1]
        for line in str(exc).splitlines():
            doc.err(where, "sonar.targets", line)
    return cfg if cfg.enabled else None
