"""`auv-multihil node ...` / `auv-multihil world ...` (also `python -m
tools.launch.multihil_cli`): one multi-HIL node (sim.multihil.standalone), or a
whole world on this machine (tools/launch/world.py)."""

from __future__ import annotations

import sys

USAGE = (
    "usage: auv-multihil node --id ID --lcm-url URL [options]     (node --help)\n"
    "       auv-multihil world [--vehicles N] [--clock MODE] ...  (world --help)"
)


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if argv and argv[0] == "world":
        from tools.launch.world import main as world_main

        return world_main(argv[1:])
    if argv and argv[0] == "node":
        from sim.multihil.standalone import main as node_main

        return node_main(argv[1:])
    if argv and argv[0] in ("-h", "--help"):
        print(USAGE)
        return 0
    print(USAGE, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main())
