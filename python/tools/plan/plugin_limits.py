"""What the plugins accept, asked of the plugins themselves, and a plan check.

The planner must never write a plan that a plugin refuses at run time, so it
reads each limit from the plugin's own description (`chasm describe`), never
from a second copy of the number, and checks every plan it writes with
`chasm check` and the same plugins the launcher will load.
"""

from __future__ import annotations

import re
import subprocess
from dataclasses import dataclass
from pathlib import Path


class LimitsError(RuntimeError):
    pass


@dataclass(frozen=True)
class PolygonLimits:
    max_vertices: int
    max_chars: int


def _chasm(build: Path) -> Path:
    exe = build / "bin" / "chasm"
    if not exe.is_file():
        raise LimitsError(f"{exe} not found: build the project first (make build)")
    return exe


def polygon_limits(build: Path, plugin: str = "checks", handler: str = "outside_area") -> PolygonLimits:
    """The `polygon` parameter's limits of a test handler, from `chasm describe`."""
    run = subprocess.run(
        [str(_chasm(build)), "describe", "-P", str(build / "plugins"), plugin], capture_output=True, text=True
    )
    if run.returncode != 0:
        raise LimitsError(f"chasm describe {plugin}: {(run.stderr or run.stdout).strip()}")
    section = re.search(
        rf"^\s*test handler {re.escape(handler)}\b.*?(?=^\s*(?:test handler|behavior) |\Z)", run.stdout, re.S | re.M
    )
    line = re.search(r"^\s*polygon\s.*$", section.group(0), re.M) if section else None
    m = re.search(r"at most (\d+) vertices and (\d+) characters", line.group(0)) if line else None
    if not m:
        raise LimitsError(f"chasm describe {plugin}: no vertex limit for {handler}(polygon = ...) in its description")
    return PolygonLimits(int(m.group(1)), int(m.group(2)))


def check_plan(plan: Path, build: Path) -> list[str]:
    """`chasm check` with the build's plugins: [] when the plan loads."""
    run = subprocess.run(
        [str(_chasm(build)), "check", "-P", str(build / "plugins"), str(plan)], capture_output=True, text=True
    )
    if run.returncode == 0:
        return []
    return [f"{plan}: does not load:"] + ["  " + ln for ln in (run.stdout + run.stderr).strip().splitlines()]
