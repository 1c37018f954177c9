"""The Python side is one installed project (pyproject.toml): every console
command it declares runs from the venv with no path set by hand, and no
module sets one either."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import tomllib
from conftest import ROOT

SCRIPTS = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["scripts"]
BIN = Path(sys.executable).parent


def test_every_console_command_is_installed_and_answers_help():
    # PYTHONPATH removed: the commands must find the project through the install alone
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    assert len(SCRIPTS) >= 15, sorted(SCRIPTS)
    runs = {
        name: subprocess.Popen(
            [BIN / name, "--help"], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
        )
        for name in SCRIPTS
    }
    for name, proc in runs.items():
        out, err = proc.communicate(timeout=120)
        assert proc.returncode == 0 and "usage:" in out.lower(), (name, proc.returncode, err[-2000:])
        assert "Traceback" not in err, (name, err)


def test_no_module_changes_the_import_path():
    offenders = [
        f"{path.relative_to(ROOT)}:{n}"
        for path in sorted((ROOT / "python").rglob("*.py"))
        for n, line in enumerate(path.read_text().splitlines(), 1)
        if re.search(r"\bsys\.path\s*(\.insert|\.append|\[|=|\+=)", line)
    ]
    assert not offenders, offenders
