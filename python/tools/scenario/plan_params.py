"""The parameter names a CHASM plan declares (`param NAME = value`), through its
includes, so the launcher can refuse a scenario's `params:` key that no plan
declares (a misspelt `-D` name would silently keep the plan's default).

A light scan, not the Loader: a plan that does not parse is reported by
`chasm check` anyway.
"""

from __future__ import annotations

import re
from pathlib import Path

_PARAM = re.compile(r"^\s*param\s+([A-Za-z_][A-Za-z0-9_]*)\s*=", re.M)
_INCLUDE = re.compile(r'^\s*include\s+"([^"\n]+)"', re.M)
MAX_INCLUDE_DEPTH = 16  # the Loader's limit (docs/chasm.md)


def declared_params(plan: Path) -> set[str] | None:
    """Every parameter name plan and its includes declare; None if a file cannot be read."""
    names: set[str] = set()
    seen: set[Path] = set()

    def scan(path: Path, depth: int) -> bool:
        path = path.resolve()
        if path in seen or depth > MAX_INCLUDE_DEPTH:
            return True
        seen.add(path)
        try:
            text = path.read_text(encoding="utf-8", errors="replace")
        except OSError:
            return False
        text = re.sub(r"#[^\n]*", "", text)  # comments (a '#' inside a string is rare in these lines)
        names.update(_PARAM.findall(text))
        return all(scan(path.parent / inc, depth + 1) for inc in _INCLUDE.findall(text))

    return names if scan(plan, 0) else None
