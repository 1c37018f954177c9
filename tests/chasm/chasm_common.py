"""Helpers shared by the CHASM pytest files: program paths per variant, runs."""

from __future__ import annotations

import subprocess
from pathlib import Path

HERE = Path(__file__).resolve().parent
PLANS = HERE / "plans"
BAD_PLANS = HERE / "bad_plans"

VARIANTS = ["normal", "sanitized"]


def variant_root(build: Path, variant: str) -> Path:
    return build if variant == "normal" else build / "san"


def run(args, env, cwd=None, timeout=120) -> subprocess.CompletedProcess:
    """Runs a program; sanitizer reports make the exit code 86/87 (tests/conftest.py)."""
    p = subprocess.run([str(a) for a in args], cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout)
    assert p.returncode not in (86, 87), f"sanitizer report:\n{p.stderr}"
    return p
