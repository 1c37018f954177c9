"""A host agent's supervised processes: restart policy with back-off, and
CPU and memory read from /proc (docs/hosts.md).

Each process is a tools.launch.procs.Child: its own process group (a stop reaches
all of it) and PR_SET_PDEATHSIG, so an agent that dies, even by SIGKILL,
leaves nothing behind.
"""

from __future__ import annotations

import fnmatch
import math
import os
import time
from dataclasses import dataclass
from pathlib import Path

from tools.launch.procs import Child

RUNNING, BACKOFF, EXITED, FAILED, STOPPED = range(5)  # agent_process_t.STATE_*
STATE_NAMES = ("running", "backoff", "exited", "failed", "stopped")
_TICK = os.sysconf("SC_CLK_TCK")
_PAGE = os.sysconf("SC_PAGE_SIZE")


@dataclass
class Policy:
    on_failure: bool = False  # False: never restart
    max_restarts: int = 0
    backoff_s: float = 1.0  # first wait; doubles each restart
    backoff_max_s: float = 30.0

    def wait_s(self, restarts_done: int) -> float:
        return min(self.backoff_s * 2.0**restarts_done, self.backoff_max_s)


def rule_errors(pattern: str, policy: int, max_restarts: int, backoff_s: float, backoff_max_s: float) -> list[str]:
    """What is wrong with one agent_restart_t rule ([] if nothing)."""
    errs = []
    if not pattern:
        errs.append("empty process pattern")
    if policy not in (0, 1):
        errs.append(f"policy {policy} is not 0 (never) or 1 (on failure)")
    if max_restarts < 0:
        errs.append(f"max_restarts {max_restarts} < 0")
    for name, v in (("backoff_s", backoff_s), ("backoff_max_s", backoff_max_s)):
        if not math.isfinite(v) or v < 0:
            errs.append(f"{name} {v} is not a finite number >= 0")
    return [f"restart rule '{pattern}': {e}" for e in errs]


def policy_for(name: str, rules: list) -> Policy:
    """The first rule (agent_restart_t) whose pattern matches; none: never restart."""
    for r in rules:
        if fnmatch.fnmatchcase(name, r.process):
            return Policy(r.policy == 1, r.max_restarts, r.backoff_s, max(r.backoff_max_s, r.backoff_s))
    return Policy()


def proc_usage(pid: int) -> tuple[float, int]:
    """(CPU seconds so far, resident bytes) of a live pid; (0, 0) if gone."""
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return 0.0, 0
    fields = stat[stat.rfind(")") + 2 :].split()  # the name may hold spaces
    return (int(fields[11]) + int(fields[12])) / _TICK, int(fields[21]) * _PAGE


class Supervised:
    def __init__(self, name: str, cmd: list[str], out: Path, policy: Policy, log, tier: int = 0) -> None:
        self.name, self.cmd, self.out, self.policy, self.log = name, cmd, out, policy, log
        self.tier = tier  # stop order (tools.launch.procs.stop_together): higher first
        self.child: Child | None = None
        self.state = STOPPED
        self.exit_code = 0
        self.restarts = 0
        self.due = 0.0  # BACKOFF: when to restart (monotonic)
        self.cpu_load = 0.0
        self.rss = 0
        self._last = (0.0, 0.0)  # (monotonic, cpu seconds) of the last sample

    @property
    def pid(self) -> int:
        return self.child.pid if self.child is not None and self.state == RUNNING else -1

    def start(self) -> None:
        out = self.out if self.restarts == 0 else self.out.with_suffix(f".{self.restarts}.out")
        self.child = Child(self.name, self.cmd, out, stopping=False, tier=self.tier).start()
        self.state, self._last, self.cpu_load = RUNNING, (time.monotonic(), 0.0), 0.0
        self.log(
            f"{self.name}: started pid {self.child.pid}"
            + (f" (restart {self.restarts}/{self.policy.max_restarts})" if self.restarts else "")
        )

    def tick(self, now: float) -> bool:
        """Notice a death, restart when due; True if the state changed."""
        if self.state == RUNNING and self.child is not None and self.child.poll() is not None:
            self.child.stop()  # anything the process left in its group
            self.exit_code = self.child.proc.returncode
            if self.exit_code == 0:
                self.state = EXITED
            elif self.policy.on_failure and self.restarts < self.policy.max_restarts:
                self.state, self.due = BACKOFF, now + self.policy.wait_s(self.restarts)
            else:
                self.state = FAILED
            self.log(
                f"{self.name}: pid {self.child.pid} exited with status {self.exit_code}: "
                f"{STATE_NAMES[self.state]}" + (f", restart in {self.due - now:.1f} s" if self.state == BACKOFF else "")
            )
            return True
        if self.state == BACKOFF and now >= self.due:
            self.restarts += 1
            self.start()
            return True
        return False

    def sample(self, now: float) -> None:
        if self.state != RUNNING or self.child is None:
            self.cpu_load, self.rss = 0.0, 0
            return
        cpu, self.rss = proc_usage(self.child.pid)
        t0, cpu0 = self._last
        if now > t0:
            self.cpu_load = max(0.0, (cpu - cpu0) / (now - t0))
        self._last = (now, cpu)

    def uptime(self, now: float) -> float:
        return now - self.child.started_wall if self.state == RUNNING and self.child else 0.0

    def stop(self, timeout: float = 5.0) -> None:
        self.ask_stop()
        self.finish_stop(time.monotonic() + timeout)

    def ask_stop(self) -> None:
        """The first half of a stop (tools.launch.procs.stop_together asks a tier at once)."""
        if self.child is not None and self.state == RUNNING:
            self.child.ask_stop()

    def finish_stop(self, deadline: float) -> int | None:
        if self.child is not None and self.state == RUNNING:
            self.exit_code = self.child.finish_stop(deadline) or 0
            self.log(f"{self.name}: pid {self.child.pid} stopped, status {self.exit_code}")
        if self.state in (RUNNING, BACKOFF):  # a failed or exited process keeps saying so
            self.state = STOPPED
        return self.exit_code
