"""The C unit tests of the vehicle's dynamics (tests/dynamics/test_dynamics.c
on the shared harness, build/bin/test_dynamics), one pytest per C test and
build variant (normal and ASan+UBSan: the library itself is loaded by Python,
unsanitized, so this is where the sanitizers see the equations)."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

NAMES = re.findall(r'^\s*\{"(\w+)", \w+\},', (Path(__file__).parent / "test_dynamics.c").read_text(), re.M)


def test_the_c_test_list_is_found():
    assert len(NAMES) >= 7, NAMES


@pytest.mark.parametrize("name", NAMES)
def test_c_unit(name, variant_dir, child_env):
    exe = variant_dir / "bin" / "test_dynamics"
    if not exe.exists():
        pytest.fail(f"{exe} is not built: run `make build sanitize` first")
    p = subprocess.run([str(exe), name], env=child_env, capture_output=True, text=True, timeout=120)
    assert p.returncode not in (86, 87), f"sanitizer report:\n{p.stderr}"
    assert p.returncode == 0 and f"ok {name}" in p.stdout, p.stdout + p.stderr
