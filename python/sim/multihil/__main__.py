"""`python -m sim.multihil node ...`: see sim.multihil.standalone."""

from __future__ import annotations

import sys
from pathlib import Path

_ROOT = Path(__file__).resolve().parents[3]
if str(_ROOT / "python") not in sys.path:
    sys.path.insert(0, str(_ROOT / "python"))
import auvlcm  # noqa: E402,F401  (puts the generated types on sys.path)


def main(argv: list[str]) -> int:
    if argv and argv[0] == "world":
        from sim.multihil.world import main as world_main
        return world_main(argv[1:])
    if not argv or argv[0] != "node":
        print("usage: python -m sim.multihil node --id ID --url URL [options]\n"
              "       python -m sim.multihil world [--vehicles N] [--clock MODE] ...  (--help)",
              file=sys.stderr)
        return 2
    from sim.multihil.standalone import main as node_main
    return node_main(argv[1:])


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
