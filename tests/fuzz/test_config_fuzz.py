"""A short seeded fuzz run of the configuration readers; `make fuzz` runs the long one."""

from __future__ import annotations

import subprocess
import sys

from conftest import ROOT


def test_config_readers_survive_a_seeded_mutation_run(tmp_path):
    run = subprocess.run(
        [sys.executable, str(ROOT / "tests" / "fuzz" / "config_fuzz.py"), "--runs", "300", "--seed", "7"],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        timeout=300,
    )
    assert run.returncode == 0, run.stdout + run.stderr
    assert "300 inputs (seed 7), no crash" in run.stdout
    assert not list(tmp_path.glob("config-crash-*"))
