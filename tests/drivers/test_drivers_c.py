"""The C unit tests of the device layer (tests/drivers/*.c on the shared harness,
build/bin/test_drivers): NMEA framing and fields, each driver's parser; one pytest
per C test and build variant (normal and ASan+UBSan)."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest
from conftest import BUILD

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


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_protocols_fuzz_short(sanitized, tmp_path, child_env):
    """A short seeded run of the protocol fuzzer (`make fuzz` runs it long):
    the hostile corpus and mutations of it through every protocol."""
    exe = (BUILD / "san" if sanitized else BUILD) / "bin" / "drivers_fuzz"
    if not exe.exists():
        pytest.fail(f"{exe} is not built: run `make build sanitize` first")
    corpus = ROOT / "tests" / "drivers" / "corpus"
    cmd = [str(exe), "--runs", "3000", "--seed", "31", "--no-dict", str(corpus)]
    p = subprocess.run(cmd, env=child_env, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert p.returncode == 0 and "no crash" in p.stdout, p.stdout + p.stderr
