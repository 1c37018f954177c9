"""ConfigError: every problem of one file, each already `file:line:col: key: message`."""

from __future__ import annotations

import re
import sys


class ConfigError(ValueError):
    def __init__(self, errors: list[str]) -> None:
        super().__init__("\n".join(errors))
        self.errors = errors


def position(msg: str) -> tuple[int, int]:
    """(line, column) of a formatted error, for sorting; (0, 0) without one."""
    m = re.match(r".*?:(\d+):(\d+): ", msg)
    return (int(m.group(1)), int(m.group(2))) if m else (0, 0)


def report(exc: ConfigError, what: str, tool: str = "") -> int:
    """Print every error and a count to stderr; the exit status for it (2)."""
    for line in exc.errors:
        print(line, file=sys.stderr)
    print(f"{tool + ': ' if tool else ''}{what}: {len(exc.errors)} error(s)", file=sys.stderr)
    return 2
