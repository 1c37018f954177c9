"""The C unit tests of the device layer (tests/drivers/*.c on the shared harness,
build/bin/test_drivers): NMEA framing and fields, each driver's parser; one pytest
per C test and build variant (normal and ASan+UBSan)."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

NAMES = [
    name
    for source in sorted(Path(__file__).parent.glob("*.c"))
    for name in re.findall(r'^\s*\{"(\w+)", \w+\},', source.read_text(), re.M)
]


def test_the_c_test_list_is_found():
    assert len(NAMES) >= 3, NAMES


@pytest.mark.parametrize("name", NAMES)
def test_c_unit(name, variant_dir, child_env):
    exe = variant_dir / "bin" / "test_drivers"
    if not exe.exists():
        pytest.fail(f"{exe} is not built: run `make build sanitize` first")
    p = subprocess.run([str(exe), name], env=child_env, capture_output=True, text=True, timeout=120, cwd=ROOT)
    assert p.returncode not in (86, 87), f"sanitizer report:\n{p.stderr}"
    assert p.returncode == 0 and f"ok {name}" in p.stdout, p.stdout + p.stderr
