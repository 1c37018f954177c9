"""The C unit tests of plugin `guidance` (tests/plugins/guidance/*.c), one
pytest per C test and build variant (normal and ASan+UBSan)."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
NAMES = sorted({m for f in HERE.glob("test_*.c") for m in re.findall(r'^\s*\{"(\w+)", \w+\},', f.read_text(), re.M)})


def test_the_c_test_list_is_complete():
    assert len(NAMES) >= 20, NAMES


@pytest.mark.parametrize("name", NAMES)
def test_c_unit(name, variant_dir, child_env):
    exe = variant_dir / "bin" / "test_plugin_guidance"
    if not exe.exists():
        pytest.fail(f"{exe} is not built: run `make build sanitize` first")
    p = subprocess.run([str(exe), "--plugins", str(variant_dir / "plugins"), name], env=child_env,
                       capture_output=True, text=True, timeout=120)
    assert p.returncode not in (86, 87), f"sanitizer report:\n{p.stderr}"
    assert p.returncode == 0 and f"ok {name}" in p.stdout, p.stdout + p.stderr
