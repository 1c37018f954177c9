"""One vocabulary for how a world's clock runs, in every file, flag and message.

- realtime: at wall-clock speed;
- scaled:   at `warp` times wall-clock speed;
- lockstep: step n + 1 only after every participant finished step n, as fast
  as the slowest of them (or paced by a scenario's realtime/scaled setting).

These are the three modes SIM.CLOCK carries (sim_clock_t.MODE_*). Older files
said `stepped` (a simulator's clock) or `fast` (a scenario's time) for
lockstep; both are still read, as lockstep, and never written.
"""

from __future__ import annotations

import argparse

from auv import sim_clock_t

REALTIME, SCALED, LOCKSTEP = "realtime", "scaled", "lockstep"
MODES = (REALTIME, SCALED, LOCKSTEP)
OLD_NAMES = (("stepped", LOCKSTEP), ("fast", LOCKSTEP))
WIRE = {REALTIME: sim_clock_t.MODE_REALTIME, SCALED: sim_clock_t.MODE_SCALED, LOCKSTEP: sim_clock_t.MODE_LOCKSTEP}
NAME_OF_WIRE = {v: k for k, v in WIRE.items()}


def canonical(name: str) -> str:
    """The mode's name in this vocabulary (an old name read as its mode); ValueError if none."""
    name = dict(OLD_NAMES).get(name, name)
    if name not in MODES:
        raise ValueError(f"unknown clock mode {name!r}: one of {', '.join(MODES)}")
    return name


def name_of_wire(mode: int) -> str:
    """The name of sim_clock_t.mode, or `mode N` for a value this build does not know."""
    return NAME_OF_WIRE.get(mode, f"mode {mode}")


def argument(text: str) -> str:
    """argparse type= for a --clock/--time flag: the canonical name, old names accepted."""
    try:
        return canonical(text)
    except ValueError as e:
        raise argparse.ArgumentTypeError(str(e)) from None
