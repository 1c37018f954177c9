"""The front estimator's C++ unit tests (tests/frontest/unit/), one pytest per
C++ test and build variant (normal and ASan+UBSan)."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
NAMES = sorted(
    {m for f in (HERE / "unit").glob("test_*.cpp") for m in re.findall(r"^TEST\((\w+)\)", f.read_text(), re.M)}
)


def test_the_unit_test_list_is_not_empty():
    assert len(NAMES) >= 8 and "degenerate_data_diverge_never_ok" in NAMES, NAMES


@pytest.mark.parametrize("name", NAMES)
def test_frontest_unit(name, variant_dir, child_env):
    exe = variant_dir / "bin" / "frontest_unit_tests"
    if not exe.exists():
        pytest.fail(f"{exe} is not built: run `make build sanitize` first")
    p = subprocess.run([exe, name], env=child_env, capture_output=True, text=True, timeout=120)
    assert p.returncode not in (86, 87), f"sanitizer report:\n{p.stderr}"
    assert p.returncode == 0 and f"ok {name}" in p.stdout, p.stdout + p.stderr
