"""`python -m sim.multihil node ...`: one multi-HIL node (sim.multihil.standalone).

`auv-multihil` (tools/launch/multihil_cli.py) also starts whole worlds; a world
is a starter of processes, so it lives with the launcher, above the simulator.
"""

from __future__ import annotations

import sys

USAGE = "usage: python -m sim.multihil node --id ID --lcm-url URL [options]     (node --help)"


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
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
