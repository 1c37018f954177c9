"""The CPU scheduling policy of a fast-time world (docs/performance.md).

In a lockstep world nothing waits on the wall clock: every process wakes for
a datagram, does a step's work and sleeps. Under the default policy each
datagram's receiver, once woken, preempts its sender: a simulator publishing
its step's sensor messages hands the core to the filter after the first and
takes it back, and the filter woke 2.3 times per step where once would do. Under
SCHED_BATCH the kernel does not preempt on wake-up: the sender finishes its
step, and the receivers read what has queued in one go. Measured on 2 cores,
same run against the default policy (docs/performance.md): 4 vehicles x1.10,
8 vehicles x1.05 and x1.09, 16 vehicles x0.96, x1.06 and x1.17 vehicle-seconds
per wall second.

A paced world (realtime, scaled) keeps the default policy: there a wake-up's
latency is what the clock is about. The launcher itself, the lockstep clock,
keeps the default policy too: the last report of a step must get it the core
at once (with the clock under SCHED_BATCH as well, 16 vehicles ran 5 % slower
and the clock took twice the CPU).
"""

from __future__ import annotations

import os

from sim import clock_modes

CHOICES = ("auto", "batch", "normal")


def wants_batch(time_mode: str, choice: str = "auto") -> bool:
    """Whether the world's processes run SCHED_BATCH: `auto` means for a
    lockstep clock that runs as fast as the slowest process, never for a
    paced one."""
    if choice not in CHOICES:
        raise ValueError(f"--sched {choice}: expected one of {', '.join(CHOICES)}")
    if choice == "auto":
        return time_mode == clock_modes.LOCKSTEP
    return choice == "batch"


def batch_available() -> str | None:
    """None, or why SCHED_BATCH cannot be had here (it needs Linux; any
    process may take it for itself)."""
    if not hasattr(os, "SCHED_BATCH"):
        return "SCHED_BATCH not available on this system: default scheduling"
    return None
