"""The CPU scheduling policy of a fast-time world (docs/performance.md).

In a lockstep world nothing waits on the wall clock: every process wakes for
a datagram, does a step's work and sleeps. Under the default policy each
datagram's receiver, once woken, preempts its sender: a simulator publishing
its step's five sensor messages hands the core to the filter five times, and
the filter wakes twice or more per step where once would do. Under
SCHED_BATCH the kernel does not preempt on wake-up: the sender finishes its
step, and the receivers read what has queued in one go. Measured on 2 cores
with 8 vehicles: +4 to +8 % vehicle-seconds per wall second.

A paced world (realtime, scaled) keeps the default policy: there a wake-up's
latency is what the clock is about. The policy is inherited by every process
the launcher starts.
"""

from __future__ import annotations

import os

from sim import clock_modes

CHOICES = ("auto", "batch", "normal")


def wants_batch(time_mode: str, choice: str = "auto") -> bool:
    """Whether the world runs SCHED_BATCH: `auto` means for a lockstep clock
    that runs as fast as the slowest process, never for a paced one."""
    if choice not in CHOICES:
        raise ValueError(f"--sched {choice}: expected one of {', '.join(CHOICES)}")
    if choice == "auto":
        return time_mode == clock_modes.LOCKSTEP
    return choice == "batch"


def use_batch() -> str | None:
    """This process (and what it starts from now on) under SCHED_BATCH; None,
    or why not (the policy needs Linux; an unprivileged process may take it)."""
    try:
        os.sched_setscheduler(0, os.SCHED_BATCH, os.sched_param(0))
    except (AttributeError, OSError) as exc:
        return f"SCHED_BATCH not available here ({exc}): default scheduling"
    return None


def policy_name(pid: int = 0) -> str:
    names = {getattr(os, n): n for n in ("SCHED_OTHER", "SCHED_BATCH", "SCHED_IDLE", "SCHED_FIFO", "SCHED_RR")}
    return names.get(os.sched_getscheduler(pid), "unknown")
