"""Child processes that can never outlive the launcher.

Each child runs in its own session and process group (a stop reaches all of
it, and a terminal's Ctrl-C reaches only the launcher, which then stops the
children in order). Each also asks the kernel for SIGTERM when its parent
dies (prctl PR_SET_PDEATHSIG), so even a SIGKILLed launcher leaves no logger
or simulator behind.
"""

from __future__ import annotations

import ctypes
import os
import signal
import subprocess
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Protocol

PR_SET_PDEATHSIG = 1
# The order a world's processes stop in (stop_together: the highest first): the
# managers, then the filters they read, the simulators, the recorder last.
TIER_RECORDER, TIER_SIMULATOR, TIER_FILTER, TIER_MANAGER = range(4)
_libc = ctypes.CDLL(None, use_errno=True)


# Children started from now on run SCHED_BATCH (tools/launch/sched_policy.py); the
# launcher itself keeps its policy: it is the lockstep clock, and the last
# report of a step must get it the core at once.
_children_batch = False


def children_batch(on: bool) -> None:
    global _children_batch
    _children_batch = on


def _die_with(parent_pid: int):
    batch = _children_batch

    def setup() -> None:  # runs in the child between fork and exec
        _libc.prctl(PR_SET_PDEATHSIG, signal.SIGTERM, 0, 0, 0)
        if os.getppid() != parent_pid:  # the parent died before prctl took effect
            os._exit(1)
        if batch:
            try:
                os.sched_setscheduler(0, os.SCHED_BATCH, os.sched_param(0))
            except OSError:
                pass  # an unprivileged process may always take it; if not, default scheduling

    return setup


@dataclass
class Child:
    name: str  # "logger", "AUV1.sim", "AUV1.NAVIGATOR"
    cmd: list[str]
    out: Path  # stdout + stderr
    proc: subprocess.Popen | None = None
    stopping: bool = False  # we asked it to stop: its exit is not a death
    started_wall: float = field(default_factory=time.monotonic)
    tier: int = 0  # stop_together() stops the higher tiers first: one of TIER_*

    @property
    def pid(self) -> int:
        return self.proc.pid if self.proc else -1

    def start(self, env: dict[str, str] | None = None) -> "Child":
        with open(self.out, "w") as f:
            self.proc = subprocess.Popen(
                self.cmd,
                stdout=f,
                stderr=subprocess.STDOUT,
                stdin=subprocess.DEVNULL,
                start_new_session=True,
                preexec_fn=_die_with(os.getpid()),
                env=env,
            )
        self.started_wall = time.monotonic()
        return self

    def poll(self) -> int | None:
        return self.proc.poll() if self.proc else None

    def tail(self, lines: int = 5) -> str:
        try:
            return "\n".join(self.out.read_text(errors="replace").splitlines()[-lines:])
        except OSError:
            return ""

    def stop(self, timeout: float = 10.0) -> int | None:
        """SIGINT to the whole group, then SIGKILL if it does not end in time."""
        self.ask_stop()
        return self.finish_stop(time.monotonic() + timeout)

    def ask_stop(self) -> None:
        """SIGINT to the whole group, if it still runs; finish_stop() waits."""
        if self.proc is None:
            return
        self.stopping = True
        if self.proc.poll() is None:
            _signal_group(self.proc.pid, signal.SIGINT)

    def finish_stop(self, deadline: float) -> int | None:
        """Wait for the exit asked by ask_stop() until deadline (monotonic), then
        SIGKILL; SIGKILL to anything the process left in its group."""
        if self.proc is None:
            return None
        try:
            self.proc.wait(max(deadline - time.monotonic(), 0.0))
        except subprocess.TimeoutExpired:
            pass
        _signal_group(self.proc.pid, signal.SIGKILL)
        return self.proc.wait()

    def kill(self) -> int | None:
        """SIGKILL to the whole group at once (a planned fault: no goodbye)."""
        if self.proc is None:
            return None
        self.stopping = True
        _signal_group(self.proc.pid, signal.SIGKILL)
        return self.proc.wait()


class Stoppable(Protocol):
    name: str
    tier: int

    def ask_stop(self) -> None: ...
    def finish_stop(self, deadline: float) -> int | None: ...


def stop_together(children: Sequence[Stoppable], timeout: float = 10.0) -> dict[str, int | None]:
    """Stop children (a Child, or what wraps one: an agent's Supervised) a tier at
    a time, the highest first (the order they must go in), and the children of
    one tier together: all asked, then all waited for with one deadline. One
    after another, a 40-process world took a second to stop (each Python exit
    waited for alone); together it takes the slowest."""
    codes: dict[str, int | None] = {}
    for tier in sorted({c.tier for c in children}, reverse=True):
        group = [c for c in children if c.tier == tier]
        for c in group:
            c.ask_stop()
        deadline = time.monotonic() + timeout
        for c in group:
            codes[c.name] = c.finish_stop(deadline)
    return codes


def _signal_group(pgid: int, sig: int) -> None:
    try:
        os.killpg(pgid, sig)
    except ProcessLookupError:
        pass
