"""Print the effective configuration of simulator files as JSON: every field
of the loaded SimConfig (sensors in their build order, the order they publish
in), the file's own path left out.

    .venv/bin/python tests/sim/effective_config.py missions/sim/*.yaml > after.json

Run once before and once after a change to the files' text that must not
change what they mean (e.g. moving shared keys into a base they `extends`),
and compare: `diff before.json after.json` prints nothing when they agree.
"""

from __future__ import annotations

import dataclasses
import json
import sys
from pathlib import Path
from typing import Any

from sim.config import load


def plain(x: Any) -> Any:
    if dataclasses.is_dataclass(x):
        return {"__class__": type(x).__name__, **{f.name: plain(getattr(x, f.name)) for f in dataclasses.fields(x)}}
    if isinstance(x, dict):
        return [[k, plain(v)] for k, v in x.items()]  # a list of pairs: the order is part of it
    if isinstance(x, (list, tuple)):
        return [plain(v) for v in x]
    if isinstance(x, Path):
        return str(x)
    return x


def effective(path: Path) -> dict:
    cfg = load(path)
    out = plain(cfg)
    out.pop("path")
    return out


def main(argv: list[str]) -> int:
    json.dump({Path(p).name: effective(Path(p)) for p in argv}, sys.stdout, indent=1, sort_keys=False)
    print()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
