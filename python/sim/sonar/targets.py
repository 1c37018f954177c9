"""The seabed's objects: mine-like targets and clutter, placed by seed or read from a file.

Every simulator of a world builds the same field from the same seed and area
(or file), and the field is published as target_field_t on SIM.TARGETS so a
log holds the truth that detections are scored against.

File format (CSV, header required, `#` comments allowed):

    id,north_m,east_m,kind,length_m
    1,120.0,-35.5,mine_like,1.5
    2,80.2,10.0,clutter,0.6

`kind` is mine_like or clutter; ids are unique integers. The seabed depth at
each object comes from the world's bathymetry.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from sim.noise import Noise
from sim.sonar.config import TargetsConfig

MINE_LIKE, CLUTTER = "mine_like", "clutter"
KINDS = (MINE_LIKE, CLUTTER)
COLUMNS = ("id", "north_m", "east_m", "kind", "length_m")


class TargetFileError(ValueError):
    pass


@dataclass
class Target:
    id: int
    north_m: float
    east_m: float
    kind: str
    length_m: float
    depth_m: float = 0.0  # seabed depth at the object


@dataclass
class TargetField:
    targets: list[Target]
    seed: int  # 0 when read from a file
    source: str  # "seed" or the file

    def mines(self) -> list[Target]:
        return [t for t in self.targets if t.kind == MINE_LIKE]

    def to_lcm(self, utime: int, world: str):
        from auv import seabed_target_t, target_field_t

        m = target_field_t()
        m.utime, m.world, m.seed, m.source = utime, world, self.seed, self.source
        m.targets = []
        for t in self.targets:
            s = seabed_target_t()
            s.id, s.north_m, s.east_m, s.depth_m, s.length_m = (t.id, t.north_m, t.east_m, t.depth_m, t.length_m)
            s.kind = seabed_target_t.KIND_MINE_LIKE if t.kind == MINE_LIKE else seabed_target_t.KIND_CLUTTER
            m.targets.append(s)
        m.n_targets = len(m.targets)
        return m


def place(cfg: TargetsConfig, seed: int, depth_at: Callable[[float, float], float]) -> TargetField:
    """Mines then clutter, uniform in the area, at least min_separation_m apart."""
    rng = Noise(f"{seed}:targets")
    a = cfg.area
    placed: list[Target] = []
    sep2 = cfg.min_separation_m**2
    for kind, count, length in (
        (MINE_LIKE, cfg.mines, cfg.mine_length_m),
        (CLUTTER, cfg.clutter, cfg.clutter_length_m),
    ):
        for _ in range(count):
            for _attempt in range(1000):
                n = a.north_m + rng.random() * a.length_m
                e = a.east_m + rng.random() * a.width_m
                if all((n - t.north_m) ** 2 + (e - t.east_m) ** 2 >= sep2 for t in placed):
                    break
            else:
                raise ValueError(
                    f"cannot place {cfg.mines + cfg.clutter} objects "
                    f"{cfg.min_separation_m:g} m apart in a {a.length_m:g} x "
                    f"{a.width_m:g} m area"
                )
            placed.append(Target(len(placed) + 1, n, e, kind, length, depth_at(n, e)))
    return TargetField(placed, seed, "seed")


def load(path: Path, depth_at: Callable[[float, float], float]) -> TargetField:
    """Read a target file; TargetFileError lists every bad line as file:line: message."""
    try:
        text = path.read_text()
    except OSError as exc:
        raise TargetFileError(f"{path}: cannot read ({exc.strerror})") from None
    rows = [
        (i + 1, line) for i, line in enumerate(text.splitlines()) if line.strip() and not line.lstrip().startswith("#")
    ]
    if not rows:
        raise TargetFileError(f"{path}: empty; expected a header {','.join(COLUMNS)}")
    header_line, header = rows[0]
    names = [h.strip() for h in next(csv.reader([header]))]
    if sorted(names) != sorted(COLUMNS):
        raise TargetFileError(
            f"{path}:{header_line}: header must name the columns {','.join(COLUMNS)} (got {','.join(names)})"
        )
    errors: list[str] = []
    out: list[Target] = []
    seen: dict[int, int] = {}
    for lineno, line in rows[1:]:
        cells = [c.strip() for c in next(csv.reader([line]))]
        if len(cells) != len(names):
            errors.append(f"{path}:{lineno}: expected {len(names)} columns, got {len(cells)}")
            continue
        row = dict(zip(names, cells))
        try:
            tid = int(row["id"])
            n, e, length = float(row["north_m"]), float(row["east_m"]), float(row["length_m"])
        except ValueError as exc:
            errors.append(f"{path}:{lineno}: {exc}")
            continue
        if not all(math.isfinite(v) for v in (n, e, length)) or length <= 0:
            errors.append(f"{path}:{lineno}: positions must be finite and length_m > 0")
        elif row["kind"] not in KINDS:
            errors.append(f"{path}:{lineno}: kind {row['kind']!r} is not one of {', '.join(KINDS)}")
        elif tid in seen:
            errors.append(f"{path}:{lineno}: duplicate id {tid} (first on line {seen[tid]})")
        else:
            seen[tid] = lineno
            out.append(Target(tid, n, e, row["kind"], length, depth_at(n, e)))
    if errors:
        raise TargetFileError("\n".join(errors))
    return TargetField(out, 0, str(path))
