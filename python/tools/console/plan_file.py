"""A plan file for its author, without running it (docs/console.md, "Plan
files"): its states as parsed (`chasm outline`, even when it does not load),
every load error at its file:line:col beside the state it concerns, and
`chasm check`'s summary and findings. The console serves it at /api/plans
for the files given with --plan; each request reads the files again, so an
author edits and reloads the page."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path
from typing import Any

from auvlcm.paths import build_dir

LOC = re.compile(r"^(?P<file>[^:\n]+):(?P<line>\d+):(?P<col>\d+): (?P<what>error|warning): (?P<text>.*)$")
TIMEOUT_S = 20.0


def _chasm(*args: str) -> subprocess.CompletedProcess:
    exe = build_dir() / "bin" / "chasm"
    return subprocess.run([str(exe), *args], capture_output=True, text=True, timeout=TIMEOUT_S, check=False)


def _state_of(states: list[dict[str, Any]], file: str, line: int) -> int:
    """The state declared last before the line, in the same file: the one the line is in
    (or -1: before any state, or in another file)."""
    best, best_line = -1, 0
    for i, s in enumerate(states):
        f, ln = s["file"], s["line"]
        if Path(f).resolve() == Path(file).resolve() and best_line <= ln <= line:
            best, best_line = i, ln
    return best


def describe(path: Path) -> dict[str, Any]:
    """What the page draws for one plan file."""
    out: dict[str, Any] = {"file": str(path), "states": [], "errors": [], "findings": [], "summary": ""}
    try:
        outline = _chasm("outline", str(path))
        check = _chasm("check", str(path))
    except (OSError, subprocess.TimeoutExpired) as exc:
        out["errors"].append({"loc": str(path), "text": f"chasm could not run: {exc}", "state": -1})
        return out
    for row in outline.stdout.splitlines():
        parts = row.split("\t")
        if len(parts) != 4:
            continue
        loc = parts[2].rsplit(":", 2)
        out["states"].append(
            {"parent": int(parts[1]), "path": parts[3], "loc": parts[2], "file": loc[0], "line": int(loc[1])}
        )
    for line in (check.stderr + check.stdout).splitlines():
        m = LOC.match(line)
        if m:
            item = {
                "loc": f"{m['file']}:{m['line']}:{m['col']}",
                "text": m["text"],
                "state": _state_of(out["states"], m["file"], int(m["line"])),
            }
            out["errors" if m["what"] == "error" else "findings"].append(item)
        elif ": ok (" in line or re.search(r": \d+ (errors|findings?)$", line) or "marked expected" in line:
            out["summary"] += line + "\n"
    if check.returncode != 0 and not out["errors"]:
        out["errors"].append({"loc": str(path), "text": check.stderr.strip() or "chasm check failed", "state": -1})
    return out
