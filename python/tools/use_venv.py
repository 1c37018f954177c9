"""Run a tool under the project's .venv whatever Python started it.

The tools import lcm, numpy and friends, which `make` installs into .venv. A
tool started as `python/tools/X.py` (its #! line finds the system python3) or
as `python3 python/tools/X.py` re-executes itself with .venv/bin/python, so the
commands in the docs work without activating anything.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
VENV = ROOT / ".venv"


def ensure() -> None:
    if Path(sys.prefix).resolve() == VENV.resolve():
        return
    try:
        import lcm  # noqa: F401
        return                      # another environment that has what the tools need
    except ImportError:
        pass
    python = VENV / "bin" / "python"
    if python.exists() and not os.environ.get("AUV_VENV_REEXEC"):
        os.environ["AUV_VENV_REEXEC"] = "1"
        os.execv(str(python), [str(python), *sys.argv])
    sys.exit(f"{Path(sys.argv[0]).name}: the lcm package is missing: run `make` in {ROOT} first "
             "(it creates .venv), or run the tool with .venv/bin/python")
