"""Where the checkout and its build are: one answer for every tool.

The build folder is $AUV_BUILD when set (relative to the checkout), else
build/: a second build tree (`make BUILD=x`) is used by setting AUV_BUILD.
"""

from __future__ import annotations

import os
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def build_dir() -> Path:
    b = Path(os.environ.get("AUV_BUILD", ROOT / "build"))
    return b if b.is_absolute() else ROOT / b
