"""The filter's C++ unit tests (tests/nav/unit/), one pytest per C++ test and
build variant (normal and ASan+UBSan). The Monte Carlo consistency test runs
in the normal build only: 100 runs under the sanitizers take minutes, and
every code path it drives is also run sanitized by the other tests."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
NAMES = sorted(
    {m for f in (HERE / "unit").glob("test_*.cpp") for m in re.findall(r"^TEST\((\w+)\)", f.read_text(), re.M)}
)
MONTE_CARLO = "nees_is_within_chi_square_bounds_over_monte_carlo_runs"


def test_the_unit_test_list_is_not_empty():
    assert len(NAMES) >= 12 and MONTE_CARLO in NAMES, NAMES


@pytest.mark.parametrize("name", NAMES)
def test_nav_unit(name, variant_dir, child_env):
    if name == MONTE_CARLO and variant_dir.name == "san":
        pytest.skip("Monte Carlo NEES runs in the normal build only (minutes under ASan)")
    exe = variant_dir / "bin" / "nav_unit_tests"
    if not exe.exists():
        pytest.fail(f"{exe} is not built: run `make build sanitize` first")
    p = subprocess.run([exe, name], env=child_env, capture_output=True, text=True, timeout=300)
    assert p.returncode not in (86, 87), f"sanitizer report:\n{p.stderr}"
    assert p.returncode == 0 and f"ok {name}" in p.stdout, p.stdout + p.stderr
